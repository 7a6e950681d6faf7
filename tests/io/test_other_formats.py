"""Other ways in: the top-level A/b/c short form, CSV/TSV Butcher arrays, nodepy text
files, and ``@name`` for the shipped library.  Each is compared with the same tableau
written out by hand in the long TOML form (exact rationals compared exactly)."""

from __future__ import annotations

import json
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

from rkcheck.errors import RkcheckError, TableauError, UnknownMethodError, UserError
from rkcheck.io.loader import load, loads

RK4_LONG = """
[tableau]
A = [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]]
b = ["1/6", "1/3", "1/3", "1/6"]
c = [0, "1/2", "1/2", 1]
"""
RK4_A = [[0, 0, 0, 0], [Fraction(1, 2), 0, 0, 0], [0, Fraction(1, 2), 0, 0], [0, 0, 1, 0]]
RK4_B = [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)]


def exact(tab):
    return [[e.exact for e in row] for row in tab.A], [e.exact for e in tab.b], \
        None if tab.c is None else [e.exact for e in tab.c]


def test_long_form_is_what_we_compare_with():
    A, b, c = exact(loads(RK4_LONG, "rk4.toml"))
    assert A == RK4_A and b == RK4_B and c == [0, Fraction(1, 2), Fraction(1, 2), 1]


def test_short_form_json_and_toml_equal_the_long_form():
    long = exact(loads(RK4_LONG, "rk4.toml"))
    short_json = json.dumps({"A": [["0", "0", "0", "0"], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]],
                             "b": ["1/6", "1/3", "1/3", "1/6"], "c": [0, "1/2", "1/2", 1]})
    short_toml = RK4_LONG.replace("[tableau]", "")
    for text, name in ((short_json, "rk4.json"), (short_toml, "rk4.toml")):
        tab = loads(text, name)
        assert exact(tab) == long
        assert not tab.info.warnings, tab.info.warnings  # no "unknown table [A]" noise


def test_short_form_keeps_the_other_tables():
    tab = loads('{"method": {"name": "m"}, "A": [["1/2"]], "b": [1], "expect": {"classical_order": 2}}', "x.json")
    assert tab.name == "m" and [c.kind for c in tab.info.claims] == ["classical_order"]


def test_short_form_errors_keep_their_places():
    with pytest.raises(UserError) as err:
        loads('{"A": [["1/2", "x("]], "b": [1]}', "bad.json")
    assert str(err.value).startswith("bad.json: A[1]")


def test_no_tableau_shows_the_smallest_valid_file_and_that_file_loads():
    with pytest.raises(UserError) as err:
        loads('[method]\nname = "x"\n', "t.toml")
    msg = str(err.value)
    assert "missing [tableau] table" in msg and "\n" not in msg
    # the two files the message shows are themselves valid
    assert exact(loads('[tableau]\nA = [["1/2"]]\nb = [1]\n', "s.toml"))[0] == [[Fraction(1, 2)]]
    assert exact(loads('{"A": [["1/2"]], "b": [1]}', "s.json"))[1] == [1]


# ------------------------------------------------------------------ CSV / TSV


def test_csv_butcher_array(tmp_path):
    f = tmp_path / "rk4.csv"
    f.write_text("0,0,0,0,0\n1/2,1/2,0,0,0\n1/2,0,1/2,0,0\n1,0,0,1,0\n,1/6,1/3,1/3,1/6\n")
    assert exact(load(str(f))) == exact(loads(RK4_LONG, "rk4.toml"))
    assert load(str(f)).name == "rk4"


def test_tsv_geometric_integrators_layout(tmp_path):
    # writeTableauToFile: "# order stages type", then rows c_i, b_i, a_i1 … a_is
    f = tmp_path / "heun.tsv"
    f.write_text("# 2 2 Float64\n0.0\t0.5\t0.0\t0.0\n1.0\t0.5\t1.0\t0.0\n")
    A, b, c = exact(load(str(f)))
    assert A == [[0, 0], [1, 0]] and b == [Fraction(1, 2)] * 2 and c == [0, 1]


def test_space_separated_with_expressions(tmp_path):
    f = tmp_path / "gauss.csv"
    f.write_text("1/2-sqrt(3)/6; 1/4; 1/4-sqrt(3)/6\n1/2+sqrt(3)/6; 1/4+sqrt(3)/6; 1/4\n; 1/2; 1/2\n")
    tab = load(str(f))
    assert tab.uses_sqrt and tab.stages == 2


@pytest.mark.parametrize("text, place", [
    ("0,0\n1,0,0\n,1,1\n", "line 2"),  # ragged
    ("0,0,0\n1,1,0\n", None),  # 2 rows of 3: no layout
    ("0,0,0\n1,,0\n,1/2,1/2\n", "A[2][1]"),  # empty cell
    ("0,0,0\n1,x(,0\n,1/2,1/2\n", "A[2][1]"),  # bad entry: the loader's own message
])
def test_csv_errors_are_one_line_with_place(tmp_path, text, place):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    with pytest.raises(UserError) as err:
        load(str(f))
    msg = str(err.value)
    assert msg.startswith(f"{f}: ") and "\n" not in msg
    if place:
        assert place in msg


# ------------------------------------------------------------------ nodepy text


NODEPY_HEUN = """
   k              c[k]
   0    0.0
   1    1.0

   k   j          A[k,j]
   1   0    1.0

   k              b[k]
   0    0.5
   1    0.5

   k              bhat[k]
   0    1.0
"""


def test_nodepy_text_file(tmp_path):
    f = tmp_path / "heun.txt"
    f.write_text(NODEPY_HEUN)
    A, b, c = exact(load(str(f)))
    assert A == [[0, 0], [1, 0]] and b == [Fraction(1, 2)] * 2 and c == [0, 1]


def test_nodepy_text_feagin_style_long_decimals_are_rounded_decimals(tmp_path):
    digits = "0.200000000000000000000000000000000000000000000000000000000000"
    f = tmp_path / "x.txt"
    f.write_text(f"k c[k]\n0 0\n1 {digits}\nk j A[k,j]\n1 0 {digits}\nk b[k]\n0 0\n1 1\n")
    tab = load(str(f))
    assert tab.A[1][0].exact == Fraction(1, 5) and tab.A[1][0].is_rounded  # definitions §5


def test_nodepy_bad_line(tmp_path):
    f = tmp_path / "x.txt"
    f.write_text("k b[k]\n0 x y z\n")
    with pytest.raises(TableauError) as err:
        load(str(f))
    assert "line 2" in str(err.value)


def test_nodepy_entry_given_twice_is_refused(tmp_path):
    # as a duplicate key of a JSON file: the second value silently won
    f = tmp_path / "x.txt"
    f.write_text("k j A[k,j]\n0 0 0.5\n0 0 0.7\nk b[k]\n0 1\n")
    with pytest.raises(TableauError) as err:
        load(str(f))
    assert "line 3" in str(err.value) and "A[0,0] is given twice (first as '0.5')" in str(err.value)


# ------------------------------------------------------------------ @name


def test_at_name_loads_the_shipped_file_under_any_spelling():
    want = exact(load(str(TABLEAUX / "collocation" / "gauss-3.toml")))
    for name in ("@gauss-3", "@gauss3", "@Gauss_3", "@collocation/gauss-3"):
        tab = load(name)
        assert tab.info.source == "@collocation/gauss-3"
        assert [[e.text for e in row] for row in tab.A] == [[e.text for e in row] for row in
                                                             load(str(TABLEAUX / "collocation/gauss-3.toml")).A]
        assert exact(tab) == want


def test_at_name_falls_back_to_the_classics():
    tab = load("@sdirk2")
    assert tab.info.source == "@sdirk2" and tab.stages == 2 and tab.info.claims


def test_unknown_name_suggests_and_is_a_user_error():
    with pytest.raises(UnknownMethodError) as err:
        load("@gaus3")
    assert isinstance(err.value, UserError) and isinstance(err.value, RkcheckError)
    assert "@gauss-3" in str(err.value)


def test_cli_verify_at_name(capsys):
    run = run_cli(capsys, "verify", "@heun", "--order", "4", "-q")
    assert run.code == 0, run.err
    run = run_cli(capsys, "verify", "@nope-nope")
    assert run.code == 2 and run.err.count("\n") == 1 and "no tableau called @nope-nope" in run.err


def test_catalog_without_paths_lists_the_shipped_library(capsys, tmp_path, monkeypatch):
    import shutil

    from rkcheck.io import library

    (tmp_path / "explicit").mkdir()
    shutil.copy(TABLEAUX / "explicit" / "heun.toml", tmp_path / "explicit" / "heun.toml")
    monkeypatch.setattr(library, "library_root", lambda: tmp_path)
    run = run_cli(capsys, "catalog", "--order", "3", "--degrees", "2")
    assert run.code == 0, run.err
    assert "`explicit/heun.toml`" in run.out and "Generated by `rkcheck catalog --degrees 2 --order 3`" in run.out


def test_input_format_overrides_the_suffix(capsys, tmp_path):
    f = tmp_path / "heun.dat"
    f.write_text("0,0,0\n1,1,0\n,1/2,1/2\n")
    run = run_cli(capsys, "show", str(f), "--input-format", "csv", "--format", "toml")
    assert run.code == 0, run.err
    assert [[e.exact for e in r] for r in loads(run.out, "x.toml").A] == [[0, 0], [1, 0]]
    run = run_cli(capsys, "verify", str(f), "--input-format", "csv", "--order", "3", "-q")
    assert run.code == 1 and "energy order 2" in run.out  # Heun: Σ b c² = 1/2 ≠ 1/3 fails at 4 vertices
    run = run_cli(capsys, "verify", str(f))  # guessed as TOML: a one-line syntax error
    assert run.code == 2 and run.err.count("\n") == 1
