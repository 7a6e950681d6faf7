"""Algebraic tableaux are decided exactly (definitions §5): no digits.

Independent derivations:

* AVF over an s-point rule of quadrature order q integrates ``∇H`` along the segment
  exactly when ``deg H ≤ q``, so it preserves every Hamiltonian of degree ``m ≤ q``
  (seed §4, Quispel–McLaren): every energy condition with degree ≤ q holds *exactly*
  (Gauss: q = 2s, Radau: 2s − 1, Lobatto: 2s − 2).
* Gauss-2 collocation, no degree bound, six vertices: ``R(1,2,3,3,3,2) = −1/432`` and
  ``R(1,2,3,2,3,2) = 1/288`` (the issue's sympy cross-check), checked here once more by
  the brute-force reference in sympy's exact arithmetic (``sqrt(3)`` as a symbol-free
  algebraic number).
"""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest
from support import reference as ref

from rkcheck.energy.check import check
from rkcheck.io.loader import loads as load_text
from rkcheck.options import CheckOptions
from rkcheck.verdicts import HOLDS

TABLEAUX = Path(__file__).resolve().parents[2] / "tableaux"

RULES = {"gauss": lambda s: 2 * s, "radau-ii": lambda s: 2 * s - 1, "radau-i": lambda s: 2 * s - 1,
         "lobatto": lambda s: 2 * s - 2}


def _family(rule: str, s: int):
    return load_text(f'[family]\nname = "avf"\ns = {s}\nrule = "{rule}"\n', f"avf-{rule}-{s}.toml")


@pytest.mark.parametrize("rule,s", [(r, s) for r in RULES for s in range(2, 6) if not (r == "lobatto" and s < 3)])
def test_avf_over_algebraic_rules_holds_exactly(rule, s):
    tab = _family(rule, s)
    q = RULES[rule](s)
    # Radau's 5-point nodes generate a field of degree 24 (their quartic's Galois group is
    # S4), the largest field of these rules
    order = 10
    res = check(tab, CheckOptions(degree=q, order=order))
    assert res.backend == "exact", "an algebraic tableau must be checked exactly"
    states = {r.verdict.state for r in res.conditions}
    assert states == {HOLDS}, (rule, s, states)
    assert res.avf is not None and res.avf.equals_avf and res.avf.verdict.state == HOLDS


def _phi(seq, A):
    """Φ(t) by the recursion of definitions §2, in sympy (children from the reference)."""
    import sympy

    s = len(A)
    out = [sympy.Integer(1)] * s
    for child in ref.subtrees_at_root(seq):
        phi = _phi(child, A)
        out = [out[i] * sum(A[i][j] * phi[j] for j in range(s)) for i in range(s)]
    return out


def _residual_sympy(cond, A, b):
    import sympy

    total = sympy.Integer(0)
    for _u, sign, sigma, forest in cond["terms"]:
        term = sympy.Rational(sign, sigma)
        for t in forest:
            term *= sum(bi * p for bi, p in zip(b, _phi(t, A)))
        total += term
    return total


def test_gauss2_residuals_at_six_vertices_are_exact():
    import sympy

    tab = load_text((TABLEAUX / "collocation" / "gauss-2.toml").read_text(), "gauss-2.toml")
    res = check(tab, CheckOptions(degree=None, order=5))
    assert res.backend == "exact"
    got = {r.id: r for r in res.conditions}
    r3 = sympy.sqrt(3)
    A = [[sympy.Rational(1, 4), sympy.Rational(1, 4) - r3 / 6], [sympy.Rational(1, 4) + r3 / 6, sympy.Rational(1, 4)]]
    b = [sympy.Rational(1, 2), sympy.Rational(1, 2)]
    for lseq, expected in (("1,2,3,3,3,2", Fraction(-1, 432)), ("1,2,3,2,3,2", Fraction(1, 288))):
        seq = tuple(int(x) for x in lseq.split(","))
        cond = next(c for c in ref.energy_conditions(6) if ref.canonicalize(seq) in {ref.canonicalize(u) for u, *_ in c["terms"]})
        value = sympy.nsimplify(sympy.expand(_residual_sympy(cond, A, b)))
        assert abs(value) == abs(sympy.Rational(expected.numerator, expected.denominator))
        r = got[lseq]
        assert r.verdict.digits is None and r.verdict.state == "fails"
        assert abs(Fraction(r.enclosure.mid)) == abs(expected) and r.enclosure.rad == 0
