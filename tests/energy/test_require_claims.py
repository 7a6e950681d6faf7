"""``--require`` gates a file with claims too (definitions §5: a gate that asks for proofs
does not pass a result that holds only to digits): a claim met only to digits, or an
``all`` claim met only by the orders checked, is not a proof; the exit code, the verdict
line and the JSON agree."""

from __future__ import annotations

import json

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

import rkcheck

DECIMAL16 = TABLEAUX / "avf" / "avf-gauss-2-decimal16.toml"  # claims met to 15 digits
RK4_ALL = """[tableau]
A = [[0,0,0,0],["1/2",0,0,0],[0,"1/2",0,0],[0,0,1,0]]
b = ["1/6","1/3","1/3","1/6"]
[expect]
energy_order = {degree = "none", value = "all"}
[check]
order = 4
"""


def test_claims_met_to_digits_fail_a_proof_gate(capsys):
    assert run_cli(capsys, "verify", str(DECIMAL16), "-q").code == 0  # the claims are met
    r = run_cli(capsys, "verify", str(DECIMAL16), "-q", "--require", "proof")
    assert r.code == 1 and "\nFAIL: --require proof" in r.out  # the verdict line, after the warnings
    assert "energy_order = 4 holds only to 15 digits" in " ".join(r.out.split())
    doc = json.loads(run_cli(capsys, "verify", str(DECIMAL16), "--require", "proof", "--format", "json").out)
    assert doc["summary"]["require"]["met"] is False and doc["summary"]["claims_ok"] is True
    assert rkcheck.verify(DECIMAL16, require="proof").failed


@pytest.mark.parametrize("digits, code", [(10, 0), (20, 1)])
def test_claims_met_to_15_digits_meet_10_not_20(capsys, digits, code):
    assert run_cli(capsys, "verify", str(DECIMAL16), "-q", "--require", f"digits:{digits}").code == code


def test_an_all_claim_verified_to_its_order_is_not_a_proof(capsys, tmp_path):
    path = tmp_path / "rk4all.toml"
    path.write_text(RK4_ALL, encoding="utf-8")
    assert run_cli(capsys, "verify", str(path), "-q").code == 0  # verified to order 4, as documented
    r = run_cli(capsys, "verify", str(path), "-q", "--require", "proof")
    assert r.code == 1
    assert "energy_order = all is verified to order 4, not proven beyond" in " ".join(r.out.split())
    # AVF Gauss-2 has an exact certificate of every order: its "all" claim is a proof
    assert run_cli(capsys, "verify", str(TABLEAUX / "avf" / "avf-gauss-2.toml"), "-q", "--require", "proof").code == 0


def test_a_scan_applies_the_gate_to_files_with_claims_and_never_is_never(capsys, tmp_path):
    (tmp_path / "d16.toml").write_text(DECIMAL16.read_text(), encoding="utf-8")
    assert run_cli(capsys, "scan", str(tmp_path), "--require", "proof", "--jobs", "1").code == 1
    assert run_cli(capsys, "scan", str(tmp_path), "--require", "proof", "--jobs", "1", "--fail-on", "never").code == 0
    assert run_cli(capsys, "scan", str(tmp_path), "--jobs", "1").code == 0
