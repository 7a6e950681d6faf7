"""Polynomials: every polynomial rkcheck computes with goes through this module.

A polynomial is a list of coefficients, lowest power first (``[c0, c1, c2]`` is
``c0 + c1·x + c2·x²``); results keep at least one coefficient (``[0]`` is zero).

* **Arithmetic over any field** — sums, products, division with remainder, Euclid's gcd,
  Horner's scheme, ``p(x + h)`` — is written once here for Fractions, the number-field
  elements of :mod:`rkcheck.numbers.algebraic` and (without division) intervals.  FLINT
  has no polynomials over those fields.  Callers pass the zero of their field and, for
  coefficients that cannot be compared with 0 (intervals), the test for zero.
* **Over Q**, FLINT (``fmpq_poly``) does the algebra: gcd, exact division, square-free
  factorisation, factorisation, rational roots and certified real roots
  (:class:`RealRoots`).  FLINT is imported on first use, so that checking a small rational
  tableau never loads it (start-up).

Real roots are isolated by FLINT's certified complex root finder (``fmpz_poly
.complex_roots``, which proves which roots are real) on the square-free part, at rising
precision until every real root is enclosed in an interval of width at most ``2^-bits``;
the end points are exact rationals read off the Arb balls, and a rational root is the
point it is.
"""

from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache
from typing import Any, Callable, Sequence, cast

from rkcheck.numbers.intervals import Interval

Poly = list[Any]  # coefficients, lowest power first
ZeroTest = Callable[[Any], bool]

_ZERO = Fraction(0)


def _equals_zero(c: Any) -> bool:
    # an exact zero (Fraction, int, number-field element); an interval is never one
    return not c


# ------------------------------------------------------------ over any field


def trim(p: Sequence[Any], is_zero: ZeroTest = _equals_zero) -> Poly:
    """Drop leading (highest-power) zero coefficients, keeping at least one."""
    out = list(p)
    while len(out) > 1 and is_zero(out[-1]):
        out.pop()
    return out


def is_zero_poly(p: Sequence[Any], is_zero: ZeroTest = _equals_zero) -> bool:
    return all(is_zero(c) for c in p)


def add(p: Sequence[Any], q: Sequence[Any], zero: Any = _ZERO) -> Poly:
    n = max(len(p), len(q))
    return [(p[k] if k < len(p) else zero) + (q[k] if k < len(q) else zero) for k in range(n)]


def sub(p: Sequence[Any], q: Sequence[Any], zero: Any = _ZERO) -> Poly:
    n = max(len(p), len(q))
    return [(p[k] if k < len(p) else zero) - (q[k] if k < len(q) else zero) for k in range(n)]


def scale(p: Sequence[Any], a: Any) -> Poly:
    """``a·p``."""
    return [a * c for c in p]


#: a product of rational polynomials with more pairs of coefficients than this is
#: FLINT's: the schoolbook sum in Fractions of a 200-stage tableau's R(z)R(−z) (hundreds
#: of digits in each of 40 000 products) takes seconds
MAX_FRACTION_PRODUCT = 256


def mul(p: Sequence[Any], q: Sequence[Any], zero: Any = _ZERO) -> Poly:
    """``p·q`` (schoolbook over any field: the polynomials here are mostly short, their
    coefficients not; long rational ones by FLINT)."""
    if not p or not q:
        return [zero]
    if len(p) * len(q) > MAX_FRACTION_PRODUCT and _rational(zero) and _rational(*p) and _rational(*q):
        coeffs = from_flint(to_flint(p) * to_flint(q))
        return coeffs + [Fraction(0)] * (len(p) + len(q) - 1 - len(coeffs))
    out = [zero] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        if _equals_zero(a):
            continue
        for j, b in enumerate(q):
            out[i + j] = out[i + j] + a * b
    return out


def _rational(*coeffs: Any) -> bool:
    return all(isinstance(c, (Fraction, int)) for c in coeffs)


def reflect(p: Sequence[Any]) -> Poly:
    """``p(−x)``."""
    return [-c if k % 2 else c for k, c in enumerate(p)]


def derivative(p: Sequence[Any]) -> Poly:
    return [k * p[k] for k in range(1, len(p))] or [_ZERO]


def integral(p: Sequence[Any]) -> Poly:
    """The antiderivative vanishing at 0."""
    return [_ZERO] + [c / (k + 1) for k, c in enumerate(p)]


def evaluate(p: Sequence[Any], x: Any, zero: Any = _ZERO) -> Any:
    """``p(x)`` by Horner's scheme."""
    acc = zero
    for c in reversed(p):
        acc = acc * x + c
    return acc


def evaluate_at_interval(coeffs: Sequence[Fraction], x: Interval) -> Interval:
    """The polynomial with rational ``coeffs`` at the interval ``x`` (Horner's scheme)."""
    value: Interval = evaluate([Interval.point(c) for c in coeffs], x, Interval.point(0))
    return value


def shift(p: Sequence[Any], h: Any, zero: Any = _ZERO, one: Any = Fraction(1)) -> Poly:
    """The coefficients of ``p(x + h)`` in x."""
    out = [zero]
    for c in reversed(p):
        out = add(mul(out, [h, one], zero), [c], zero)
    return out


def divide(p: Sequence[Any], d: Sequence[Any], zero: Any = _ZERO, is_zero: ZeroTest = _equals_zero) -> tuple[Poly, Poly]:
    """``(quotient, remainder)`` of ``p`` by ``d`` (trimmed, leading coefficient nonzero);
    the remainder is trimmed.  A monic ``d`` costs no division, and its zero
    coefficients no products (reduction modulo a sparse minimal polynomial)."""
    p = list(p)
    n = len(d) - 1
    if len(p) <= n:
        return [zero], trim(p or [zero], is_zero)
    lead = d[-1]
    monic = lead == 1
    quot = [zero] * (len(p) - n)
    for k in range(len(p) - 1 - n, -1, -1):
        coef = p[k + n] if monic else p[k + n] / lead
        quot[k] = coef
        for j in range(n):
            if not is_zero(d[j]):
                p[k + j] = p[k + j] - coef * d[j]
    return quot, trim(p[:n] or [zero], is_zero)


def gcd(p: Sequence[Any], q: Sequence[Any], zero: Any = _ZERO, is_zero: ZeroTest = _equals_zero) -> Poly:
    """A gcd of two polynomials over an exact field (Euclid; not normalised)."""
    a, b = trim(p, is_zero), trim(q, is_zero)
    while not is_zero_poly(b, is_zero):
        a, b = b, divide(a, b, zero, is_zero)[1]
    return a


def lowest_terms(P: Sequence[Any], Q: Sequence[Any], zero: Any = _ZERO,
                 is_zero: ZeroTest = _equals_zero) -> tuple[Poly, Poly]:
    """``P/Q`` cancelled by their gcd and scaled to ``Q(0) = 1`` (``Q(0) ≠ 0``), trimmed."""
    g = gcd(P, Q, zero, is_zero)
    if len(g) > 1:
        P, Q = divide(P, g, zero, is_zero)[0], divide(Q, g, zero, is_zero)[0]
    q0 = Q[0]
    return trim([a / q0 for a in P], is_zero), trim([a / q0 for a in Q], is_zero)


# ------------------------------------------------------------ over Q, with FLINT


def to_fmpq(x: Fraction | int) -> Any:
    from flint import fmpq

    x = Fraction(x)
    return fmpq(x.numerator, x.denominator)


def _coprime_by_keyword(p: int, q: int) -> Fraction:
    make: Any = Fraction  # Python 3.11's spelling, which the type stubs do not declare
    made: Fraction = make(p, q, _normalize=False)
    return made


#: ``p/q`` from integers already in lowest terms, ``q > 0``, without the gcd that
#: normalising costs (most of the time of converting a FLINT matrix of large rationals)
_coprime: Callable[[int, int], Fraction] = getattr(Fraction, "_from_coprime_ints", _coprime_by_keyword)


def to_fraction(x: Any) -> Fraction:
    """An exact FLINT number as a Fraction: ``fmpq``, ``fmpz``, or an exact ``arb``/``arf``
    (a ball's mid-point or radius)."""
    if hasattr(x, "p"):  # fmpq, the common case first; FLINT keeps it in lowest terms
        return _coprime(int(x.p), int(x.q))
    if hasattr(x, "man_exp"):
        man, exp = x.man_exp()
        man, exp = int(man), int(exp)
        return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)
    return Fraction(int(x))


def to_flint(coeffs: Any) -> Any:
    """The ``fmpq_poly`` of rational coefficients (an ``fmpq_poly`` is returned as it is)."""
    from flint import fmpq_poly

    if isinstance(coeffs, fmpq_poly):
        return coeffs
    return fmpq_poly([to_fmpq(c) for c in coeffs])


def from_flint(p: Any) -> list[Fraction]:
    """The coefficients of an ``fmpq_poly`` (or ``fmpz_poly``) as Fractions (``[0]`` for 0)."""
    return [to_fraction(c) for c in p.coeffs()] or [Fraction(0)]


def inverse_mod(g: Any, f: Any) -> Any:
    """``g⁻¹ mod f`` for fmpq_polys g prime to f (Bézout: ``s·g + t·f = d``, d constant)."""
    d, s, _ = g.xgcd(f)
    return (s / d) % f


def rational_lowest_terms(P: Any, Q: Any) -> tuple[list[Fraction], list[Fraction]]:
    """:func:`lowest_terms` over Q, by FLINT (Euclid on Fractions swells beyond degree
    ~15); ``P`` and ``Q`` are coefficient lists or ``fmpq_poly``."""
    p, q = to_flint(P), to_flint(Q)
    g = p.gcd(q)
    if g.degree() > 0:
        p, q = p // g, q // g
    q0 = q.coeffs()[0]
    return from_flint(p / q0), from_flint(q / q0)


def rational_roots(coeffs: Sequence[Fraction]) -> list[Fraction]:
    """The distinct rational roots, increasing."""
    coeffs = trim([Fraction(c) for c in coeffs])
    if len(coeffs) < 2:
        return []
    return sorted({to_fraction(r) for r, _ in to_flint(coeffs).roots()})


def squarefree_part(coeffs: Sequence[Fraction]) -> list[Fraction]:
    """The product of the distinct irreducible factors of a nonconstant ``p``: the same
    roots, each simple (primitive integer coefficients, from FLINT's square-free
    factorisation)."""
    _, factors = to_flint(trim(coeffs)).factor_squarefree()
    part = None
    for f, _ in factors:
        part = f if part is None else part * f
    assert part is not None  # degree >= 1: at least one factor
    return from_flint(part.numer())


#: isolations kept per polynomial (one per width asked for)
_KEPT_WIDTHS = 8


class RealRoots:
    """The distinct real roots of a nonzero rational polynomial, certified: how many,
    which are rational (exactly), and isolating intervals with rational end points of
    any width, computed once per width."""

    def __init__(self, coeffs: Sequence[Fraction]):
        self.poly = trim([Fraction(c) for c in coeffs])
        if is_zero_poly(self.poly):
            raise ValueError("the zero polynomial has no isolated roots")
        self._cache: dict[int, list[Interval]] = {}
        self._rational = rational_roots(self.poly)
        self._squarefree: list[int] | None = None  # integer coefficients, on first isolation

    def __reduce__(self) -> tuple[type[RealRoots], tuple[list[Fraction]]]:
        # FLINT objects do not pickle; the roots are recomputed from the coefficients
        return (RealRoots, (self.poly,))

    @property
    def count(self) -> int:
        return len(self.intervals(8))

    @property
    def exact(self) -> list[Fraction | None]:
        """Each real root (increasing) as a Fraction when it is rational, else None."""
        return [iv.lo if iv.is_point else None for iv in self.intervals(8)]

    def intervals(self, bits: int) -> list[Interval]:
        """Enclosures of the distinct real roots, increasing, each of width ``<= 2^-bits``
        (a point for a rational root)."""
        if bits not in self._cache:
            if len(self._cache) >= _KEPT_WIDTHS:  # callers refine by doubling: keep the latest
                del self._cache[next(iter(self._cache))]
            self._cache[bits] = self._isolate(bits) if len(self.poly) > 1 else []
        return self._cache[bits]

    def _isolate(self, bits: int) -> list[Interval]:
        from flint import arb

        if self._squarefree is None:
            self._squarefree = [int(c) for c in to_flint(squarefree_part(self.poly)).numer().coeffs()]
        width = Fraction(1, 2**bits)
        # a power of two, so that nearby widths share one isolation (complex_roots)
        prec = 1 << max(6, (bits + 32 - 1).bit_length())
        while True:
            roots = complex_roots(self._squarefree, prec)
            intervals = []
            for r in roots:
                # FLINT proves a root real by returning it with an exactly zero imaginary part
                real = r if isinstance(r, arb) else (r.real if r.imag.is_zero() else None)
                if real is not None:
                    intervals.append(arb_interval(real))
            if all(iv.hi - iv.lo <= width for iv in intervals):
                break
            prec *= 2
        intervals.sort(key=lambda iv: iv.lo)
        out = []
        for iv in intervals:
            # Arb's balls are disjoint: a rational root inside one is its root
            inside = [r for r in self._rational if iv.lo <= r <= iv.hi]
            out.append(Interval.point(inside[0]) if len(inside) == 1 else iv)
        return out


@lru_cache(maxsize=256)
def _real_roots(coeffs: tuple[Fraction, ...]) -> RealRoots:
    return RealRoots(coeffs)


def real_roots(coeffs: Sequence[Fraction]) -> RealRoots:
    """The :class:`RealRoots` of ``coeffs``, shared by every caller asking for the same
    polynomial (a field's minimal polynomial is asked for its roots again and again)."""
    return _real_roots(tuple(trim([Fraction(c) for c in coeffs])))


def real_root_intervals(coeffs: Sequence[Fraction], bits: int) -> list[Interval]:
    """Certified enclosures of the distinct real roots, increasing, each of width
    ``<= 2^-bits`` (a point for a rational root).  ``coeffs`` must not be the zero
    polynomial."""
    return real_roots(coeffs).intervals(bits)


def refine_root(coeffs: Sequence[Fraction], start: Interval, bits: int) -> Interval | None:
    """An enclosure of width ``<= 2^-bits`` of the one real root of the square-free
    ``coeffs`` in ``start`` (which must hold exactly one, as :func:`real_root_intervals`
    gives), or
    None when the steps below do not prove one.  Newton's method on Arb midpoints finds
    a candidate x; the root lies in ``[x − h, x + h]`` (h = 2^-(bits+1)) when that lies in
    ``start`` and f takes opposite signs at its ends, evaluated at those exact points in
    Arb balls that exclude 0 (the root in ``start`` is the only one).  Isolating every
    root of a minimal polynomial of degree 48 at the 1 024 bits a field element's
    enclosure asks for costs 0.15 s; this costs about a millisecond."""
    if start.is_point:
        return start
    integers = integer_coefficients(coeffs)
    # the terms (coefficients times powers of the root) cancel down to the value: the
    # precision covers their size, and doubles when a ball still cannot tell a sign
    reach = math.ceil(max(abs(start.lo), abs(start.hi), Fraction(1))).bit_length()
    size = max(abs(c).bit_length() for c in integers) + (len(integers) - 1) * reach
    prec = 2 * bits + size + 64
    h = Fraction(1, 1 << (bits + 1))
    while prec <= 1 << 16:
        decided, found = _newton_bracket(integers, start, h, bits, prec)
        if decided:
            return found
        prec *= 2
    return None


def _newton_bracket(integers: list[int], start: Interval, h: Fraction, bits: int,
                    prec: int) -> tuple[bool, Interval | None]:
    """:func:`refine_root` at one working precision: ``(True, bracket)``, ``(True, None)``
    when the candidate leaves ``start`` or the signs do not differ, ``(False, None)``
    when the balls are too wide to tell."""
    from flint import arb_poly, ctx

    with ctx.workprec(prec):
        f = arb_poly(integers)  # the coefficients exact: made at this precision
        df = f.derivative()
        x = (start.lo + start.hi) / 2
        for _ in range(4 * prec.bit_length()):
            value, slope = f(to_arb(x)), df(to_arb(x))
            if not (value.is_finite() and slope.is_finite()) or slope.contains(0):
                return False, None
            step = to_fraction((value / slope).mid())
            x = _dyadic(x - step, bits + 8)
            if abs(step) < h / 4:
                break
        lo, hi = x - h, x + h
        if not (start.lo <= lo and hi <= start.hi):
            return True, None
        left, right = f(to_arb(lo)), f(to_arb(hi))
        if left.contains(0) or right.contains(0):
            return False, None
        if (left > 0) == (right > 0):
            return True, None
    return True, Interval(lo, hi)


def _dyadic(q: Fraction, bits: int) -> Fraction:
    """``q`` rounded to a multiple of ``2^-bits`` (so that the points stay short)."""
    return Fraction(round(q * (1 << bits)), 1 << bits)


# ------------------------------------------------------------ integers, text


#: How many polynomials :func:`complex_roots` remembers roots of.
_ROOTS_KEPT = 8
_roots: dict[tuple[int, ...], tuple[int, list[Any]]] = {}


def complex_roots(coeffs: Sequence[int], prec: int) -> list[Any]:
    """The complex roots of the square-free integer polynomial ``coeffs`` (ascending) as
    FLINT ``acb`` balls of at least ``prec`` bits, remembered per polynomial at the
    highest precision asked so far: a ball of a higher precision encloses the same root,
    and isolating the 48 roots of a degree-48 field costs 0.25 s at 2 048 bits and 1.4 s
    at 8 192, which the bounds of the exact engine and the minimal polynomials of the
    entries would otherwise pay again at each precision (call under ``prec`` bits)."""
    from flint import ctx, fmpz_poly

    key = tuple(int(c) for c in coeffs)
    kept = _roots.get(key)
    if kept is not None and kept[0] >= prec:
        return kept[1]
    with ctx.workprec(prec):
        # python-flint types complex_roots() as acb; it is a list of (acb, multiplicity)
        found = [root for root, _ in cast(list[Any], fmpz_poly(list(key)).complex_roots())]
    if len(_roots) >= _ROOTS_KEPT and key not in _roots:
        _roots.pop(next(iter(_roots)))
    _roots[key] = (prec, found)
    return found


def squarefree_split(n: int, limit: int) -> tuple[int, int]:
    """``n = s²·m`` for ``n >= 1``, with m free of the squares of all integers below
    ``limit`` (so square-free when ``n < limit²``) and ``m = 1`` when n is a square: trial
    division, enough for readable square roots; nothing correct depends on m being
    square-free."""
    s, m = 1, n
    d = 2
    while d < limit and d * d <= m:
        while m % (d * d) == 0:
            m //= d * d
            s *= d
        d += 1
    r = math.isqrt(m)
    if r * r == m:
        s, m = s * r, 1
    return s, m


def poly_text(coeffs: Sequence[Fraction], variable: str = "x") -> str:
    """The polynomial as entry text (``x^2 - 15``), scaled to primitive integer
    coefficients with a positive leading one (same roots), highest power first."""
    coeffs = trim([Fraction(c) for c in coeffs])
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


def to_arb(q: Fraction | int) -> Any:
    """The rational ``q`` as an Arb ball at the current working precision."""
    from flint import arb, fmpz

    q = Fraction(q)
    return arb(fmpz(q.numerator)) / fmpz(q.denominator)


def arb_interval(ball: Any) -> Interval:
    """The rational interval ``mid ± rad`` of a finite real Arb ball."""
    mid, rad = to_fraction(ball.mid()), to_fraction(ball.rad())
    return Interval(mid - rad, mid + rad)


def interval_arb(x: Interval) -> Any:
    """The Arb ball enclosing an interval with rational end points (at the current
    working precision)."""
    from flint import arb, fmpq

    lo = arb(fmpq(x.lo.numerator, x.lo.denominator))
    return lo if x.is_point else lo.union(arb(fmpq(x.hi.numerator, x.hi.denominator)))


def integer_coefficients(coeffs: Sequence[Fraction | int]) -> list[int]:
    """The rational polynomial ``coeffs`` times the lcm of its denominators (the same roots)."""
    den = math.lcm(*(Fraction(c).denominator for c in coeffs))
    return [int(Fraction(c) * den) for c in coeffs]
