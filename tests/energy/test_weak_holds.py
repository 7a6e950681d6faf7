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
