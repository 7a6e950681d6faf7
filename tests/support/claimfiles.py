"""Small tableau files with an ``[expect]`` table, shared by the claims tests."""

from __future__ import annotations

from pathlib import Path

RK4 = """
[method]
name = "RK4"
[tableau]
A = [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]]
b = ["1/6", "1/3", "1/3", "1/6"]
"""

MIDPOINT = """
[tableau]
A = [["1/2"]]
b = [1]
"""


def write(tmp_path: Path, text: str, expect: str) -> str:
    p = tmp_path / "t.toml"
    p.write_text(text + "\n[expect]\n" + expect + "\n", encoding="utf-8")
    return str(p)
