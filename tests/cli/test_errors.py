"""Hostile files and environments end in one line naming file and place, exit 2, no
traceback."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from support.clirun import run_cli, run_subprocess
from support.guards import hang_guard
from support.paths import TABLEAUX


def one_line_exit_2(r, path: str, message: str) -> None:
    assert r.code == 2, r.err
    assert "Traceback" not in r.err
    lines = r.err.splitlines()
    assert len(lines) == 1, r.err
    assert lines[0].startswith(f"rkcheck: error: {path}: {message}"), lines[0]
    assert lines[0].isprintable()


def entry_file(tmp_path, entry: str) -> str:
    f = tmp_path / "e.json"
    f.write_text(json.dumps({"tableau": {"A": [[entry]], "b": [1]}}), encoding="utf-8")
    return str(f)


ENTRIES = {
    "pi": ("\u03c0", "A[1][1]: unexpected character '\u03c0' (U+03C0) at column 1"),
    "superscript": ("2\u00b2", "A[1][1]: unexpected character '\u00b2' (U+00B2) at column 2"),
    "accented": ("\u00e9", "A[1][1]: unexpected character '\u00e9' (U+00E9) at column 1"),
    "escape": ("1\x1b[2J", "A[1][1]: unexpected character '\\x1b' at column 2"),
    "surrogate": ("\ud800", "A[1][1]: unexpected character '\\ud800' (U+D800) at column 1"),
    "enormous exponent": ("2^99999999", "A[1][1]: exponent 99999999 at column 2 is out of range"),
    "enormous decimal exponent": ("1e99999999", "A[1][1]: exponent 99999999 of '1e99999999' is out of range"),
    "product of powers": ("*".join(["2^1000"] * 250), "A[1][1]: value at column"),
}


@pytest.mark.parametrize("entry, message", list(ENTRIES.values()), ids=list(ENTRIES))
def test_hostile_entries_reach_the_cli_as_one_line(tmp_path, capsys, entry, message):
    path = entry_file(tmp_path, entry)
    one_line_exit_2(run_cli(capsys, "verify", path, "--order", "3"), path, message)


def test_typographic_operators_verify_like_ascii(tmp_path, capsys):
    # 1/2 written with U+2212 and U+00D7: the implicit midpoint rule, whose energy
    # conditions for quadratic H hold exactly (it is symplectic)
    path = entry_file(tmp_path, "3/2 \u2212 2\u00d71/2")
    r = run_cli(capsys, "verify", path, "--degree", "2", "--order", "4")
    assert r.code == 0, r.err


def write(tmp_path, name: str, content: str | bytes) -> str:
    f = tmp_path / name
    if isinstance(content, bytes):
        f.write_bytes(content)
    else:
        f.write_text(content, encoding="utf-8")
    return str(f)


FILES = {
    "duplicate JSON key": ("d.json", '{"tableau": {"A": [["1/2"]], "b": [1], "b": [0]}}', "JSON: key 'b' is given twice"),
    "huge TOML integer": ("h.toml", "[tableau]\nA = [[" + "9" * 200_000 + "]]\nb = [1]\n", "TOML: "),
    "binary": ("b.toml", bytes(range(256)) * 4, "not UTF-8 text"),
    "NUL bytes": ("n.toml", b"[tableau]\x00\x00", "line 1, column 10: TOML syntax error"),
    "deep JSON": ("deep.json", "[" * 100_000 + "]" * 100_000, "nesting too deep"),
    "deep TOML": ("deep.toml", "a = " + "[" * 100_000 + "]" * 100_000 + "\n", "nesting too deep"),
    "top-level list": ("l.json", "[1, 2]", "the top level must be a table/object"),
    "NaN": ("nan.json", '{"tableau": {"A": [[NaN]], "b": [1]}}', "JSON: NaN is not a finite number"),
    "inf": ("inf.toml", "[tableau]\nA = [[inf]]\nb = [1]\n", "A[1][1]: inf is not a finite number"),
    "wrong shape": ("w.json", '{"tableau": {"A": {"x": 1}, "b": [1]}}', "A: expected a list of rows, got a table"),
    "tableau not a table": ("t.json", '{"tableau": [1]}', "tableau: [tableau] must be a table, not a list"),
}


@pytest.mark.parametrize("name, content, message", list(FILES.values()), ids=list(FILES))
def test_hostile_files_are_one_line_exit_2(tmp_path, capsys, name, content, message):
    path = write(tmp_path, name, content)
    one_line_exit_2(run_cli(capsys, "verify", path), path, message)


def test_control_characters_from_a_file_never_reach_the_terminal(tmp_path, capsys):
    doc = {"method": {"name": "\x1b[2J\ud800OK\nfake"}, "tableau\nx": 1, "tableau": {"A": [["1/2"]], "b": [1]}}
    path = write(tmp_path, "c.json", json.dumps(doc))
    r = run_cli(capsys, "verify", path, "--degree", "2", "--order", "3")
    assert r.code == 0, r.err
    assert "\x1b" not in r.out + r.err
    assert "\\x1b[2J\\ud800OK\\nfake" in r.out
    assert "unknown key tableau\\nx ignored" in r.out + r.err  # a key, its value no table


def test_directories_links_and_permissions(tmp_path, capsys):
    loop = tmp_path / "loop.toml"
    loop.symlink_to(loop)
    one_line_exit_2(run_cli(capsys, "verify", str(loop)), str(loop), "cannot read: Too many levels of symbolic links")
    dangling = tmp_path / "dangling.toml"
    dangling.symlink_to(tmp_path / "missing.toml")
    one_line_exit_2(run_cli(capsys, "verify", str(dangling)), str(dangling), "no such file")
    one_line_exit_2(run_cli(capsys, "verify", str(tmp_path)), str(tmp_path), "is a directory")


def test_io_errors_of_the_output_are_one_line_exit_2(tmp_path, capsys):
    path = str(TABLEAUX / "collocation" / "gauss-2.toml")
    missing = tmp_path / "no" / "such" / "dir" / "out.json"
    r = run_cli(capsys, "scan", path, "--jobs", "1", "--format", "json", "-o", str(missing))
    assert r.code == 2 and len(r.err.splitlines()) == 1 and "Traceback" not in r.err, r.err
    if not os.path.exists("/dev/full"):
        return
    for command in (["show", path, "--format", "json"], ["verify", path, "--order", "4"],
                    ["verify", path, "--order", "4", "--format", "json"]):
        with open("/dev/full", "w") as full:  # every write fails: the line names standard output
            proc = subprocess.run([sys.executable, "-m", "rkcheck", *command],
                                  stdout=full, stderr=subprocess.PIPE, text=True, timeout=60)
        assert proc.returncode == 2, (command, proc.stderr)
        assert proc.stderr == "rkcheck: error: standard output: No space left on device\n", (command, proc.stderr)


def test_residuals_longer_than_4300_digits_are_printed(tmp_path):
    # a 600-digit entry whose conditions leave long exact residuals: no ValueError from
    # Python's integer-string limit
    x = "0." + "1234567" * 90
    doc = {"tableau": {"A": [[x, "0"], ["1/3", x]], "b": ["1/2", "1/2"]}}
    path = write(tmp_path, "long.json", json.dumps(doc))
    r = run_subprocess("verify", path, "--decimals", "exact", "--order", "6", "--format", "json")
    assert r.code in (0, 1), r.err
    json.loads(r.out)


@pytest.mark.parametrize(
    "args, message",
    [
        (["new", "gauss", "-s", "64"], "Invalid value for '--stages' / '-s': 64 is not in the range 1<=x<=20"),
        (["new", "hbvm", "-k", "64", "-s", "2"], "Invalid value for '-k': 64 is not in the range 1<=x<=20"),
        (["perturb", str(TABLEAUX / "collocation" / "gauss-2.toml"), "--direction", "random", "--eps", "-1"],
         "--eps: every ε must be in (0, 1], got '-1'"),
        (["perturb", str(TABLEAUX / "collocation" / "gauss-2.toml"), "--direction", "random", "--eps", "1e300"],
         "--eps: every ε must be in (0, 1], got '1e300'"),
    ],
)
def test_command_options_out_of_range_are_one_line(capsys, args, message):
    r = run_cli(capsys, *args)
    assert r.code == 2 and len(r.err.splitlines()) == 1 and message in r.err, r.err


def test_family_stages_are_bounded_in_files_too(tmp_path, capsys):
    path = write(tmp_path, "f.toml", '[family]\nname = "gauss"\ns = 64\n')
    one_line_exit_2(run_cli(capsys, "verify", path), path, "family.s: at most 20, got 64")


def test_explain_names_indices_past_sixteen_vertices(capsys):
    # a path with 21 vertices, shown rooted at its centre: the root and 9 inner vertices on
    # each side get an index (the two ends are c_x factors): 19 indices, the 16 letters
    # then i17, i18, i19
    r = run_cli(capsys, "explain", ",".join(str(i) for i in range(1, 22)))
    assert r.code == 0, r.err
    assert "i19" in r.out and "i20" not in r.out


GUARDED = {
    "bench": ["bench", str(TABLEAUX / "explicit" / "rk4.toml"), "--order", "30"],
    "perturb": ["perturb", str(TABLEAUX / "explicit" / "rk4.toml"), "--direction", "random", "--order", "30"],
    "catalog": ["catalog", str(TABLEAUX / "explicit"), "--order", "30"],
    "scan": ["scan", str(TABLEAUX / "explicit"), "--order", "30", "--jobs", "1"],
}


@pytest.mark.parametrize("args", list(GUARDED.values()), ids=list(GUARDED))
def test_the_resource_guard_applies_to_every_command(capsys, args):
    # order 30 has 63 853 307 421 conditions (A000055 - A000081 summed to 31 vertices):
    # tens of terabytes, refused before any table is built
    with hang_guard(30):
        r = run_cli(capsys, *args)
    assert r.code == 2 and len(r.err.splitlines()) == 1, r.err
    assert r.err.startswith("rkcheck: error: order 30 needs about") and "63,853,307,421 conditions" in r.err


def test_a_file_asking_for_too_much_is_an_error_row_in_a_scan(tmp_path, capsys):
    folder = tmp_path / "in"
    folder.mkdir()
    (folder / "a-big.toml").write_text('[tableau]\nA = [["1/2"]]\nb = [1]\n[check]\norder = 30\n', encoding="utf-8")
    (folder / "b-ok.toml").write_text('[tableau]\nA = [["1/2"]]\nb = [1]\n', encoding="utf-8")
    for jobs in ("1", "2"):
        with hang_guard(60):
            r = run_cli(capsys, "scan", str(folder), "--jobs", jobs, "--format", "json", "--order", "4")
        doc = json.loads(r.out)
        assert [f["status"] for f in doc["files"]] == ["ok", "ok"]  # --order 4 overrides [check]
        r = run_cli(capsys, "scan", str(folder), "--jobs", jobs, "--format", "json")
        doc = json.loads(r.out)
        assert [f["status"] for f in doc["files"]] == ["error", "ok"], jobs
        assert "order 30 needs about" in doc["files"][0]["error"]


def test_a_required_order_left_out_is_clicks_usage_error(capsys):
    # `conditions` needs --order (click ≥ 8.3 stopped requiring an option whose default
    # is given as None: the command then ran and failed on "got None")
    r = run_cli(capsys, "conditions", "--degree", "3")
    assert r.code == 2 and "Missing option '--order'" in r.err and r.err.count("\n") == 1, r.err


@pytest.mark.parametrize("args, message", [
    (["new", "rk4", "-s", "3"], "rk4 is a classical method (written exactly as published): -s does not apply"),
    (["new", "euler", "--zeta", "1", "--beta", "2"], "--zeta, --beta do not apply"),
    (["new", "kernel", "--beta", "x"], "--beta: unknown constant 'x'"),
    (["new", "hbvm", "-k", "2", "-s", "3"], "-k: expected an integer >= 3, got 2"),
    (["catalog", "tableaux/avf", "--degrees", "0"], "--degrees: '0' is not a degree"),
    (["catalog", "tableaux/avf", "--degrees", "2,2"], "--degrees: a degree is given twice"),
])
def test_new_and_catalog_options_are_refused_by_their_own_names(capsys, args, message):
    # an option that does not apply is refused, not ignored; an error names the option
    # the user typed, not the [family] key behind it
    r = run_cli(capsys, *args)
    assert r.code == 2 and r.err.count("\n") == 1 and message in r.err and "family." not in r.err, r.err


@pytest.mark.parametrize("args, message", [
    (["kernel", "-m", "3", "--tableau", "tableaux/avf/avf-radau-ii-2.toml", "--rule", "lobatto"],
     "--rule does not apply"),
    (["kernel", "-m", "3", "-s", "5", "--tableau", "tableaux/avf/avf-radau-ii-2.toml"], "-s does not apply"),
    (["conditions", "-N", "3", "--emit", "python", "--format", "json"], "--format json and --emit"),
    (["verify", "@rk4", "-N", "3", "--draw", "--format", "json"], "--draw draws in the text report"),
    (["simulate", "@rk4", "--problem", "random:degree=3,degree=4", "--steps", "3"], "degree is given twice"),
    (["simulate", "@rk4", "--problem", "harmonic", "--steps", "3", "--chart", ""], "expected a file name"),
])
def test_option_combinations_that_would_be_ignored_are_refused(capsys, args, message):
    r = run_cli(capsys, *args)
    assert r.code == 2 and r.err.count("\n") == 1 and message in r.err, r.err


def test_catalog_exits_as_a_scan_on_unreadable_and_missing_files(capsys, tmp_path):
    # an unreadable file is a row saying why and exit 1; no tableau at all: exit 2
    (tmp_path / "one").mkdir()
    (tmp_path / "one" / "bad.toml").write_text("garbage[", encoding="utf-8")
    (tmp_path / "one" / "euler.toml").write_text('[tableau]\nA = [["0"]]\nb = ["1"]\n', encoding="utf-8")
    r = run_cli(capsys, "catalog", str(tmp_path / "one"), "-N", "3")
    assert r.code == 1 and "| `bad.toml` | error:" in r.out and "euler" in r.out, (r.code, r.out)
    (tmp_path / "none").mkdir()
    r = run_cli(capsys, "catalog", str(tmp_path / "none"))
    assert r.code == 2 and "no tableau file" in r.err and r.err.count("\n") == 1
    # files that are no tableau files are passed over, as a scan passes over them
    (tmp_path / "none" / "pyproject.toml").write_text("[tool.x]\na = 1\n", encoding="utf-8")
    (tmp_path / "none" / "package.json").write_text('{"name": "x"}', encoding="utf-8")
    for command in ("catalog", "scan"):
        r = run_cli(capsys, command, str(tmp_path / "none"))
        assert r.code == 2 and r.err.count("\n") == 1, (command, r.err)
    (tmp_path / "none" / "euler.toml").write_text('[tableau]\nA = [["0"]]\nb = ["1"]\n', encoding="utf-8")
    r = run_cli(capsys, "catalog", str(tmp_path / "none"), "-N", "3")
    assert r.code == 0 and "euler" in r.out and "pyproject" not in r.out and "package" not in r.out, r.out


@pytest.mark.parametrize("T, message", [("1e400", "--T: expected a final time up to 1,000,000"),
                                        ("1e-1000", "--T/--steps: the step size is 0")])
def test_workprec_names_its_own_options_never_an_h_it_does_not_have(capsys, T, message):
    r = run_cli(capsys, "workprec", "@rk4", "-p", "harmonic", "--T", T, "--steps", "10")
    assert r.code == 2 and r.err.count("\n") == 1 and message in r.err and "--h" not in r.err, r.err


@pytest.mark.parametrize("args, unused", [
    (["kernel", "-s", "3", "-k", "5", "--rule", "lobatto"], "-s, -k, --rule do not apply"),
    (["gauss", "-s", "2", "-k", "3", "--beta", "1"], "-k, --beta do not apply"),
    (["avf", "-s", "2", "--zeta", "1"], "--zeta does not apply"),
])
def test_new_refuses_the_options_a_family_does_not_read(capsys, args, unused):
    r = run_cli(capsys, "new", *args)
    assert r.code == 2 and r.err.count("\n") == 1 and unused in r.err, r.err


def test_the_api_refuses_them_too():
    import rkcheck

    for call in (lambda: rkcheck.new("rk4", stages=3), lambda: rkcheck.new_toml("rk4", digits=20),
                 lambda: rkcheck.new("kernel", stages=3), lambda: rkcheck.new_toml("gauss", stages=2, k=3)):
        with pytest.raises(rkcheck.RkcheckError, match="not apply"):
            call()
    assert rkcheck.new("kernel", zeta="1/3").stages == 2 and rkcheck.new("hbvm", stages=2, k=3).stages == 3
