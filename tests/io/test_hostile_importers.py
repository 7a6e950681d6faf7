"""Importers (nodepy text, CSV) under hostile or merely spreadsheet-made input: bounded
before allocating, one-line errors, and what spreadsheets write is read."""

from __future__ import annotations

import pytest
from support.clirun import run_cli, run_subprocess
from support.guards import hang_guard

from rkcheck.errors import RkcheckError
from rkcheck.io.loader import loads


def test_a_nodepy_stage_index_beyond_max_stages_is_refused_before_allocating(tmp_path):
    # index 99999 would be a 100 000 × 100 000 matrix; run as a process with its own timeout
    path = tmp_path / "m.txt"
    path.write_text("Feagin\nA[k,j]\n99999 0 1\nb[k]\n0 1\n", encoding="utf-8")
    r = run_subprocess("verify", str(path), timeout=30)
    assert r.code == 2, r.err
    assert r.err == (f"rkcheck: error: {path}: line 3: stage index 99999 means 100000 stages, which exceeds "
                     "the limit of 64 (raise it with --max-stages, or max_stages= in Python)\n")


def test_max_stages_itself_is_bounded(capsys, tmp_path):
    r = run_cli(capsys, "verify", "@rk4", "--max-stages", "100000")
    assert r.code == 2 and "1<=x<=1000" in r.err, r.err
    with pytest.raises(RkcheckError, match="max_stages: expected an integer from 1 to 1000"):
        loads("A[k,j]\n0 0 0\nb[k]\n0 1\n", "m.txt", max_stages=10**6)


@pytest.mark.parametrize("line", ["\u00b2 0 1", "1.5 0 1", "-1 0 1", "0 0", "0 0 1 2", "x 0 1", "\u0661 0 1"])
def test_malformed_nodepy_lines_are_one_line_errors(capsys, tmp_path, line):
    path = tmp_path / "m.txt"
    path.write_text(f"A[k,j]\n{line}\nb[k]\n0 1\n", encoding="utf-8")
    with hang_guard(20):
        r = run_cli(capsys, "verify", str(path), "--order", "2")
    assert r.code == 2 and r.err == (f"rkcheck: error: {path}: line 2: expected 2 index(es) and a value in "
                                     "section A\n"), r.err


# A = [[0, 0], [2/3, 0]], b = [1/4, 3/4]: Ralston's second-order method, as a spreadsheet
# saves it (quotes around every cell, a decimal comma inside one, a BOM, CRLF)
RALSTON = (b'\xef\xbb\xbf"0";"0";"0"\r\n"2/3";"2/3";"0"\r\n"";"0,25";"3/4"\r\n')


def test_a_spreadsheet_csv_with_quotes_and_a_bom_is_read(tmp_path):
    path = tmp_path / "ralston.csv"
    path.write_bytes(RALSTON.replace(b'"0,25"', b'"1/4"'))
    tab = loads(path.read_bytes().decode("utf-8"), str(path))
    assert [[str(e.exact) for e in row] for row in tab.A] == [["0", "0"], ["2/3", "0"]]
    assert [str(e.exact) for e in tab.b] == ["1/4", "3/4"]


def test_a_quoted_cell_keeps_its_separator_inside(tmp_path, capsys):
    # "0,25" is one cell (a decimal comma, which rkcheck's grammar does not read): the
    # error names that cell instead of miscounting the row
    path = tmp_path / "ralston.csv"
    path.write_bytes(RALSTON)
    r = run_cli(capsys, "verify", str(path))
    assert r.code == 2 and r.err.startswith(f"rkcheck: error: {path}: b[1]: unexpected ','"), r.err


@pytest.mark.parametrize("suffix, text", [(".toml", '[tableau]\nA = [["1/2"]]\nb = [1]\n'),
                                          (".json", '{"A": [["1/2"]], "b": [1]}')])
def test_a_bom_before_toml_or_json_is_skipped(tmp_path, capsys, suffix, text):
    path = tmp_path / f"t{suffix}"
    path.write_bytes(b"\xef\xbb\xbf" + text.encode())
    r = run_cli(capsys, "show", str(path))
    assert r.code == 0 and "1 stage" in r.out, r.err
