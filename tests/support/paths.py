"""Where the test-suite finds the repository and its shipped tableaux."""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
TABLEAUX = REPO / "tableaux"
