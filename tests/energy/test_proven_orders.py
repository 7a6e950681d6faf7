"""Orders count proven holds only (definitions §5): a condition that holds to D digits is
reported as "holds to D digits beyond order N", in the table, the headline and the JSON,
never counted in the energy, classical or quadrature order or as a certificate."""

from __future__ import annotations

import json

from support.clirun import run_cli

# One stage, a = 1/2 + 10⁻⁴⁰, b = 1.  By hand: R(z) = (1 + (1 − a)z)/(1 − az), so
# R(z)R(−z) − 1 = 2(a − 1/2)z²/(1 − a²z²) = 2·10⁻⁴⁰ z² + O(z⁴) ≠ 0: the one m = 2
# condition at order 2 fails and the energy order is exactly 1; Σ b_i c_i = a ≠ 1/2, so
# the quadrature and classical orders are exactly 1.
NEAR_MIDPOINT = {"A": [["1/2 + 10^-40"]], "b": ["1"]}


def _verify(capsys, path, *args):
    run = run_cli(capsys, "verify", str(path), *args)
    return run


def test_forced_balls_do_not_count_digits_in_the_energy_order(tmp_path, capsys):
    path = tmp_path / "mid.json"
    path.write_text(json.dumps(NEAR_MIDPOINT))
    exact = json.loads(_verify(capsys, path, "--degree", "2", "--order", "4", "--format", "json").out)["summary"]
    assert exact["energy_order"] == 1 and exact["conditions_failed"] == 2  # the slower exact route agrees
    balls = _verify(capsys, path, "--degree", "2", "--order", "4", "--arithmetic", "ball", "--dps", "30")
    line = next(x for x in balls.out.splitlines() if x.startswith("energy order"))
    assert "≥ 4" not in line
    assert line.split()[2] == "1," and "holds to 38 digits beyond order 1 up to order 4" in line
    doc = json.loads(_verify(capsys, path, "--degree", "2", "--order", "4", "--arithmetic", "ball", "--dps", "30",
                             "--format", "json").out)["summary"]
    # the proven order never exceeds the true one; the reach to digits is the old number
    assert doc["energy_order"] <= exact["energy_order"]
    assert (doc["energy_order"], doc["energy_order_to_digits"], doc["energy_order_digits"]) == (1, 4, 38)
    assert doc["energy_order_label"] == "1; ≥ 4 to 38 digits"
    # the classical and quadrature orders are the tableau's own, exact whatever the
    # conditions were evaluated in: Σb = 1 exactly, Σbc = a ≠ 1/2 (by hand, above)
    for key in ("classical_order", "quadrature_order"):
        assert exact[key] == doc[key] == 1 and doc[f"{key}_to_digits"] == 1 and doc[f"{key}_digits"] is None


def _rk4_16_digits(tmp_path):
    # RK4 with 16 significant digits: 1/6 → 0.1666666666666667, 1/3 → 0.3333333333333333
    A = [["0"] * 4, ["0.5000000000000000", "0", "0", "0"], ["0", "0.5000000000000000", "0", "0"],
         ["0", "0", "1", "0"]]
    b = ["0.1666666666666667", "0.3333333333333333", "0.3333333333333333", "0.1666666666666667"]
    path = tmp_path / "rk4-16.json"
    path.write_text(json.dumps({"A": A, "b": b}))
    return path


def test_fail_headline_qualifies_an_order_reached_to_digits(tmp_path, capsys):
    path = _rk4_16_digits(tmp_path)
    # By hand, at face value: Σb = 2(0.1666666666666667 + 0.3333333333333333) = 1 and
    # Σbc = 0.3333333333333333 + 0.1666666666666667 = 1/2 exactly, but Σbc² =
    # 0.3333333333333333/2 + 0.1666666666666667 = 0.33333333333333335 ≠ 1/3: order 2.
    face = json.loads(_verify(capsys, path, "--degree", "3", "--order", "6", "--decimals", "exact",
                              "--format", "json").out)["summary"]
    assert face["energy_order"] == 2 and face["classical_order"] == 2
    run = _verify(capsys, path, "--degree", "3", "--order", "6")
    assert run.code == 1
    head = run.out.strip().splitlines()[-1]
    assert head.startswith("FAIL: 7 of 12 conditions fail; energy order ")
    # as the per-order table says: every condition of orders 2–4 holds to ≥ 15 digits
    table = {int(r.split()[0]): r.split() for r in run.out.splitlines() if r.split()[:1] in (["2"], ["3"], ["4"])}
    digits = min(int(row[-1]) for row in table.values())
    assert head.endswith(f"energy order 1, holds to {digits} digits beyond order 1 up to order 4")
    assert digits == 15
    for what in ("quadrature order", "classical order"):
        row = next(x for x in run.out.splitlines() if x.startswith(what))
        assert f"holds to {digits} digits beyond order 0 up to order 4" in row


def test_a_numerical_certificate_is_not_energy_order_all(capsys):
    from support.paths import TABLEAUX

    doc = json.loads(run_cli(capsys, "verify", str(TABLEAUX / "avf" / "avf-gauss-2-decimal16.toml"),
                             "--format", "json").out)["summary"]
    assert doc["certificate"]["state"] == "holds_to_digits"
    assert doc["energy_order_all"] is False and doc["energy_order_all_digits"] == doc["certificate"]["digits"]
    assert doc["energy_order_label"] == f"all to {doc['certificate']['digits']} digits"
    assert doc["passed"] is True and doc["proven"] is False
    exact = json.loads(run_cli(capsys, "verify", str(TABLEAUX / "avf" / "avf-gauss-2.toml"),
                               "--format", "json").out)["summary"]
    assert exact["energy_order_all"] is True and exact["energy_order_all_digits"] is None


def test_claims_met_to_digits_say_so(capsys):
    from support.paths import TABLEAUX

    doc = json.loads(run_cli(capsys, "verify", str(TABLEAUX / "avf" / "avf-gauss-2-decimal16.toml"),
                             "--format", "json").out)
    claims = {(c["claim"], c["degree"]): c for c in doc["claims"]}
    quad = claims[("quadrature_order", None)]
    assert quad["met"] and quad["found"].endswith("digits") and "proven to order 1" in quad["note"]
    assert claims[("energy_order", 4)]["found"].startswith("all to ")


def test_quadratic_energy_order_counts_exact_coefficients_only(tmp_path, capsys):
    # RK4: R(z) = 1 + z + z²/2 + z³/6 + z⁴/24, so R(z)R(−z) − 1 = −z⁶/72 + z⁸/576 (by hand:
    # e_2 = 2·1/2 − 1 = 0, e_4 = 2·1/24 − 2·1/6 + 1/4 = 0): order 5 for m = 2.  With
    # 16-digit decimals e_2 and e_4 vanish only to digits: proven 1, reached 5.
    path = _rk4_16_digits(tmp_path)
    doc = json.loads(_verify(capsys, path, "--degree", "2", "--order", "6", "--format", "json").out)
    st = doc["summary"]["stability"]
    assert (st["quadratic_energy_order"], st["quadratic_energy_order_to_digits"]) == (1, 5)
    assert st["quadratic_energy_order_digits"] >= 15
    face = json.loads(_verify(capsys, path, "--degree", "2", "--order", "6", "--decimals", "exact",
                              "--format", "json").out)["summary"]["stability"]
    assert face["quadratic_energy_order"] == face["quadratic_energy_order_to_digits"]


def _classical(A, b, order=4):
    import rkcheck

    summary = json.loads(rkcheck.verify(rkcheck.from_arrays(A, b), degree=2, order=order).to_json())["summary"]
    return {k[len("classical_"):]: v for k, v in summary.items() if k.startswith("classical_")}


def test_a_classical_condition_free_of_the_decimals_is_proven():
    # b exact, A one 7-digit decimal: Σb = 1 involves no decimal (exact on the whole
    # box: order 1 proven), Σbc = 0.1234567 ± 5·10⁻⁸ ≠ 1/2 (fails everywhere)
    got = _classical([["0.1234567"]], ["1"])
    assert (got["order"], got["order_to_digits"], got["order_digits"], got["first_failure"]) == (1, 1, None,
                                                                                               "a([τ]) = 1/2")
    # a decimal met only through a zero weight: b = (1, 0) never reads stage 2, so
    # Σb = 1 and Σbc = c₁ = 1/2 hold exactly; Σbc² = 1/4 ≠ 1/3 fails
    got = _classical([["1/2", "0"], ["0.1234567", "0"]], ["1", "0"])
    assert (got["order"], got["order_digits"], got["first_failure"]) == (2, None, "a([τ²]) = 1/3")


def test_a_classical_condition_that_meets_a_decimal_holds_only_to_digits():
    # Σbc = a, and a = 0.5000000 stands for [0.49999995, 0.50000005] ∋ 1/2: not proven
    got = _classical([["0.5000000"]], ["1"])
    assert (got["order"], got["order_to_digits"], got["first_failure"]) == (1, 2, "a([τ²]) = 1/3")
    assert got["order_digits"] is not None and 7 <= got["order_digits"] <= 8
