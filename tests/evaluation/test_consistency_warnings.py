"""The consistency warnings (definitions §1) print exact values or the decimals the user
wrote — never a value passed through a binary float (``Σb = 0.98999999999999999`` for
b summing to 0.99, ``Σb = 1 ≠ 1`` for RK4 in floats)."""

from __future__ import annotations

import decimal
import json
import warnings
from fractions import Fraction

from support.clirun import run_cli

import rkcheck
from rkcheck.api.tableaux import tableau_warnings

RK4_A = [[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 1.0, 0]]
RK4_B = [1 / 6, 1 / 3, 1 / 3, 1 / 6]


def _sum_warning(lines):
    return next(w for w in lines if w.startswith("Σb ="))


def test_weights_summing_to_099_print_099(tmp_path, capsys):
    # by hand: 0.49 + 0.5 = 0.99 exactly, as decimals; the binary values do not sum to it
    assert Fraction(0.49) + Fraction(0.5) != Fraction(99, 100)
    path = tmp_path / "s99.json"
    path.write_text(json.dumps({"A": [["0", "0"], ["1", "0"]], "b": ["0.49", "0.5"]}))
    out = run_cli(capsys, "verify", str(path), "--order", "2").out
    assert "warning: Σb = 0.99 ≠ 1: the method is inconsistent" in out
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rkcheck.RkcheckWarning)
        floats = rkcheck.from_arrays([[0, 0], [1, 0]], [0.49, 0.5])  # the API reads the printed decimals
    assert _sum_warning(tableau_warnings(floats)) == "Σb = 0.99 ≠ 1: the method is inconsistent (not even order 1)"


def test_float_rk4_at_its_binary_values_prints_the_exact_sum():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rkcheck.RkcheckWarning)
        tab = rkcheck.from_arrays(RK4_A, RK4_B, floats="exact")
    total = sum((Fraction(x) for x in RK4_B), Fraction(0))  # the binary values, added exactly
    assert total != 1
    text = _sum_warning(tableau_warnings(tab))
    assert text.startswith(f"Σb = {total.numerator}/{total.denominator} ≠ 1")


def test_float_rk4_read_at_face_value_prints_the_decimals_sum(tmp_path, capsys):
    # json.dumps writes 0.16666666666666666 and 0.3333333333333333; at face value
    # 2·(0.16666666666666666 + 0.3333333333333333) = 0.99999999999999992 (by hand)
    path = tmp_path / "rk4.json"
    path.write_text(json.dumps({"A": RK4_A, "b": RK4_B}))
    out = run_cli(capsys, "verify", str(path), "--order", "2", "--decimals", "exact").out
    assert "warning: Σb = 0.99999999999999992 ≠ 1" in out
    # read as the doubles' rounding intervals (auto), Σb = 1 is possible: no warning
    assert "Σb" not in run_cli(capsys, "verify", str(path), "--order", "2").out.split("quadrature order")[0]


def test_exact_entries_are_compared_exactly_however_small_the_difference(tmp_path, capsys):
    # c₂ = 1/2 + 2^-300 against the row sum 1/2: below any working precision, yet certain
    path = tmp_path / "tiny.toml"
    path.write_text('[tableau]\nA = [["0", "0"], ["1/2", "0"]]\nb = ["0", "1"]\nc = ["0", "1/2 + 1/2^300"]\n')
    r = run_cli(capsys, "verify", str(path), "--order", "2")
    # a long fraction is shown by its 20 leading digits (by hand: 2^-300 = 4.90909346529772655309…e-91)
    digits = decimal.Context(prec=20).divide(decimal.Decimal(1), decimal.Decimal(2**300))
    assert f"c[2] - (A·1)[2] = ≈{str(digits).replace('E', 'e')}" in r.out + r.err
    # equal exactly, written differently: no warning
    path.write_text('[tableau]\nA = [["0", "0"], ["sqrt(2)/4", "sqrt(8)/8"]]\nb = ["0", "1"]\nc = ["0", "sqrt(2)/2"]\n')
    r = run_cli(capsys, "verify", str(path), "--order", "2")
    assert "differs from the row sums" not in r.out + r.err
    path.write_text('[tableau]\nA = [["0", "0"], ["sqrt(2)/4", "sqrt(8)/8"]]\nb = ["0", "1"]\nc = ["0", "sqrt(2)/3"]\n')
    r = run_cli(capsys, "verify", str(path), "--order", "2")
    assert "c[2] - (A·1)[2] = -sqrt(2)/6" in r.out + r.err  # √2/3 − √2/2 = −√2/6


GAUSS2_EXACT = '[tableau]\nA = [["1/4","1/4 - sqrt(3)/6"],["1/4 + sqrt(3)/6","1/4"]]\nb = ["1/2","1/2"]\nc = [{}]\n'


def test_a_decimal_c_beside_an_exact_a_is_compared_within_its_rounding(tmp_path, capsys):
    # by hand: 1/2 ∓ √3/6 = 0.21132486540518…, 0.78867513459481…; ten digits round them
    # within half a unit (5e-11), seven digits (0.2113248: 5.4e-8 away) do not
    within, beyond = tmp_path / "within.toml", tmp_path / "beyond.toml"
    within.write_text(GAUSS2_EXACT.format('"0.2113248654", "0.7886751346"'), encoding="utf-8")
    beyond.write_text(GAUSS2_EXACT.format('"0.2113248", "0.7886751346"'), encoding="utf-8")
    assert "differs" not in run_cli(capsys, "verify", str(within), "--order", "2").out
    out = run_cli(capsys, "verify", str(beyond), "--order", "2").out
    assert "c[1] - (A·1)[1]" in out and "c[2]" not in out.split("warning: c differs")[1].split("\n")[0]
    # at face value both are off
    assert "c[2] - (A·1)[2]" in run_cli(capsys, "verify", str(within), "--order", "2", "--decimals", "exact").out


def test_the_verdict_line_names_an_inconsistency_beside_failing_conditions(tmp_path, capsys):
    # b = (1, 1): Σb = 2, certainly not 1; R([τ²]) = (Σb)²/2 − Σ b_i c_i = 2 − 3/2 = 1/2 fails too
    path = tmp_path / "inc.toml"
    path.write_text('[tableau]\nA = [["1/2", "0"], ["1/2", "1/2"]]\nb = ["1", "1"]\n', encoding="utf-8")
    last = run_cli(capsys, "verify", str(path), "--order", "2", "-q").out.strip().splitlines()[-1]
    assert last.startswith("FAIL: 1 of 1 condition fails;") and last.endswith("Σb ≠ 1 (certain): the method is inconsistent")
