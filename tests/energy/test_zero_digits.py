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
from support.paths import REPO

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
    words = {0: "not decided", 1: "yes, to 1 digit"}.get(digits, f"yes, to {digits} digits")
    assert exact.answer() == words


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
    # the stability certificate holds to 0 digits too: it certifies nothing
    assert summary["certificate"]["digits"] == 0 and summary["energy_order_all_digits"] is None
    assert summary["energy_order_all"] is False
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


# ---------------------------------------------------------------- what decides nothing meets no claim

WIDE_SYMPLECTIC = """[tableau]
A = [["0.250000","123456789.250000"],["-123456788.750000","0.250000"]]
b = ["0.500000","0.500000"]
[check]
degree = 4
order = 1
decimals = "rounded"
[expect]
symplectic = true
"""


def test_a_property_held_to_0_digits_meets_no_claim(capsys, tmp_path):
    # BA + AᵀB − bbᵀ at (1,2): b₁a₁₂ + b₂a₂₁ − b₁b₂ = (a₁₂ + a₂₁)/2 − 1/4, each aᵢⱼ ± 5·10⁻⁷,
    # times 1.2·10⁸ in the other entries of the products: the enclosure is far wider than 1
    path = tmp_path / "wide.toml"
    path.write_text(WIDE_SYMPLECTIC, encoding="utf-8")
    doc = json.loads(run_cli(capsys, "verify", str(path), "--format", "json").out)
    assert doc["summary"]["symplectic"]["state"] == "holds_to_digits" and doc["summary"]["symplectic"]["digits"] == 0
    (claim,) = doc["claims"]
    assert claim["met"] is False and claim["found"] == "undecided"
    run = run_cli(capsys, "verify", str(path), "-q")
    assert run.code == 1 and "CLAIMS NOT SHOWN: 1 of 1" in run.out


def test_property_claims_met_to_digits_fall_short_of_a_proof(capsys, tmp_path):
    # the 6-digit Gauss-2 tableau is symplectic and symmetric only to its digits
    path = tmp_path / "g2six.toml"
    path.write_text((REPO / "docs" / "examples" / "g2six.toml").read_text(encoding="utf-8")
                    + "\n[expect]\nsymplectic = true\nsymmetric = true\n", encoding="utf-8")
    assert run_cli(capsys, "verify", str(path), "--degree", "4", "--order", "1", "-q").code == 0
    run = run_cli(capsys, "verify", str(path), "--degree", "4", "--order", "1", "--require", "proof", "-q")
    text = " ".join(run.out.split())
    assert run.code == 1 and "the claim symplectic = true holds only to" in text
    assert "the claim symmetric = true holds only to" in text
    assert rkcheck.verify(path, degree=4, order=1, require="proof").failed


THEOREM1 = """[constants]
K = "1.00000e3"
d = "K^2 - 10^6"
c1 = "1/2 - sqrt(3)/6"
c2 = "1/2 + sqrt(3)/6"
[tableau]
A = [["c1/2 + d", "c1/2 - d"], ["c2/2", "c2/2"]]
b = ["1/2", "1/2"]
"""


def test_theorem1_does_not_conclude_from_stages_merged_to_digits(capsys, tmp_path):
    # rows 1 and 2 are equal only where d = (c2 − c1)/2 = √3/6; d = K² − 10⁶ ranges over about
    # [−10, 10] on the box, so their equality is not decided, and the stages are two
    path = tmp_path / "t1.toml"
    path.write_text(THEOREM1, encoding="utf-8")
    doc = json.loads(run_cli(capsys, "verify", str(path), "--degree", "4", "--decimals", "rounded",
                             "--format", "json").out)
    assert doc["summary"]["reduction"]["exact"] is False
    assert "so it cannot" not in doc["summary"]["theorem1"] and "not a proof" in doc["summary"]["theorem1"]
    assert doc["summary"]["equals_avf"] is None  # AVF to 0 digits decides nothing


def test_failing_conditions_head_the_line_under_fail_on_conditions(capsys, tmp_path):
    # K = √2·10³⁰: R([τ³]) fails by about K², and at order 6 one zero residual's ball stays
    # wider than 1 even at 8 × 10 digits, so the gate falls short too
    path = tmp_path / "k.toml"
    path.write_text('[constants]\nK = "sqrt(2)*10^30"\n[tableau]\nA = [["1/4","1/4 + K"],["1/4 - K","1/4"]]\n'
                    'b = ["1/2","1/2"]\n[expect]\nsymplectic = true\n', encoding="utf-8")
    args = ("verify", str(path), "--degree", "4", "--order", "6", "--arithmetic", "ball", "--dps", "10", "-q")
    doc = json.loads(run_cli(capsys, *args[:-1], "--format", "json").out)
    failing = sum(1 for c in doc["conditions"] if c["state"] == "fails")
    assert failing >= 1 and doc["summary"]["require"]["met"] is False
    last = run_cli(capsys, *args, "--fail-on", "conditions").out.strip().splitlines()[-1]
    assert last.startswith(f"FAIL: {failing} of ")


def test_a_kernel_reason_is_said_of_its_face_values_when_the_box_differs(capsys, tmp_path):
    # A = τ + (3 + K² − 10⁶)(τ² − τ)(2σ − 1) with K = 1000 ± 5·10⁻³: at face value the extra
    # term is 3(τ² − τ)(2σ − 1), not AVF; on the box its coefficient ranges over about ±10
    path = tmp_path / "ker.toml"
    path.write_text('[constants]\nK = "1.00000e3"\n[continuous]\n'
                    'A = "tau + (3 + K^2 - 10^6)*(tau^2 - tau)*(2*sigma - 1)"\n', encoding="utf-8")
    doc = json.loads(run_cli(capsys, "verify", str(path), "--order", "2", "--decimals", "rounded",
                             "--format", "json").out)
    avf = doc["summary"]["avf"]
    assert avf["state"] == "holds_to_digits" and avf["digits"] == 0 and doc["summary"]["equals_avf"] is None
    assert avf["reason"].endswith("at face value, which the box of its decimals does not exclude")


def test_the_catalogue_marks_what_is_not_decided(tmp_path):
    from rkcheck.batch.catalog import catalog_row

    # symmetric needs B(τ) = B(1 − τ), and B = 2σ is not; yet no rooted tree the series
    # search reaches refutes it (the kernel's own report says "not decided")
    path = tmp_path / "k2.toml"
    path.write_text('[continuous]\nA = "(1/2 + tau^2 - sigma^2)*2*sigma"\nb = "2*sigma"\n', encoding="utf-8")
    doc = rkcheck.verify(path).to_json()
    assert json.loads(doc)["summary"]["symmetric"]["state"] == "undecided"
    assert catalog_row(str(path), [None], 4).symmetric == "?"
