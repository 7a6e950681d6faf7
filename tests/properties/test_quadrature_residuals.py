"""The running residuals Σ b_i c_i^(k−1) − 1/k against their definition, each power taken
anew (and, for Gauss-3, against the rule's exactness by hand: zero for k ≤ 6 only)."""

from __future__ import annotations

import itertools
from fractions import Fraction

from rkcheck.numbers import grammar as ex
from rkcheck.numbers.field_builder import field_of
from rkcheck.numbers.intervals import Interval
from rkcheck.properties import scalars as sc


def _first(b, c, n):
    return list(itertools.islice(sc.quadrature_residuals(b, c), n))


def test_rational_nodes_give_the_definitions_residuals():
    b = [Fraction(1, 6), Fraction(2, 3), Fraction(1, 6)]  # Simpson: exact for k ≤ 4
    c = [Fraction(0), Fraction(1, 2), Fraction(1)]
    got = _first(b, c, 8)
    assert got == [sum(bi * ci ** (k - 1) for bi, ci in zip(b, c)) - Fraction(1, k) for k in range(1, 9)]
    assert [r == 0 for r in got] == [True] * 4 + [False] * 4


def test_gauss_3_in_its_field_is_exact_to_degree_5():
    found = field_of([ex.parse(t) for t in ("1/2 - sqrt(15)/10", "1/2", "1/2 + sqrt(15)/10", "5/18", "4/9", "5/18")])
    c, b = found.values[:3], found.values[3:]
    got = _first(b, c, 8)
    assert [r == sc.quadrature_residual(b, c, k) for k, r in enumerate(got, start=1)] == [True] * 8
    assert [sc.verdict(r).state.value for r in got] == ["holds"] * 6 + ["fails"] * 2


def test_intervals_take_each_power_on_its_own():
    b = [Interval(Fraction(49, 100), Fraction(51, 100))] * 2
    c = [Interval(Fraction(-1, 3), Fraction(-1, 4)), Interval(Fraction(1, 4), Fraction(1, 3))]
    got = _first(b, c, 5)
    for k, r in enumerate(got, start=1):
        direct = sc.quadrature_residual(b, c, k)
        assert (r.lo, r.hi) == (direct.lo, direct.hi)
