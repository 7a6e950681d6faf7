"""Exact decimal rendering of rationals (no floating point, no mpmath import)."""

from __future__ import annotations

import math
from fractions import Fraction


def _at_least(p: int, q: int, e: int) -> bool:
    """p/q >= 10^e, in integers."""
    return bool(p >= q * 10**e) if e >= 0 else bool(p * 10**-e >= q)


def decimal_exponent(x: Fraction) -> int:
    """floor(log10 |x|) for x != 0, exactly (integer comparisons only)."""
    p, q = abs(x.numerator), x.denominator
    e = math.floor((p.bit_length() - q.bit_length()) * math.log10(2))
    while _at_least(p, q, e + 1):
        e += 1
    while not _at_least(p, q, e):
        e -= 1
    return e


def _scaled_round(p: int, q: int, up: bool) -> int:
    """p/q rounded half-even (or up) to an integer, p, q > 0."""
    n, r = divmod(p, q)
    if up:
        return n + (r > 0)
    twice = 2 * r
    return n + (twice > q or (twice == q and n % 2 == 1))


def _digits(x: Fraction, sig: int, up: bool = False) -> tuple[int, int]:
    """(N, e) with |x| ≈ N · 10^(e-sig+1), N having ``sig`` digits (rounded half-even or up)."""
    e = decimal_exponent(x)
    p, q = abs(x.numerator), x.denominator
    shift = sig - 1 - e  # |x| · 10^shift has sig digits before the point
    n = _scaled_round(p * 10**shift, q, up) if shift >= 0 else _scaled_round(p, q * 10**-shift, up)
    if n >= 10**sig:
        n = _scaled_round(n, 10, up)
        e += 1
    return n, e


def decimal_digits(x: Fraction, sig: int) -> tuple[int, int]:
    """(N, e) with |x| ≈ N · 10^(e-sig+1), N of ``sig`` digits (x ≠ 0, rounded half-even)."""
    return _digits(Fraction(x), sig)


def decimal_string(x: Fraction | int | float, sig: int = 20, up: bool = False, keep_zeros: bool = False) -> str:
    """``x`` rounded to ``sig`` significant digits (``up``: away from zero), e.g.
    ``-3.4722222222222222222e-4``, ``0.5``, ``12.25``.  Trailing zeros are dropped unless
    ``keep_zeros`` (then the text states exactly ``sig`` significant digits).  A float is
    taken at its exact binary value."""
    x = Fraction(x)
    if x == 0:
        return "0"
    n, e = _digits(x, sig, up)
    digits = str(n) if keep_zeros else (str(n).rstrip("0") or "0")
    sign = "-" if x < 0 else ""
    if -5 <= e < 16 and len(digits) <= max(e + 1, 0) + sig:
        # plain positional notation
        if e >= 0:
            whole = digits[: e + 1].ljust(e + 1, "0")
            frac = digits[e + 1:]
            return sign + whole + ("." + frac if frac else "")
        return sign + "0." + "0" * (-e - 1) + digits
    mant = digits[0] + ("." + digits[1:] if len(digits) > 1 else "")
    return f"{sign}{mant}e{e}"


def radius_string(r: Fraction | float) -> str:
    """A radius rounded *up* to 2 significant digits (an upper bound stays an upper bound)."""
    if r == 0:
        return "0"
    return decimal_string(r, 2, up=True)


def short(x: Fraction, sig: int = 6) -> str:
    return decimal_string(x, sig)


def exact_string(q: Fraction | int, max_digits: int = 40) -> str:
    """A rational written exactly: as a decimal when it has a short finite expansion
    (``0.99``, ``12.25``), else as ``p/q`` (``1/3``); a rational too long for either is
    its 20 leading digits, marked ``≈``."""
    q = Fraction(q)
    # lengths by bits first: Python refuses to write an integer of more than
    # sys.get_int_max_str_digits() digits (4 300 unless raised), and this never needs to
    bits = 3.33 * max_digits + 4
    if q.denominator == 1 and q.numerator.bit_length() <= bits and len(str(abs(q.numerator))) <= max_digits:
        return str(q.numerator)
    places = _decimal_places(q.denominator, max_digits)
    if places is not None:
        digits = _without_trailing_zeros(abs(q.numerator * 10**places // q.denominator))
        if digits.bit_length() <= bits and (sig := len(str(digits))) <= max_digits:
            return decimal_string(q, max(sig, 1))
    if q.numerator.bit_length() + q.denominator.bit_length() <= 3.33 * max_digits:
        return f"{q.numerator}/{q.denominator}"
    return "≈" + decimal_string(q, 20)


def _without_trailing_zeros(n: int) -> int:
    """``n`` with its trailing decimal zeros removed (``7e1000`` -> 7), never written out."""
    while n and n % 10**20 == 0:
        n //= 10**20
    while n and n % 10 == 0:
        n //= 10
    return n


def _decimal_places(denominator: int, limit: int) -> int | None:
    """The digits after the point of p/denominator when it terminates within a few
    times ``limit`` places (the denominator is 2^a·5^b), else None."""
    twos = (denominator & -denominator).bit_length() - 1
    rest = denominator >> twos
    fives = 0
    while rest % 5 == 0 and fives <= 4 * limit:
        rest //= 5
        fives += 1
    if rest != 1 or max(twos, fives) > 4 * limit:
        return None
    return max(twos, fives)


def ball_strings(mid: Fraction | float, rad: Fraction | float, sig: int) -> tuple[str, str]:
    """A ball ``mid ± rad`` as text that still encloses it: the mid-point rounded to
    ``sig`` significant digits, and the radius grown by what that rounding moved the
    mid-point, rounded up (a ball printed with fewer digits than its radius allows would
    otherwise leave out the value it stands for).  Floats are taken at their exact
    binary value; a ball that is not finite is ``nan ± inf``."""
    if any(isinstance(x, float) and not math.isfinite(x) for x in (mid, rad)):  # a Fraction is finite
        return "nan", "inf"
    text = decimal_string(mid, sig)
    return text, radius_string(Fraction(rad) + abs(Fraction(text) - Fraction(mid)))


def count_text(n: int) -> str:
    """A count as every text report prints it: plain up to 9999, in groups of three
    separated by commas from 10,000 on (``9999``, ``80,936``, ``3,489,323``); machine
    formats (JSON, CSV) keep plain integers."""
    return f"{n:,}" if abs(n) >= 10_000 else str(n)


def counted(n: int, noun: str, plural: str | None = None) -> str:
    """A count and its noun in agreement: ``1 error``, ``2 errors``, ``0 files``,
    ``80,936 conditions`` (the count as :func:`count_text` writes it)."""
    return f"{count_text(n)} {noun if n == 1 else (plural or noun + 's')}"


def digits_text(d: int | None) -> str:
    """``1 digit``, ``15 digits``: the certain digits of a verdict held to digits."""
    return counted(d or 0, "digit")


def human_bytes(n: float) -> str:
    """A size in bytes for people, in decimal units (1 KB = 1000 B)."""
    for unit in ("B", "KB", "MB", "GB", "TB", "PB"):
        if n < 1000 or unit == "PB":
            return f"{n:.0f} {unit}" if unit in ("B", "KB", "MB") else f"{n:.1f} {unit}"
        n /= 1000
    return f"{n:.1f} PB"  # pragma: no cover
