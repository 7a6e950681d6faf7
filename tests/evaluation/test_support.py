"""Contexts run only where a weight may be nonzero (the tableau's pattern of zeros),
against the same contexts run over every weight, and against brute force:

* the rows left out are zero: the reference's exact elementary weights of RK4 (SPEC §2)
  are zero wherever the pattern says so;
* the exact mid-points of certified balls (sums of exact integer products) are the same
  with and without the rows left out, and the radii no larger;
* the float screen's mid-points are the same, bit for bit (the terms left out add 0.0).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from support import reference as ref

from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.balls import BallContext, FloatContext
from rkcheck.evaluation.support import SupportContext, _rows, zero_pattern
from rkcheck.numbers.intervals import Interval
from rkcheck.trees.listing import ConditionListing

RK4 = ([[0, 0, 0, 0], [Fraction(1, 2), 0, 0, 0], [0, Fraction(1, 2), 0, 0], [0, 0, 1, 0]],
       [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)])
#: a diagonally implicit pattern with a zero weight: some zeros, fewer than RK4's
DIRK = ([[Fraction(1, 4), 0, 0], [Fraction(1, 3), Fraction(1, 5), 0], [Fraction(-1, 7), Fraction(2, 3), Fraction(1, 6)]],
        [Fraction(1, 2), Fraction(1, 2), 0])


def _points(A, b):
    return [[Interval(Fraction(x), Fraction(x)) for x in row] for row in A], [Interval(Fraction(x), Fraction(x)) for x in b]


def test_weights_left_out_are_zero_by_brute_force():
    A, b = RK4
    listing = ConditionListing(8, None)
    zA, zb = zero_pattern(A, b)
    ctx = SupportContext(FloatContext(*_points(A, b)), zA, zb)
    from rkcheck.evaluation.algorithm import _Weights

    top = max(listing.orders)
    listing.ensure(top)
    weights = _Weights(listing, ctx, 4, top - 2, top - 1)
    for n in range(2, top):
        weights.compute_order(n, listing.first[n], listing.first[n + 1], 1 << 14)
    stored_phi = weights.store["phi"]
    stored_a = weights.store["a"]
    checked = 0
    for t in range(listing.first[top - 1]):
        seq = listing.tree_level_sequence(t)
        phi = ref.elementary_weight_vector(seq, A)
        if t < weights.limit["phi"]:
            for i in range(4):
                if not stored_phi.flags[t, i]:
                    assert phi[i] == 0
                    checked += 1
        if not stored_a.flags[t]:
            assert ref.elementary_weight(seq, A, b) == 0
            checked += 1
    assert checked > 100  # most of RK4's weights are left out


def _with_and_without_support(data, order: int, make):
    """The condition sums of every order up to ``order`` in the context ``make(A, b)``
    (point entries), over every row and over the rows the zeros leave."""
    A, b = data
    listing = ConditionListing(order, None)
    wanted = sorted(listing.orders)
    pA, pb = _points(A, b)
    full = condition_sums(listing, make(pA, pb), len(b), wanted)
    some = condition_sums(listing, SupportContext(make(pA, pb), *zero_pattern(A, b)), len(b), wanted)
    return [(full[n], some[n]) for n in wanted]


@pytest.mark.parametrize("data", [RK4, DIRK])
def test_ball_mid_points_are_those_of_every_row(data):
    for full, some in _with_and_without_support(data, 9, lambda A, b: BallContext(A, b, 120)):
        assert list(some.mids) == list(full.mids)
        assert np.all(some.rads <= full.rads)


@pytest.mark.parametrize("data", [RK4, DIRK])
def test_screen_mid_points_are_those_of_every_row(data):
    for full, some in _with_and_without_support(data, 10, FloatContext):
        assert some.mid.tobytes() == full.mid.tobytes()
        assert np.all(some.rad <= full.rad)


def test_zero_pattern_reads_exact_numbers_and_point_intervals():
    zA, zb = zero_pattern([[0, Interval(Fraction(0), Fraction(0))], [Interval(Fraction(-1, 10**9), Fraction(1, 10**9)), 1]],
                          [Fraction(0), Interval(Fraction(1), Fraction(1))])
    assert zA.tolist() == [[True, True], [False, False]]  # an interval around 0 may be nonzero
    assert zb.tolist() == [True, False]


@pytest.mark.parametrize("data", [RK4, DIRK])
def test_digit_ball_mid_points_are_those_of_every_row(data):
    # the digit balls keep one multiplier per term of an order: the rows given to them
    # must read the multipliers of their own terms (orders of 15 vertices and more)
    from rkcheck.evaluation.limbs import LimbBallContext

    def context(A, b):
        ctx = LimbBallContext.create(A, b, 190, 16)
        assert ctx is not None
        return ctx

    for full, some in _with_and_without_support(data, 15, context):
        assert list(some.mids) == list(full.mids)
        # radius bounds summed in another grouping of runs: equal up to their last bits
        assert np.all(some.rads <= full.rads * (1 + 2.0**-40))


@pytest.mark.parametrize("s", range(1, 10))
def test_rows_with_a_flag_are_those_with_any_stage_set(s):
    # rows of 2, 4 or 8 flags are read as one integer: the same rows as or-ing the stages
    rng = np.random.default_rng(s)
    flags = rng.random((200, s)) < 0.15
    expected = [bool(row.any()) for row in flags]
    assert _rows(flags).tolist() == expected
    assert _rows(np.asfortranarray(flags)).tolist() == expected
    assert _rows(flags[::2]).tolist() == expected[::2]
    assert _rows(flags[:0]).tolist() == []
