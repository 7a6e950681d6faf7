"""Enclosures in mean value form: a function of a box of inputs held as its exact value
at the box's centre and enclosures of its partial derivatives over the box
(definitions §5.2).

Interval arithmetic treats every occurrence of an input as independent of the others,
so ``b(1 − b)`` with ``b ∈ [1.0000005, 1.0000015]`` encloses about ``[−3·10⁻⁶, 10⁻⁶]``:
it contains 0, although the function is below ``−5·10⁻⁷`` on the whole box.  The mean
value theorem removes that dependency to first order: for the centre ``x̃`` of the box
``X`` (radius ``r_e`` along each input ``e``),

    f(x) ∈ f(x̃) + Σ_e ∂_e f(X) · [−r_e, r_e]   for every x in X,

with ``∂_e f(X)`` an enclosure of the partial derivative over all of ``X``.  A
:class:`Centred` value carries ``f(x̃)`` exactly (a Fraction) and those enclosures
(float intervals, every operation rounded outwards: a derivative is multiplied by a
radius, so a few correct digits are all it needs, and exact end points made a 6-stage
tableau's properties 20 times slower), which the product rule propagates through
``+ − × ÷``; its ``lo``/``hi`` are that form intersected with the plain interval
result, so it is never wider than interval arithmetic and, like it, always an
enclosure.  It *is* an
:class:`~rkcheck.numbers.intervals.Interval` (a subclass), so everything that reads an
enclosure reads it unchanged; mixed with a plain point interval, a Fraction or an int,
the result stays centred (Python tries the subclass's reflected operator first).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rkcheck.numbers.intervals import Interval, float_above

#: an enclosure ``(lo, hi)`` of a partial derivative, in floats
_Slope = tuple[float, float]
_Slopes = tuple[tuple[int, _Slope], ...]
_ANY: _Slope = (-math.inf, math.inf)
_ONE: _Slope = (1.0, 1.0)


@dataclass(frozen=True, slots=True)
class Centred(Interval):
    """``f`` over the box: the enclosure ``[lo, hi]``, ``f(x̃)`` exactly (``centre``),
    and ``(e, ∂_e f(X))`` for the inputs ``f`` depends on (``slopes``); ``radii[e]`` is
    the box's radius along input ``e`` (a float rounded up)."""

    centre: Fraction
    slopes: _Slopes
    radii: tuple[float, ...]

    @staticmethod
    def inputs(boxes: list[Interval]) -> list[Interval]:
        """The inputs of a box: each interval that is not a point as a centred value
        depending on itself alone (centre its mid-point), the points as they are."""
        moving = [i for i, x in enumerate(boxes) if not x.is_point]
        radii = tuple(float_above(boxes[i].rad) for i in moving)
        out = list(boxes)
        for e, i in enumerate(moving):
            x = boxes[i]
            out[i] = Centred(x.lo, x.hi, x.mid, ((e, _ONE),), radii)
        return out

    # ------------------------------------------------------------------ construction

    def _made(self, centre: Fraction, slopes: dict[int, _Slope], plain: Interval) -> Interval:
        if not slopes:
            return Interval.point(centre)
        spread = 0.0
        for e, (lo, hi) in slopes.items():
            spread = _add_up(spread, _mul_up(max(-lo, hi), self.radii[e]))
        lo_, hi_ = plain.lo, plain.hi
        if math.isfinite(spread):
            reach = Fraction(spread)
            lo_, hi_ = max(centre - reach, lo_), min(centre + reach, hi_)
        return Centred(lo_, hi_, centre, tuple(sorted(slopes.items())), self.radii)

    def _range(self) -> Interval:
        return Interval(self.lo, self.hi)

    # ------------------------------------------------------------------ arithmetic

    def __neg__(self) -> Interval:
        return self._made(-self.centre, {e: (-hi, -lo) for e, (lo, hi) in self.slopes}, -self._range())

    def __add__(self, other: Any) -> Interval:
        parts = _parts(other)
        if parts is None:
            return NotImplemented if not isinstance(other, Interval) else self._range() + other
        centre, slopes, plain = parts
        merged = dict(self.slopes)
        for e, g in slopes:
            merged[e] = _slope_sum(merged[e], g) if e in merged else g
        return self._made(self.centre + centre, merged, self._range() + plain)

    __radd__ = __add__

    def __sub__(self, other: Any) -> Interval:
        negated = _negated(other)
        if negated is NotImplemented:
            return NotImplemented
        out: Interval = self + negated
        return out

    def __rsub__(self, other: Any) -> Interval:
        out: Interval = (-self) + other
        return out

    def __mul__(self, other: Any) -> Interval:
        parts = _parts(other)
        if parts is None:
            return NotImplemented if not isinstance(other, Interval) else self._range() * other
        centre, slopes, plain = parts
        mine = self._range()
        # ∂(fg) = f·∂g + g·∂f, each factor enclosed over the whole box
        theirs_f, mine_f = _floats(plain), _floats(mine)
        merged = {e: _slope_product(theirs_f, g) for e, g in self.slopes}
        for e, g in slopes:
            term = _slope_product(mine_f, g)
            merged[e] = _slope_sum(merged[e], term) if e in merged else term
        return self._made(self.centre * centre, merged, mine * plain)

    __rmul__ = __mul__

    def reciprocal(self) -> Interval:
        """``1/f``; like :meth:`Interval.reciprocal`, only where the enclosure excludes 0."""
        plain = self._range().reciprocal()
        factor = _floats(-(plain * plain))  # ∂(1/f) = −∂f/f²
        return self._made(1 / self.centre, {e: _slope_product(factor, g) for e, g in self.slopes}, plain)

    def __truediv__(self, other: Any) -> Interval:
        if isinstance(other, (int, Fraction)) and not isinstance(other, bool):
            return self * (1 / Fraction(other))  # ZeroDivisionError for 0, as Fraction's
        if isinstance(other, Interval):
            return self * other.reciprocal()
        return NotImplemented

    def __rtruediv__(self, other: Any) -> Interval:
        out: Interval = self.reciprocal() * other
        return out

    def power(self, n: int) -> Interval:
        if n < 0:
            return self.power(-n).reciprocal()
        out: Interval = Interval.point(1)
        for _ in range(n):
            out = self * out
        return out

    def round_out(self, bits: int) -> Interval:
        """The enclosure rounded outwards (the centre stays exact)."""
        plain = self._range().round_out(bits)
        return Centred(plain.lo, plain.hi, self.centre, self.slopes, self.radii)

    def sqrt(self, bits: int) -> Interval:
        return self._range().sqrt(bits)


def _parts(x: Any) -> tuple[Fraction, _Slopes, Interval] | None:
    """(value at the centre, slopes, enclosure) of a centred value or a constant; None
    for an interval that is not a point (no centre known: plain interval arithmetic)."""
    if isinstance(x, Centred):
        return x.centre, x.slopes, Interval(x.lo, x.hi)
    if isinstance(x, Interval):
        return (x.lo, (), x) if x.is_point else None
    if isinstance(x, (int, Fraction)) and not isinstance(x, bool):
        q = Fraction(x)
        return q, (), Interval.point(q)
    return None


def _negated(x: Any) -> Any:
    if isinstance(x, (Interval, int, Fraction)) and not isinstance(x, bool):
        return -x
    return NotImplemented


# ------------------------------------------------------------------ float enclosures


def _down(x: float) -> float:
    return math.nextafter(x, -math.inf)


def _floats(x: Interval) -> _Slope:
    """A float enclosure of the rational interval ``x``."""
    return -float_above(-x.lo), float_above(x.hi)


def _add_up(a: float, b: float) -> float:
    return math.nextafter(a + b, math.inf)


def _mul_up(a: float, b: float) -> float:
    p = a * b
    return math.inf if math.isnan(p) else math.nextafter(p, math.inf)


def _slope_sum(a: _Slope, b: _Slope) -> _Slope:
    lo, hi = a[0] + b[0], a[1] + b[1]
    if math.isnan(lo) or math.isnan(hi):
        return _ANY
    return _down(lo), math.nextafter(hi, math.inf)


def _slope_product(a: _Slope, b: _Slope) -> _Slope:
    """The float interval product, rounded outwards (each product is the exact one
    rounded to nearest, so one ulp outwards covers it; inf·0 claims nothing)."""
    products = (a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1])
    if any(math.isnan(p) for p in products):
        return _ANY
    return _down(min(products)), math.nextafter(max(products), math.inf)


__all__ = ["Centred"]
