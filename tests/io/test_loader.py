"""Tableau files: formats, validation errors (one line, exit 2, the place), warnings."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import pytest
from support.clirun import run_cli, run_subprocess
from support.paths import REPO as ROOT  # noqa: E402

from rkcheck.errors import UserError
from rkcheck.evaluation.values import TableauValues
from rkcheck.io.loader import load, loads
from rkcheck.numbers.reading import Reading

TABLEAUX = ROOT / "tableaux"

GAUSS2_TOML = """
[method]
name = "Gauss–Legendre, 2 stages"
description = "test"
references = ["doi:10.1090/S0025-5718-1964-0159424-9"]
[constants]
r3 = "sqrt(3)"
[tableau]
A = [["1/4", "1/4 - r3/6"], ["1/4 + r3/6", "1/4"]]
b = ["1/2", "1/2"]
c = ["1/2 - r3/6", "1/2 + r3/6"]
[check]
degree = 4
order = 6
"""

GAUSS2_JSON = {
    "method": {"name": "Gauss–Legendre, 2 stages", "description": "test",
               "references": ["doi:10.1090/S0025-5718-1964-0159424-9"]},
    "constants": {"r3": "sqrt(3)"},
    "tableau": {
        "A": [["1/4", "1/4 - r3/6"], ["1/4 + r3/6", "1/4"]],
        "b": ["1/2", "1/2"],
        "c": ["1/2 - r3/6", "1/2 + r3/6"],
    },
    "check": {"degree": 4, "order": 6},
}


def write(tmp_path: Path, name: str, text: str) -> str:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return str(p)


def test_toml_and_json_load_to_identical_values(tmp_path):
    t = load(write(tmp_path, "g.toml", GAUSS2_TOML))
    j = load(write(tmp_path, "g.json", json.dumps(GAUSS2_JSON)))
    assert (t.name, t.info.description, t.info.references, t.info.check) == (j.name, j.info.description, j.info.references, j.info.check)
    for et, ej in zip(t.entries(), j.entries()):
        assert et.text == ej.text and et.exact == ej.exact
        assert et.enclosure(300) == ej.enclosure(300)
    assert t.info.check == {"degree": 4, "order": 6}


def test_bare_toml_float_keeps_its_digits_and_warns(tmp_path):
    text = '[tableau]\nA = [[0.21132486540518711774542560974902127]]\nb = [1]\n'
    tab = load(write(tmp_path, "f.toml", text))
    e = tab.A[0][0]
    assert e.exact == Fraction(21132486540518711774542560974902127, 10**35)  # not a binary64 double
    assert e.rounded_digits == 35
    assert any("1 entry is a bare float (0.2113248654" in w for w in tab.info.warnings)


@pytest.mark.parametrize("table", ['A = "tau"\nb = 1.0', 'A = 0.5', 'M = [[1.0]]', 'M = [["1", 0.5], [0.5, "2"]]'])
def test_bare_floats_in_a_kernel_warn_as_in_a_tableau(tmp_path, table):
    method = load(write(tmp_path, "k.toml", f"[continuous]\n{table}\n"))
    floats = table.count(".")
    word = "1 entry is a bare float" if floats == 1 else f"{floats} entries are bare floats"
    assert any(w.startswith(word) for w in method.info.warnings), method.info.warnings
    quiet = load(write(tmp_path, "q.toml", '[continuous]\nA = "tau"\nb = 1\n'))  # a bare integer is exact
    assert not any("bare float" in w for w in quiet.info.warnings)


def test_bare_json_float_keeps_its_digits(tmp_path):
    text = '{"tableau": {"A": [[0.1]], "b": [1.0000000000000000000001]}}'
    tab = load(write(tmp_path, "f.json", text))
    assert tab.A[0][0].exact == Fraction(1, 10)  # 0.1 exactly, not 0.1000000000000000055511...
    assert tab.b[0].exact == 1 + Fraction(1, 10**22)


def test_fifty_digit_decimal_keeps_fifty_digits():
    tab = load(str(TABLEAUX / "avf" / "avf-gauss-2-decimal50.toml"))
    e = tab.c[0]
    assert e.exact == Fraction(21132486540518711774542560974902127217619912436494, 10**50)
    assert e.rounded_digits == 50


def consistency_warnings(tab, decimals):
    return TableauValues(tab, Reading(decimals)).consistency_warnings()


def test_warnings_for_c_and_sum_b_are_not_errors(tmp_path):
    text = '[tableau]\nA = [["1/3", 0], [0, "1/3"]]\nb = ["1/2", "1/3"]\nc = ["1/3", "1/2"]\n'
    tab = load(write(tmp_path, "w.toml", text))
    ws = consistency_warnings(tab, "rounded")
    assert any("c differs" in w and "c[2]" in w and "c[1]" not in w for w in ws)
    assert any("Σb" in w and "inconsistent" in w for w in ws)


def test_c_within_decimal_rounding_is_not_a_warning():
    tab = load(str(TABLEAUX / "avf" / "avf-gauss-2-decimal16.toml"))
    assert consistency_warnings(tab, "rounded") == []
    assert any("c differs" in w for w in consistency_warnings(tab, "exact"))


# --------------------------------------------------------------- error classes

VALID_ROWS = '[tableau]\nA = [["1/4", "1/4"], ["1/4", "1/4"]]\nb = ["1/2", "1/2"]\n'

ERRORS = {
    "toml syntax": ('[tableau]\nA = [["1"]\nb = ["1"]\n', "t.toml", "line 3, column 1: TOML syntax error"),
    "json syntax": ('{"tableau": {"A": [["1"]],\n "b": ["1"],}}', "t.json", "line 2, column 13: JSON syntax error"),
    "missing tableau": ('[method]\nname = "x"\n', "t.toml", "missing [tableau] table"),
    "missing A": ('[tableau]\nb = ["1"]\n', "t.toml", "tableau: missing A"),
    "missing b": ('[tableau]\nA = [["1"]]\n', "t.toml", "tableau: missing b"),
    "empty": ('[tableau]\nA = []\nb = []\n', "t.toml", "A: the tableau is empty"),
    "empty rows": ('[tableau]\nA = [[]]\nb = []\n', "t.toml", "A: the tableau is empty (A's rows have no entries)"),
    "table in another case": ('[Parameters]\np = "free"\n[tableau]\nA = [["p"]]\nb = ["1"]\n', "t.toml",
                              "Parameters: unknown table: table names are case-sensitive, and this one would be "
                              "ignored; write [parameters]"),
    "short-form key in another case": ('{"A": [["1/2"]], "B": ["1"]}', "t.json",
                                       "B: unknown key: keys are case-sensitive, and this one would be ignored; write b"),
    "empty claim list": (VALID_ROWS + '[expect]\nenergy_order = []\n', "t.toml",
                         "expect.energy_order: an empty list claims nothing"),
    "null c": ('{"A": [["1/2"]], "b": ["1"], "c": null}', "t.json", "c: expected a list of 1 entries, got null"),
    "one-cell csv": ("1/2\n", "t.csv", "1 row of 1 cell: expected a Butcher array"),
    "huge exponent": ('[tableau]\nA = [["2^1000^1000"]]\nb = [1]\n', "t.toml",
                      "A[1][1]: exponent 1e3000 at column 2 is out of range (|n| <= 1000)"),
    "non-square": ('[tableau]\nA = [["1", "2"], ["3"]]\nb = ["1", "0"]\n', "t.toml",
                   "A[2]: row has 1 entries, expected 2 (A must be square)"),
    "b length": ('[tableau]\nA = [["1", "2"], ["3", "4"]]\nb = ["1"]\n', "t.toml",
                 "b: has 1 entries, expected 2 (one per stage)"),
    "c length": ('[tableau]\nA = [["1"]]\nb = ["1"]\nc = ["1", "2"]\n', "t.toml",
                 "c: has 2 entries, expected 1 (one per stage)"),
    "unparsable entry": ('[tableau]\nA = [["1", "2", "3"], ["1", "2", "3"], ["1", "2", "1/4 + )"]]\nb = [1, 0, 0]\n',
                         "t.toml", "A[3][3]: unexpected ')' at column 7"),
    "unclosed sqrt": ('[tableau]\nA = [["1", "2"], ["1", "sqrt(3"]]\nb = [1, 0]\n', "t.toml",
                      "A[2][2]: unexpected end of expression at column 7"),
    "unknown constant": ('[constants]\nr3 = "sqrt(3)"\n[tableau]\nA = [["r5"]]\nb = [1]\n', "t.toml",
                         "A[1][1]: unknown constant 'r5' at column 1"),
    "division by zero": ('[tableau]\nA = [["1/(1-1)"]]\nb = [1]\n', "t.toml", "A[1][1]: division by zero at column 2"),
    "sqrt negative": ('[tableau]\nA = [["0"]]\nb = ["sqrt(1-2)"]\n', "t.toml", "b[1]: square root of a negative number"),
    "sqrt negative constant": ('[constants]\nq = "sqrt(-3)"\n[tableau]\nA = [["q"]]\nb = [1]\n', "t.toml",
                               "constants.q: square root of a negative number"),
    "deep nesting": ('[tableau]\nA = [["' + "(" * 150 + "1" + ")" * 150 + '"]]\nb = [1]\n', "t.toml",
                     "A[1][1]: parentheses nested deeper than 100 at column 101"),
    "entry too long": ('[tableau]\nA = [["' + "1" * 30_000 + '"]]\nb = [1]\n', "t.toml",
                       "A[1][1]: entry too long (30,000 characters; the limit is 20,000)"),
    "boolean entry": ('[tableau]\nA = [[true]]\nb = [1]\n', "t.toml", "A[1][1]: expected a number or a string, got a boolean"),
    "nan entry": ('[tableau]\nA = [[nan]]\nb = [1]\n', "t.toml", "A[1][1]: nan is not a finite number"),
    "row not a list": ('[tableau]\nA = ["1"]\nb = [1]\n', "t.toml", "A[1]: expected a row (a list), got a string"),
    "bad check": (VALID_ROWS + '[check]\ndegree = -1\n', "t.toml", "check.degree: expected a positive integer or 'none'"),
    "unknown check key": (VALID_ROWS + '[check]\nordr = 3\n', "t.toml", "check.ordr: unknown key"),
    "constant cycle": ('[constants]\na = "b"\nb = "a"\n' + VALID_ROWS, "t.toml", "constants.a: constants refer to each other in a cycle"),
    # each of [tableau], [family], [continuous] defines the whole method: two are refused
    "tableau and family": (VALID_ROWS + '[family]\nname = "gauss"\ns = 2\n', "t.toml",
                           "give one of [tableau], [family], [continuous], not [tableau] and [family]"),
    "family and continuous": ('[family]\nname = "gauss"\ns = 2\n[continuous]\nA = "tau"\n', "t.toml",
                              "give one of [tableau], [family], [continuous], not [family] and [continuous]"),
    "tableau and continuous": (VALID_ROWS + '[continuous]\nA = "tau"\n', "t.toml",
                               "give one of [tableau], [family], [continuous], not [tableau] and [continuous]"),
    "family with parameters": ('[parameters]\nx = "free"\n[family]\nname = "gauss"\ns = 2\n', "t.toml",
                               "a named [family] is one method: it takes no free [parameters]"),
}


@pytest.mark.parametrize("text, name, message", list(ERRORS.values()), ids=list(ERRORS))
def test_each_error_class_is_one_line_with_the_place_and_exit_2(tmp_path, capsys, text, name, message):
    path = write(tmp_path, name, text)
    r = run_cli(capsys, "show", path)
    assert r.code == 2
    lines = r.err.strip().splitlines()
    assert len(lines) == 1, r.err
    assert lines[0] == f"rkcheck: error: {path}: {message}" or lines[0].startswith(f"rkcheck: error: {path}: {message}"), lines[0]
    assert "Traceback" not in r.err and r.out == ""


def test_more_than_64_stages_is_refused_unless_allowed(tmp_path, capsys):
    s = 65
    rows = [[0] * s for _ in range(s)]
    path = write(tmp_path, "big.json", json.dumps({"tableau": {"A": rows, "b": [1] + [0] * (s - 1)}}))
    r = run_cli(capsys, "show", path)
    assert r.code == 2
    assert f"{path}: A: 65 stages exceeds the limit of 64 (raise it with --max-stages, or max_stages= in Python)" in r.err
    r = run_cli(capsys, "show", path, "--max-stages", "70")
    assert r.code == 0


def test_unreadable_files(tmp_path, capsys):
    r = run_cli(capsys, "show", str(tmp_path / "nope.toml"))
    assert r.code == 2 and r.err.strip() == f"rkcheck: error: {tmp_path / 'nope.toml'}: no such file"
    r = run_cli(capsys, "show", str(tmp_path))
    assert r.code == 2 and "is a directory" in r.err
    bad = tmp_path / "latin1.toml"
    bad.write_bytes(b"[method]\nname = \"\xe9\"\n")
    r = run_cli(capsys, "show", str(bad))
    assert r.code == 2 and "not UTF-8 text" in r.err


def test_bad_option_is_one_line_exit_2(capsys):
    r = run_cli(capsys, "verify", str(TABLEAUX / "explicit" / "rk4.toml"), "--order", "0")
    assert r.code == 2 and len(r.err.strip().splitlines()) == 1 and "--order" in r.err
    r = run_cli(capsys, "verify", str(TABLEAUX / "explicit" / "rk4.toml"), "--degree", "x")
    assert r.code == 2 and "not a degree" in r.err
    r = run_cli(capsys, "verify", str(TABLEAUX / "explicit" / "rk4.toml"), "--frobnicate")
    assert r.code == 2 and "No such option" in r.err


def test_end_to_end_errors_have_no_traceback(tmp_path):
    path = write(tmp_path, "t.toml", ERRORS["unparsable entry"][0])
    r = run_subprocess("verify", path)
    assert r.code == 2
    assert r.err.strip() == f"rkcheck: error: {path}: A[3][3]: unexpected ')' at column 7"


def test_stdin_is_read_with_dash():
    r = run_subprocess("show", "-", "--format", "json", stdin=GAUSS2_TOML)
    assert r.code == 0
    doc = json.loads(r.out)
    assert doc["tableau"]["A"][0][1]["text"] == "1/4 - r3/6"


def test_loads_detects_json_without_suffix():
    tab = loads(json.dumps(GAUSS2_JSON), source="-")
    assert tab.stages == 2 and tab.uses_sqrt


def test_user_error_str_orders_source_place_message():
    err = UserError("bad", "A[1][2]").located(source="f.toml")
    assert str(err) == "f.toml: A[1][2]: bad"


def test_internal_errors_are_one_line_with_exit_3(capsys, monkeypatch):
    import rkcheck.energy.check

    def boom(*args, **kwargs):
        raise RuntimeError("simulated bug")

    monkeypatch.setattr(rkcheck.energy.check, "check", boom)
    monkeypatch.setattr(rkcheck.energy.check.CheckRunner, "__call__", lambda self, t, o: boom())
    r = run_cli(capsys, "verify", str(TABLEAUX / "explicit" / "rk4.toml"))
    assert r.code == 3
    assert r.err.strip().startswith("rkcheck: internal error: RuntimeError: simulated bug")
    assert "Traceback" not in r.err and len(r.err.strip().splitlines()) == 1


def test_memory_error_is_a_limit_not_a_bug(capsys, monkeypatch):
    import rkcheck.energy.check

    def exhausted(*args, **kwargs):
        raise MemoryError()

    monkeypatch.setattr(rkcheck.energy.check.CheckRunner, "__call__", lambda self, t, o: exhausted())
    r = run_cli(capsys, "verify", str(TABLEAUX / "explicit" / "rk4.toml"))
    assert r.code == 2
    assert "out of memory" in r.err and "internal error" not in r.err
    assert "Traceback" not in r.err and len(r.err.strip().splitlines()) == 1


def test_a_short_form_beside_a_tableau_table_is_named_as_ignored(tmp_path):
    tab = load(write(tmp_path, "t.toml", 'A = [["1"]]\nb = ["1"]\n' + VALID_ROWS))
    assert tab.A[0][0].exact == Fraction(1, 4)  # the [tableau] table's
    assert [w for w in tab.info.warnings if "ignored" in w] == [
        "A, b at the top level ignored: the method is given by [tableau]"]


@pytest.mark.parametrize("fmt", ["json", "toml"])
def test_bare_integers_beyond_pythons_text_limit_load_in_a_library(fmt):
    # Python converts at most 4 300 digits at once by default; the CLI raises that limit
    # for itself, a library must neither need it raised nor change it
    import sys

    ones, minus = "1" * 5000, "-" + "7" * 6000
    text = (json.dumps({"A": [[0]], "b": [1]}).replace("[[0]]", f"[[{ones}]]").replace("[1]", f"[{minus}]")
            if fmt == "json" else f"[tableau]\nA = [[{ones}]]\nb = [{minus}]\n")
    before = sys.get_int_max_str_digits()
    tab = loads(text, fmt=fmt)
    assert sys.get_int_max_str_digits() == before
    assert tab.A[0][0].exact == (10**5000 - 1) // 9 and tab.b[0].exact == -7 * (10**6000 - 1) // 9


@pytest.mark.parametrize("fmt", ["json", "toml"])
def test_a_bare_integer_longer_than_any_value_is_one_line(fmt):
    digits = "9" * 70_000  # 232 535 bits: past MAX_BITS = 200 000, refused before it is converted
    text = f'{{"A": [[{digits}]], "b": [1]}}' if fmt == "json" else f"[tableau]\nA = [[{digits}]]\nb = [1]\n"
    with pytest.raises(UserError) as err:
        loads(text, fmt=fmt)
    assert "MAX_BITS" in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("text, place, twin", [
    ('[tableau]\nA = [["0", "0"], ["1", "0"]]\nb = ["1/2", "1/2"]\nC = ["0", "1/2"]\n', "tableau.C", "c"),
    ('[continuous]\nA = "sigma"\nB = "2*tau"\n', "continuous.B", "b"),
    ('[continuous]\na = "tau"\n', "continuous.a", "A"),
])
def test_a_known_key_in_another_case_is_refused_not_ignored(tmp_path, capsys, text, place, twin):
    # ignored, B = "2*tau" would leave B = 1 and check another method (exit 0 or 1 on it)
    path = tmp_path / "m.toml"
    path.write_text(text, encoding="utf-8")
    r = run_cli(capsys, "verify", str(path), "--order", "3")
    assert r.code == 2 and r.err.strip() == (f"rkcheck: error: {path}: {place}: unknown key: keys are case-sensitive, "
                                             f"and this one would be ignored; write {twin}")
    if twin != "A":  # any other unknown key is only a warning
        path.write_text(text.replace(place.split(".")[1] + " =", "note ="), encoding="utf-8")
        assert f"unknown key {place.split('.')[0]}.note ignored" in run_cli(capsys, "verify", str(path), "--order", "3").out
