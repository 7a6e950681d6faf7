"""The classical methods of ``rkcheck new``: every claim re-derived by a second route.

Classical order: brute force over all rooted trees (tests/support/reference.py, sympy
for entries with square roots).  Quadrature order: Σ b_i c_i^(k−1) = 1/k with sympy.
Energy order for degree 2: the first nonzero term of R(z)R(−z) − 1 (sympy series of the
stability function R(z) = 1 + z bᵀ(I − zA)⁻¹1), which is independent of the free-tree
machinery.  Finally rkcheck itself must agree with the claims."""

from __future__ import annotations

import pytest
import sympy as sp
from support import reference as ref

from rkcheck.energy.check import check
from rkcheck.energy.claims import check_claims
from rkcheck.methods.classics import CLASSICS, NAMES, classic, classic_tableau
from rkcheck.options import CheckOptions

z = sp.symbols("z")


def sym(spec):
    loc = {k: sp.sympify(v) for k, v in spec.constants.items()}
    A = [[sp.nsimplify(sp.sympify(x, locals=loc)) for x in row] for row in spec.A]
    b = [sp.nsimplify(sp.sympify(x, locals=loc)) for x in spec.b]
    return A, b


def weight(seq, A, b):
    s = len(b)

    def phi(t):
        out = [sp.Integer(1)] * s
        for sub in ref.split_children(t):
            p = phi(sub)
            out = [out[i] * sum(A[i][j] * p[j] for j in range(s)) for i in range(s)]
        return out

    return sp.expand(sum(b[i] * x for i, x in enumerate(phi(seq))))


def classical_order(A, b, limit=6):
    p = 0
    for n in range(1, limit + 1):
        if all(sp.expand(weight(t, A, b) - sp.Rational(1, ref.gamma(t))) == 0 for t in ref.rooted_trees(n)):
            p = n
        else:
            break
    return p


@pytest.mark.parametrize("key", sorted(CLASSICS))
def test_claims_by_a_second_route(key):
    spec = CLASSICS[key]
    A, b = sym(spec)
    s = len(b)
    c = [sum(row) for row in A]
    assert classical_order(A, b, spec.classical_order + 1) == spec.classical_order
    q = 0
    while sp.expand(sum(b[i] * c[i] ** q for i in range(s)) - sp.Rational(1, q + 1)) == 0:
        q += 1
    assert q == spec.quadrature_order
    R = 1 + z * (sp.Matrix([b]) * (sp.eye(s) - z * sp.Matrix(A)).inv() * sp.ones(s, 1))[0]
    RR = sp.cancel(sp.together(R * R.subs(z, -z)))
    num, den = sp.fraction(RR)
    # R(z)R(−z) − 1 = (num − den)/den with den(0) ≠ 0: its first term is that of num − den
    diff = sp.Poly(sp.expand(num - den), z)
    terms = sorted(k for (k,), coef in diff.terms() if sp.expand(coef) != 0)
    expected = "all" if not terms else terms[0] - 1
    assert spec.energy_order_quadratic == expected


@pytest.mark.parametrize("key", sorted(CLASSICS))
def test_rkcheck_meets_the_claims(key):
    tab = classic_tableau(key)
    base = CheckOptions(order=6)
    results = check_claims(tab, tab.info.claims, base, check)
    assert results and all(r.met for r in results), [(r.claim.kind, r.found, r.note) for r in results]


def test_rational_classics_agree_with_the_fraction_reference():
    for spec in CLASSICS.values():
        if spec.constants:
            continue
        tab = classic_tableau(spec.key)
        assert ref.classical_order(tab.exact_A(), tab.exact_b(), 6) == spec.classical_order


def test_names_and_aliases():
    assert classic("RK4") is CLASSICS["rk4"] and classic("crank-nicolson") is CLASSICS["trapezoid"]
    assert classic("nope") is None
    assert set(NAMES.values()) == set(CLASSICS)
    assert {"rk4", "rk38", "heun", "ralston", "midpoint", "sdirk2"} <= set(CLASSICS)


def test_c_is_the_row_sums():
    for spec in CLASSICS.values():
        A, b = sym(spec)
        loc = {k: sp.sympify(v) for k, v in spec.constants.items()}
        for row, ci in zip(A, spec.c):
            assert sp.simplify(sum(row) - sp.sympify(ci, locals=loc)) == 0
