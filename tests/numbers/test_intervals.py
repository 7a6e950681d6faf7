"""Interval products against their definition: ``[a]·[b]`` is the smallest interval
holding the four products of end points (the product takes only those its signs pick)."""

from __future__ import annotations

from fractions import Fraction as F

from hypothesis import given, settings
from hypothesis import strategies as st

from rkcheck.numbers.intervals import Interval

# end points of every sign, zero and equal end points (points) among them
ends = st.fractions(min_value=-50, max_value=50, max_denominator=60) | st.sampled_from([F(0), F(1), F(-1)])


@st.composite
def intervals(draw):
    x, y = draw(ends), draw(ends)
    return Interval(min(x, y), max(x, y))


@settings(max_examples=300, deadline=None)
@given(intervals(), intervals())
def test_a_product_is_the_hull_of_the_four_end_point_products(a, b):
    products = [a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi]
    assert a * b == Interval(min(products), max(products))
    assert b * a == a * b


def test_every_sign_pattern_by_hand():
    # one case per row of the sign table, computed by hand
    I = lambda lo, hi: Interval(F(lo), F(hi))  # noqa: E731
    assert I(1, 2) * I(3, 4) == I(3, 8)
    assert I(1, 2) * I(-4, -3) == I(-8, -3)
    assert I(1, 2) * I(-3, 4) == I(-6, 8)
    assert I(-2, -1) * I(3, 4) == I(-8, -3)
    assert I(-2, -1) * I(-4, -3) == I(3, 8)
    assert I(-2, -1) * I(-3, 4) == I(-8, 6)
    assert I(-2, 1) * I(3, 4) == I(-8, 4)
    assert I(-2, 1) * I(-4, -3) == I(-4, 8)
    assert I(-2, 1) * I(-3, 4) == I(-8, 6)
    assert I(0, 0) * I(-3, 4) == I(0, 0)
