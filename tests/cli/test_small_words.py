"""Small things a maintainer notices: counts agree with their nouns, one vocabulary per
CSV column, ``@name`` suggestions include the names it is the start of, and every
command's --help lists the exit codes it can give."""

from __future__ import annotations

import csv
import importlib
import inspect
import io
import re
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

from rkcheck.numbers.formatting import counted


@pytest.mark.parametrize("n, noun, want", [(0, "error", "0 errors"), (1, "error", "1 error"), (2, "file", "2 files"),
                                           (1, "vertex", "1 vertex"), (12_345, "condition", "12,345 conditions")])
def test_counted_agrees(n, noun, want):
    assert counted(n, noun, "vertices" if noun == "vertex" else None) == want


def test_scan_and_verify_say_one_error_and_one_condition(capsys, tmp_path):
    (tmp_path / "bad.toml").write_text("[tableau]\nA = [[\"1/\"]]\nb = [1]\n", encoding="utf-8")
    (tmp_path / "euler.toml").write_text("[tableau]\nA = [[0]]\nb = [1]\n", encoding="utf-8")
    r = run_cli(capsys, "scan", str(tmp_path), "--jobs", "1", "--fail-on", "never")
    assert r.out.rstrip().splitlines()[-1].startswith("2 files: 1 ok, 0 failed, 1 error, 0 skipped")
    # explicit Euler to order 2: the one condition (the path with 3 vertices) fails
    r = run_cli(capsys, "verify", str(tmp_path / "euler.toml"), "--order", "2")
    assert "order ≤ 2: 1 condition," in r.out and r.out.rstrip().endswith("FAIL: 1 of 1 condition fails; energy order 1")
    r = run_cli(capsys, "verify", "@implicit-midpoint", "--order", "2", "--degree", "2", "--fail-on", "conditions")
    assert r.out.rstrip().endswith("1 condition checked  (OK: all 9 claims met)")


def _symplectic(A, b) -> bool:
    """BA + AᵀB − bbᵀ = 0 (B = diag b), by hand in fractions."""
    s = len(b)
    return all(b[i] * A[i][j] + b[j] * A[j][i] - b[i] * b[j] == 0 for i in range(s) for j in range(s))


def test_csv_columns_have_one_vocabulary_each(capsys, tmp_path):
    tableaux = {
        "midpoint": ([["1/2"]], ["1"]),
        "trapezoid": ([["0", "0"], ["1/2", "1/2"]], ["1/2", "1/2"]),
        "radau": ([["5/12", "-1/12"], ["3/4", "1/4"]], ["3/4", "1/4"]),
    }
    for name, (A, b) in tableaux.items():
        rows = ", ".join("[" + ", ".join(f'"{x}"' for x in row) + "]" for row in A)
        (tmp_path / f"{name}.toml").write_text(f"[tableau]\nA = [{rows}]\nb = [{', '.join(repr(x) for x in b)}]\n"
                                               .replace("'", '"'), encoding="utf-8")
    (tmp_path / "broken.toml").write_text("[tableau]\nA = [[\"(\"]]\nb = [1]\n", encoding="utf-8")
    r = run_cli(capsys, "scan", str(tmp_path), "--format", "csv", "--jobs", "1", "--degree", "2", "--order", "4")
    rows = {re.sub(r".*/|\.toml$", "", row["file"]): row for row in csv.DictReader(io.StringIO(r.out))}
    booleans = ("energy_order_all", "equals_avf", "claims_ok")
    verdicts = ("symplectic", "symmetric")
    for row in rows.values():
        assert all(row[c] in ("true", "false", "") for c in booleans), row
        assert all(row[c] in ("holds", "holds_to_digits", "fails", "") for c in verdicts), row
    assert all(rows["broken"][c] == "" for c in booleans + verdicts)  # not checked: nothing to say
    for name, (A, b) in tableaux.items():
        A_q = [[Fraction(x) for x in row] for row in A]
        want = "holds" if _symplectic(A_q, [Fraction(x) for x in b]) else "fails"
        assert rows[name]["symplectic"] == want, name


def test_a_name_suggests_every_shipped_name_it_starts():
    from rkcheck import UnknownMethodError, load

    gauss = sorted(p.stem for p in (TABLEAUX / "collocation").glob("gauss-*.toml"))
    assert len(gauss) >= 2
    with pytest.raises(UnknownMethodError) as err:
        load("@gauss")
    suggested = re.findall(r"@([\w-]+)", str(err.value).split("did you mean", 1)[1])
    assert sorted(suggested) == gauss


def _commands():
    from rkcheck.cli.main import COMMANDS

    return list(COMMANDS.items())


@pytest.mark.parametrize("name, module", _commands())
def test_every_help_lists_the_exit_codes_it_can_give(capsys, name, module):
    r = run_cli(capsys, name, "--help")
    assert r.code == 0
    codes = r.out.split("Exit codes:", 1)[1]
    listed = [int(m) for m in re.findall(r"^\s+(\d+)\s+\S", codes, re.M)]
    # exit 1 exactly for the commands whose code can exit with EXIT_FAIL
    source = inspect.getsource(getattr(importlib.import_module(module), name).callback)
    assert listed == ([0, 1] if "EXIT_FAIL" in source else [0]) + [2, 3, 130]
    assert "Exit codes:" in run_cli(capsys, "--help").out
