"""Claims ([expect]): met claims pass, each broken claim kind fails naming claimed and found."""

from __future__ import annotations

import json

import pytest
from support.claimfiles import MIDPOINT, RK4, write  # noqa: F401
from support.clirun import run_cli

import rkcheck

# RK4: classical order 4 (Kutta), quadrature order 4 (Simpson's rule: nodes 0, 1/2, 1
# with weights 1/6, 2/3, 1/6 is exact to degree 3), energy order 4 for all H (its h^5
# energy error term does not vanish: see test_verify.test_rk4_energy_order_is_4).
CORRECT_RK4 = 'energy_order = {degree = "none", value = 4}\nclassical_order = 4\nquadrature_order = 4'


def test_honest_rk4_passes_although_higher_conditions_fail(tmp_path, capsys):
    path = write(tmp_path, RK4, CORRECT_RK4)
    r = run_cli(capsys, "verify", path)
    assert r.code == 0, r.out
    assert "all 3 claims met" in r.out
    # the same file judged by its conditions fails
    assert run_cli(capsys, "verify", path, "--fail-on", "conditions").code == 1
    assert run_cli(capsys, "verify", path, "--fail-on", "never").code == 0


# implicit midpoint = AVF for quadratic H (A = c bᵀ with c = 1/2, b = 1, and Σ b c = 1/2):
# energy preserved to all orders for degree 2; not AVF for degree 3 (Σ b c² = 1/4 ≠ 1/3).
WRONG = {
    "energy order": (RK4, 'energy_order = {degree = "none", value = 5}', "energy_order (all H)", "5", "4"),
    "energy all": (RK4, 'energy_order = {degree = 3, value = "all"}', "energy_order (degree 3)", "all", "4"),
    "avf": (MIDPOINT, "avf = {degree = 3, value = true}", "avf (degree 3)", "true", "false"),
    "avf false": (MIDPOINT, "avf = {degree = 2, value = false}", "avf (degree 2)", "false", "true"),
    "classical": (RK4, "classical_order = 5", "classical_order", "5", "4"),
    "quadrature": (MIDPOINT, "quadrature_order = 3", "quadrature_order", "3", "2"),
}


@pytest.mark.parametrize("text, expect, label, claimed, found", list(WRONG.values()), ids=list(WRONG))
def test_each_wrong_claim_fails_naming_claimed_and_found(tmp_path, capsys, text, expect, label, claimed, found):
    path = write(tmp_path, text, expect)
    r = run_cli(capsys, "verify", path, "--format", "json")
    assert r.code == 1
    doc = json.loads(r.out)
    assert doc["summary"]["claims_ok"] is False
    (claim,) = doc["claims"]
    assert (claim["claimed"], claim["found"], claim["met"]) == (claimed, found, False)
    text_run = run_cli(capsys, "verify", path)
    row = next(line for line in text_run.out.splitlines() if line.strip().startswith(label))
    assert claimed in row and found in row and "BROKEN" in row


def test_all_claim_without_certificate_is_met_up_to_n_with_a_note(tmp_path, capsys):
    # RK4 has no failing condition for degree 2 up to order 4 (its stability function is
    # the degree-4 Taylor polynomial of e^z, so R(z)R(-z) - 1 = O(z^6)).
    path = write(tmp_path, RK4, 'energy_order = {degree = 2, order = 4, value = "all"}')
    r = run_cli(capsys, "verify", path, "--format", "json")
    assert r.code == 0
    (claim,) = json.loads(r.out)["claims"]
    assert claim["met"] and claim["note"] == "verified to order 4, not proven beyond"


def test_all_claim_met_by_certificate(tmp_path, capsys):
    path = write(tmp_path, MIDPOINT, 'energy_order = {degree = 2, value = "all"}\navf = {degree = 2, value = true}')
    r = run_cli(capsys, "verify", path, "--format", "json")
    assert r.code == 0
    claims = json.loads(r.out)["claims"]
    assert claims[0]["found"] == "all" and "every order" in claims[0]["note"]


@pytest.mark.parametrize(
    "expect, message",
    [
        ("energy = 3", "expect.energy: unknown claim"),
        ("avf = {value = true}", "expect.avf: missing degree"),
        ("avf = {degree = 3, value = 1}", "expect.avf.value: expected true or false"),
        ('energy_order = {degree = 3, value = "many"}', "expect.energy_order.value: expected an integer"),
        ("classical_order = -1", "expect.classical_order: expected an integer >= 0"),
        ("energy_order = [{degree = 3, value = 2}, {degree = 0, value = 2}]", "expect.energy_order[2].degree"),
    ],
)
def test_malformed_claims_are_user_errors(tmp_path, capsys, expect, message):
    path = write(tmp_path, MIDPOINT, expect)
    r = run_cli(capsys, "verify", path)
    assert r.code == 2 and message in r.err and len(r.err.strip().splitlines()) == 1


def test_a_stability_claim_of_a_continuous_method_is_an_error_naming_it(tmp_path, capsys):
    path = tmp_path / "c1.toml"
    path.write_text('[continuous]\nA = "tau"\n[expect]\nstability_defect = 0\n', encoding="utf-8")
    r = run_cli(capsys, "verify", str(path))
    assert r.code == 2 and len(r.err.splitlines()) == 1
    assert r.err.startswith(f"rkcheck: error: {path}: expect.stability_defect: does not apply to a continuous method")


def test_theorem_1_says_nothing_of_an_inconsistent_method(tmp_path, capsys):
    # AVF Gauss-2 with A and b doubled: every weight of a tree t scales by 2^|t|, so every
    # residual by 2^(n−1): all conditions hold, while Σb = 2 (not AVF, not consistent)
    path = tmp_path / "avf2x.toml"
    path.write_text('[constants]\nc1 = "1/2 - sqrt(3)/6"\nc2 = "1/2 + sqrt(3)/6"\n[tableau]\n'
                    'A = [["c1", "c1"], ["c2", "c2"]]\nb = ["1", "1"]\n', encoding="utf-8")
    r = run_cli(capsys, "verify", str(path), "--degree", "4", "--order", "8")
    assert "all 66" in r.out or "66 energy conditions" in r.out
    assert "Theorem 1" not in r.out and "must fail" not in r.out
    assert rkcheck.verify(path, degree=4, order=8).theorem1 is None
