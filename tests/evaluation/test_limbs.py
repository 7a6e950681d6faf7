"""The int64-digit balls (``rkcheck.evaluation.limbs``) against exact values.

* every condition enclosure contains the exact residual of the exact tableau, computed
  independently (multi-modular exact arithmetic; those residues are checked against the
  brute-force Fraction reference in ``test_contexts.py``), on random tableaux with small,
  tiny, cancelling and interval (6-digit decimal) entries, at 15 to 110 digits;
* single products, matrix products and dot products of random digit values lie within
  the stated ``e`` units of the exact product of their mid-points (Python integers);
* chunked evaluation gives the same mid-points as one chunk;
* large entries, high precision and weights beyond the integer digit use the
  Python-integer balls instead (and still enclose).
"""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import rkcheck.evaluation.algorithm as algorithm
import rkcheck.evaluation.digit_sums as digit_sums
import rkcheck.trees.classes as classes
import rkcheck.trees.table as table_module
from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.backends import certified_context
from rkcheck.evaluation.balls import LIMB_MIN_VERTICES, BallContext
from rkcheck.evaluation.limbs import LimbBallContext
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_rational
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.precision import bits_for_dps
from rkcheck.trees.listing import ConditionListing


def small_tableau(seed: int, scale: Fraction = Fraction(1)):
    """Entries of size about 1/s·scale (so that the weights fit the integer digit)."""
    rng = random.Random(seed)
    s = rng.randint(1, 5)
    A = [[Fraction(rng.randint(-9, 9), 9 * s) * scale for _ in range(s)] for _ in range(s)]
    b = [Fraction(rng.randint(-9, 9), 9 * s) * scale for _ in range(s)]
    if rng.random() < 0.5:  # Σb = 1: some conditions vanish exactly (cancellation)
        b[-1] = 1 - sum(b[:-1])
    return A, b


def points(A, b):
    return [[Interval.point(x) for x in r] for r in A], [Interval.point(x) for x in b]


def assert_encloses(listing, A, b, ctx, tol):
    truth = exact_condition_sums(scaled_rational(A, b), listing)
    sums = condition_sums(listing, ctx, len(b))
    for n, o in sums.items():
        for k in range(len(o)):
            e, t = o.enclosure(k), truth[n].value(k)
            assert abs(e.mid - t) <= e.rad, (n, k)
            assert e.rad < tol * max(1, abs(t)), (n, k, float(e.rad))
    return sums


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("dps", [15, 50, 110])
def test_digit_balls_enclose_the_exact_values(seed, dps):
    A, b = small_tableau(seed)
    ctx = LimbBallContext.create(*points(A, b), bits_for_dps(dps), vertices=9)
    assert ctx is not None
    assert_encloses(ConditionListing(8, None), A, b, ctx, Fraction(1, 10**dps))


@pytest.mark.parametrize("seed", range(3))
def test_tiny_entries_keep_absolute_precision(seed):
    A, b = small_tableau(seed, Fraction(1, 10**30))
    ctx = LimbBallContext.create(*points(A, b), bits_for_dps(50), vertices=8)
    assert ctx is not None
    assert_encloses(ConditionListing(7, None), A, b, ctx, Fraction(1, 10**50))


@pytest.mark.parametrize("seed", range(3))
def test_wide_intervals_enclose_every_point_of_the_box(seed):
    # 6-digit decimals: the exact tableau (and the box's corners) lie in the intervals
    A, b = small_tableau(seed)
    half = Fraction(1, 2 * 10**6)

    def box(x):
        m = Fraction(round(x * 10**6), 10**6)
        return Interval(m - half, m + half)

    S, P = [[box(x) for x in r] for r in A], [box(x) for x in b]
    ctx = LimbBallContext.create(S, P, bits_for_dps(50), vertices=9)
    assert ctx is not None
    listing = ConditionListing(8, None)
    sums = condition_sums(listing, ctx, len(b))
    rng = random.Random(seed)
    for corner in range(3):  # the exact tableau, then random corners of the box
        pick = (lambda iv: rng.choice([iv.lo, iv.hi])) if corner else None
        Ax = [[pick(iv) if pick else x for iv, x in zip(rs, ra)] for rs, ra in zip(S, A)]
        bx = [pick(iv) if pick else x for iv, x in zip(P, b)]
        truth = exact_condition_sums(scaled_rational(Ax, bx), listing)
        for n, o in sums.items():
            for k in range(len(o)):
                e = o.enclosure(k)
                assert abs(e.mid - truth[n].value(k)) <= e.rad


def test_chunked_digit_balls_are_bit_identical(monkeypatch):
    A, b = small_tableau(4)
    S, P = points(A, b)
    whole = condition_sums(ConditionListing(9, None), LimbBallContext.create(S, P, 200, vertices=10), len(b))
    monkeypatch.setattr(algorithm, "_TERM_CHUNK", 5)
    monkeypatch.setattr(classes, "_CHUNK", 7)
    monkeypatch.setattr(table_module, "_CHUNK", 7)
    monkeypatch.setattr("rkcheck.evaluation.limbs._BLOCK", 3)
    chunked = condition_sums(ConditionListing(9, None), LimbBallContext.create(S, P, 200, vertices=10), len(b))
    for n in whole:
        assert list(chunked[n].mids) == list(whole[n].mids)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("explicit", [True, False])
def test_zero_and_one_mid_points_skipped_or_multiplied_give_the_same_balls(monkeypatch, seed, explicit):
    # an explicit tableau (strictly lower triangular A): most weights of tall trees are
    # exactly zero; in any tableau the products with the factor τ are by exactly one.
    # Skipping their digit products (every row sparse) or multiplying them (none), and
    # storing the digits of the nonzero rows only or of every row, gives the same balls,
    # bit for bit, and they enclose the exact values
    rng = random.Random(seed)
    s = 4
    A = [[Fraction(rng.randint(1, 9), 9 * s) if j < i or not explicit else Fraction(0) for j in range(s)]
         for i in range(s)]
    b = [Fraction(rng.randint(1, 9), 9 * s) for _ in range(s)]
    listing = ConditionListing(11, None)
    runs = []
    # rows multiplied (only the nonzero ones: 1.0, all of them: -1.0), digits stored for
    # the nonzero rows only
    for share, compact in ((-1.0, False), (1.0, True), (-1.0, True), (1.0, False)):
        monkeypatch.setattr("rkcheck.evaluation.limbs._SPARSE", share)
        monkeypatch.setattr("rkcheck.evaluation.limbs._COMPACT", compact)
        runs.append(assert_encloses(listing, A, b, LimbBallContext.create(*points(A, b), 200, vertices=12), 1e-50))
    dense = runs[0]
    for other in runs[1:]:
        for n in dense:
            assert list(other[n].mids) == list(dense[n].mids)
            assert other[n].rads.tolist() == dense[n].rads.tolist()


def test_large_listings_of_small_weights_use_digits():
    A = [[Fraction(1, 3), Fraction(1, 7)], [Fraction(-2, 9), Fraction(1, 3)]]
    b = [Fraction(1, 2), Fraction(1, 2)]
    assert isinstance(certified_context(*points(A, b), bits_for_dps(50), vertices=LIMB_MIN_VERTICES), LimbBallContext)
    assert type(certified_context(*points(A, b), bits_for_dps(50), vertices=LIMB_MIN_VERTICES - 1)) is BallContext
    assert type(certified_context(*points(A, b), bits_for_dps(50))) is BallContext


@pytest.mark.parametrize("entries, dps", [(Fraction(10**6), 50), (Fraction(1, 3), 200), (Fraction(1, 3), 1000)])
def test_large_entries_and_high_precision_use_python_integers(entries, dps):
    A = [[entries, Fraction(1, 7)], [Fraction(-2, 9), entries]]
    b = [Fraction(1, 2), Fraction(1, 2)]
    ctx = certified_context(*points(A, b), bits_for_dps(dps), vertices=LIMB_MIN_VERTICES)
    assert type(ctx) is BallContext
    assert_encloses(ConditionListing(6, None), A, b, ctx, Fraction(1, 10**dps) * 10**40)


def test_weights_beyond_the_integer_digit_are_refused():
    # M = 2: weights up to 2^n; the integer digit holds 2^(β−4) with β <= 30
    A = [[Fraction(2)]]
    b = [Fraction(1)]
    assert LimbBallContext.create(*points(A, b), 200, vertices=10) is not None
    assert LimbBallContext.create(*points(A, b), 200, vertices=40) is None


# ------------------------------------------------------------------ single operations

def digit_values(ctx, draw_ints):
    """Digits (n, L) of the given integers (mid-points at scale 2^−P) and the values."""
    return np.array([ctx._digits(m) for m in draw_ints], dtype=np.int64).reshape(len(draw_ints), ctx.L)


def as_int(ctx, digits):
    return sum(int(d) << (ctx.digit_bits * j) for j, d in enumerate(digits))


def _entries(s: int):
    """Entries with dense digits (p/(10^6·s)), and zeros and dyadic entries with one
    nonzero digit (RK4's 0, 1/2, 1): the matrix products take other passes for those."""
    dense = st.integers(-10**6, 10**6).map(lambda k: Fraction(k, 10**6 * s))
    sparse = st.sampled_from([Fraction(0), Fraction(1, 2), Fraction(-1, 4), Fraction(1)])
    return st.one_of(dense, sparse, sparse)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 6), st.sampled_from([60, 200, 400]), st.data())
def test_single_operations_are_within_their_error_units(s, bits, data):
    A = [[Interval.point(data.draw(_entries(s))) for _ in range(s)] for _ in range(s)]
    b = [Interval.point(data.draw(_entries(s))) for _ in range(s)]
    ctx = LimbBallContext.create(A, b, bits, vertices=4)
    assert ctx is not None
    P = ctx.bits
    # |x|, |y| < 2^((β−5)/2), so that x·y too stays inside the integer digit: the
    # magnitudes handed to the context say so (they are what guards the digit's range;
    # hypothesis found that larger mid-points with magnitudes of 1 overflow it)
    half = (ctx.digit_bits - 5) // 2
    bound = 1 << (P + half)
    mids = st.integers(-bound, bound)
    n = data.draw(st.integers(1, 5))
    xs = [data.draw(mids) for _ in range(n * s)]
    ys = [data.draw(mids) for _ in range(n * s)]
    X = digit_values(ctx, xs).reshape(n, s, ctx.L)
    Y = digit_values(ctx, ys).reshape(n, s, ctx.L)
    zero, one = np.zeros((n, s)), np.full((n, s), 2.0**half)
    for a, x, y in zip(ctx.mul((X, zero, one), (Y, zero, one))[0].reshape(-1, ctx.L), xs, ys):
        err = as_int(ctx, a) - Fraction(x * y, 1 << P)
        assert -ctx.e_mul <= err <= 0
    Am = [[_mid(e, P) for e in row] for row in A]
    bm = [_mid(e, P) for e in b]
    psi = ctx.matvec((X, zero, one))[0]
    a = ctx.dot((X, zero, one))[0]
    for t in range(n):
        xt = xs[t * s:(t + 1) * s]
        for i in range(s):
            err = as_int(ctx, psi[t, i]) - Fraction(sum(Am[i][j] * xt[j] for j in range(s)), 1 << P)
            assert -ctx.e_dot <= err <= 0
        err = as_int(ctx, a[t]) - Fraction(sum(bm[j] * xt[j] for j in range(s)), 1 << P)
        assert -ctx.e_dot <= err <= 0


def _mid(iv: Interval, P: int) -> int:
    """The mid-point the context builds for an entry (floor of the centre at scale 2^−P)."""
    from rkcheck.evaluation.balls import _ball_at

    return _ball_at(iv, P, 0)[0]


def test_evaluate_uses_digits_on_a_large_listing_and_encloses_every_value():
    # the benchmark's dense tableau to 15 vertices (13 102 conditions): the path of
    # `verify --arithmetic ball`, against the exact engine's values
    from rkcheck.evaluation.backends import evaluate
    from rkcheck.evaluation.values import TableauValues
    from rkcheck.methods.tableau import Tableau
    from rkcheck.numbers.reading import Reading
    from rkcheck.trees.listing import condition_listing

    A = [["1/7", "-2/9", "3/11", "1/13"], ["2/5", "1/8", "-1/6", "3/10"],
         ["-1/12", "5/9", "1/4", "2/15"], ["3/8", "1/3", "-2/7", "1/5"]]
    tableau = Tableau.from_values(A, ["1/5", "3/10", "1/4", "1/4"])
    listing = condition_listing(14, None)
    assert max(listing.orders) >= LIMB_MIN_VERTICES
    balls = evaluate(listing, TableauValues(tableau, Reading("rounded", 50, "ball")))
    exact = evaluate(listing, TableauValues(tableau, Reading("rounded", 50, "exact")))
    for n, sums in balls.orders.items():
        for k in range(len(sums)):
            e, t = sums.enclosure(k), exact.orders[n].value(k)
            assert abs(e.mid - t) <= e.rad and e.rad < Fraction(1, 10**50), (n, k)


def test_condition_divisors_from_orbits_or_gcds_give_the_same_sums(monkeypatch):
    # the divisor of a condition's coefficients is Σ|c|/n (one term per orbit of the free
    # tree's automorphisms), checked against every coefficient, else their gcd: both
    # give the exact sums, and the quotients c/g_k of a condition add up to at most n
    A, b = small_tableau(5)
    S, P = points(A, b)
    listing = ConditionListing(9, None)
    orbits = assert_encloses(listing, A, b, LimbBallContext.create(S, P, 200, vertices=10), 1e-50)
    for n, terms in listing.orders.items():
        mult, _, g = digit_sums.multipliers(terms, 28)
        cond, idx = terms.block(0, terms.rows)
        real = cond < len(terms)
        coef = np.array(terms.coefficients, dtype=object)[idx[real]]
        assert list(mult[real].astype(object) * g[cond[real]].astype(object)) == list(coef)
        assert np.bincount(cond[real], weights=np.abs(mult[real])).max(initial=0) <= n
    # the sums of |c| in two halves of 31 bits (the orders past 20 vertices) give the same divisors
    for terms in listing.orders.values():
        exact = np.array(terms.coefficients, dtype=np.int64)
        at_once = digit_sums._orbit_divisors(terms, exact)
        with monkeypatch.context() as m:
            m.setattr(digit_sums, "_INT64_SUMS", 0)
            assert digit_sums._orbit_divisors(terms, exact).tolist() == at_once.tolist()
    monkeypatch.setattr(digit_sums, "_orbit_divisors", lambda terms, exact: None)
    gcds = assert_encloses(ConditionListing(9, None), A, b, LimbBallContext.create(S, P, 200, vertices=10), 1e-50)
    for n in orbits:
        assert list(gcds[n].mids) == list(orbits[n].mids)


@pytest.mark.parametrize("layout", ["rows", "digit-major", "vectors", "vectors by trees", "vectors by stages", "strided"])
def test_rows_are_read_from_every_layout_of_digits(layout):
    # every layout the kernel hands the digit gathers (a stored or gathered value is
    # C-contiguous, a product's digits digit-major, a matrix product's vectors with the
    # stages before the trees) against plain reshaping and fancy indexing
    from rkcheck.evaluation.balls import take_rows
    from rkcheck.evaluation.limbs import _flat_rows

    rng = np.random.default_rng(7)
    n, s, L = 37, 3, 5
    base = {
        "rows": lambda: rng.integers(-9, 9, (n, L)),
        "digit-major": lambda: rng.integers(-9, 9, (L, n)).T,
        "vectors": lambda: rng.integers(-9, 9, (n, s, L)),
        "vectors by trees": lambda: rng.integers(-9, 9, (L, n * s)).T.reshape(n, s, L),
        "vectors by stages": lambda: rng.integers(-9, 9, (L, s, n)).transpose(2, 1, 0),
        "strided": lambda: rng.integers(-9, 9, (n, 2 * s, L))[:, ::2, :],
    }[layout]()
    flat = np.array(base).reshape(-1, L)  # a copy, C-ordered: the reference
    rows = rng.choice(len(flat), size=11, replace=False)
    assert np.array_equal(_flat_rows(base, rows), flat[rows])
    trees = rng.choice(n, size=7, replace=False)
    assert np.array_equal(take_rows(base, trees), np.array(base)[trees])
