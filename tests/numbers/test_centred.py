"""Enclosures in mean value form (rkcheck.numbers.centred), against exact rational
evaluation at points of the box and against plain interval arithmetic."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest

from rkcheck.numbers.centred import Centred
from rkcheck.numbers.intervals import Interval


def _random_box(rng: random.Random, n: int) -> list[Interval]:
    box = []
    for _ in range(n):
        mid = Fraction(rng.randint(-2000, 2000), rng.randint(1, 300))
        rad = Fraction(rng.randint(0, 5), 10 ** rng.randint(1, 9))  # some points among them
        box.append(Interval(mid - rad, mid + rad))
    return box


def _expression(rng: random.Random, n: int, depth: int) -> list:
    """A random expression tree over the inputs 0 … n−1 and small rational constants."""
    if depth == 0 or rng.random() < 0.25:
        return ["x", rng.randrange(n)] if rng.random() < 0.8 else ["c", Fraction(rng.randint(-9, 9), rng.randint(1, 9))]
    op = rng.choice("+-*/")
    return [op, _expression(rng, n, depth - 1), _expression(rng, n, depth - 1)]


def _evaluate(e: list, x: list, lift=Interval.point):
    """``e`` at the inputs ``x``, its constants lifted by ``lift`` (point intervals, as
    the tableau algebra's constants are, or the Fractions themselves)."""
    kind = e[0]
    if kind == "x":
        return x[e[1]]
    if kind == "c":
        return lift(e[1])
    a, b = _evaluate(e[1], x, lift), _evaluate(e[2], x, lift)
    if kind == "+":
        return a + b
    if kind == "-":
        return a - b
    if kind == "*":
        return a * b
    return a / b


@pytest.mark.parametrize("seed", range(40))
def test_the_mean_value_form_encloses_every_point_and_is_never_wider(seed):
    rng = random.Random(seed)
    n = rng.randint(1, 4)
    box = _random_box(rng, n)
    e = _expression(rng, n, 4)
    try:
        plain = _evaluate(e, box)
        centred = _evaluate(e, Centred.inputs(box))
    except ZeroDivisionError:  # a divisor whose enclosure contains 0: refused by both
        pytest.skip("a divisor's enclosure contains 0")
    centred = centred if isinstance(centred, Interval) else Interval.point(Fraction(centred))
    plain = plain if isinstance(plain, Interval) else Interval.point(Fraction(plain))
    assert plain.lo <= centred.lo <= centred.hi <= plain.hi
    # the exact function at the corners, the centre and random points of the box
    points = [[x.lo for x in box], [x.hi for x in box], [x.mid for x in box]]
    points += [[x.lo + (x.hi - x.lo) * Fraction(rng.randint(0, 64), 64) for x in box] for _ in range(20)]
    for p in points:
        try:
            value = Fraction(_evaluate(e, p, Fraction))
        except ZeroDivisionError:
            continue
        assert centred.lo <= value <= centred.hi


def test_a_product_nonzero_on_the_whole_box_is_found_so():
    # M = 2·b·(1/2) − b² = b(1 − b), the symplecticity defect of the one-stage method
    # (1/2; b), on b = 1.000001 ± 5·10⁻⁷: it decreases through the box from
    # −5.0000025·10⁻⁷ to −1.5000023·10⁻⁶ (by hand), so it is nonzero on all of it;
    # plain intervals, taking the three b's as independent, contain 0
    b = Interval(Fraction("1.0000005"), Fraction("1.0000015"))
    half = Interval.point(Fraction(1, 2))
    (cb,) = Centred.inputs([b])
    plain = b * half + b * half - b * b
    centred = cb * half + cb * half - cb * cb
    assert plain.contains_zero() and not centred.contains_zero()
    ends = [x * (1 - x) for x in (b.lo, b.hi)]
    assert centred.lo <= min(ends) and max(ends) <= centred.hi < 0


def test_an_expression_constant_on_the_box_is_enclosed_within_rounding():
    # its derivatives cancel (in floats rounded outwards, to within a few ulps): the
    # enclosure is its value, widened by the rounding times the box's radius only
    x = Interval(Fraction(1, 3), Fraction(1, 2))
    (cx,) = Centred.inputs([x])
    for e in (cx * 2 - cx - cx, cx - cx):
        assert e.contains_zero() and e.hi - e.lo <= Fraction(1, 2**48) * x.rad
