"""Values at the edges of what numbers can say: magnitudes past float64's range, constants
chained through decimals.  Each ends in the right answer or one line and exit 2, never
an internal error (exit 3)."""

from __future__ import annotations

import json
import math
from decimal import Decimal, getcontext
from fractions import Fraction as F

import pytest
from support import reference as ref
from support.clirun import run_cli
from support.paths import TABLEAUX


def write(tmp_path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def no_bug(r) -> None:
    assert r.code in (0, 1, 2), r.err
    assert "internal error" not in r.err and "Traceback" not in r.err, r.err


# ------------------------------------------------------------------ large magnitudes

def one_stage(a: str, b: str = "1") -> str:
    return f'[tableau]\nA = [["{a}"]]\nb = ["{b}"]\n'


def test_an_entry_of_1e200_gets_its_error_constant_exactly(tmp_path, capsys):
    # A = [[1e200]], b = [1]: the first failing order is 2 (three vertices); C is the
    # norm of the reference residuals there, far beyond float64 once squared
    path = write(tmp_path, "big.toml", one_stage("1e200"))
    r = run_cli(capsys, "verify", path, "--order", "3", "--format", "json")
    assert r.code == 1, r.err
    ec = json.loads(r.out)["summary"]["error_constant"]
    A, b = [[F(10) ** 200]], [F(1)]
    residuals = [ref.energy_residual(c, A, b) for c in ref.energy_conditions(3)]
    squared = sum(x * x for x in residuals)
    assert ec["order"] == 2 and F(ec["squared"]) == squared
    getcontext().prec = 60
    root = (Decimal(squared.numerator) / Decimal(squared.denominator)).sqrt()
    assert abs(Decimal(ec["value"]) / root - 1) < Decimal("1e-11")
    assert Decimal(ec["lower"]) <= root <= Decimal(ec["upper"])


@pytest.mark.parametrize("entry", ["1e200", "-1e250", "2^1100", "10^999", "sqrt(2)*10^400", "1e-300",
                                   "root(x^3-2,1)*10^500", "0.2113248654051871e400"])
@pytest.mark.parametrize("command", [
    ["verify", "--order", "4"], ["verify", "--order", "4", "--arithmetic", "ball"],
    ["verify", "--order", "4", "--decimals", "float64"], ["verify", "--order", "3", "--format", "json"],
    ["show"], ["simulate", "--problem", "harmonic", "--steps", "5"], ["bench", "--order", "3"],
    ["explain", "1,2,2", "--tableau"], ["scan", "--order", "4", "--sort", "energy"], ["catalog"],
])
def test_huge_and_tiny_entries_never_end_in_an_internal_error(tmp_path, capsys, entry, command):
    a = write(tmp_path, "a.toml", f'[tableau]\nA = [["{entry}", "0"], ["1", "0"]]\nb = ["{entry}", "1"]\n')
    r = run_cli(capsys, *command, a)
    no_bug(r)


def test_a_step_beyond_float64_is_refused_with_the_value(tmp_path, capsys):
    path = write(tmp_path, "a.toml", one_stage("10^999"))
    r = run_cli(capsys, "simulate", path, "--problem", "harmonic", "--steps", "5")
    assert r.code == 2 and "beyond float64's range" in r.err and "--dps" in r.err, r.err


def test_ball_bounds_past_float64_are_refused_with_the_reason(tmp_path, capsys):
    path = write(tmp_path, "a.toml", one_stage("10^999"))
    r = run_cli(capsys, "verify", path, "--order", "3", "--arithmetic", "ball")
    assert r.code == 2 and "overflow float64" in r.err and "magnitude" in r.err, r.err
    # the way out it names works: exact arithmetic decides (a = 10^999, b = 1: R([τ²]) = 1/2 − a fails)
    assert "--arithmetic exact" in r.err
    assert run_cli(capsys, "verify", path, "--order", "3", "--arithmetic", "exact").code == 1


def test_explain_evaluates_irrational_entries(tmp_path, capsys):
    # A = [[√2]], b = [1]: condition 1,2,2 has R = Σb·Σb/2 − Σ b_i c_i = 1/2 − √2
    path = write(tmp_path, "a.toml", one_stage("sqrt(2)"))
    r = run_cli(capsys, "explain", "1,2,2", "--tableau", path)
    assert r.code == 0, r.err
    line = [x for x in r.out.splitlines() if x.startswith("R = -")][0]
    shown = F(line.split()[2])
    assert abs(shown - (F(1, 2) - F(math.sqrt(2)))) < F(1, 10**10) and line.endswith("fails")


def test_scan_constants_column_past_float64(tmp_path, capsys):
    folder = tmp_path / "d"
    folder.mkdir()
    (folder / "big.toml").write_text(one_stage("1e200"), encoding="utf-8")
    (folder / "rk.toml").write_text(one_stage("1/2", "1"), encoding="utf-8")
    r = run_cli(capsys, "scan", str(folder), "--order", "4", "--sort", "energy")
    no_bug(r)
    assert "1.0e200" in r.out, r.out


# ------------------------------------------------------------------ constants through decimals

CHAIN = """[constants]
r = "0.2113248654051871"
s = "1 - r"
t = "s * s"
[tableau]
A = [["r", "0"], ["s", "0"]]
b = ["1/2", "1/2"]
"""


def test_a_constant_chained_through_a_decimal_is_read_as_rounded(tmp_path, capsys):
    # r has 16 significant digits; s and t depend on r only through other constants
    path = write(tmp_path, "chain.toml", CHAIN)
    r = run_cli(capsys, "verify", path, "--order", "3")
    no_bug(r)
    assert r.code == 0 and "as few as 16" in r.out, r.out
    from rkcheck.io.loader import loads
    from rkcheck.numbers.entries import Entry

    tab = loads(CHAIN, "chain.toml")
    assert [e.rounded_digits for e in tab.A[1]] == [16, None]
    assert Entry.parse("t + 1/3", tab.info.constants).rounded_digits == 16


# ------------------------------------------------------------------ one bad row, not a bad report

@pytest.mark.parametrize("fmt", ["json", "csv", "junit", "github", "text"])
def test_a_report_row_that_cannot_be_built_is_that_files_error_row(tmp_path, capsys, monkeypatch, fmt):
    import rkcheck.reports.scan as scan_report
    import rkcheck.reports.scan_json as scan_json

    folder = tmp_path / "d"
    folder.mkdir()
    for name in ("a", "bad", "c"):
        (folder / f"{name}.toml").write_text(one_stage("1/2"), encoding="utf-8")
    real = scan_report.check_doc

    def broken(result, *how):
        if result.tableau.name == "bad":
            raise ZeroDivisionError("injected")
        return real(result, *how)

    monkeypatch.setattr(scan_report, "check_doc", broken)
    # a JSON scan has its workers encode the documents first: there the failure leaves
    # the document to the report, which fails again and turns it into the row's error
    monkeypatch.setattr(scan_json, "check_doc", broken)
    out = tmp_path / f"report.{fmt}"
    r = run_cli(capsys, "scan", str(folder), "--order", "3", "--jobs", "1", "--format", fmt, "-o", str(out))
    assert r.code == 1, r.err
    text = out.read_text(encoding="utf-8")
    words = " ".join(text.split())  # the text table wraps long messages
    assert "bad.toml" in text and "internal error while writing its report: ZeroDivisionError: injected" in words
    if fmt == "json":
        files = {f["file"].rsplit("/", 1)[-1]: f for f in json.loads(text)["files"]}
        assert [files[k]["status"] for k in ("a.toml", "bad.toml", "c.toml")] == ["ok", "error", "ok"]
        assert files["a.toml"]["result"] is not None and files["bad.toml"]["result"] is None


@pytest.mark.parametrize("command", ["verify", "scan", "explain"])
def test_a_report_past_the_printed_digits_limit_is_one_line_naming_the_file(tmp_path, capsys, monkeypatch, command):
    # b = 3^6000 (2 863 digits) puts residuals of thousands of digits in the report: past
    # the CLI's limit (lowered here to 5 000) verify ends with one line naming the file
    # and a scan gives the file an error row — a limit the numbers met, not a bug
    import importlib

    monkeypatch.setattr(importlib.import_module("rkcheck.cli.main"), "MAX_PRINTED_DIGITS", 5000)
    path = write(tmp_path, "huge.toml", '[constants]\nx = "3^1000"\n[tableau]\nA = [["1/2"]]\nb = ["x^6"]\n')
    args = ("explain", "1,2,2", "--tableau", path) if command == "explain" else (command, path, "--order", "2")
    r = run_cli(capsys, *args)
    assert r.code == (1 if command == "scan" else 2)
    message = f"{path}: a number of the report has more than 5,000 digits, too many to print (docs/errors.md)"
    if command != "scan":
        assert r.err.strip().splitlines()[-1] == f"rkcheck: error: {message}"
    else:
        assert message in " ".join(r.out.split()) and "internal error" not in r.out


# ------------------------------------------------------------------ long decimals

def test_a_decimal_of_4437_digits_gets_exact_residuals(tmp_path, capsys):
    # thousands of primes for the exact residuals: merged by a product tree (Garner's
    # digits took minutes); each residual is checked against the reference in Fractions
    from support.guards import hang_guard

    digits = "0." + ("1234567890" * 444)[:4437]
    path = write(tmp_path, "long.toml", one_stage(digits))
    with hang_guard(120):
        r = run_cli(capsys, "verify", path, "--order", "6", "--decimals", "exact", "--format", "json")
    assert r.code == 1, r.err
    import sys

    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)  # thousands of digits, read here
    try:
        A, b = [[F(digits)]], [F(1)]
        expected = {}
        for n in range(3, 8):
            for cond in ref.energy_conditions(n):
                expected[",".join(map(str, cond["id"]))] = ref.energy_residual(cond, A, b)
        got = {c["id"]: F(c["residual_exact"]) for c in json.loads(r.out)["conditions"]}
    finally:
        sys.set_int_max_str_digits(limit)
    assert got == expected


# ------------------------------------------------------------------ number-field limits

def test_root_obeys_the_field_degree_limit(tmp_path, capsys):
    # root(x^60 - 2, 1) generates Q(2^(1/60)), of degree 60 > MAX_FIELD_DEGREE = 48
    from rkcheck.numbers.algebraic import MAX_FIELD_DEGREE, NotAlgebraic
    from rkcheck.numbers.field_builder import field_of
    from rkcheck.numbers.grammar import parse

    assert MAX_FIELD_DEGREE < 60
    with pytest.raises(NotAlgebraic, match="degree at least 60 .more than 48, the limit MAX_FIELD_DEGREE"):
        field_of([parse("root(x^60 - 2, 1)")])
    assert field_of([parse("root(x^48 - 2, 1)")]).field.degree == 48
    path = write(tmp_path, "r.toml", one_stage("root(x^60 - 2, 1)"))
    r = run_cli(capsys, "verify", path, "--order", "3")
    assert r.code == 1 and "not exact: the entries generate a number field of degree at least 60" in " ".join(r.out.split())


def test_building_a_field_stops_at_its_time_limit(tmp_path, capsys, monkeypatch):
    # a nested radical of degree 16 needs seconds of exact work: with the limit at zero
    # it is left to balls at once, and the report says which limit
    import rkcheck.numbers.field_builder as builder
    from rkcheck.numbers.algebraic import NotAlgebraic
    from rkcheck.numbers.grammar import parse

    monkeypatch.setattr(builder, "FIELD_SECONDS", 0.0)
    with pytest.raises(NotAlgebraic, match="the limit FIELD_SECONDS"):
        builder.field_of([parse("sqrt(2 + sqrt(3 + sqrt(5)))")])
    path = write(tmp_path, "n.toml", one_stage("sqrt(2 + sqrt(3 + sqrt(5)))"))
    r = run_cli(capsys, "verify", path, "--order", "3")
    assert r.code == 1 and "not exact: building their number field took more than 0 s (the limit FIELD_SECONDS)" in (
        " ".join(r.out.split())), r.out


def test_a_nested_radical_of_degree_512_ends_within_the_field_limit(tmp_path):
    # run as a process with its own timeout: FIELD_SECONDS (10 s) bounds the exact attempt
    from support.clirun import run_subprocess

    path = write(tmp_path, "n.toml", one_stage("sqrt(2+sqrt(3+sqrt(5+sqrt(7+sqrt(11)))))"))
    r = run_subprocess("verify", path, "--order", "3", timeout=90)
    assert r.code == 1 and "not exact" in r.out, r.err


# ------------------------------------------------------------------ claims within limits

def test_a_classical_order_claim_beyond_its_limit_is_refused(tmp_path, capsys):
    path = write(tmp_path, "c.toml", one_stage("1/2") + "[expect]\nclassical_order = 20\n")
    r = run_cli(capsys, "verify", path)
    assert r.code == 2 and r.err == (f"rkcheck: error: {path}: expect.classical_order: expected an integer from 0 "
                                     "to 14, got 20 (the limit MAX_CLASSICAL_CLAIM: judging it checks every rooted "
                                     "tree of one more vertex)\n"), r.err


@pytest.mark.parametrize("claim, met", [(2, True), (3, False), (14, False)])
def test_a_classical_order_claim_is_judged_without_an_energy_run_to_its_order(tmp_path, capsys, claim, met):
    # the implicit midpoint rule has classical order 2 (Butcher); --order 1 asks for one
    # energy order only, and the claim is still judged exactly
    path = write(tmp_path, "c.toml", one_stage("1/2") + f"[expect]\nclassical_order = {claim}\n")
    r = run_cli(capsys, "verify", path, "--order", "1", "--format", "json")
    assert r.code == (0 if met else 1), r.err
    doc = json.loads(r.out)
    (c,) = doc["claims"]
    assert (c["met"], c["found"]) == (met, "2") and doc["options"]["order"] == 1


# ------------------------------------------------------------------ deep expressions

SQRT_SUM = "+".join(f"sqrt({p})" for p in (2, 3, 5, 7, 11, 13) * 200)  # 1 200 terms, a tree 1 200 deep


def test_a_long_sum_of_square_roots_is_checked_in_balls(tmp_path, capsys):
    import mpmath

    path = write(tmp_path, "s.toml", one_stage(SQRT_SUM))
    r = run_cli(capsys, "verify", path, "--order", "2", "--format", "json")
    assert r.code == 1, r.err
    doc = json.loads(r.out)
    # condition 1,2,2: R = (Σb)²/2 − Σ b_i c_i = 1/2 − a, a = 200·(√2 + √3 + … + √13)
    (cond,) = doc["conditions"]
    with mpmath.workdps(30):  # not the global precision: other tests read mpmath's default
        a = 200 * sum(mpmath.sqrt(p) for p in (2, 3, 5, 7, 11, 13))
        assert abs(mpmath.mpf(cond["residual"]) - (mpmath.mpf(1) / 2 - a)) < mpmath.mpf(10) ** -20


def test_a_deep_expression_survives_a_scan_with_workers(tmp_path, capsys):
    folder = tmp_path / "d"
    folder.mkdir()
    (folder / "s.toml").write_text(one_stage(SQRT_SUM), encoding="utf-8")
    (folder / "t.toml").write_text(one_stage("1/2"), encoding="utf-8")
    r = run_cli(capsys, "scan", str(folder), "--order", "2", "--jobs", "2", "--format", "json")
    assert r.code == 0, r.err
    assert [f["status"] for f in json.loads(r.out)["files"]] == ["ok", "ok"]


def test_deep_expression_trees_pickle_without_recursion():
    import pickle

    from rkcheck.numbers import expressions as xp
    from rkcheck.numbers import grammar as ex

    node = ex.parse(SQRT_SUM + " - root(x^3 - 2*x + 1, 2)*1.25e3 / -c^2")
    back = pickle.loads(pickle.dumps(node))
    shape = [(type(n).__name__, getattr(n, "op", None), getattr(n, "text", None)) for n in xp.walk(node)]
    assert [(type(n).__name__, getattr(n, "op", None), getattr(n, "text", None)) for n in xp.walk(back)] == shape


@pytest.mark.parametrize("fmt", ["python", "latex", "julia"])
def test_writing_a_deep_expression_as_code_is_one_line(tmp_path, capsys, fmt):
    path = write(tmp_path, "s.toml", one_stage(SQRT_SUM))
    r = run_cli(capsys, "show", path, "--format", fmt)
    # one_stage puts the entry in A[1][1] (b is 1): the place names it
    assert r.code == 2 and r.err == (f"rkcheck: error: {path}: A[1][1]: nested too deeply to write as {fmt} "
                                     "(a chain of thousands of terms); write the tableau as TOML or JSON\n"), r.err


# ------------------------------------------------------------------ the advertised precision range

@pytest.mark.parametrize("dps", ["700", "5000"])
def test_the_whole_dps_range_works_on_decimal_tableaux(capsys, dps):
    # 50-digit decimals of AVF(Gauss-2): the same verdicts at the top of the range as at 50
    from support.paths import TABLEAUX

    path = str(TABLEAUX / "avf" / "avf-gauss-2-decimal50.toml")
    base = run_cli(capsys, "verify", path, "--order", "5", "--format", "json")
    high = run_cli(capsys, "verify", path, "--order", "5", "--format", "json", "--dps", dps)
    assert base.code == high.code == 0, high.err
    states = [[c["state"] for c in json.loads(r.out)["conditions"]] for r in (base, high)]
    assert states[0] == states[1]


# ------------------------------------------------------------------ kernel within its limit

def test_kernel_beyond_its_work_limit_is_refused_before_any_work(capsys):
    # a tableau's rule (not a named one, whose rank is exact over Q) is eliminated entry by
    # entry: HBVM(6, 2) has 6 stages, so m = 40 makes M 741 + 6 rows by 36 columns
    hbvm = str(TABLEAUX / "hbvm" / "hbvm-6-2.toml")
    r = run_cli(capsys, "kernel", "-m", "40", "--tableau", hbvm)
    assert r.code == 2 and "is 747 × 36" in r.err and "the limit MAX_KERNEL_WORK = 500,000" in r.err, r.err
    import rkcheck

    with pytest.raises(rkcheck.RkcheckError, match="MAX_KERNEL_WORK"):
        rkcheck.kernel(40, tableau=hbvm)


def test_kernel_within_its_limit_still_answers(capsys):
    # Gauss, m = 2s (seed Lemma 2): rank M = s² − 1
    r = run_cli(capsys, "kernel", "-s", "2", "-m", "4")
    assert r.code == 0 and "rank M = 3" in r.out, r.out


# ------------------------------------------------------------------ errors of the check name file and place

def test_an_irrational_square_root_of_a_negative_number_names_its_entry(tmp_path, capsys):
    # 1 − √3 < 0: found while building the number field, not while parsing
    path = write(tmp_path, "n.toml", '[constants]\nq = "1 - sqrt(3)"\n[tableau]\nA = [["0", "0"], ["1", "sqrt(q)"]]\n'
                                     'b = ["1", "0"]\n')
    r = run_cli(capsys, "verify", path)
    assert r.code == 2 and r.err == f"rkcheck: error: {path}: A[2][2]: square root of a negative number at column 1\n"


@pytest.mark.parametrize("command", [["verify"], ["show"], ["explain", "1,2,3,3,2", "--tableau"]])
def test_every_command_names_the_file_of_an_entry_found_negative_under_a_root(tmp_path, capsys, command):
    # 2 − √2 − √2 = 2 − 2√2 < 0: found while building the number field, after loading
    path = write(tmp_path, "n.toml", '[tableau]\nA = [["sqrt(2-sqrt(2)-sqrt(2))"]]\nb = ["1"]\n')
    r = run_cli(capsys, *command, path)
    assert r.code == 2 and r.err == f"rkcheck: error: {path}: A[1][1]: square root of a negative number at column 1\n"


def test_the_api_names_the_file_of_an_entry_found_negative_under_a_root(tmp_path):
    import rkcheck

    path = write(tmp_path, "n.toml", '[tableau]\nA = [["sqrt(2-sqrt(2)-sqrt(2))"]]\nb = ["1"]\n')
    with pytest.raises(rkcheck.RkcheckError) as err:
        rkcheck.verify(path)
    assert str(err.value) == f"{path}: A[1][1]: square root of a negative number at column 1"


@pytest.mark.parametrize("entry, message", [
    # decimals: the argument's interval straddles 0, the divisor's contains it
    ("sqrt(1.234567 - 1.234567)", "A[1][1]: square root at column 1: the argument cannot be shown to be >= 0"),
    ("1/(sqrt(2)-1.41421356237)", "A[1][1]: division at column 2: the divisor cannot be shown to be nonzero"),
])
def test_an_entry_that_cannot_be_enclosed_is_named(tmp_path, capsys, entry, message):
    path = write(tmp_path, "e.toml", f'[tableau]\nA = [["{entry}"]]\nb = ["1"]\n')
    r = run_cli(capsys, "verify", path)
    assert r.code == 2 and r.err.startswith(f"rkcheck: error: {path}: {message}") and r.err.count("\n") == 1, r.err


def test_an_error_of_the_check_names_the_file(tmp_path, capsys):
    path = write(tmp_path, "a.toml", one_stage("10^999"))
    r = run_cli(capsys, "verify", path, "--order", "3", "--arithmetic", "ball")
    assert r.code == 2 and r.err.startswith(f"rkcheck: error: {path}: the certified error bounds overflow"), r.err


def test_one_files_check_error_is_its_catalogue_row(tmp_path, capsys):
    folder = tmp_path / "d"
    folder.mkdir()
    (folder / "good.toml").write_text(one_stage("1/2"), encoding="utf-8")
    (folder / "neg.toml").write_text(one_stage("sqrt(1 - sqrt(3))"), encoding="utf-8")
    r = run_cli(capsys, "catalog", str(folder))
    assert r.code == 1, r.err  # the catalogue written, the run failed (as a scan)
    rows = [line for line in r.out.splitlines() if line.startswith("| `")]
    assert any(line.startswith("| `good.toml` | good |") for line in rows), rows
    assert any("neg.toml` | error: " in line and "A\\[1\\]\\[1\\]: square root of a negative number" in line
               for line in rows), rows


def test_simulate_energy_order_on_a_weight_of_10_to_999(tmp_path, capsys):
    # the leading one-step error is R·h²·F(H)(y0) with R = b²/2 − b·c ≈ 5e1997 (b = 10^999,
    # c = 1/2) and F(H)(y0) of order 1 at a random point: about 1e1996 at h = 1/8, printed
    # with its own exponent (float64 would say inf)
    import re

    path = write(tmp_path, "c.toml", one_stage("1/2", "10^999"))
    r = run_cli(capsys, "simulate", path, "--problem", "harmonic", "--energy-order", "--points", "1")
    assert r.code in (0, 1), r.err
    assert "inf" not in r.out, r.out
    first = next(line for line in r.out.splitlines() if line.strip().startswith("2^-3"))
    exponent = int(re.search(r"e\+(\d+)", first).group(1))
    assert 1993 <= exponent <= 1998, first


def test_ball_magnitude_bounds_past_float64_are_infinite_not_an_error(tmp_path, capsys):
    # b[2] = 1/6 − √(10^300) ≈ −1e150: its products pass 1e308 in the magnitude bounds
    path = write(tmp_path, "m.json", json.dumps({"constants": {"c0": "-(root(x^2 - (10^300), 1))"},
                                                 "tableau": {"A": [["1/4", "0"], ["1/2", "1/4"]],
                                                             "b": ["1/2", "c0 + 1/6"]}}))
    r = run_cli(capsys, "verify", path, "--order", "3", "--arithmetic", "ball")
    no_bug(r)
    assert r.code == 1 and "energy order 1" in r.out, r.out


def test_rationals_too_large_for_the_primes_allowed_say_so_not_splitting(tmp_path, capsys, monkeypatch):
    # over Q every prime serves: past the limit it is the entries' size that is too much
    # (64 primes of 30 bits cover some 1 900 bits; (1/3 + 10^700)^3 takes about 7 000)
    import rkcheck.evaluation.scaled as scaled

    monkeypatch.setattr(scaled, "MAX_PRIMES_SCANNED", 64)
    path = write(tmp_path, "big.toml", '[tableau]\nA = [["1/3 + 10^700"]]\nb = ["1"]\n')
    r = run_cli(capsys, "verify", path, "--order", "2")
    assert r.code == 2 and len(r.err.splitlines()) == 1, r.err
    assert "the entries are too large for exact arithmetic" in r.err and "splits" not in r.err, r.err


def test_the_search_for_split_primes_stops_at_its_limit(capsys, monkeypatch):
    # with no prime allowed, Q(√3) of Gauss-2 cannot be checked exactly: one line names
    # the limit and the way out, which works
    import rkcheck.evaluation.scaled as scaled

    monkeypatch.setattr(scaled, "MAX_PRIMES_SCANNED", 0)
    r = run_cli(capsys, "verify", "@gauss-2", "--order", "3")
    assert r.code == 2 and "(the limit MAX_PRIMES_SCANNED); use --arithmetic ball" in r.err, r.err
    assert len(r.err.splitlines()) == 1
    r = run_cli(capsys, "verify", "@gauss-2", "--order", "3", "--arithmetic", "ball")
    assert r.code == 0, r.err


@pytest.mark.heavy
def test_a_root_isolation_that_runs_for_minutes_is_stopped_at_the_field_limit(tmp_path):
    # one FLINT call (roots of a degree-8 polynomial with 8 000-bit coefficients) ran for
    # minutes: the limit holds inside it, and the check goes on in ball arithmetic
    from support.clirun import run_subprocess

    path = write(tmp_path, "n.toml", one_stage("sqrt(sqrt(sqrt(2^-1000 + 10^300))) + sqrt(3)"))
    r = run_subprocess("verify", path, "--order", "3", timeout=120)
    assert "the limit FIELD_SECONDS" in " ".join(r.out.split()), (r.out, r.err)


def test_a_field_past_the_limit_is_reported_as_a_lower_bound(tmp_path, capsys):
    # eight square roots of distinct primes generate a field of degree 2^8 = 256; the
    # builder stops at the first field past 48 (degree 64 after six), so that is what it
    # can say: at least 64, never a degree the entries' field does not have
    roots = "+".join(f"sqrt({p})" for p in (2, 3, 5, 7, 11, 13, 17, 19))
    path = write(tmp_path, "r.toml", one_stage(f"({roots})/100"))
    r = run_cli(capsys, "verify", path, "--order", "3")
    assert r.code in (0, 1), r.err
    assert "number field of degree at least 64 (more than 48" in " ".join(r.out.split()), r.out
