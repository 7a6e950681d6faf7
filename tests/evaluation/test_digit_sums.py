"""The judging of digit ball sums (``rkcheck.evaluation.digit_sums.DigitBallSums``)
against the same sums as Python integers (``BallSums``, the reference of the object
context): ``|mid| > rad`` decided exactly, the magnitude bound the same float wherever a
verdict's digits come from it, and a bound on ``|mid| + rad`` (exact rationals) elsewhere.
Mid-points of every size and sign, zeros, and radii just around ``|mid|``.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from rkcheck.evaluation.balls import BallSums
from rkcheck.evaluation.digit_sums import DigitBallSums

BETA, L, BITS, F = 28, 9, 224, 5040


def carried_digits(n: int) -> list[int]:
    mask = (1 << BETA) - 1
    return [(n >> (BETA * j)) & mask for j in range(L - 1)] + [n >> (BETA * (L - 1))]


def random_sums(seed: int, k: int = 600):
    rng = np.random.default_rng(seed)
    ns, rads = [], []
    divisors = rng.integers(1, 2**40, k)
    for i in range(k):
        size = int(rng.integers(0, 245))
        n = int(rng.integers(0, 2**62)) >> (62 - min(size, 62)) << max(size - 62, 0) if size else 0
        n = -n if rng.random() < 0.5 else n
        m = abs(n) * int(divisors[i])
        kind = i % 5
        if kind == 0:  # radius a hair below, at, or above |mid|: only exact integers decide
            r = float(Fraction(m, 1 << BITS)) * (1 + float(rng.choice([-2.0**-52, 0.0, 2.0**-52])))
        elif kind == 1:  # |mid| just past the radius by one unit of 2^−P
            r = float(Fraction(max(m - 1, 0), 1 << BITS))
        else:
            r = float(rng.random()) * 2.0 ** float(rng.integers(-240, -150))
        ns.append(n)
        rads.append(r)
    digits = np.array([carried_digits(n) for n in ns], dtype=np.int64).T.copy()
    mids = np.array([n * int(g) for n, g in zip(ns, divisors)], dtype=object)
    rads = np.array(rads)
    return DigitBallSums(digits, divisors, rads, BITS, BETA, F), BallSums(mids, rads, BITS, 0, F)


@pytest.mark.parametrize("seed", range(6))
def test_digit_sums_judge_as_the_integer_sums(seed):
    digit, ref = random_sums(seed)
    excludes = ref.excludes_zero()
    assert digit.excludes_zero().tolist() == excludes.tolist()
    assert 0 < excludes.sum() < len(excludes)
    bound, ref_bound = digit.magnitude_bound(), ref.magnitude_bound()
    small = np.array([abs(int(m)) < 2**59 for m in ref.mids])
    same = ~excludes | small
    assert bound[same].tolist() == ref_bound[same].tolist()
    for k in np.flatnonzero(~same):  # a ball that excludes 0: any bound on |mid| + rad
        assert Fraction(float(bound[k])) >= abs(Fraction(int(ref.mids[k]), F << BITS)) + Fraction(float(ref.rads[k])) / F
    for k in range(0, len(ref), 37):
        assert digit.enclosure(k) == ref.enclosure(k)
    assert list(digit.mids) == list(ref.mids)


@pytest.mark.parametrize("seed", range(4))
def test_digit_sums_exceed_as_the_fractions(seed):
    # |mid| > t·2^P against exact rationals: t a hair below, at and above |mid|·2^−P (only
    # the integers decide), far from it either way, zero, past float64's range once
    # scaled, and infinite or NaN (no claim)
    digit, ref = random_sums(seed)
    rng = np.random.default_rng(100 + seed)
    mids = [abs(int(m)) for m in ref.mids]
    near = [float(Fraction(m, 1 << BITS)) for m in mids]
    t = np.array([x * float(rng.choice([1 - 2.0**-52, 1.0, 1 + 2.0**-52, 0.5, 2.0])) for x in near])
    t = np.concatenate([t, [0.0, 2.0**1000, 1.7e308, np.inf, np.nan, 2.0**-1074]])
    mids += [mids[1]] * 6
    digit = DigitBallSums(np.concatenate([digit.digits, digit.digits[:, [1] * 6]], axis=1),
                          np.concatenate([digit.divisors, digit.divisors[[1] * 6]]),
                          np.concatenate([digit.rads, digit.rads[[1] * 6]]), BITS, BETA, F)
    expected = [np.isfinite(x) and m > Fraction(float(x)) * (1 << BITS) for m, x in zip(mids, t)]
    assert digit.exceeds(t).tolist() == expected
    assert 0 < sum(expected) < len(expected)
    ref = BallSums(np.array([int(m) for m in digit.mids], dtype=object), digit.rads, BITS, 0, F)
    assert ref.exceeds(t).tolist() == expected


@pytest.mark.parametrize("vertices", [5, 8, 10])
def test_multiplier_divisors_are_the_integer_sums(vertices, monkeypatch):
    """Each condition's divisor, by either route (int64 sums, or float64 halves), is
    Σ|c|/n computed with Python integers where that is an integer, and each term's
    multiplier times it gives back the term's coefficient."""
    from rkcheck.evaluation import digit_sums
    from rkcheck.trees.listing import ConditionListing

    terms = ConditionListing(vertices - 1, None).orders[vertices]
    coef = terms.coefficients
    cond, idx = terms.block(0, terms.rows)
    totals = [0] * (len(terms) + 1)
    for k, i in zip(cond.tolist(), idx.tolist()):
        totals[k] += abs(coef[i])
    expected = [t // vertices if t % vertices == 0 and t else 2**62 for t in totals[:-1]]
    exact = np.array(coef, dtype=np.int64)
    routes = [digit_sums._orbit_divisors(terms, exact)]
    monkeypatch.setattr(digit_sums, "_INT64_SUMS", 0)  # the halves, as past 20 vertices
    routes.append(digit_sums._orbit_divisors(terms, exact))
    for g in routes:
        assert g is not None
        assert g[:-1].tolist() == expected
        mult = digit_sums._quotients(terms, exact, g)
        assert mult is not None
        real = cond < len(terms)
        assert all(int(m) * int(g[k]) == coef[i]
                   for m, k, i in zip(mult[real].tolist(), cond[real].tolist(), idx[real].tolist()))
