"""A holds whose enclosure is wider than 1 certifies no digit: it is ``holds to 0 digits``
in every route (never a negative count), and no ``--require`` gate passes it, not even
``any`` (definitions §5, docs/verdicts.md).

The tableau below is symplectic at its face values, by hand: with b = (1/2, 1/2),
``b_i a_ij + b_j a_ji − b_i b_j`` is ``2·(1/2)(1/4) − 1/4 = 0`` on the diagonal and
``(1/2)(123456.25 − 123455.75) − 1/4 = 0`` off it.  So every energy condition of degree 2
holds exactly at the face values (a quadratic invariant is conserved), while the rounding
of its 1.2·10⁵ entries, read as intervals, leaves enclosures around 0 far wider than 1 at
orders 4 and 6."""

from __future__ import annotations

import json
from fractions import Fraction

import pytest
from support.clirun import run_cli

import rkcheck
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.verdicts import HOLDS_TO_DIGITS, Verdict, classify, classify_many

BIG = """[tableau]
A = [["0.25000000", "123456.25000"], ["-123455.75000", "0.25000000"]]
b = ["0.50000000", "0.50000000"]
"""
ARGS = ("--degree", "2", "--order", "6", "--decimals", "rounded")


@pytest.fixture
def big(tmp_path):
    path = tmp_path / "big.toml"
    path.write_text(BIG, encoding="utf-8")
    return path


@pytest.mark.parametrize("rad, digits", [(Fraction(10**8), 0), (Fraction(3, 2), 0), (Fraction(1, 2), 0),
                                         (Fraction(1, 10), 1), (Fraction(1, 20), 1), (Fraction(1, 10**5), 5)])
def test_certain_digits_count_from_zero(rad, digits):
    # D is the largest integer with rad <= 10^-D, by hand, and none when that is negative
    exact, screened = classify(Enclosure(Fraction(0), rad, False)), classify_many([Enclosure(0.0, float(rad), False)])[0]
    assert exact == Verdict(HOLDS_TO_DIGITS, digits)
    # the float screen may be one digit conservative, never optimistic, and never negative
    assert screened.state == HOLDS_TO_DIGITS and max(0, digits - 1) <= screened.digits <= digits
    assert exact.answer() == ("not decided" if digits == 0 else f"yes, to {digits} digits")


def test_a_negative_count_is_no_digit():
    assert Verdict(HOLDS_TO_DIGITS, -8).digits == 0 and not Verdict(HOLDS_TO_DIGITS, -8).decided


@pytest.mark.parametrize("arithmetic", ["auto", "ball"])
def test_every_route_reports_the_digits_its_enclosure_certifies(capsys, big, arithmetic):
    run = run_cli(capsys, "verify", str(big), *ARGS, "--arithmetic", arithmetic, "--format", "json")
    doc = json.loads(run.out)
    rows = {c["id"]: c for c in doc["conditions"]}
    for c in rows.values():
        bound = abs(Fraction(c["residual"])) + Fraction(c["radius"])
        assert c["digits"] >= 0 and (c["digits"] == 0 or bound <= Fraction(1, 10 ** c["digits"]))
    wide = [i for i, c in rows.items() if Fraction(c["radius"]) > 1]
    assert wide and all(rows[i]["digits"] == 0 for i in wide)
    summary = doc["summary"]
    assert summary["certificate"]["digits"] >= 0 and summary["energy_order_all_digits"] >= 0
    assert summary["require"]["met"] is False and summary["passed"] is False and run.code == 1
    assert set(summary["require"]["examples"]) == set(wide)


def test_the_default_gate_fails_what_no_digit_decides(capsys, big):
    run = run_cli(capsys, "verify", str(big), *ARGS, "-q")
    assert run.code == 1
    assert "FAIL: --require any: 2 conditions hold to 0 digits" in run.out
    assert "not one digit is certain" in " ".join(run.out.split())
    assert not rkcheck.verify(big, degree=2, order=6, decimals="rounded").ok
    # at face value the tableau is symplectic (by hand, above): every condition holds
    assert run_cli(capsys, "verify", str(big), *ARGS[:4], "--decimals", "exact", "-q").code == 0
