"""[expect] claims on the tableau's own algebra: symplectic, symmetric, stability_defect.

Expected values: RK4's R(z)R(−z) − 1 = z⁶/72 + z⁸/576 and the implicit midpoint rule's
R = (1 + z/2)/(1 − z/2) (so R(z)R(−z) = 1) by hand; the midpoint rule (Gauss-1) is
symplectic and symmetric, RK4 neither (Hairer–Lubich–Wanner, §VI.4, §V.1)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support.claimfiles import MIDPOINT, RK4, write  # noqa: F401
from support.clirun import run_cli
from support.numbers import exact_under
from support.paths import TABLEAUX, tableau_files


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


def test_algebraic_gauss_claims_are_met(capsys):
    path = TABLEAUX / "collocation" / "gauss-3.toml"
    text = path.read_text(encoding="utf-8")
    assert "symplectic = true" in text and "symmetric = true" in text and "stability_defect = 0" in text
    code, cs = claims(capsys, str(path))
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


# ------------------------------------------- shipped claims by a second route (sympy)

import sympy  # noqa: E402

from rkcheck.io.loader import load  # noqa: E402

# rational tableaux: sympy takes their entries as they are (the algebraic ones are checked
# exactly against their own claims by tests/methods' shipped-claims test)
SHIPPED = [f for f in tableau_files() if load(f).is_rational and exact_under(load(f), "rounded")]


@pytest.mark.parametrize("path", SHIPPED, ids=[str(Path(f).relative_to(TABLEAUX)) for f in SHIPPED])
def test_shipped_property_claims_agree_with_sympy(path):
    tab = load(path)
    A = sympy.Matrix([[sympy.Rational(x.numerator, x.denominator) for x in row] for row in tab.exact_A()])
    b = sympy.Matrix([sympy.Rational(x.numerator, x.denominator) for x in tab.exact_b()])
    s, z = len(b), sympy.Symbol("z")
    for claim in tab.info.claims:
        if claim.kind == "symplectic":
            M = sympy.diag(*b) * A + A.T * sympy.diag(*b) - b * b.T
            # M = 0 as written proves symplecticity; a claim 'false' needs M ≠ 0 as written
            # (the converse needs the irreducible form: Lobatto IIIB-2 is the midpoint rule)
            if M == sympy.zeros(s, s):
                assert claim.value is True
            if claim.value is False:
                assert M != sympy.zeros(s, s)
        elif claim.kind == "stability_defect":
            I, one = sympy.eye(s), sympy.ones(s, 1)
            R = sympy.cancel((I - z * A + z * one * b.T).det() / (I - z * A).det())
            E = sympy.cancel(R * R.subs(z, -z) - 1)
            if claim.power is None:
                assert E == 0
            else:
                series = sympy.series(E, z, 0, claim.power + 1).removeO()
                assert sympy.expand(series - sympy.Rational(claim.coefficient) * z**claim.power) == 0
