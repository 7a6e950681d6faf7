"""Exact energy residuals of tableaux with entries in a number field (the modular engine
over ``Z[θ]``) against sympy arithmetic on the reference's conditions.

Independent route: the conditions (rootings, signs, σ) come from
``support.reference.energy_conditions`` (brute force, nothing from rkcheck); elementary
weights are recomputed here with sympy in ``Q(√n)`` (polynomials in ``r`` reduced modulo
``r² − n``).  Published facts used: AVF over a rule of quadrature order q preserves every
polynomial Hamiltonian of degree ≤ q (seed §1), so AVF over Gauss-2 (q = 4) and Gauss-3
(q = 6) satisfy every condition of degree ≤ q; Gauss collocation preserves quadratic
Hamiltonians (degree 2: every condition holds).
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import pytest
import sympy as sp
from support import reference as ref
from support.numbers import exact_under

from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_field
from rkcheck.methods.tableau import Tableau
from rkcheck.trees.listing import ConditionListing

R = sp.Symbol("r")

GAUSS2 = {  # c = 1/2 ∓ √3/6
    "A": [["1/4", "1/4 - sqrt(3)/6"], ["1/4 + sqrt(3)/6", "1/4"]],
    "b": ["1/2", "1/2"],
}
GAUSS3 = {
    "A": [["5/36", "2/9 - sqrt(15)/15", "5/36 - sqrt(15)/30"],
          ["5/36 + sqrt(15)/24", "2/9", "5/36 - sqrt(15)/24"],
          ["5/36 + sqrt(15)/30", "2/9 + sqrt(15)/15", "5/36"]],
    "b": ["5/18", "4/9", "5/18"],
}


def avf(rule):
    """A = c bᵀ over the rule's nodes c = A·1 (as text)."""
    c = [" + ".join(f"({x})" for x in row) for row in rule["A"]]
    return {"A": [[f"({ci})*({bj})" for bj in rule["b"]] for ci in c], "b": rule["b"]}


def tableau(spec):
    return Tableau.from_values(spec["A"], spec["b"])


# --------------------------------------------------------------- sympy reference

def _sym(text: str, n: int):
    """An entry text as a sympy polynomial in r = √n (only sqrt(n) occurs)."""
    e = sp.sympify(text.replace("^", "**"), locals={"sqrt": sp.sqrt})
    return sp.Poly(sp.expand(e.subs(sp.sqrt(n), R)), R, domain="QQ").rem(sp.Poly(R**2 - n, R))


def sympy_residuals(spec, n: int, vertices: int):
    """{centre canonical id: residual as (a, b) meaning a + b√n} for every condition."""
    mod = sp.Poly(R**2 - n, R)
    A = [[_sym(x, n) for x in row] for row in spec["A"]]
    b = [_sym(x, n) for x in spec["b"]]
    s = len(b)
    one = sp.Poly(1, R, domain="QQ")

    @lru_cache(maxsize=None)
    def phi(t):
        out = [one] * s
        for child in ref.split_children(t):
            v = phi(child)
            Av = [sum((A[i][j] * v[j] for j in range(s)), sp.Poly(0, R, domain="QQ")).rem(mod) for i in range(s)]
            out = [(out[i] * Av[i]).rem(mod) for i in range(s)]
        return tuple(out)

    def weight(t):
        v = phi(t)
        return sum((b[i] * v[i] for i in range(s)), sp.Poly(0, R, domain="QQ")).rem(mod)

    out = {}
    for cond in ref.energy_conditions(vertices):
        total = sp.Poly(0, R, domain="QQ")
        for _u, sign, sig, forest in cond["terms"]:
            w = one
            for t in forest:
                w = (w * weight(t)).rem(mod)
            total += w * sp.Rational(sign, sig)
        c = total.all_coeffs()[::-1] + [0, 0]
        out[cond["id"]] = (Fraction(str(c[0])), Fraction(str(c[1])))
    return out


# --------------------------------------------------------------- engine

def engine_residuals(tab, max_order: int, degree=None):
    listing = ConditionListing(max_order, degree)
    values = tab.exact_values()
    scaled = scaled_field(values)
    sums = exact_condition_sums(scaled, listing)
    return listing, sums


@pytest.mark.parametrize("rule, degree", [(GAUSS2, 4), (GAUSS3, 6)])
def test_avf_over_gauss_holds_exactly_through_order_8(rule, degree):
    tab = tableau(avf(rule))
    assert exact_under(tab, "rounded") and tab.exact_values().field is not None
    listing, sums = engine_residuals(tab, 8, degree)
    for n, o in sums.items():
        assert o.is_zero().all(), n
    # one degree beyond the quadrature order the star condition Σ b c^q = 1/(q+1) fails
    _, over = engine_residuals(tab, degree + 1, degree + 1)
    assert not over[degree + 2].is_zero().all()


@pytest.mark.parametrize("rule", [GAUSS2, GAUSS3])
def test_gauss_collocation_degree_2_holds_exactly(rule):
    _, sums = engine_residuals(tableau(rule), 8, 2)
    assert all(o.is_zero().all() for o in sums.values())


def _compare(spec, n, vertices_max):
    tab = tableau(spec)
    listing, sums = engine_residuals(tab, vertices_max - 1)
    nonzero = 0
    for vertices in range(3, vertices_max + 1):
        want = sympy_residuals(spec, n, vertices)
        o = sums[vertices]
        assert len(o.residues) == len(want)
        whole = o.values()  # every condition at once (one Vandermonde inverse per prime)
        for k in range(len(o.residues)):
            seq = listing.record(vertices, k).level_sequence
            for value in (o.value(k), whole[k]):
                v = value * listing.flip(vertices, k)
                if isinstance(v, Fraction):
                    got = (v, Fraction(0))
                else:
                    got = (v.coeffs[0], v.coeffs[1])
                    assert v.field.sqrt_of == n
                assert got == want[seq], (vertices, seq)
            assert bool(o.is_zero()[k]) == (got == (0, 0))
            nonzero += got != (0, 0)
    return nonzero


def test_gauss2_residuals_equal_sympy_and_the_issue_values():
    # the issue's sympy cross-check: R = −1/432 for 1,2,3,3,3,2 and 1/288 for 1,2,3,2,3,2
    assert _compare(GAUSS2, 3, 6) > 0
    want = sympy_residuals(GAUSS2, 3, 6)
    assert want[(1, 2, 3, 3, 3, 2)] == (Fraction(-1, 432), 0)
    assert want[(1, 2, 3, 2, 3, 2)] == (Fraction(1, 288), 0)


def test_perturbed_algebraic_tableau_gives_the_exact_irrational_residual():
    spec = {"A": [["1/4 + sqrt(3)/100", "1/4 - sqrt(3)/6"], ["1/4 + sqrt(3)/6", "1/4 - 2/7"]],
            "b": ["1/2 + sqrt(3)/11", "1/2"]}
    assert _compare(spec, 3, 7) > 10


def test_degree_8_field_avf_over_gauss_4():
    # Gauss-4's nodes 1/2 ± sqrt(3/28 ± sqrt(30)/70) generate a degree-8 field; AVF over the
    # 4-point rule (q = 8) satisfies every condition of degree ≤ 8
    from support.paths import TABLEAUX

    from rkcheck.io.loader import load

    tab = load(str(TABLEAUX / "avf" / "avf-gauss-4.toml"))
    values = tab.exact_values()
    assert values.field.degree == 8
    scaled = scaled_field(values)
    assert scaled.minpoly[-1] == 1 and all(isinstance(c, int) for c in scaled.minpoly)
    _, sums = engine_residuals(tab, 7, 8)
    assert all(o.is_zero().all() for o in sums.values())


def test_vandermonde_bound_is_an_upper_bound():
    import mpmath

    tab = tableau(GAUSS3)
    scaled = scaled_field(tab.exact_values())
    with mpmath.workdps(50):  # never the global precision: other tests rely on its default
        g = [mpmath.mpf(c) for c in reversed(scaled.minpoly)]
        try:  # the order said: mpmath 1.4 deprecates descending coefficients by default
            roots = mpmath.polyroots(g, maxsteps=200, extraprec=200, asc=False)
        except TypeError:  # before 1.4 they were always descending
            roots = mpmath.polyroots(g, maxsteps=200, extraprec=200)
        V = mpmath.matrix([[r**k for k in range(len(roots))] for r in roots])
        W = V**-1
        norm = max(sum(abs(W[i, j]) for j in range(W.cols)) for i in range(W.rows))
    assert mpmath.log(norm, 2) <= scaled.log2_Vinv <= mpmath.log(norm, 2) + 1e-6


def test_scaled_field_makes_theta_an_algebraic_integer():
    # θ = √3/2 (minimal polynomial x² − 3/4): λ = 2 gives θ̃ = √3 with x² − 3, and the
    # entries' coefficients are rewritten in the basis 1, √3 (by hand: 1/2 + θ = 1/2 + √3/2)
    from rkcheck.methods.tableau import ExactValues
    from rkcheck.numbers.algebraic import NumberField

    K = NumberField([Fraction(-3, 4), 0, 1], 2)
    theta = K.gen
    values = ExactValues(K, [[theta, K(Fraction(1, 2)) + theta], [K(0), K(1)]], [K(Fraction(1, 2)), K(Fraction(1, 2))], None)
    scaled = scaled_field(values)
    assert scaled.theta_scale == 2 and scaled.minpoly == [-3, 0, 1]
    assert scaled.d == 2
    assert scaled.A == [[[0, 1], [1, 1]], [[0, 0], [2, 0]]]  # 2·(√3/2) = √3, 2·(1/2 + √3/2)
    back = scaled.field_element([1, 1], 2)  # (1 + √3)/2 = 1/2 + θ
    assert back == K(Fraction(1, 2)) + theta


@pytest.mark.parametrize("spec", [GAUSS3, avf(GAUSS2)], ids=["gauss-3", "avf-gauss-2"])
def test_integrality_denominator_is_the_least_that_makes_every_entry_integral(spec):
    # definition, checked with sympy's minimal polynomials (not FLINT's charpoly): e·x is
    # an algebraic integer for every entry, and no proper divisor e/q does that
    from rkcheck.evaluation.field_bounds import integrality_denominator

    values = tableau(spec).exact_values()
    e = integrality_denominator([x for row in values.A for x in row] + list(values.b), values.field)
    texts = [x for row in spec["A"] for x in row] + list(spec["b"])
    X = sp.Symbol("X")

    def integral(k: int, text: str) -> bool:
        x = sp.sympify(text.replace("^", "**"), locals={"sqrt": sp.sqrt})
        poly = sp.Poly(sp.minimal_polynomial(k * x, X), X)
        return all(c.is_integer for c in poly.monic().all_coeffs())

    assert all(integral(e, t) for t in texts)
    for q in sp.primefactors(e):
        assert not all(integral(e // q, t) for t in texts), q


def test_values_complete_on_demand(monkeypatch):
    # a nonzero residual in a field needs the coefficients' bound, larger than the
    # decision's: the missing primes are evaluated once, on demand.  The decision is made
    # to stop 2 primes short here so that the path runs on a small field whose values
    # sympy checks independently.
    from rkcheck.evaluation.scaled import ScaledTableau

    spec = {"A": [["1/4 + sqrt(3)/100", "1/4 - sqrt(3)/6"], ["1/4 + sqrt(3)/6", "1/4 - 2/7"]],
            "b": ["1/2 + sqrt(3)/11", "1/2"]}
    monkeypatch.setattr(ScaledTableau, "decision_bits", lambda self, n, t, weight=None: self.coefficient_bits(n, t) - 58)
    listing, sums = engine_residuals(tableau(spec), 6)
    o = sums[7]
    decided = len(o.primes)
    want = sympy_residuals(spec, 3, 7)
    k = next(k for k in range(len(o.residues)) if not o.is_zero()[k])
    v = o.value(k) * listing.flip(7, k)
    assert len(o.primes) == decided + 2
    assert (v.coeffs[0], v.coeffs[1]) == want[listing.record(7, k).level_sequence]


def test_the_norm_decision_needs_fewer_primes_for_gauss_5():
    # The Gauss-5 case: the integrality denominator is a proper divisor of the power
    # basis's, and with the geometric mean over embeddings the decision at order 10 needs
    # fewer than half the primes the coefficients would
    from support.paths import TABLEAUX

    from rkcheck.io.loader import load

    scaled = scaled_field(load(str(TABLEAUX / "collocation" / "gauss-5.toml")).exact_values())
    assert scaled.d % scaled.integral_d == 0 and scaled.integral_d < scaled.d
    listing = ConditionListing(10, None)
    terms = listing.orders[10].max_terms
    assert len(scaled.primes_for(scaled.decision_bits(10, terms))) < len(scaled.primes_for(scaled.coefficient_bits(10, terms))) / 2


@pytest.mark.parametrize("path", ["collocation/gauss-5.toml", "avf/avf-gauss-4.toml", "collocation/radau-iia-3.toml",
                                  "explicit/rk4.toml"])
def test_channels_in_one_pass_equal_channel_by_channel(path, monkeypatch):
    # every root of every prime in one pass (PrimeChannels) against one ModularChannel
    # pass per (prime, root): the same residues, bit for bit, for every condition up to
    # order 9; and the exact sums with one prime per pass equal those with all at once
    import numpy as np
    from support.paths import TABLEAUX

    import rkcheck.evaluation.scaled as scaled_module
    from rkcheck.evaluation.algorithm import condition_sums
    from rkcheck.io.loader import load

    scaled = scaled_field(load(str(TABLEAUX / path)).exact_values())
    listing = ConditionListing(9, None)
    orders = sorted(listing.orders)
    pairs = [(p, r) for p, roots in scaled.primes_for(120) for r in roots]
    batched = scaled.residues_at(listing, pairs, orders)
    for c, (p, r) in enumerate(pairs):
        alone = condition_sums(listing, scaled.channel(p, r), scaled.s, orders)
        for n in orders:
            assert np.array_equal(batched[n][:, c], alone[n]), (n, p, r)
    all_at_once = exact_condition_sums(scaled, listing)
    values = {n: [all_at_once[n].value(k) for k in range(len(all_at_once[n]))] for n in (3, 4, 5, 6)}
    monkeypatch.setattr(scaled_module, "PASS_BYTES", 0)  # one channel per pass: a prime's roots split
    one_by_one = exact_condition_sums(scaled, listing)
    for n in one_by_one:
        assert one_by_one[n].primes == all_at_once[n].primes, n
        assert np.array_equal(one_by_one[n].residues, all_at_once[n].residues), n
    for n, expected in values.items():  # values that need primes beyond the decision's, too
        assert [one_by_one[n].value(k) for k in range(len(one_by_one[n]))] == expected, n


def test_values_through_the_dual_basis_bound_equal_sympy(monkeypatch):
    # a nonzero residual is rebuilt from g'(θ)·N_e ∈ Z[θ] (O_K ⊆ Z[θ]/g'(θ)) when that
    # bound is below the power basis's (in fields of high degree: HBVM(6, σ)).  Here the
    # power basis's bound is made huge so that the dual route runs on a small field,
    # whose values sympy computes independently
    from rkcheck.evaluation.scaled import ScaledTableau

    spec = {"A": [["1/4 + sqrt(5)/100", "1/4 - (1 + sqrt(5))/6"], ["1/4 + sqrt(5)/6", "1/4 - 2/7"]],
            "b": ["1/2 + (1 + sqrt(5))/22", "1/2"]}
    monkeypatch.setattr(ScaledTableau, "coefficient_bits", lambda self, n, t: 10**6)
    listing, sums = engine_residuals(tableau(spec), 6)
    o = sums[7]
    assert o.dual
    want = sympy_residuals(spec, 5, 7)
    checked = 0
    whole = o.values()  # the whole order at once, through the same dual basis
    for k in range(len(o.residues)):
        if not o.is_zero()[k]:
            for value in (o.value(k), whole[k]):
                v = value * listing.flip(7, k)
                assert (v.coeffs[0], v.coeffs[1]) == want[listing.record(7, k).level_sequence]
            checked += 1
    assert checked > 5
