"""Closed intervals with exact rational end points (definitions §5).

Every arithmetic operation on tableau entries is carried out here exactly; the only
inexact step is ``sqrt`` of a non-square, whose end points are rounded *outwards* to
dyadic rationals with the requested number of bits.  The result is therefore a
rigorous enclosure of the true value, whatever the expression, without relying on the
rounding modes of any floating-point library.

Entries are short expressions, so exact end points cost nothing here; the hot loops of
the energy check never see this class (they run on the fixed-point balls of
:mod:`rkcheck.evaluation.backends`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction


@dataclass(frozen=True, slots=True)
class Interval:
    """The closed interval ``[lo, hi]`` with rational end points, ``lo <= hi``."""

    lo: Fraction
    hi: Fraction

    @staticmethod
    def point(x: Fraction | int) -> "Interval":
        x = Fraction(x)
        return Interval(x, x)

    @property
    def is_point(self) -> bool:
        return self.lo == self.hi

    @property
    def mid(self) -> Fraction:
        return (self.lo + self.hi) / 2

    @property
    def rad(self) -> Fraction:
        return (self.hi - self.lo) / 2

    def round_out(self, bits: int) -> "Interval":
        """Widen to dyadic end points with ``bits`` fractional bits (points stay exact),
        so that long interval computations do not grow huge denominators."""
        if self.is_point:
            return self
        scale = 1 << bits
        return Interval(
            Fraction(math.floor(self.lo * scale), scale), Fraction(math.ceil(self.hi * scale), scale)
        )

    def contains_zero(self) -> bool:
        return self.lo <= 0 <= self.hi

    def __neg__(self) -> "Interval":
        return Interval(-self.hi, -self.lo)

    def __add__(self, other: "Interval") -> "Interval":
        return Interval(self.lo + other.lo, self.hi + other.hi)

    def __sub__(self, other: "Interval") -> "Interval":
        return Interval(self.lo - other.hi, self.hi - other.lo)

    def __mul__(self, other: "Interval") -> "Interval":
        """By the signs of the end points, which pick the products that bound it (two,
        or four where both intervals hold 0 inside): comparing products of long
        fractions costs more than forming them."""
        a, b = self, other
        if a.is_point and b.is_point:
            return Interval.point(a.lo * b.lo)
        if a.lo >= 0:
            if b.lo >= 0:
                return Interval(a.lo * b.lo, a.hi * b.hi)
            return Interval(a.hi * b.lo, a.lo * b.hi) if b.hi <= 0 else Interval(a.hi * b.lo, a.hi * b.hi)
        if a.hi <= 0:
            if b.lo >= 0:
                return Interval(a.lo * b.hi, a.hi * b.lo)
            return Interval(a.hi * b.hi, a.lo * b.lo) if b.hi <= 0 else Interval(a.lo * b.hi, a.lo * b.lo)
        if b.lo >= 0:
            return Interval(a.lo * b.hi, a.hi * b.hi)
        if b.hi <= 0:
            return Interval(a.hi * b.lo, a.lo * b.lo)
        return Interval(min(a.lo * b.hi, a.hi * b.lo), max(a.lo * b.lo, a.hi * b.hi))

    def reciprocal(self) -> "Interval":
        """``1/x``; the caller must have excluded intervals that contain 0."""
        if self.contains_zero():
            raise ZeroDivisionError("interval contains zero")
        return Interval(1 / self.hi, 1 / self.lo)

    def __truediv__(self, other: "Interval") -> "Interval":
        return self * other.reciprocal()

    def power(self, n: int) -> "Interval":
        """``x**n`` for an integer ``n`` (tight: even powers of a sign-changing interval start at 0)."""
        if n < 0:
            return self.power(-n).reciprocal()
        if n == 0:
            return Interval.point(1)
        lo_n, hi_n = self.lo**n, self.hi**n
        if n % 2 == 1:
            return Interval(lo_n, hi_n)
        if self.lo >= 0:
            return Interval(lo_n, hi_n)
        if self.hi <= 0:
            return Interval(hi_n, lo_n)
        return Interval(Fraction(0), max(lo_n, hi_n))

    def sqrt(self, bits: int) -> "Interval":
        """Outward-rounded square root; end points are multiples of ``2**-bits``.

        Exact squares of rationals stay exact, so ``sqrt(9/4)`` is the point 3/2.
        The caller must have excluded negative values.
        """
        if self.lo < 0:
            raise ValueError("square root of a negative number")
        if self.is_point:
            exact = exact_sqrt(self.lo)
            if exact is not None:
                return Interval.point(exact)
        scale = 1 << (2 * bits)
        lo = _isqrt_floor(self.lo * scale)
        hi_arg = self.hi * scale
        hi = math.isqrt(math.ceil(hi_arg))
        if hi * hi < hi_arg:
            hi += 1
        return Interval(Fraction(lo, 1 << bits), Fraction(hi, 1 << bits))


def float_above(x: Fraction | float) -> float:
    """One float above ``x`` (rounded to nearest, then up): inf past float64's range."""
    try:
        return math.nextafter(float(x), math.inf)
    except OverflowError:
        return math.inf


def interval_sum(xs: Iterable[Interval]) -> Interval:
    """The sum of intervals (the point 0 for none)."""
    total = Interval.point(0)
    for x in xs:
        total = total + x
    return total


def _isqrt_floor(x: Fraction) -> int:
    """floor(sqrt(x)) for a rational x >= 0."""
    return math.isqrt(math.floor(x))


def exact_sqrt(x: Fraction) -> Fraction | None:
    """The square root of ``x`` if it is rational, else None."""
    if x < 0:
        return None
    num, den = x.numerator, x.denominator
    rn, rd = math.isqrt(num), math.isqrt(den)
    if rn * rn == num and rd * rd == den:
        return Fraction(rn, rd)
    return None
