"""A ball wider than 1 that contains 0 is not a holds: on point data
the check raises the precision until every condition is decided.

By hand: with two identical stages (``A = [[x, 0], [x, 0]]``) and ``b = (1, −1)``, every
elementary weight is ``a(t) = Φ_1(t) − Φ_2(t) = 0``, so every product ``w(u)`` over the
children of a rooting vanishes and every energy residual with ≥ 3 vertices is exactly 0,
however large x is.  With ``x = √2·10³⁰`` the intermediate weights reach 10¹⁵⁰ at six
vertices, and at 50 digits the balls around the zero residuals are ~10¹⁰⁰ wide."""

from __future__ import annotations

import json

from support.clirun import run_subprocess


def test_huge_entries_never_give_negative_digits(tmp_path):
    path = tmp_path / "big.json"
    x = "sqrt(2)*10^30"
    path.write_text(json.dumps({"tableau": {"A": [[x, "0"], [x, "0"]], "b": ["1", "-1"]}}))
    run = run_subprocess("verify", str(path), "--degree", "3", "--order", "6", "--arithmetic", "ball",
                         "--format", "json")
    doc = json.loads(run.out)
    states = {(c["state"], c["digits"]) for c in doc["conditions"]}
    assert all(state == "holds_to_digits" and digits >= 1 for state, digits in states), states
    assert any("digits to decide" in w for w in doc["warnings"])
    # Σb = 0: the method is inconsistent, which fails it whatever the conditions say
    assert doc["summary"]["inconsistent"] is True and run.code == 1


def test_nonzero_residuals_of_huge_entries_fail(tmp_path):
    # one stage, a = √2·10³⁰, b = 1: R([τ²]) = (Σb)²/2 − bᵀc = 1/2 − a (by hand), nonzero
    path = tmp_path / "big1.json"
    path.write_text(json.dumps({"tableau": {"A": [["sqrt(2)*10^30"]], "b": ["1"]}}))
    doc = json.loads(run_subprocess("verify", str(path), "--degree", "2", "--order", "2", "--arithmetic", "ball",
                                    "--format", "json").out)
    row = next(c for c in doc["conditions"] if c["id"] == "1,2,2")
    assert row["state"] == "fails"


def test_sum_b_held_to_digits_is_not_inconsistent(tmp_path):
    """Radau IIA with nine stages has no closed-form nodes: its rule is enclosed, so
    Σb = 1 holds only to digits, and Σ b_i c_i^(2s−1) = 1/(2s) certainly fails (Radau
    IIA has quadrature order 2s − 1, Hairer–Wanner II §IV.5).  The method is consistent:
    the failure of a later power is not Σb ≠ 1."""
    path = tmp_path / "radau9.toml"
    path.write_text('[family]\nname = "radau-iia"\ns = 9\n')
    run = run_subprocess("verify", str(path), "--degree", "4", "--order", "5", "--format", "json")
    summary = json.loads(run.out)["summary"]
    assert summary["quadrature_order_to_digits"] == 17 and summary["quadrature_first_failure"] == "Σ b_i c_i^17 = 1/18"
    assert summary["inconsistent"] is False
    assert summary["verdict"] == "holds_to_digits" and run.code == 0
