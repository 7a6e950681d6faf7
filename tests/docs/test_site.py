"""The documentation site builds strictly, and nothing points at a page or a section that
does not exist: the README's links, the docs' links to files outside the site, and the
"docs/PAGE.md" or 'README "Section"' references in rkcheck's docstrings and messages."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
import unicodedata
from pathlib import Path

import pytest
from support.paths import REPO

DOCS = REPO / "docs"
PAGES = sorted(DOCS.rglob("*.md"))
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
SOURCES = sorted((REPO / "rkcheck").rglob("*.py"))


def slug(heading: str) -> str:
    """The anchor of a heading: Python-Markdown's ``toc`` slugify, which mkdocs uses."""
    text = unicodedata.normalize("NFKD", heading).encode("ascii", "ignore").decode("ascii")
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def headings(page: Path) -> list[str]:
    text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S)
    return [m.group(1).strip() for m in re.finditer(r"^#{1,6}\s+(.*)$", text, flags=re.M)]


def test_slug_matches_the_anchors_mkdocs_writes():
    # the anchors the pages link to, written out by hand from their headings
    assert slug("§5 Numbers and verdicts") == "5-numbers-and-verdicts"
    assert slug("`[expect]`: claims") == "expect-claims"
    assert slug("Configuration: `[tool.rkcheck]`") == "configuration-toolrkcheck"


@pytest.mark.skipif(importlib.util.find_spec("mkdocs") is None, reason="mkdocs is not installed (pip install '.[docs]')")
def test_mkdocs_builds_strictly(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
                          cwd=REPO, capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, NO_MKDOCS_2_WARNING="1"))
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "site" / "commands" / "verify" / "index.html").is_file()
    # the API reference is generated from docstrings: it must name the public functions
    reference = (tmp_path / "site" / "reference" / "index.html").read_text(encoding="utf-8")
    for name in ("verify", "load", "free_trees", "scan", "simulate"):
        assert re.search(rf'id="rkcheck\.api\.\w+\.{name}"', reference), name


def test_every_docs_page_is_in_the_navigation():
    nav = (REPO / "mkdocs.yml").read_text(encoding="utf-8")
    for page in PAGES:
        assert str(page.relative_to(DOCS)) in nav, page


def test_the_reference_covers_every_api_module():
    import rkcheck.api

    text = (DOCS / "reference.md").read_text(encoding="utf-8")
    documented = re.findall(r"^::: rkcheck\.api\.(\w+)$", text, flags=re.M)
    assert sorted(documented) == sorted(rkcheck.api.MODULES)


def _local_links(page: Path):
    text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S)
    for target in LINK.findall(text):
        if not re.match(r"[a-z]+:", target):
            yield target


@pytest.mark.parametrize("page", [REPO / "README.md", *PAGES], ids=lambda p: str(p.relative_to(REPO)))
def test_links_point_at_existing_pages_and_sections(page):
    for target in _local_links(page):
        path, _, anchor = target.partition("#")
        file = (page.parent / path).resolve() if path else page
        assert file.exists(), f"{page.name}: {target}: no such file"
        if anchor and file.suffix == ".md":
            assert anchor in {slug(h) for h in headings(file)}, f"{page.name}: {target}: no such section"


def test_the_readme_is_a_front_door():
    text = (REPO / "README.md").read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 200
    linked = {(REPO / t.partition("#")[0]).resolve() for t in _local_links(REPO / "README.md")}
    assert {DOCS / "index.md", DOCS / "tutorial.md", DOCS / "file-format.md", DOCS / "api.md"} <= linked


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: str(p.relative_to(REPO)))
def test_references_in_the_code_point_at_existing_docs(source):
    text = source.read_text(encoding="utf-8")
    readme_sections = {h for h in headings(REPO / "README.md")}
    for section in re.findall(r"README(?:'s)? \\?\"([^\"\\]+)\\?\"", text):
        assert section in readme_sections, f"{source.name}: README has no section {section!r}"
    for page, _, anchor in re.findall(r"\bdocs/([\w/-]+\.md)(#([\w-]+))?", text):
        assert (DOCS / page).is_file(), f"{source.name}: no page docs/{page}"
        if anchor:
            assert anchor in {slug(h) for h in headings(DOCS / page)}, f"{source.name}: docs/{page}#{anchor}"


def test_the_count_of_curated_files_is_the_library_s():
    # README and file-format.md say how many files the six curated folders hold
    folders = ("avf", "collocation", "hbvm", "explicit", "pseudo-energy-preserving", "counterexamples")
    count = sum(len(list((REPO / "tableaux" / f).glob("*.toml"))) for f in folders)
    for page in (REPO / "README.md", REPO / "docs" / "file-format.md"):
        said = re.search(r"`tableaux/` holds (\d+) curated", page.read_text(encoding="utf-8"))
        assert said is not None and int(said.group(1)) == count, page
