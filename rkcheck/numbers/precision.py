"""Decimal digits and binary bits: the one place that converts between them.

``dps`` (decimal digits) is what users ask for; the arithmetic works in bits.  Every
conversion adds guard bits so that the rounding of long sums and products stays below
the requested precision.
"""

from __future__ import annotations

import math

LOG2_10 = math.log2(10)

#: Extra bits of the certified ball arithmetic: the rounding of sums of many terms.
GUARD_BITS = 32
#: Extra bits at which entries are enclosed before they enter the arithmetic.
ENTRY_GUARD_BITS = 8


def bits_for_digits(digits: int | float, guard: int = 0) -> int:
    """The bits that hold ``digits`` decimal digits, plus ``guard`` bits."""
    return math.ceil(digits * LOG2_10) + guard


def bits_for_dps(dps: int) -> int:
    """Working bits of the ball arithmetic at ``dps`` decimal digits (with guard bits)."""
    return bits_for_digits(dps, GUARD_BITS)


def entry_bits(dps: int) -> int:
    """Bits at which entries are enclosed for a check at ``dps`` digits."""
    return bits_for_dps(dps) + ENTRY_GUARD_BITS


def mpmath_bits(dps: int) -> int:
    """Bits at which exact data is enclosed before it is handed to mpmath at ``dps``
    digits (mpmath computes without a certificate; 40 guard bits keep the input exact
    to well below its working precision)."""
    return bits_for_digits(dps, 40)
