"""The seed's s = 2, m = 3 family (SPEC §4, seed §2.4) and 2-stage Gauss collocation,
checked through the high-level ``check`` path against sympy exact algebra.

Derivations (by hand, confirmed symbolically below):

* shifted Legendre ``P_1 = 2x−1``, ``P_2 = 6x²−6x+1``; the zeros of ``P_2 − ζP_1 =
  6x² − (6+2ζ)x + (1+ζ)`` are ``c = (3 + ζ ∓ √(3+ζ²))/6``; Σb = 1, bᵀc = 1/2 give
  ``b = (1/2 + ζ/(2√(3+ζ²)), 1/2 − ζ/(2√(3+ζ²)))``.  ζ = 0: c = (3 ∓ √3)/6 (Gauss);
  ζ = 1/3: c = (5 ∓ √7)/9, b = 1/2 ± √7/28.
* ``A = c bᵀ + βN``, ``N = ((ζ−1)1 − 2ζc) bᵀ(I − 2C)``; ``N·1 = 0`` because
  ``bᵀ(I−2C)1 = Σb − 2bᵀc = 0``, so the engine's ``c = A·1`` is the same c.
* Engine residuals vs the seed's expressions (see tests/test_conditions.py docstring):
  double bush ``R(t_{1,2}) = −DB_{1,2}/(1!2!)``; asymbush ``R = −S_2/2!``; the seed's
  (3bush) with P = Q = x(x−1), R = 1 equals ``T_{1,0,1} − 2T_{1,0,2} + T_{2,0,2}
  = 2R(t_{1,0,1}) − 4R(t_{1,0,2}) + 8R(t_{2,0,2})`` (σ_M = 2, 2, 8).
"""

from __future__ import annotations

from fractions import Fraction as F
from functools import lru_cache

import pytest
import sympy as sp
from support import reference as ref
from support.shapes import asymbush, double_bush, triple_bush

from rkcheck.energy.check import CheckOptions, check
from rkcheck.methods.tableau import Tableau
from rkcheck.verdicts import FAILS, HOLDS

beta = sp.Symbol("beta")
ZETAS = {"0": 3, "1/3": 7}  # ζ -> squarefree k with √(3+ζ²) ∈ Q(√k)


# ------------------------------------------------------------------ sympy side


@lru_cache(maxsize=None)
def family(zeta: str):
    """(ζ, c, b, N, A(β)) as sympy objects, from the closed forms above."""
    z = sp.Rational(zeta)
    D = 3 + z ** 2
    c = sp.Matrix([(3 + z - sp.sqrt(D)) / 6, (3 + z + sp.sqrt(D)) / 6])
    b = sp.Matrix([sp.Rational(1, 2) + z / (2 * sp.sqrt(D)), sp.Rational(1, 2) - z / (2 * sp.sqrt(D))])
    C = sp.diag(*c)
    one = sp.Matrix([1, 1])
    N = ((z - 1) * one - 2 * z * c) * b.T * (sp.eye(2) - 2 * C)
    A = c * b.T + beta * N
    return z, c, b, N, A


def simp(e):
    return sp.expand(sp.radsimp(sp.expand(e)))


def vpow(v, k):
    return v.applyfunc(lambda x: x ** k)


def entry_str(e, k: int) -> str:
    """An exact element x + y√k of Q(√k) as an rkcheck entry string."""
    v = simp(e)
    y = v.coeff(sp.sqrt(k))
    x = simp(v - y * sp.sqrt(k))
    assert x.is_Rational and y.is_Rational, v
    return f"({x}) + ({y})*sqrt({k})"


@lru_cache(maxsize=None)
def family_tableau(zeta: str, b_value: str) -> Tableau:
    z, c, b, N, A = family(zeta)
    k = ZETAS[zeta]
    Ab = A.subs(beta, sp.Rational(b_value))
    return Tableau.from_values([[entry_str(Ab[i, j], k) for j in range(2)] for i in range(2)],
                               [entry_str(x, k) for x in b])


@lru_cache(maxsize=None)
def family_check(zeta: str, b_value: str, degree=3, order=8):
    return check(family_tableau(zeta, b_value), CheckOptions(degree=degree, order=order))


class SympyWeights:
    """Elementary weights a(t) = bᵀΦ(t) in sympy (SPEC §2 recursion on level sequences)."""

    def __init__(self, A, b):
        self.A, self.b = A, b
        self._phi = {}

    def phi(self, t):
        if t not in self._phi:
            v = sp.ones(self.A.rows, 1)
            for ch in ref.subtrees_at_root(t):
                v = v.multiply_elementwise(self.A * self.phi(ch)).applyfunc(sp.expand)
            self._phi[t] = v
        return self._phi[t]

    def a(self, t):
        return sp.expand((self.b.T * self.phi(t))[0])

    def residual(self, cond):
        """R of a reference.energy_conditions entry."""
        return simp(sum(sp.Rational(sign, sig) * sp.Mul(*[self.a(t) for t in forest])
                        for _, sign, sig, forest in cond["terms"]))


def encloses(enc, value) -> bool:
    """Does the engine enclosure contain the sympy value?  Exact for rationals."""
    value = simp(value)
    if value.is_Rational:
        return abs(enc.mid - F(int(value.p), int(value.q))) <= enc.rad
    approx = F(str(sp.N(value, 120)))
    return abs(enc.mid - approx) <= enc.rad + F(1, 10 ** 100)


def result_by_id(res, seq):
    rs = [r for r in res.conditions if r.level_sequence == tuple(seq)]
    assert len(rs) == 1, seq
    return rs[0]


DB12_ID = ref.centre_canonical_id(double_bush(1, 2))


# ------------------------------------------------------- (a) symbolic facts


@pytest.mark.parametrize("zeta", list(ZETAS))
def test_family_symbolic_facts(zeta):
    z, c, b, N, A = family(zeta)
    x = sp.Symbol("x")
    P1, P2 = 2 * x - 1, 6 * x ** 2 - 6 * x + 1
    for ci in c:  # the nodes are the zeros of P_2 − ζP_1
        assert simp((P2 - z * P1).subs(x, ci)) == 0
    # quadrature conditions k = 1, 2, 3, and the seed's bᵀc³ = 1/4 + ζ/36 (so not k = 4 unless ζ = 0)
    for k in (1, 2, 3):
        assert simp((b.T * vpow(c, k - 1))[0]) == sp.Rational(1, k)
    assert simp((b.T * vpow(c, 3))[0]) == sp.Rational(1, 4) + z / 36
    # N·1 = 0, hence A·1 = c for every β
    assert [simp(v) for v in N * sp.ones(2, 1)] == [0, 0]
    cc = (A * sp.ones(2, 1)).applyfunc(simp)
    assert cc == c.applyfunc(simp)
    # double bush (p, q) = (1, 2), seed eq. (DBmono): bᵀAc² − 2bᵀCAc = 1/3 − 1/2 for all β
    db = (b.T * A * vpow(cc, 2))[0] - 2 * (b.T * sp.diag(*cc) * A * cc)[0]
    assert sp.Poly(simp(db), beta).all_coeffs() == [sp.Rational(1, 3) - sp.Rational(1, 2)]
    # ... because N is in the kernel of M: bᵀNc² − 2bᵀCNc = 0
    assert simp((b.T * N * vpow(c, 2))[0] - 2 * (b.T * sp.diag(*c) * N * c)[0]) == 0


def test_family_closed_form_nodes():
    # hand values: ζ = 0 gives Gauss (3 ∓ √3)/6, ζ = 1/3 gives (5 ∓ √7)/9, b = 1/2 ± √7/28
    _, c, b, _, _ = family("0")
    assert [simp(v) for v in c] == [simp((3 - sp.sqrt(3)) / 6), simp((3 + sp.sqrt(3)) / 6)]
    _, c, b, _, _ = family("1/3")
    assert [simp(v) for v in c] == [simp((5 - sp.sqrt(7)) / 9), simp((5 + sp.sqrt(7)) / 9)]
    assert [simp(v) for v in b] == [simp(sp.Rational(1, 2) + sp.sqrt(7) / 28),
                                    simp(sp.Rational(1, 2) - sp.sqrt(7) / 28)]


# ----------------------------------------------------- (b) double bush holds


@pytest.mark.parametrize("zeta", list(ZETAS))
@pytest.mark.parametrize("b_value", ["1/10", "1/1000000000000"])
def test_double_bush_holds_in_the_family(zeta, b_value):
    # (a) shows DB_{1,2} = 0 exactly for all β; the square roots are decided exactly in
    # their number field, so the verdict is an exact `holds`
    assert DB12_ID == (1, 2, 3, 3, 2)  # hand: [τ[τ²]], rooted at the 1-leaf bush
    res = family_check(zeta, b_value)
    assert res.backend == "exact"
    r = result_by_id(res, DB12_ID)
    assert r.verdict.state == HOLDS


# ------------------------------------------- (c) β = 1/10 fails, β = 0 is AVF


@lru_cache(maxsize=None)
def sympy_residuals(zeta: str, b_value: str, degree: int, max_vertices: int = 9):
    """{id: exact R} for every reference condition with max degree <= degree."""
    z, c, b, N, A = family(zeta)
    W = SympyWeights(A.subs(beta, sp.Rational(b_value)).applyfunc(simp), b.applyfunc(simp))
    return {d["id"]: W.residual(d) for n in range(3, max_vertices + 1)
            for d in ref.energy_conditions(n, degree)}


@pytest.mark.parametrize("zeta", list(ZETAS))
def test_beta_tenth_fails_exactly_where_sympy_says(zeta):
    res = family_check(zeta, "1/10")
    assert res.failures, "β ≠ 0: the minimal-stage method is not AVF, some condition fails"
    assert all(r.max_degree <= 3 for r in res.failures)
    assert not res.avf.equals_avf
    # expected: the exact residual of every condition (reference conditions, sympy weights)
    exact = sympy_residuals(zeta, "1/10", 3)
    assert {r.level_sequence for r in res.conditions} == set(exact)
    assert {r.level_sequence for r in res.failures} == {i for i, v in exact.items() if v != 0}
    for r in res.conditions:
        assert encloses(r.enclosure, exact[r.level_sequence]), r.id
    first_bad = min(len(i) for i, v in exact.items() if v != 0)
    assert res.energy_order == first_bad - 2


@pytest.mark.parametrize("zeta", list(ZETAS))
def test_beta_zero_is_avf(zeta):
    res = family_check(zeta, "0")
    assert res.failures == []
    assert all(r.verdict.state == HOLDS for r in res.conditions)
    assert res.avf is not None and res.avf.equals_avf
    assert res.energy_order_all and res.energy_order == 8
    assert res.quadrature.order == (4 if zeta == "0" else 3)  # bᵀc³ = 1/4 + ζ/36


# ------------------------------------------------ (d) tiny β fails, quadratically


def max_failure(res):
    return max(abs(r.enclosure.mid) for r in res.failures)


@pytest.mark.parametrize("zeta", list(ZETAS))
def test_tiny_beta_fails_at_default_precision(zeta):
    res = family_check(zeta, "1/1000000000000")  # dps 50 (default), order 8, degree 3
    assert res.options.dps == 50
    assert res.failures
    biggest = max_failure(res)
    assert F(1, 10 ** 27) <= biggest <= F(1, 10 ** 21)  # ~β² = 1e-24
    assert all(abs(r.enclosure.mid) <= F(1, 10 ** 21) for r in res.failures)
    # quadratic: 1e-6 vs 1e-12 -> ratio (1e6)² = 1e12 within 1%
    ratio = max_failure(family_check(zeta, "1/1000000")) / biggest
    assert abs(ratio / 10 ** 12 - 1) < F(1, 100)


# --------------------------------------------------- (e) the seed closed forms


def three_bush_seed(zeta: str):
    """Seed eq. (3bush) with P = Q = x(x−1), R = 1, symbolic in β."""
    z, c, b, N, A = family(zeta)
    Pc = vpow(c, 2) - c
    dP = sp.diag(*(2 * c - sp.ones(2, 1)))
    intP = sp.Rational(1, 3) - sp.Rational(1, 2)
    # bᵀP'(C)A R(C) A Q(c) + bᵀQ'(C)A R(C) A P(c) − P(1)(…) − Q(1)(…) − bᵀR'(C)(…) + R(1)∫P∫Q
    return simp(2 * (b.T * dP * A * A * Pc)[0] + intP * intP)


def asymbush_seed(zeta: str, q: int = 2):
    """Seed eq. (asymbush), symbolic in β."""
    z, c, b, N, A = family(zeta)
    Ac = A * c
    C = sp.diag(*c)
    return simp((b.T * vpow(Ac, q))[0] - q * (b.T * A * C * vpow(Ac, q - 1))[0]
                + q * (b.T * C * vpow(Ac, q - 1))[0] - sp.Rational(1, 2) ** q)


@pytest.mark.parametrize("zeta", list(ZETAS))
def test_seed_closed_forms_symbolically(zeta):
    # the paper's claims: (3bush) = β²ζ³/81, (asymbush, q = 2) = −β²(1+ζ)²/36
    z = sp.Rational(zeta)
    assert sp.expand(three_bush_seed(zeta) - beta ** 2 * z ** 3 / 81) == 0
    assert sp.expand(asymbush_seed(zeta) + beta ** 2 * (1 + z) ** 2 / 36) == 0
    if z != 0:
        assert three_bush_seed(zeta) != 0  # proves β = 0 for ζ ≠ 0
    else:
        assert three_bush_seed(zeta) == 0  # why the seed needs (asymbush) for ζ = 0


@pytest.mark.parametrize("zeta", list(ZETAS))
@pytest.mark.parametrize("b_value", ["1/10", "1/1000000000000"])
def test_engine_matches_seed_closed_forms(zeta, b_value):
    res = family_check(zeta, b_value)
    bv = sp.Rational(b_value)
    # asymbush q = 2: R = −S_2/2!
    asym = result_by_id(res, ref.centre_canonical_id(asymbush(2)))
    want_asym = -asymbush_seed(zeta).subs(beta, bv) / 2
    assert want_asym != 0
    assert encloses(asym.enclosure, want_asym)
    assert asym.verdict.state == FAILS
    # (3bush), P = Q = x(x−1), R = 1: 2R(t101) − 4R(t102) + 8R(t202)
    weights = {(1, 0, 1): 2, (1, 0, 2): -4, (2, 0, 2): 8}
    mid = rad = F(0)
    for (p, r, q), k in weights.items():
        enc = result_by_id(res, ref.centre_canonical_id(triple_bush(p, r, q))).enclosure
        mid += k * enc.mid
        rad += abs(k) * enc.rad
    want = three_bush_seed(zeta).subs(beta, bv)
    assert want.is_Rational
    assert abs(mid - F(int(want.p), int(want.q))) <= rad
    if zeta != "0":
        assert abs(mid) > rad  # certified nonzero: the engine sees the seed's β²ζ³/81


# ------------------------------------------------ 2-stage Gauss collocation


GAUSS2_A = [["1/4", "1/4 - sqrt(3)/6"], ["1/4 + sqrt(3)/6", "1/4"]]
GAUSS2_B = ["1/2", "1/2"]


@lru_cache(maxsize=None)
def gauss2_sympy_residuals():
    r3 = sp.sqrt(3)
    A = sp.Matrix([[sp.Rational(1, 4), sp.Rational(1, 4) - r3 / 6],
                   [sp.Rational(1, 4) + r3 / 6, sp.Rational(1, 4)]])
    b = sp.Matrix([sp.Rational(1, 2), sp.Rational(1, 2)])
    W = SympyWeights(A, b)
    return {d["id"]: W.residual(d) for n in range(3, 10) for d in ref.energy_conditions(n, 4)}


def test_gauss2_collocation_degree4_energy_order():
    exact = gauss2_sympy_residuals()
    nonzero = {i for i, v in exact.items() if v != 0}
    assert nonzero, "Gauss collocation is not energy preserving for quartic H"
    first_bad = min(len(i) for i in nonzero)  # number of vertices of the first failure
    res = check(Tableau.from_values(GAUSS2_A, GAUSS2_B), CheckOptions(degree=4, order=8))
    assert res.backend == "exact"
    for r in res.conditions:  # the exact residuals in Q(√3) are sympy's
        v = r.residual if isinstance(r.residual, F) else sp.sympify(r.residual.text().replace("^", "**"))
        assert sp.simplify(sp.sympify(v) - exact[r.level_sequence]) == 0
    assert res.energy_order == first_bad - 2
    assert res.classical.order == 4  # 2-stage Gauss: order 2s (Butcher), hand value
    failing_at_first = {r.level_sequence for r in res.failures
                        if r.vertices == first_bad}
    assert failing_at_first == {i for i in nonzero if len(i) == first_bad}
    # and every condition up to 9 vertices agrees with sympy
    assert {r.level_sequence for r in res.conditions} == set(exact)
    assert {r.level_sequence for r in res.failures} == nonzero
    for r in res.conditions:
        assert encloses(r.enclosure, exact[r.level_sequence]), r.id
    assert not res.avf.equals_avf
