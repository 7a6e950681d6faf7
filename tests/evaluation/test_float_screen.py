"""The a-priori float screen and the balls behind it.

* the screen's enclosures (mid-point ± κ_n·S̄) contain the exact residuals, rebuilt
  exactly by the multi-modular evaluation, on random tableaux — cancelling ones too —
  and it never says ``fails`` where exact arithmetic says ``holds``;
* it is not made where its bound could not hold: entries that are not floats within
  2^−52, or weights that could underflow or overflow;
* screened balls are the balls: every verdict, digit count and enclosure (the mid-point
  exactly, the radius to its last bits) equals one pass of the certified balls over the
  whole listing, on Gauss-3 (entries in Q(√15)), a random tableau and one whose
  residuals lie below the balls' resolution (entries 2⁻²⁰), at 15 vertices, where the
  int64-digit balls run;
* a Ctrl-C during the screen leaves the finished orders' certified enclosures.
"""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
import pytest
from support.paths import TABLEAUX

from rkcheck.evaluation.algorithm import EvaluationInterrupted, condition_sums
from rkcheck.evaluation.backends import ball_context, screen_for
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_rational
from rkcheck.evaluation.screen import ScreenContext
from rkcheck.evaluation.screened import ScreenedSums, screened_sums
from rkcheck.evaluation.values import TableauValues
from rkcheck.io.loader import load
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import Reading
from rkcheck.trees.listing import ConditionListing
from rkcheck.verdicts import classify_bounds


def random_tableau(seed: int) -> tuple[list[list[Fraction]], list[Fraction]]:
    """Random rationals; one seed in three with entries of very different sizes and
    signs (large cancellations), and b summing to 1 in half of them (low orders vanish)."""
    rng = random.Random(seed)
    s = rng.randint(2, 4)
    scale = 10**6 if seed % 3 == 0 else 1
    A = [[Fraction(rng.randint(-12, 12) * rng.choice([1, scale]), rng.randint(1, 12)) for _ in range(s)]
         for _ in range(s)]
    b = [Fraction(rng.randint(-12, 12), rng.randint(1, 12)) for _ in range(s)]
    if seed % 2:
        b[-1] = 1 - sum(b[:-1])
    return A, b


def points(A, b):
    return [[Interval.point(x) for x in row] for row in A], [Interval.point(x) for x in b]


@pytest.mark.parametrize("seed", range(12))
def test_screen_encloses_the_exact_residuals(seed):
    A, b = random_tableau(seed)
    listing = ConditionListing(9, None)
    truth = exact_condition_sums(scaled_rational(A, b), listing)
    screen = ScreenContext.create(*points(A, b), max(listing.orders))
    assert screen is not None
    sums = condition_sums(listing, screen, len(b))
    failing = decided = 0
    for n, order in sums.items():
        zero, fails = truth[n].is_zero(), order.excludes_zero()
        assert not np.any(fails & zero)  # never fails where exact arithmetic holds
        for k in range(len(order)):
            e, t = order.enclosure(k), truth[n].value(k)
            assert abs(Fraction(e.mid) - t) <= Fraction(e.rad)
        failing += int(np.count_nonzero(~zero))
        decided += int(np.count_nonzero(fails))
    assert failing == 0 or decided / failing > 0.9  # random data fails by far more than a float's error


def test_screen_is_not_made_where_its_bound_could_fail():
    A, b = [[Fraction(0), Fraction(0)], [Fraction(1, 2), Fraction(0)]], [Fraction(1, 2), Fraction(1, 2)]
    assert ScreenContext.create(*points(A, b), 20) is not None
    tiny = [[Fraction(0), Fraction(0)], [Fraction(1, 10**20), Fraction(0)]]
    assert ScreenContext.create(*points(tiny, b), 10) is not None  # (10^−20)^10/9!: within 2^−1000
    assert ScreenContext.create(*points(tiny, b), 20) is None  # (10^−20)^20/19! could underflow
    huge = [[Fraction(0), Fraction(0)], [Fraction(10**40), Fraction(0)]]
    assert ScreenContext.create(*points(huge, b), 30) is None  # (10^40)^30 could overflow
    S, P = points(A, b)
    wide = [[S[0][0], S[0][1]], [Interval(Fraction(1, 2) - Fraction(1, 10**12), Fraction(1, 2)), S[1][1]]]
    assert ScreenContext.create(wide, P, 10) is None  # an entry known to 12 digits is no float
    third = [[S[0][0], S[0][1]], [Interval.point(Fraction(1, 3)), S[1][1]]]
    assert ScreenContext.create(third, P, 10) is not None  # 1/3 rounds within 2^−53


def _compare(values: TableauValues, order: int) -> int:
    """Every condition of ``order`` screened and in one pass of the balls: the same
    verdict, digits and enclosure; returns how many conditions the balls evaluated."""
    listing = ConditionListing(order, None)
    wanted = sorted(listing.orders)
    ctx = ball_context(values, wanted[-1])
    screen = screen_for(values, wanted, ctx.bits)
    assert screen is not None
    screened = screened_sums(listing, ctx, screen, values.stages, wanted)
    whole = condition_sums(listing, ctx, values.stages, wanted)
    opened = 0
    for n in wanted:
        # (an order the screen gave up on is one pass of the balls: every condition open)
        opened += len(screened[n].open) if isinstance(screened[n], ScreenedSums) else len(whole[n])
        got = classify_bounds(screened[n].excludes_zero(), screened[n].magnitude_bound())
        want = classify_bounds(whole[n].excludes_zero(), whole[n].magnitude_bound())
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1])
        for k in range(len(whole[n])):
            e, f = screened[n].enclosure(k), whole[n].enclosure(k)
            # radii: the same sums of the same terms; BLAS may round a row's matrix
            # product differently in a batch of another size (the subset's), in the last bit
            assert e.mid == f.mid and abs(e.rad - f.rad) <= f.rad * Fraction(1, 2**40)
    return opened


def test_screened_balls_are_the_balls_on_gauss_3():
    values = TableauValues.of(load(str(TABLEAUX / "collocation" / "gauss-3.toml")), Reading(arithmetic="ball"))
    opened = _compare(values, 14)
    assert 0 < opened < 13102 // 20  # the conditions Gauss-3 satisfies, and few others


def test_screened_balls_are_the_balls_on_a_random_tableau():
    rng = random.Random(7)
    # rows summing to c = (0, 1/2, 1), b Simpson's: bᵀ1 = 1 and bᵀc = 1/2, classical order 2,
    # so the condition of order 2 holds; the rest random
    A = [[Fraction(rng.randint(-2, 2), rng.randint(5, 9)) for _ in range(2)] for _ in range(3)]
    for row, c in zip(A, (Fraction(0), Fraction(1, 2), Fraction(1))):
        row.append(c - sum(row))
    b = [Fraction(1, 6), Fraction(2, 3), Fraction(1, 6)]
    values = TableauValues.of(Tableau.from_values(A, b), Reading(arithmetic="ball"))
    assert _compare(values, 14) >= 1


def test_a_report_of_the_low_orders_pays_for_those_alone():
    values = TableauValues.of(load(str(TABLEAUX / "collocation" / "gauss-3.toml")), Reading(arithmetic="ball"))
    listing = ConditionListing(14, None)
    wanted = sorted(listing.orders)
    ctx = ball_context(values, wanted[-1])
    sums = screened_sums(listing, ctx, screen_for(values, wanted, ctx.bits), values.stages, wanted)
    failing = int(np.flatnonzero(sums[9].excludes_zero())[0])
    sums[9].enclosure(failing)
    assert max(sums[9].whole.orders) == 9


def test_an_interrupted_screen_keeps_its_finished_orders(monkeypatch):
    A, b = random_tableau(1)
    listing = ConditionListing(10, None)
    truth = exact_condition_sums(scaled_rational(A, b), listing)
    S, P = points(A, b)
    screen = ScreenContext.create(S, P, 11)
    real = ScreenContext.add_terms

    def interrupted(self, acc, w_terms, terms, n, i0, i1):
        if n == 9:
            raise KeyboardInterrupt
        real(self, acc, w_terms, terms, n, i0, i1)

    monkeypatch.setattr(ScreenContext, "add_terms", interrupted)
    with pytest.raises(EvaluationInterrupted) as stop:
        ctx = ball_context(TableauValues.of(Tableau.from_values(A, b), Reading(arithmetic="ball")))
        screened_sums(listing, ctx, screen, len(b), sorted(listing.orders))
    assert sorted(stop.value.finished) == list(range(3, 9))  # 3 vertices: order 2, the first
    for n, order in stop.value.finished.items():
        for k in range(len(order)):
            e = order.enclosure(k)
            assert abs(Fraction(e.mid) - truth[n].value(k)) <= Fraction(e.rad)



def test_screened_balls_are_the_balls_at_high_precision():
    """Beyond the int64 digits' precision the balls are Python integers: screened the same."""
    values = TableauValues.of(load(str(TABLEAUX / "collocation" / "gauss-3.toml")), Reading(dps=150, arithmetic="ball"))
    assert type(ball_context(values, 15)).__name__ == "BallContext"
    assert _compare(values, 14) > 0


def test_residuals_below_the_balls_resolution_are_left_to_the_balls():
    """Entries 2⁻²⁰: most residuals are nonzero but below the 50-digit balls' unit 2⁻¹⁹⁹
    — the balls say "holds to D digits", and so must the screened check (the screen's
    radii are widened by the balls' resolution, so it leaves them open)."""
    t = Fraction(1, 2**20)
    values = TableauValues.of(Tableau.from_values([[t, 0], [2 * t, t]], [t, t]), Reading(arithmetic="ball"))
    assert _compare(values, 14) > 10_000


def test_progress_tells_every_order_once_when_the_screen_gives_way():
    """An energy-preserving method leaves every condition open: the screen gives way to
    one pass of the balls, and each order is told to the progress callback once, in
    order."""
    values = TableauValues.of(load(str(TABLEAUX / "avf" / "avf-gauss-2.toml")), Reading(arithmetic="ball"))
    listing = ConditionListing(14, None)
    wanted = sorted(listing.orders)
    ctx = ball_context(values, wanted[-1])
    told: list[int] = []
    sums = screened_sums(listing, ctx, screen_for(values, wanted, ctx.bits), values.stages, wanted,
                         lambda n, _: told.append(n))
    assert told == wanted
    assert not any(isinstance(x, ScreenedSums) for x in sums.values())
