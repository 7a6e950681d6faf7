"""Where the test-suite finds the repository and its shipped tableaux."""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
TABLEAUX = REPO / "tableaux"


def tableau_files() -> list[str]:
    """The shipped tableau files, without the families (files with free [parameters],
    which are not one tableau: tests/families covers them) and the continuous-stage
    methods (:func:`continuous_files`)."""
    from rkcheck.io.discovery import find_tableau_files

    return [f for f in find_tableau_files([str(TABLEAUX)])
            if "[parameters]" not in (text := Path(f).read_text(encoding="utf-8")) and "[continuous]" not in text]


def continuous_files() -> list[str]:
    """The shipped continuous-stage methods (``[continuous]``: a kernel, not a tableau;
    tests/continuous covers them), without kernel families (``[parameters]``)."""
    from rkcheck.io.discovery import find_tableau_files

    return [f for f in find_tableau_files([str(TABLEAUX)])
            if "[continuous]" in (text := Path(f).read_text(encoding="utf-8")) and "[parameters]" not in text]
