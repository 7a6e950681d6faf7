"""Which cross-checks are ``heavy``: plain ``pytest`` leaves them out (pyproject addopts
``-m "not heavy"``), CI runs them with ``pytest -m heavy`` (.ci/run).

Heavy means seconds per test spent repeating, at a larger size, what a lighter test
already covers: HBVM(6, ·), whose entries live in the degree-48 splitting field of the
Gauss-6 nodes (every exact check of it takes seconds), simulations of high-degree
Hamiltonians, regenerating the whole catalogue.  The default run keeps one exact check
in that field (tests/methods/test_library.py) so that its arithmetic is never left to CI
alone.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from support.paths import TABLEAUX

heavy = pytest.mark.heavy

#: the shipped HBVM(6, ·) tableaux in the degree-48 field, relative to tableaux/ (their
#: 60-digit decimal form is checked in balls, as fast as any other file)
HBVM6_EXACT = ("hbvm/hbvm-6-2.toml", "hbvm/hbvm-6-3.toml")


def shipped_name(path: str | Path) -> str:
    return Path(path).resolve().relative_to(TABLEAUX).as_posix()


def in_degree_48_field(path: str | Path) -> bool:
    return shipped_name(path) in HBVM6_EXACT


def shipped_params(paths: list[str], heavy_when=in_degree_48_field) -> list:
    """``pytest.param`` per shipped file, id its path under tableaux/, marked heavy when
    ``heavy_when(path)``."""
    return [pytest.param(p, id=shipped_name(p), marks=[heavy] if heavy_when(p) else [])
            for p in paths]
