"""Every key docs/json-schema.md names is in the documents the commands write (the
tables are read from the page, so a key renamed in the code or in the docs fails here)."""

from __future__ import annotations

import json
import re

import pytest
from support.clirun import run_cli
from support.paths import REPO, TABLEAUX

PAGE = (REPO / "docs" / "json-schema.md").read_text(encoding="utf-8")


def _tables(text: str) -> list[list[str]]:
    """The documented key paths of each table of ``text``, in order: the backticked
    names of each row's first column (``summary.per_order[]`` → ``summary.per_order``);
    names with a wildcard or a leading ``_`` (shorthands of the row before) are skipped."""
    tables, current = [], None
    for line in text.splitlines():
        if line.startswith("| key |"):
            current = []
            tables.append(current)
        elif line.startswith("| ") and current is not None and not line.startswith("| ---"):
            first = line.split("|")[1]
            current += [n.replace("[]", "") for n in re.findall(r"`([^`]+)`", first)
                        if "*" not in n and not n.startswith("_")]
        elif not line.startswith("|"):
            current = None
    return tables


def _has(doc: dict, path: str) -> bool:
    node = doc
    for part in path.split("."):
        if isinstance(node, list):
            node = node[0] if node else {}
        if not isinstance(node, dict) or part not in node:
            return False
        node = node[part]
    return True


def _json(capsys, *args):
    r = run_cli(capsys, *args, "--format", "json")
    assert r.code in (0, 1), r.err
    return json.loads(r.out)


def test_the_verify_keys_are_in_a_verify_document(capsys):
    main = _tables(PAGE.split("## Families")[0])
    doc = _json(capsys, "verify", "@avf-gauss-2", "--degree", "4", "--order", "6")
    missing = [k for table in main for k in table if not _has(doc, k)]
    assert not missing


@pytest.mark.parametrize("which", [0, 1, 2])
def test_the_family_keys_are_in_the_family_documents(capsys, which):
    tables = _tables(PAGE.split("## Families")[1].split("## A complete document")[0])
    families = TABLEAUX / "families"
    args = [["verify", str(families / "seed-kernel-zeta-0.toml")],
            ["solve", str(families / "theorem1-s2-m3.toml"), "--degree", "3", "--order", "6", "--where", "a22 = 0"],
            ["sweep", str(families / "seed-kernel-zeta-0.toml"), "--grid", "beta=-1:1:3"]][which]
    doc = _json(capsys, *args)
    assert tables[which] and not [k for k in tables[which] if not _has(doc, k)]


@pytest.mark.parametrize("which", [0, 1, 2])
def test_the_other_commands_keys_are_in_their_documents(capsys, which):
    tables = _tables(PAGE.split("## Other commands")[1].split("## A complete document")[0])
    args = [["conditions", "-N", "4"], ["bench", "@rk4", "-N", "4", "--dps", "15", "--repeat", "1"],
            ["perturb", "@avf-gauss-2", "--direction", "random", "-m", "3", "-N", "4", "--eps", "1e-2,1e-4",
             "--dps", "15"]][which]
    doc = _json(capsys, *args)
    assert list(doc)[:2] == ["schema", "rkcheck"]
    assert tables[which] and not [k for k in tables[which] if not _has(doc, k)]


@pytest.mark.parametrize("args", [
    ["show", "@rk4"], ["show", str(TABLEAUX / "continuous" / "avf.toml")], ["verify", "@rk4", "-N", "3"],
    ["verify", str(TABLEAUX / "continuous" / "avf.toml"), "-N", "3"], ["scan", str(TABLEAUX / "explicit")],
    ["solve", str(TABLEAUX / "families" / "theorem1-s2-m3.toml"), "-m", "3", "-N", "4"],
    ["conditions", "-N", "3"],
])
def test_every_document_starts_with_its_schema_and_the_version(capsys, args):
    """A pipeline keys on the version: every command's JSON carries it beside its schema."""
    import rkcheck

    doc = _json(capsys, *args)
    assert doc["schema"] >= 1 and doc["rkcheck"] == rkcheck.__version__
