"""Constants whose names are keywords or names the written code uses itself are renamed
in the Python and Julia a tableau is written as, so the code runs and means the tableau."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from support.clirun import run_cli

KEYWORDS = """[constants]
None = "1/2"
import = "1/3"
Fraction = "2"
A = "1/5"
end = "3"
None_ = "7"
[tableau]
A = [["None", "A"], ["end", "0"]]
b = ["import*Fraction", "None_"]
"""


def test_written_python_runs_and_has_the_tableaus_values(tmp_path, capsys):
    path = tmp_path / "kw.toml"
    path.write_text(KEYWORDS, encoding="utf-8")
    r = run_cli(capsys, "show", str(path), "--format", "python")
    assert r.code == 0, r.err
    scope: dict = {}
    exec(compile(r.out, "kw.py", "exec"), scope)  # the test's own output, written by rkcheck
    assert scope["A"] == [[F(1, 2), F(1, 5)], [F(3), F(0)]]
    assert scope["b"] == [F(2, 3), F(7)] and scope["c"] == [F(7, 10), F(3)]


@pytest.mark.parametrize("name, renamed", [("end", "end_"), ("A", "A_"), ("big", "big_")])
def test_written_julia_renames_keywords_and_its_own_names(tmp_path, capsys, name, renamed):
    path = tmp_path / "kw.toml"
    # a nested radical is written as it stands, so the constant keeps its (renamed) name
    path.write_text(f'[constants]\n{name} = "1/3 + sqrt(2 + sqrt(3))"\n[tableau]\nA = [["{name}"]]\nb = ["1"]\n',
                    encoding="utf-8")
    r = run_cli(capsys, "show", str(path), "--format", "julia")
    assert r.code == 0, r.err
    lines = r.out.splitlines()
    assert f"{renamed} = big(1)//3 + sqrt(big(2) + sqrt(big(3)))" in lines and f"A = [{renamed}]" in lines
