"""Polynomials with rational coefficients and their real roots, certified.

Coefficient lists are ascending (``[c0, c1, c2]`` is ``c0 + c1·x + c2·x²``) of Fractions.
Real roots are isolated by FLINT's certified complex root finder (``fmpz_poly
.complex_roots``, which proves which roots are real) on the square-free part, at rising
precision until every real root is enclosed in an interval of width at most ``2^-bits``;
the end points are exact rationals read off the Arb balls.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Sequence

from rkcheck.numbers.intervals import Interval


def _fmpq_poly(coeffs: Sequence[Fraction]):
    from flint import fmpq, fmpq_poly

    return fmpq_poly([fmpq(c.numerator, c.denominator) for c in map(Fraction, coeffs)])


def _fraction(x) -> Fraction:
    """An exact Arb point (or fmpq/fmpz) as a Fraction."""
    if hasattr(x, "man_exp"):
        man, exp = x.man_exp()
        man, exp = int(man), int(exp)
        return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)
    return Fraction(int(x.p), int(x.q)) if hasattr(x, "p") else Fraction(int(x))


def trim(coeffs: Sequence[Fraction]) -> list[Fraction]:
    """Drop leading (highest-degree) zero coefficients."""
    out = [Fraction(c) for c in coeffs]
    while len(out) > 1 and out[-1] == 0:
        out.pop()
    return out


def rational_roots(coeffs: Sequence[Fraction]) -> list[Fraction]:
    """The distinct rational roots, increasing."""
    coeffs = trim(coeffs)
    if len(coeffs) < 2:
        return []
    return sorted({_fraction(r) for r, _ in _fmpq_poly(coeffs).roots()})


def real_root_intervals(coeffs: Sequence[Fraction], bits: int) -> list[Interval]:
    """Certified enclosures of the distinct real roots, increasing, each of width
    ``<= 2^-bits`` (a point for a rational root).  ``coeffs`` must not be the zero
    polynomial."""
    from flint import arb, ctx

    coeffs = trim(coeffs)
    if all(c == 0 for c in coeffs):
        raise ValueError("the zero polynomial has no isolated roots")
    if len(coeffs) < 2:
        return []
    p = _fmpq_poly(coeffs)
    _, factors = p.factor_squarefree()
    squarefree = None
    for f, _ in factors:
        squarefree = f if squarefree is None else squarefree * f
    assert squarefree is not None  # degree >= 1 (trimmed, len >= 2): at least one factor
    numer = squarefree.numer()
    exact = {r: None for r in rational_roots(coeffs)}
    width = Fraction(1, 2**bits)
    prec = max(64, bits + 32)
    while True:
        with ctx.workprec(prec):
            roots = numer.complex_roots()
        intervals = []
        for r, _ in roots:
            # FLINT proves a root real by returning it with an exactly zero imaginary part
            real = r if isinstance(r, arb) else (r.real if r.imag.is_zero() else None)
            if real is not None:
                mid, rad = _fraction(real.mid()), _fraction(real.rad())
                intervals.append(Interval(mid - rad, mid + rad))
        if all(iv.hi - iv.lo <= width for iv in intervals):
            break
        prec *= 2
    intervals.sort(key=lambda iv: iv.lo)
    out = []
    for iv in intervals:
        inside = [r for r in exact if iv.lo <= r <= iv.hi]
        out.append(Interval.point(inside[0]) if len(inside) == 1 else iv)
    return out


def root_count_message(coeffs: Sequence[Fraction]) -> str:
    n = len(real_root_intervals(coeffs, 8))
    return f"{n} real root{'s' if n != 1 else ''}"


def poly_text(coeffs: Sequence[Fraction], variable: str = "x") -> str:
    """The polynomial as entry text (``x^2 - 15``), scaled to primitive integer
    coefficients with a positive leading one (same roots), highest power first."""
    coeffs = trim(coeffs)
    den = 1
    for c in coeffs:
        den = den * c.denominator // math.gcd(den, c.denominator)
    ints = [int(c * den) for c in coeffs]
    g = 0
    for n in ints:
        g = math.gcd(g, n)
    g = g or 1
    if ints[-1] < 0:
        g = -g
    ints = [n // g for n in ints]
    parts: list[tuple[int, str]] = []
    for k in range(len(ints) - 1, -1, -1):
        n = ints[k]
        if n == 0:
            continue
        mag = abs(n)
        power = "" if k == 0 else (variable if k == 1 else f"{variable}^{k}")
        if not power:
            text = str(mag)
        else:
            text = power if mag == 1 else f"{mag}*{power}"
        parts.append((1 if n > 0 else -1, text))
    if not parts:
        return "0"
    out = ("-" if parts[0][0] < 0 else "") + parts[0][1]
    for sign, text in parts[1:]:
        out += (" - " if sign < 0 else " + ") + text
    return out
