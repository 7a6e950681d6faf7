"""Which classical weights involve an interval entry (``properties.orders.Dependence``):
a weight said to involve none must be one number on the whole box — checked against
the reference's exact weights at random points of random boxes."""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
from support.reference import elementary_weight

from rkcheck.numbers.intervals import Interval
from rkcheck.properties.orders import Dependence, TreeWeights, unbounded_table


def _random_box(rng: random.Random, s: int) -> tuple[list[list[Interval]], list[Interval]]:
    def entry() -> Interval:
        kind = rng.random()
        if kind < 0.4:
            return Interval.point(Fraction(0))
        x = Fraction(rng.randint(-4, 4), rng.randint(1, 5))
        return Interval.point(x) if kind < 0.75 else Interval(x - Fraction(1, 1000), x + Fraction(1, 1000))

    return [[entry() for _ in range(s)] for _ in range(s)], [entry() for _ in range(s)]


def _sample(x: Interval, rng: random.Random) -> Fraction:
    return x.lo + (x.hi - x.lo) * Fraction(rng.randint(0, 64), 64)


def test_a_weight_free_of_the_intervals_is_one_number_on_the_box():
    rng = random.Random(3)
    table = unbounded_table()
    table.grow_to(5)
    free_seen = depends_seen = 0
    for _ in range(60):
        s = rng.choice([1, 2, 3])
        A, b = _random_box(rng, s)
        weights = TreeWeights(Dependence(A, b), s)
        points = [([[_sample(x, rng) for x in row] for row in A], [_sample(x, rng) for x in b]) for _ in range(6)]
        for p in range(1, 6):
            depends = weights.extend(table, p)
            for k, t in enumerate(range(table.first[p], table.first[p + 1])):
                tree = tuple(table.level_sequence(t))
                values = {elementary_weight(tree, pA, pb) for pA, pb in points}
                if not depends[k]:
                    free_seen += 1
                    assert len(values) == 1, (A, b, tree)
                elif len(values) > 1:
                    depends_seen += 1
    assert free_seen > 100 and depends_seen > 100  # both kinds met, often


def test_exact_zeros_cut_the_dependence():
    # b = (1, 0): stage 2, whose row holds the interval, is never read by a(t)
    A = [[Interval.point(Fraction(1, 2)), Interval.point(Fraction(0))],
         [Interval(Fraction(1, 10), Fraction(2, 10)), Interval.point(Fraction(0))]]
    b = [Interval.point(Fraction(1)), Interval.point(Fraction(0))]
    table = unbounded_table()
    table.grow_to(4)
    weights = TreeWeights(Dependence(A, b), 2)
    for p in range(1, 5):
        assert not np.any(weights.extend(table, p))
    # … and an interval in b reaches every weight
    weights = TreeWeights(Dependence(A, [b[0], Interval(Fraction(0), Fraction(1, 100))]), 2)
    assert all(np.all(weights.extend(table, p)) for p in range(1, 5))
