"""[expect] claims on the tableau's own algebra: symplectic, symmetric, stability_defect.

Expected values: RK4's R(z)R(−z) − 1 = z⁶/72 + z⁸/576 and the implicit midpoint rule's
R = (1 + z/2)/(1 − z/2) (so R(z)R(−z) = 1) by hand; the midpoint rule (Gauss-1) is
symplectic and symmetric, RK4 neither (Hairer–Lubich–Wanner, §VI.4, §V.1)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

RK4 = """
[method]
name = "RK4"
[tableau]
A = [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]]
b = ["1/6", "1/3", "1/3", "1/6"]
"""
MIDPOINT = """
[tableau]
A = [["1/2"]]
b = [1]
"""


def write(tmp_path: Path, text: str, expect: str) -> str:
    p = tmp_path / "t.toml"
    p.write_text(text + "\n[expect]\n" + expect + "\n", encoding="utf-8")
    return str(p)


def claims(capsys, path):
    r = run_cli(capsys, "verify", path, "--format", "json")
    return r.code, json.loads(r.out)["claims"]


def test_true_claims_are_met(tmp_path, capsys):
    code, cs = claims(capsys, write(tmp_path, RK4, 'symplectic = false\nsymmetric = {value = false}\n'
                                               'stability_defect = {power = 6, coefficient = "1/72"}'))
    assert code == 0 and all(c["met"] for c in cs)
    assert cs[2]["found"] == "1/72 z^6" and cs[2]["note"] == "R(z)R(−z) − 1 = z⁶/72 + z⁸/576"
    code, cs = claims(capsys, write(tmp_path, MIDPOINT, "symplectic = true\nsymmetric = true\nstability_defect = 0"))
    assert code == 0 and all(c["met"] for c in cs) and cs[2]["found"] == "0"


WRONG = {
    "symplectic": (RK4, "symplectic = true", "true", "false"),
    "symmetric": (MIDPOINT, "symmetric = false", "false", "true"),
    "identity": (RK4, "stability_defect = 0", "0", "1/72 z^6"),
    "coefficient": (RK4, 'stability_defect = {power = 6, coefficient = "1/36"}', "1/36 z^6", "1/72 z^6"),
    "power": (RK4, 'stability_defect = {power = 4, coefficient = "1/72"}', "1/72 z^4", "1/72 z^6"),
    "not identity": (MIDPOINT, 'stability_defect = {power = 2, coefficient = "1"}', "1 z^2", "0"),
}


@pytest.mark.parametrize("text, expect, claimed, found", list(WRONG.values()), ids=list(WRONG))
def test_wrong_claims_are_broken(tmp_path, capsys, text, expect, claimed, found):
    code, (c,) = claims(capsys, write(tmp_path, text, expect))
    assert code == 1 and (c["claimed"], c["found"], c["met"]) == (claimed, found, False)


def test_algebraic_gauss_claims_are_met(tmp_path, capsys):
    text = (TABLEAUX / "collocation" / "gauss-3.toml").read_text(encoding="utf-8")
    assert text.rstrip().splitlines()[-1].startswith("quadrature_order")  # [expect] is the last table
    p = tmp_path / "gauss-3.toml"
    p.write_text(text + "\nsymplectic = true\nsymmetric = true\nstability_defect = 0\n", encoding="utf-8")
    code, cs = claims(capsys, str(p))
    assert code == 0
    (sym,) = [c for c in cs if c["claim"] == "symplectic"]
    assert sym["met"] and sym["found"] == "true"


@pytest.mark.parametrize(
    "expect, message",
    [
        ("symplectic = 1", "expect.symplectic: expected true or false"),
        ("symmetric = {value = true, degree = 2}", "expect.symmetric: unknown key 'degree'"),
        ('stability_defect = {power = 5, coefficient = "1"}', "expect.stability_defect.power: R(z)R(−z) − 1 is even"),
        ("stability_defect = {power = 6}", "expect.stability_defect: missing coefficient"),
        ('stability_defect = {power = 6, coefficient = "1/0"}', "expect.stability_defect.coefficient"),
        ('stability_defect = {power = 6, coefficient = "0"}', "the leading coefficient is nonzero"),
        ("stability_defect = 3", "expect.stability_defect: expected 0 or a table"),
    ],
)
def test_malformed_property_claims_are_user_errors(tmp_path, capsys, expect, message):
    r = run_cli(capsys, "verify", write(tmp_path, MIDPOINT, expect))
    assert r.code == 2 and message in r.err and len(r.err.strip().splitlines()) == 1
