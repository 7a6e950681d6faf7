"""The docs never go stale: every ``>>>`` example of every page that has them (README.md
and docs/) is run (doctest), in order, in one namespace per page, from a directory
outside the clone."""

from __future__ import annotations

import doctest
import os

import pytest
from support.paths import REPO

PAGES = [p for p in [REPO / "README.md", *sorted((REPO / "docs").rglob("*.md"))]
         if ">>>" in p.read_text(encoding="utf-8")]


def test_the_api_page_has_examples():
    assert "api.md" in {p.name for p in PAGES}


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_page_examples_run(tmp_path, page):
    # a code fence ends an example's expected output, as a blank line does
    text = "\n".join("" if line.startswith("```") else line for line in page.read_text(encoding="utf-8").splitlines())
    test = doctest.DocTestParser().get_doctest(text, {}, page.name, str(page), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    here = os.getcwd()
    os.chdir(tmp_path)  # @name must not depend on the working directory
    try:
        runner.run(test)
    finally:
        os.chdir(here)
    results = runner.summarize(verbose=False)
    # every prompt of the page ran (a ... continuation line is part of its example)
    assert results.attempted == text.count("\n>>> ") + text.startswith(">>> ")
    assert results.failed == 0


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_the_page_has_no_untested_python_blocks(page):
    text = page.read_text(encoding="utf-8")
    assert "```python" not in text, "use ```pycon blocks with >>> so that the test runs them"
