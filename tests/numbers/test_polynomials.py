"""The polynomial module against sympy: arithmetic, gcd, division, square-free parts and
certified real roots of random polynomials (fixed seeds), arithmetic over a number field
against sympy's algebraic extension, and the integer square-free split against sympy's
factorisation."""

from __future__ import annotations

import pickle
import random
from fractions import Fraction as F

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from rkcheck.numbers import grammar as ex
from rkcheck.numbers import polynomials as pl
from rkcheck.numbers.field_builder import field_of
from rkcheck.numbers.intervals import Interval

x = sp.Symbol("x")


def to_sympy(coeffs) -> sp.Poly:
    return sp.Poly([sp.Rational(c.numerator, c.denominator) for c in reversed(coeffs)], x, domain="QQ")


def from_sympy(p: sp.Poly) -> list[F]:
    out = [F(int(c.p), int(c.q)) for c in reversed(p.all_coeffs())]
    return out or [F(0)]


def monic(p: list[F]) -> list[F]:
    p = pl.trim(p)
    return [c / p[-1] for c in p]


def random_poly(rng: random.Random, degree: int, den: int = 5) -> list[F]:
    out = [F(rng.randint(-9, 9), rng.randint(1, den)) for _ in range(degree)]
    return out + [F(rng.choice([-3, -2, -1, 1, 2, 3]), rng.randint(1, den))]


def random_cases(seed: int, n: int) -> list[tuple[list[F], list[F]]]:
    rng = random.Random(seed)
    return [(random_poly(rng, rng.randint(0, 7)), random_poly(rng, rng.randint(1, 5))) for _ in range(n)]


# ------------------------------------------------------------ arithmetic over Q


@pytest.mark.parametrize("p, q", random_cases(1, 40))
def test_arithmetic_matches_sympy(p, q):
    P, Q = to_sympy(p), to_sympy(q)
    assert pl.trim(pl.add(p, q)) == from_sympy(P + Q)
    assert pl.trim(pl.sub(p, q)) == from_sympy(P - Q)
    assert pl.trim(pl.mul(p, q)) == from_sympy(P * Q)
    assert pl.trim(pl.scale(p, F(-2, 7))) == from_sympy(P * sp.Rational(-2, 7))
    assert pl.trim(pl.reflect(p)) == from_sympy(P.compose(sp.Poly(-x, x)))
    assert pl.trim(pl.derivative(p)) == from_sympy(P.diff(x))
    assert pl.trim(pl.integral(p)) == from_sympy(P.integrate(x))
    assert pl.trim(pl.shift(p, F(-3, 2))) == from_sympy(P.compose(sp.Poly(x - sp.Rational(3, 2), x)))
    assert pl.evaluate(p, F(5, 3)) == F(str(P.eval(sp.Rational(5, 3))))


@pytest.mark.parametrize("seed", range(4))
def test_long_rational_products_are_sympys_with_their_length(seed):
    # past MAX_FRACTION_PRODUCT pairs the product is FLINT's: the same coefficients as
    # sympy's, as Fractions, and as many as the schoolbook gives (trailing zeros too)
    rng = random.Random(50 + seed)
    p = random_poly(rng, rng.randint(20, 60), den=10**30)
    q = random_poly(rng, rng.randint(20, 60)) + [F(0)] * seed
    assert len(p) * len(q) > pl.MAX_FRACTION_PRODUCT
    product = pl.mul(p, q)
    assert len(product) == len(p) + len(q) - 1
    assert all(type(c) is F for c in product)
    assert pl.trim(product) == from_sympy(to_sympy(p) * to_sympy(pl.trim(q)))


@pytest.mark.parametrize("p, d", random_cases(2, 40))
def test_division_with_remainder_matches_sympy(p, d):
    quot, rem = pl.divide(p, d)
    want_q, want_r = sp.div(to_sympy(p), to_sympy(d))
    assert pl.trim(quot) == from_sympy(want_q) and rem == from_sympy(want_r)


def gcd_cases(seed: int, n: int):
    """Pairs with a common factor of degree 0–3 (random pairs are almost always coprime)."""
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        common = random_poly(rng, rng.randint(0, 3))
        out.append((pl.mul(common, random_poly(rng, rng.randint(0, 4))), pl.mul(common, random_poly(rng, rng.randint(0, 4)))))
    return out


@pytest.mark.parametrize("p, q", gcd_cases(3, 40))
def test_gcd_and_lowest_terms_match_sympy(p, q):
    P, Q = to_sympy(p), to_sympy(q)
    assert monic(pl.gcd(p, q)) == monic(from_sympy(sp.gcd(P, Q)))
    if q[0] != 0:
        num, den = pl.lowest_terms(p, q)
        assert den[0] == 1 and sp.cancel(to_sympy(num).as_expr() / to_sympy(den).as_expr() - P.as_expr() / Q.as_expr()) == 0
        assert sp.degree(sp.gcd(to_sympy(num), to_sympy(den)), x) == 0  # nothing left to cancel
        assert pl.rational_lowest_terms(p, q) == (num, den)  # FLINT's route, the same result


@pytest.mark.parametrize("seed", range(20))
def test_squarefree_part_matches_sympy(seed):
    rng = random.Random(seed)
    p = [F(1)]
    for _ in range(rng.randint(1, 4)):
        p = pl.mul(p, random_poly(rng, rng.randint(1, 3)) if rng.random() < 0.7 else [F(rng.randint(-4, 4)), F(1)])
        if rng.random() < 0.5:
            p = pl.mul(p, p)
    assert monic(pl.squarefree_part(p)) == monic(from_sympy(sp.sqf_part(to_sympy(p))))


# ------------------------------------------------------------ certified real roots


def root_cases(seed: int, n: int):
    """Products of random factors: rational roots, repeated ones, irrational and complex."""
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        p = [F(rng.choice([-1, 1, 2, 3]), rng.randint(1, 4))]
        for _ in range(rng.randint(1, 4)):
            kind = rng.random()
            if kind < 0.3:
                f = [F(rng.randint(-9, 9), rng.randint(1, 7)), F(1)]  # a rational root
            elif kind < 0.5:
                f = [F(rng.randint(1, 9), rng.randint(1, 3)), F(0), F(1)]  # complex roots only
            else:
                f = random_poly(rng, rng.randint(2, 4))
            p = pl.mul(p, pl.mul(f, f) if rng.random() < 0.25 else f)
        out.append(p)
    return out


@pytest.mark.parametrize("p", root_cases(4, 30))
@pytest.mark.parametrize("bits", [10, 120])
def test_real_roots_are_isolated_counted_and_enclosed(p, bits):
    P = to_sympy(p)
    truth = sorted(set(sp.real_roots(P)), key=lambda r: r.evalf(60))
    got = pl.RealRoots(p)
    assert got.count == len(truth) == sp.Poly(sp.sqf_part(P)).count_roots()
    intervals = got.intervals(bits)
    assert len(intervals) == len(truth)
    for iv, r, exact in zip(intervals, truth, got.exact):
        assert iv.hi - iv.lo <= F(1, 2**bits)
        if r.is_rational:
            assert iv.is_point and iv.lo == exact == F(int(r.p), int(r.q))
        else:
            assert exact is None
            value = sp.Rational(str(r.evalf(bits // 3 + 40)))
            margin = sp.Rational(1, 10 ** (bits // 3 + 30))
            assert sp.Rational(iv.lo.numerator, iv.lo.denominator) - margin <= value <= sp.Rational(iv.hi.numerator, iv.hi.denominator) + margin
    assert pl.rational_roots(p) == [F(int(r.p), int(r.q)) for r in truth if r.is_rational]


def test_the_roots_of_the_zero_polynomial_are_refused():
    with pytest.raises(ValueError, match="zero polynomial"):
        pl.RealRoots([F(0), F(0)])
    assert pl.RealRoots([F(3)]).count == 0


def test_real_roots_travel_by_pickle():
    roots = pl.real_roots([F(-2), F(0), F(1)])
    copy = pickle.loads(pickle.dumps(roots))
    assert copy.poly == roots.poly and copy.intervals(30) == roots.intervals(30)


def test_flint_numbers_convert_exactly():
    from flint import arb, fmpq, fmpz

    assert pl.to_fraction(fmpq(-7, 12)) == F(-7, 12) and pl.to_fraction(fmpz(5)) == 5
    assert pl.to_fraction((arb(3) / 8).mid()) == F(3, 8) and pl.to_fraction(arb(12)) == 12
    p = [F(1, 3), F(0), F(-5, 2)]
    assert pl.from_flint(pl.to_flint(p)) == p and pl.from_flint(pl.to_flint([F(0)])) == [0]


def test_flint_rationals_convert_to_normalised_fractions():
    # built without a gcd (FLINT keeps p/q in lowest terms): the same Fraction as the
    # normalising constructor gives, numerator, denominator, hash and all
    from flint import fmpq

    for p, q in [(-6 * 10**300 - 18, 4 * 10**250 + 12), (0, 7), (-14, 21), (3**400, 2**500)]:
        x, y = pl.to_fraction(fmpq(p, q)), F(p, q)
        assert (x.numerator, x.denominator, hash(x)) == (y.numerator, y.denominator, hash(y))
        assert x == y and x + 1 == y + 1


# ------------------------------------------------------------ over a number field


def test_gcd_over_a_number_field_matches_sympys_extension():
    # p = (x − √2)(x + 1)(x² + 3), q = (x − √2)(x − 5)(x + √2) over Q(√2): gcd x − √2
    r2 = field_of([ex.parse("sqrt(2)")]).values[0]
    one, zero = r2.field(1), r2.field(0)
    p = pl.mul(pl.mul([-r2, one], [one, one], zero), [r2.field(3), zero, one], zero)
    q = pl.mul(pl.mul([-r2, one], [r2.field(-5), one], zero), [r2, one], zero)
    g = pl.gcd(p, q, zero)
    s2 = sp.sqrt(2)
    want = sp.gcd(sp.Poly((x - s2) * (x + 1) * (x**2 + 3), x, extension=s2),
                  sp.Poly((x - s2) * (x - 5) * (x + s2), x, extension=s2)).monic()
    got = [sp.sympify((c / g[-1]).text()) for c in g]
    assert len(got) == 2 and all(sp.simplify(a - b) == 0 for a, b in zip(got, reversed(want.all_coeffs())))
    # q/p = (x − 5)(x + √2) / ((x + 1)(x² + 3)), scaled to a denominator 1 at x = 0:
    # ((x² + (√2 − 5)x − 5√2)/3) / ((3 + 3x + x² + x³)/3)
    num, den = pl.lowest_terms(q, p, zero)
    assert [c.text() for c in den] == ["1", "1", "1/3", "1/3"]
    assert [c.text() for c in num] == ["-5*sqrt(2)/3", "-5/3 + sqrt(2)/3", "1/3"]


def test_interval_coefficients_multiply_without_division():
    a, b = Interval(F(1), F(2)), Interval(F(-1), F(1, 2))
    zero = Interval.point(0)
    got = pl.mul([a, b], [b, a], zero)  # (a + bx)(b + ax) = ab + (a² + b²)x + ab x²
    assert got == [a * b, a * a + b * b, b * a]
    # 1 − 3x + 2x² by Horner on [0, 1/4]: 2 → 2·[0, 1/4] − 3 = [−3, −5/2] → [−3, −5/2]·[0, 1/4] + 1
    assert pl.evaluate_at_interval([F(1), F(-3), F(2)], Interval(F(0), F(1, 4))) == Interval(F(1, 4), F(1))


# ------------------------------------------------------------ integers


@pytest.mark.parametrize("n", [1, 2, 12, 18, 200280098, 2**7 * 3**5 * 11, 99991**2 * 3, 49])
def test_squarefree_split_matches_sympys_factorisation(n):
    s, m = pl.squarefree_split(n, 100_000)
    square = 1
    free = 1
    for p, e in sp.factorint(n).items():
        square *= p ** (e // 2)
        free *= p ** (e % 2)
    assert (s, m) == (square, free)


def test_squarefree_split_stops_at_its_limit():
    # 10007 is prime: below the limit 10^4 its square stays inside m unless m is a square
    assert pl.squarefree_split(2 * 10007**2, 10_000) == (1, 2 * 10007**2)
    assert pl.squarefree_split(10007**2, 10_000) == (10007, 1)


# ------------------------------------------------------------ properties


polys = st.lists(st.fractions(min_value=-20, max_value=20, max_denominator=12), min_size=1, max_size=7)


@settings(max_examples=60, deadline=None)
@given(polys, polys.filter(lambda d: d[-1] != 0))
def test_division_identity(p, d):
    quot, rem = pl.divide(p, d)
    assert pl.trim(pl.add(pl.mul(quot, d), rem)) == pl.trim(p)
    assert len(rem) < len(d) or rem == [0]


@settings(max_examples=40, deadline=None)
@given(polys.filter(lambda p: any(p)), st.sampled_from([4, 40]))
def test_isolating_intervals_bracket_a_sign_change_of_the_squarefree_part(p, bits):
    S = sp.sqf_part(to_sympy(pl.trim(p))) if len(pl.trim(p)) > 1 else None
    roots = pl.RealRoots(p)
    intervals = roots.intervals(bits)
    assert roots.count == (S.count_roots() if S is not None else 0)
    for a, b in zip(intervals, intervals[1:]):
        assert a.hi < b.lo  # disjoint and increasing
    for iv in intervals:
        assert iv.hi - iv.lo <= F(1, 2**bits)
        if iv.is_point:
            assert S.eval(sp.Rational(iv.lo.numerator, iv.lo.denominator)) == 0
        else:  # a simple root of the square-free part: its sign changes across it
            lo = S.eval(sp.Rational(iv.lo.numerator, iv.lo.denominator))
            hi = S.eval(sp.Rational(iv.hi.numerator, iv.hi.denominator))
            assert lo * hi < 0


@pytest.mark.parametrize("p", root_cases(11, 30))
def test_a_refined_root_is_enclosed_and_narrow(p):
    # Newton's candidate bracketed by a sign change, against sympy's roots to 700 digits
    p = pl.squarefree_part(p)
    truth = sorted(set(sp.real_roots(to_sympy(p))), key=lambda r: r.evalf(60))
    refined = 0
    for start, r in zip(pl.RealRoots(p).intervals(30), truth):
        got = pl.refine_root(p, start, 2000)
        if start.is_point:
            assert got == start
            continue
        assert got is not None  # a simple root 2^-30 close: Newton converges
        assert start.lo <= got.lo and got.hi <= start.hi and got.hi - got.lo <= F(1, 2**2000)
        value = sp.Rational(str(r.evalf(700)))
        margin = sp.Rational(1, 10**690)
        assert sp.Rational(got.lo.numerator, got.lo.denominator) - margin <= value
        assert value <= sp.Rational(got.hi.numerator, got.hi.denominator) + margin
        refined += 1
    assert refined or not truth or all(r.is_rational for r in truth)
