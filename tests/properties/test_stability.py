"""The stability function R(z) and the certificate R(z)R(−z) ≡ 1 for quadratic H.

Independent routes: by hand (RK4, Heun), sympy's determinants (R = det(I − zA + z1bᵀ) /
det(I − zA)) and series, the brute-force reference implementation of the energy
conditions (tests/support/reference.py), and a sympy-backed exact scalar for algebraic
tableaux (tests/support/symbolic.py).
"""

from __future__ import annotations

import math
import random
from fractions import Fraction as F
from pathlib import Path

import pytest
import sympy
from support import reference as ref
from support.heavy import heavy
from support.numbers import exact_under
from support.paths import TABLEAUX, tableau_files
from support.symbolic import gauss

from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load
from rkcheck.properties.stability import stability_function

z = sympy.Symbol("z")

RK4 = ([[0, 0, 0, 0], [F(1, 2), 0, 0, 0], [0, F(1, 2), 0, 0], [0, 0, 1, 0]], [F(1, 6), F(1, 3), F(1, 3), F(1, 6)])
HEUN = ([[0, 0], [1, 0]], [F(1, 2), F(1, 2)])


def fr(A, b):
    return [[F(x) for x in row] for row in A], [F(x) for x in b]


def as_poly(coeffs) -> sympy.Expr:
    return sum(sympy.Rational(c.numerator, c.denominator) * z**k for k, c in enumerate(coeffs))


def sympy_R(A, b) -> sympy.Expr:
    s = len(b)
    Am = sympy.Matrix([[sympy.Rational(F(x).numerator, F(x).denominator) for x in row] for row in A])
    bm = sympy.Matrix([sympy.Rational(F(x).numerator, F(x).denominator) for x in b])
    one = sympy.ones(s, 1)
    I = sympy.eye(s)
    return sympy.cancel((I - z * Am + z * one * bm.T).det() / (I - z * Am).det())


# ------------------------------------------------------------------ by hand


def test_rk4_by_hand():
    # R = Σ_(k≤4) z^k/k!; R(z)R(−z) = (1 + z²/2 + z⁴/24)² − (z + z³/6)² = 1 + z⁶/72 + z⁸/576
    st = stability_function(*fr(*RK4))
    assert st.numerator == [1, 1, F(1, 2), F(1, 6), F(1, 24)] and st.denominator == [1]
    assert as_poly(st.defect_numerator) == z**6 / 72 + z**8 / 576
    assert st.leading_power == 6 and st.leading_coefficient == F(1, 72)
    assert st.quadratic_energy_order == 5
    assert st.defect_text() == "R(z)R(−z) − 1 = z⁶/72 + z⁸/576"
    assert st.text() == "R(z) = 1 + z + z²/2 + z³/6 + z⁴/24"


def test_heun_by_hand():
    # R = 1 + z + z²/2; R(z)R(−z) = (1 + z²/2)² − z² = 1 + z⁴/4
    st = stability_function(*fr(*HEUN))
    assert as_poly(st.defect_numerator) == z**4 / 4
    assert (st.leading_power, st.leading_coefficient) == (4, F(1, 4))
    assert st.defect_text() == "R(z)R(−z) − 1 = z⁴/4"


def test_lobatto_iiib_3_is_the_diagonal_pade_approximant():
    # IIIB-3: R = (1 + z/2 + z²/12)/(1 − z/2 + z²/12), so R(z)R(−z) = 1 (sympy confirms)
    tab = load(str(TABLEAUX / "collocation" / "lobatto-iiib-3.toml"))
    st = stability_function(tab.exact_A(), tab.exact_b())
    assert st.identity.state == "holds" and st.leading_power is None
    assert sympy.simplify(as_poly(st.numerator) / as_poly(st.denominator) - sympy_R(tab.exact_A(), tab.exact_b())) == 0
    R = sympy_R(tab.exact_A(), tab.exact_b())
    assert sympy.simplify(R * R.subs(z, -z) - 1) == 0
    assert st.text() == "R(z) = (1 + z/2 + z²/12) / (1 − z/2 + z²/12)"


# ------------------------------------------------------------------ sympy route


def random_tableau(rng: random.Random, s: int, explicit: bool):
    A = [[F(rng.randint(-6, 6), rng.randint(1, 6)) if (not explicit or j < i) else F(0) for j in range(s)]
         for i in range(s)]
    b = [F(rng.randint(-6, 6), rng.randint(1, 6)) for _ in range(s)]
    return A, b


RATIONAL_FILES = [f for f in tableau_files() if load(f).is_rational and exact_under(load(f), "rounded")]


@pytest.mark.parametrize("path", RATIONAL_FILES, ids=[str(Path(f).relative_to(TABLEAUX)) for f in RATIONAL_FILES])
def test_shipped_rational_tableaux_agree_with_sympy(path):
    tab = load(path)
    A, b = tab.exact_A(), tab.exact_b()
    st = stability_function(A, b)
    R = sympy_R(A, b)
    assert sympy.simplify(as_poly(st.numerator) / as_poly(st.denominator) - R) == 0
    series = sympy.series(R * R.subs(z, -z) - 1, z, 0, 2 * len(b) + 2).removeO()
    if st.leading_power is None:
        assert sympy.simplify(R * R.subs(z, -z) - 1) == 0
    else:
        poly = sympy.Poly(series, z)
        low = min(m[0] for m in poly.monoms())
        assert low == st.leading_power
        c = poly.coeff_monomial(z**low)
        assert F(int(c.p), int(c.q)) == st.leading_coefficient


@pytest.mark.parametrize("seed", range(20))
def test_random_tableaux_agree_with_sympy(seed):
    rng = random.Random(seed)
    s = rng.randint(1, 4)
    A, b = random_tableau(rng, s, explicit=seed % 2 == 0)
    st = stability_function(A, b)
    R = sympy_R(A, b)
    assert sympy.simplify(as_poly(st.numerator) / as_poly(st.denominator) - R) == 0
    N, Q = as_poly(st.defect_numerator), as_poly(st.denominator)
    assert sympy.simplify(N / (Q * Q.subs(z, -z)) - (R * R.subs(z, -z) - 1)) == 0


# ------------------------------------------- the certificate against the conditions


def path_residuals_by_reference(A, b, max_order):
    """The m = 2 conditions (odd paths) of order 2k ≤ max_order, by brute force."""
    out = {}
    for n in range(3, max_order + 2, 2):
        (cond,) = ref.energy_conditions(n, 2)
        out[n - 1] = ref.energy_residual(cond, A, b)
    return out


@pytest.mark.parametrize("seed", range(12))
def test_the_path_condition_is_half_the_defect_coefficient(seed):
    # R(path with 2k+1 vertices) = (−1)^k e_2k / 2 (module docstring), by brute force
    rng = random.Random(100 + seed)
    A, b = random_tableau(rng, rng.randint(1, 3), explicit=seed % 3 == 0)
    st = stability_function(A, b)
    residuals = path_residuals_by_reference(A, b, 2 * len(b))
    for order, r in residuals.items():
        k = order // 2
        assert r == (-1) ** k * st.defect[order] / 2


def m2_cases():
    files = [f for f in RATIONAL_FILES]
    rng = random.Random(7)
    randoms = [random_tableau(rng, rng.randint(1, 4), explicit=k % 2 == 0) for k in range(10)]
    return files, randoms


@heavy
def test_every_m2_certificate_agrees_with_the_free_tree_conditions_to_order_12():
    """For every shipped tableau and random ones: R(z)R(−z) ≡ 1 iff every m = 2 condition
    up to order 12 holds; otherwise the first failing condition has order leading_power."""
    files, randoms = m2_cases()
    tableaux = [load(f) for f in tableau_files()]
    from rkcheck.methods.tableau import Tableau

    tableaux += [Tableau.from_values(A, b, name=f"random {k}") for k, (A, b) in enumerate(randoms)]
    certified = 0
    for tab in tableaux:
        res = check(tab, CheckOptions(degree=2, order=12))
        st = res.properties.stability
        if st.identity.holds:
            certified += 1
            assert res.first_failure is None, tab.name
            # a certificate that holds only to digits proves nothing: not energy_order_all
            assert res.certified_all and res.energy_order_all == (st.identity.state == "holds"), tab.name
        else:
            assert res.first_failure is not None and res.first_failure.order == st.leading_power, tab.name
            assert not res.energy_order_all
    assert certified >= 20


def test_lobatto_iiib_is_certified_for_every_order_at_m2():
    for s in (3, 4):
        res = check(load(str(TABLEAUX / "collocation" / f"lobatto-iiib-{s}.toml")), CheckOptions(degree=2, order=8))
        assert res.energy_order_all and res.energy_order_label == "all"
        assert res.certificate.kind == "stability"
        # IIIB-3 is rational: a proof; IIIB-4 has sqrt(5) entries: exact once the tableau
        # provides exact algebraic values, else certified to the working precision
        v = res.certificate.verdict
        assert v.state == "holds" if s == 3 else (v.state == "holds" or v.digits >= 40)


# ---------------------------------------------------------- algebraic tableaux


@pytest.mark.parametrize("s", [1, 2, 3])
def test_gauss_is_a_diagonal_pade_approximant_exactly(s):
    A, b = gauss(s)
    st = stability_function(A, b)
    assert st.exact and st.identity.state == "holds"


def _pade_exp(s: int) -> list[F]:
    """The numerator of the (s, s) Padé approximant of e^z (its denominator is P(−z)):
    p_k = (2s − k)! s! / ((2s)! k! (s − k)!)."""
    from math import factorial as f

    return [F(f(2 * s - k) * f(s), f(2 * s) * f(k) * f(s - k)) for k in range(s + 1)]


@pytest.mark.parametrize("family", [{"name": "gauss", "stages": 2}, {"name": "gauss", "stages": 3},
                                    {"name": "hbvm", "k": 4, "s": 3}, {"name": "hbvm", "k": 5, "s": 2}])
def test_field_tableaux_have_the_pade_approximant_of_the_gauss_method(family):
    # entries in Q(√3), Q(√15), the field of the Gauss-4 and Gauss-5 nodes; R(z) of
    # Gauss-s, and of HBVM(k, s) (Brugnano–Iavernaro–Trigiante 2010), is the (s, s)
    # Padé approximant of e^z, in lowest terms with Q(0) = 1
    from rkcheck.methods.closed_forms import family_exact_values
    from rkcheck.methods.family_spec import parse_spec

    found, _ = family_exact_values(parse_spec(family))
    n = math.isqrt(len(found.values) + 1) - 1  # the values are A, b and c: n² + 2n of them
    A = [found.values[i * n:(i + 1) * n] for i in range(n)]
    b = found.values[n * n:n * n + n]
    st = stability_function(A, b)
    s = family.get("s", family.get("stages"))
    P = _pade_exp(s)
    assert st.exact and st.numerator == P and st.denominator == [c * (-1) ** k for k, c in enumerate(P)]


def test_enclosures_hold_to_digits():
    # Gauss-3 given as enclosures (its entries are exact in Q(sqrt(15)) for the check):
    # the identity R(z)R(-z) = 1 can then only hold to digits
    A, b = load(str(TABLEAUX / "collocation" / "gauss-3.toml")).enclosures(200, "auto")
    st = stability_function(A, b)
    assert st.identity.state == "holds_to_digits" and st.identity.digits >= 40
    assert st.text().startswith("R(z) ≈ (1 + 0.5z + 0.1z² + 0.008333333333z³)")


@pytest.mark.parametrize("seed", range(4))
def test_enclosures_contain_the_exact_stability_function(seed):
    # the same random tableau exactly and as intervals of radius 1e-30: every enclosed
    # series and denominator coefficient contains the exact one (FLINT ball route)
    from rkcheck.numbers.intervals import Interval

    rng = random.Random(50 + seed)
    A, b = random_tableau(rng, 3 + 4 * seed, explicit=False)
    exact = stability_function(A, b)
    eps = F(1, 10**30)
    st = stability_function([[Interval(x - eps, x + eps) for x in row] for row in A], [Interval(x - eps, x + eps) for x in b])
    assert not st.exact and len(st.series) == len(exact.series)
    assert all(i.lo <= e <= i.hi for i, e in zip(st.series, exact.series))
    assert st.leading_power == exact.leading_power
    # Q in lowest terms (exact) divides the enclosed det(I − zA): compare values at z = 1/7
    z0 = F(1, 7)
    q_exact = sum(c * z0**k for k, c in enumerate(exact.denominator))
    p_exact = sum(c * z0**k for k, c in enumerate(exact.numerator))
    q_enc = sum((c.mid * z0**k for k, c in enumerate(st.denominator)), F(0))
    p_enc = sum((c.mid * z0**k for k, c in enumerate(st.numerator)), F(0))
    assert abs(p_enc / q_enc - p_exact / q_exact) < F(1, 10**20)


@pytest.mark.parametrize("seed", range(13))
def test_fraction_and_flint_routes_agree(seed, monkeypatch):
    # small rational tableaux use the generic Fraction path (Hessenberg + Euclid, the
    # series by products with A, the defect by schoolbook products), large ones FLINT's
    # (integer products with DA, its charpoly, fmpq_poly gcd, the series past z^s by
    # series division, long products by fmpq_poly): two independent routes, forced here
    # on the same tableaux (up to 11 stages, and one of 20) and compared exactly
    import rkcheck.numbers.polynomials as pl
    import rkcheck.properties.stability as stab

    rng = random.Random(1000 + seed)
    A, b = random_tableau(rng, 20 if seed == 12 else rng.randint(1, 11), explicit=seed % 3 == 0)
    monkeypatch.setattr(stab, "MAX_FRACTION_STAGES", 100)
    monkeypatch.setattr(pl, "MAX_FRACTION_PRODUCT", 10**9)
    by_fractions = stability_function(A, b)
    texts = by_fractions.defect_numerator, by_fractions.defect_text()
    monkeypatch.setattr(stab, "MAX_FRACTION_STAGES", 0)
    monkeypatch.setattr(pl, "MAX_FRACTION_PRODUCT", 0)
    by_flint = stability_function(A, b)
    for attr in ("series", "numerator", "denominator", "defect", "leading_power", "leading_coefficient"):
        assert getattr(by_fractions, attr) == getattr(by_flint, attr), attr
    assert (by_flint.defect_numerator, by_flint.defect_text()) == texts
