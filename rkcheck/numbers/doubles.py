"""What a decimal literal stands for (definitions §5.2): the reals a rounded decimal
may have been rounded from, and the rounding interval of the binary64 double it names,
exact rationals both (:meth:`rkcheck.numbers.grammar.Num.interval`)."""

from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache


@lru_cache(maxsize=4096)
def rounded_interval(value: Fraction, digits: int | None, last_digit_exponent: int,
                      with_double: bool) -> tuple[Fraction, Fraction]:
    """What a rounded decimal literal stands for
    (:meth:`~rkcheck.numbers.grammar.Num.interval`), kept by its value and digits: a
    literal of a kernel is enclosed once in every entry of its surrogate, thousands of
    times per pass."""
    h = Fraction(1, 2) * Fraction(10) ** last_digit_exponent
    lo, hi = value - h, value + h
    if with_double:
        d = double_interval(value, written_digits=digits)
        if d is not None:
            lo, hi = min(lo, d[0]), max(hi, d[1])
    return lo, hi


@lru_cache(maxsize=4096)
def double_box(value: Fraction) -> tuple[Fraction, Fraction] | None:
    """:func:`double_interval` of a literal read as a double (``--decimals float64``),
    kept by its value."""
    return double_interval(value)


def double_interval(value: Fraction, written_digits: int | None = None) -> tuple[Fraction, Fraction] | None:
    """The rounding interval of the binary64 double nearest to ``value``: the closed
    interval of reals that round to it (half an ulp each side; the spacing below a power
    of two is half the spacing above; a nonzero value below half the smallest subnormal
    rounds to a signed zero, whose interval reaches from 0 to that half).  None when
    ``value`` is zero or rounds past binary64's range, or, given ``written_digits``, when
    a literal of ``value`` with that many significant digits is not the double's shortest
    decimal representation (``repr``)."""
    if value == 0:
        return None
    try:
        f = float(value)  # correctly rounded (Fraction.__float__ divides exactly)
    except OverflowError:
        return None  # rounds to infinity: no double stands for it
    if written_digits is not None and (Fraction(repr(f)) != value or _significant_digits(repr(f)) != written_digits):
        return None
    if f == 0:
        return (Fraction(0), _HALF_SUBNORMAL) if value > 0 else (-_HALF_SUBNORMAL, Fraction(0))
    x = Fraction(f)
    lo, hi = (x + _next_double(f, -math.inf)) / 2, (x + _next_double(f, math.inf)) / 2
    return lo, hi


def _next_double(f: float, towards: float) -> Fraction:
    """The double next to ``f`` towards ``towards``; past the largest double, where the
    next is infinite, the point one spacing further (rounding reaches infinity halfway)."""
    g = math.nextafter(f, towards)
    return Fraction(g) if math.isfinite(g) else 2 * Fraction(f) - Fraction(math.nextafter(f, -towards))


#: Half the smallest subnormal double: reals up to it round to zero (ties to even).
_HALF_SUBNORMAL = Fraction(1, 2**1075)


def _significant_digits(text: str) -> int:
    """Significant digits of Python's ``repr`` of a finite double, counted as a literal's
    are (leading zeros dropped, trailing ones kept: ``1e-05`` -> 1, ``123.0`` -> 4,
    ``0.16666666666666666`` -> 17), so that ``562949953421312.0`` as written is that
    double's repr."""
    mantissa = text.lstrip("-").split("e")[0].replace(".", "")
    return len(mantissa.lstrip("0")) or 1
