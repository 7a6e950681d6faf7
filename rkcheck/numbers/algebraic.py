"""Exact real algebraic numbers: one number field ``Q(θ)`` per tableau (definitions §5).

A tableau whose entries are built from rationals, ``sqrt(a)`` and ``root(p, k)`` with
``+ − × ÷`` and integer powers lies in a number field ``K = Q(θ)``: ``θ`` is a real
algebraic number given by its (monic, rational) minimal polynomial ``g`` and *which* real
root of ``g`` it is; an element of ``K`` is a polynomial in ``θ`` of degree ``< deg g``
with Fraction coefficients (:class:`FieldElement`).  Arithmetic is polynomial arithmetic
modulo ``g`` (FLINT ``fmpq_poly``); the inverse comes from the extended gcd with ``g``
(``g`` is irreducible, so every nonzero element is invertible).  Zero is decided exactly
(all coefficients zero); the sign and the value come from a certified enclosure of ``θ``
(:func:`rkcheck.numbers.polynomials.real_root_intervals`), refined until it decides.

Why this means: generic exact real algebraic arithmetic (FLINT ``qqbar``)
costs milliseconds per operation, a product in a fixed field microseconds; a tableau is
entered once and then evaluated many million times (modulo primes, by
:mod:`rkcheck.evaluation.modular`), so one primitive element per tableau suffices.

The field of a tableau's entries is found by :mod:`rkcheck.numbers.field_builder`.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Callable, Sequence

from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.polynomials import (
    complex_roots,
    from_flint,
    poly_text,
    real_root_intervals,
    refine_root,
    to_flint,
    to_fmpq,
    to_fraction,
)

#: Largest field degree :func:`field_of` builds; beyond it the entries are left to balls
#: (the exact engine's work grows with the degree: one channel per conjugate).
MAX_FIELD_DEGREE = 48


class NotAlgebraic(Exception):
    """The entries do not lie in a number field this module can build (the reason)."""


class NumberField:
    """``Q(θ)``: ``θ`` is the ``index``-th smallest real root (1-based) of the monic
    irreducible ``minpoly`` (ascending Fractions).  ``Q`` itself is the degree-1 field
    with ``θ = 0`` (minimal polynomial ``x``)."""

    def __init__(self, minpoly: Sequence[Fraction | int], index: int, name: str | None = None):
        g = to_flint(minpoly)
        lead = g.coeffs()[-1]
        self.g = g / lead
        self.minpoly = from_flint(self.g)
        self.degree = self.g.degree()
        self.index = index
        self.sqrt_of: int | None = None  # n when θ = sqrt(n), n > 1 a square-free integer
        if self.degree == 2 and self.minpoly[1] == 0 and self.minpoly[0].denominator == 1 and index == 2:
            self.sqrt_of = int(-self.minpoly[0])
        self.name = name or (f"sqrt({self.sqrt_of})" if self.sqrt_of else f"root({poly_text(self.minpoly)}, {index})")
        self._theta: Interval | None = None
        self._theta_bits = 0
        self._products: dict[tuple[Any, ...], Any] = {}  # FieldElement._memo: products and inverses
        #: minimal polynomials of elements that generate the field (its builder's
        #: generators; empty when unknown): a prime splits completely in the field only if
        #: it splits each of them, a test of low degree (ScaledTableau's channel primes)
        self.generator_polynomials: tuple[tuple[Fraction, ...], ...] = ()

    def __repr__(self) -> str:
        return f"NumberField(θ = {self.name}, degree {self.degree})"

    def same_as(self, other: "NumberField") -> bool:
        """The same field with the same θ, whether or not it is this object (two checks
        of one tableau build it twice; a result unpickled brings its own)."""
        return other is self or (other.index == self.index and other.minpoly == self.minpoly)

    def __reduce__(self) -> tuple[Callable[..., NumberField], tuple[Any, ...]]:
        # FLINT polynomials do not pickle; a field travels (to and from scan workers) as
        # its minimal polynomial, and pickle's memo keeps one field per message
        return (_field, (self.minpoly, self.index, self.name, self.generator_polynomials))

    @property
    def is_rational(self) -> bool:
        return bool(self.degree == 1)

    # ------------------------------------------------------------------ elements

    def __call__(self, x: Any) -> "FieldElement":
        """The element ``x`` (a Fraction, int, FieldElement of this field, or a list of
        coefficients in the power basis of θ, or their FLINT ``fmpq_poly``)."""
        if isinstance(x, FieldElement):
            if x.field is not self:
                raise ValueError("element of another field")
            return x
        if isinstance(x, (list, tuple)) or type(x).__name__ == "fmpq_poly":
            return FieldElement(self, to_flint(x) % self.g)
        return FieldElement(self, to_flint([x]))

    @property
    def gen(self) -> "FieldElement":
        return FieldElement(self, to_flint([0, 1]) % self.g)

    def theta_enclosure(self, bits: int) -> Interval:
        """A certified enclosure of θ of width ``<= 2^-bits``."""
        if self.degree == 1:
            return Interval.point(-self.minpoly[0])
        if self._theta is None or self._theta_bits < bits:
            # θ's root isolated coarsely with the others, then refined alone
            start = real_root_intervals(self.minpoly, min(bits, 64))[self.index - 1]
            refined = start if start.hi - start.lo <= Fraction(1, 1 << bits) else refine_root(self.minpoly, start, bits)
            if refined is None:
                refined = real_root_intervals(self.minpoly, bits)[self.index - 1]
            self._theta, self._theta_bits = refined, bits
        return self._theta

    def conjugates(self, bits: int = 64) -> list[Any]:
        """Certified complex enclosures (``acb``) of all conjugates of θ, of at least
        ``bits`` bits (:func:`rkcheck.numbers.polynomials.complex_roots`, shared with
        every user of the same polynomial)."""
        return complex_roots(self.g.numer().coeffs(), max(bits, 64))


def _field(minpoly: list[Fraction], index: int, name: str, generators: tuple[Any, ...]) -> NumberField:
    K = NumberField(minpoly, index, name)
    K.generator_polynomials = generators
    return K


def _element(field: NumberField, coeffs: list[Fraction]) -> "FieldElement":
    """Unpickling: the element with these coefficients in the powers of θ."""
    return FieldElement(field, to_flint(coeffs))


#: Fields of at least this degree remember up to MEMO_SIZE products and inverses each
#: (:meth:`FieldElement._memo`; then they start again)
MEMO_MIN_DEGREE, MEMO_SIZE = 16, 2048


class _PolyKey:
    """A FieldElement's polynomial as a dictionary key: a cheap hash of a few coefficients,
    equality of the whole polynomial (FLINT), so a collision is never a wrong answer."""

    __slots__ = ("poly", "h")

    def __init__(self, poly: Any):
        d = poly.degree()
        self.poly, self.h = poly, hash((d, poly[0], poly[d // 2], poly[max(d, 0)]))

    def __hash__(self) -> int:
        return self.h

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _PolyKey) and self.h == other.h and self.poly == other.poly


class FieldElement:
    """An element of a :class:`NumberField`: a polynomial in θ reduced modulo g."""

    __slots__ = ("field", "poly", "_key", "_coeffs")

    def __init__(self, field: NumberField, poly: Any):
        self.field = field
        self.poly = poly
        self._key: _PolyKey | None = None
        self._coeffs: list[Fraction] | None = None

    def _memo(self, op: str, other: "FieldElement | None", compute: Callable[[], "FieldElement"]) -> "FieldElement":
        """``compute()``, remembered per field of degree >= :data:`MEMO_MIN_DEGREE`: a
        product in a field of degree 48 costs about a millisecond (coefficients of
        1000–2000 bits), and the tableau's algebra asks for the same ones again (in
        HBVM(6, 3)'s check 8 714 products were 3 742 distinct ones, 70 inverses 19)."""
        K = self.field
        if K.degree < MEMO_MIN_DEGREE:
            return compute()
        mine = self._key = self._key or _PolyKey(self.poly)
        key: tuple[Any, ...] = (op, mine)
        if other is not None:
            theirs = other._key = other._key or _PolyKey(other.poly)
            key = (op, mine, theirs) if mine.h <= theirs.h else (op, theirs, mine)
        hit: FieldElement | None = K._products.get(key)
        if hit is None:
            if len(K._products) >= MEMO_SIZE:
                K._products.clear()
            hit = K._products[key] = compute()
        return hit

    def __reduce__(self) -> tuple[Callable[..., FieldElement], tuple[NumberField, list[Fraction]]]:
        return (_element, (self.field, list(self.coeffs)))

    # ------------------------------------------------------------- arithmetic
    def _other(self, y: Any) -> Any:
        if isinstance(y, FieldElement):
            if not self.field.same_as(y.field):
                raise ValueError("elements of different fields")
            return y.poly
        if isinstance(y, (int, Fraction)):
            return to_flint([y])
        return None

    def __add__(self, y: Any) -> "FieldElement":
        o = self._other(y)
        return NotImplemented if o is None else FieldElement(self.field, self.poly + o)

    __radd__ = __add__

    def __sub__(self, y: Any) -> "FieldElement":
        o = self._other(y)
        return NotImplemented if o is None else FieldElement(self.field, self.poly - o)

    def __rsub__(self, y: Any) -> "FieldElement":
        o = self._other(y)
        return NotImplemented if o is None else FieldElement(self.field, o - self.poly)

    def __neg__(self) -> "FieldElement":
        return FieldElement(self.field, -self.poly)

    def __mul__(self, y: Any) -> "FieldElement":
        o = self._other(y)
        if o is None:
            return NotImplemented
        if isinstance(y, FieldElement) and o.degree() > 0 and self.poly.degree() > 0:
            return self._memo("*", y, lambda: FieldElement(self.field, (self.poly * o) % self.field.g))
        return FieldElement(self.field, (self.poly * o) % self.field.g)

    __rmul__ = __mul__

    def inverse(self) -> "FieldElement":
        if self.is_zero():
            raise ZeroDivisionError("division by zero in a number field")
        if self.poly.degree() <= 0:
            return FieldElement(self.field, to_flint([1 / to_fraction(self.poly.coeffs()[0])]))
        return self._memo("1/", None, self._inverse)

    def _inverse(self) -> "FieldElement":
        if self.field.degree <= 8:
            d, s, _ = self.poly.xgcd(self.field.g)
            return FieldElement(self.field, (s / d) % self.field.g)
        # in larger fields the rational extended gcd swells its intermediate coefficients;
        # FLINT's (multimodular) solve of  M_α x = e_0  (M_α: multiplication by α) does not
        from flint import fmpq_mat

        D, g = self.field.degree, self.field.g
        M = fmpq_mat(D, D)
        x = self.poly
        theta = to_flint([0, 1])
        for j in range(D):  # column j: α·θ^j, each from the last by a shift and one step of reduction
            for i, c in enumerate(x.coeffs()):
                M[i, j] = c
            x = x * theta
            if x.degree() == D:
                x -= g * (x[D] / g[D])
        e0 = fmpq_mat(D, 1)
        e0[0, 0] = 1
        sol = M.solve(e0)
        return FieldElement(self.field, to_flint([to_fraction(sol[i, 0]) for i in range(D)]))

    def __truediv__(self, y: Any) -> "FieldElement":
        if isinstance(y, FieldElement):
            return self * y.inverse()
        o = self._other(y)
        if o is None:
            return NotImplemented
        if Fraction(y) == 0:
            raise ZeroDivisionError("division by zero")
        return FieldElement(self.field, self.poly / to_fmpq(y))

    def __rtruediv__(self, y: Any) -> "FieldElement":
        quotient: FieldElement = self.inverse() * y
        return quotient

    def __pow__(self, n: int) -> "FieldElement":
        if n < 0:
            return self.inverse() ** (-n)
        result = self.field(1)
        base = self
        while n:
            if n & 1:
                result = result * base
            base = base * base
            n >>= 1
        return result

    # ------------------------------------------------------------- facts
    def is_zero(self) -> bool:
        return bool(self.poly.is_zero())

    def __bool__(self) -> bool:
        return not self.is_zero()

    def __eq__(self, y: object) -> bool:
        if isinstance(y, FieldElement) and not self.field.same_as(y.field):
            # numbers of two fields: equal when both are the same rational; irrational ones
            # are compared only within one field (two θ may generate one field)
            mine, theirs = self.rational(), y.rational()
            return mine is not None and mine == theirs
        o = self._other(y)
        if o is None:
            return NotImplemented
        return bool(self.poly == o)

    def __hash__(self) -> int:
        r = self.rational()
        return hash(r) if r is not None else hash(tuple(self.coeffs))

    @property
    def coeffs(self) -> list[Fraction]:
        """Coefficients in the power basis ``1, θ, …, θ^(D−1)`` (length D; a new list,
        converted once per element: an element is never changed in place)."""
        if self._coeffs is None:
            out = from_flint(self.poly)
            self._coeffs = out + [Fraction(0)] * (self.field.degree - len(out))
        return list(self._coeffs)

    def rational(self) -> Fraction | None:
        """The value as a Fraction when it is rational, else None."""
        if self.poly.degree() <= 0:
            return to_fraction(self.poly.coeffs()[0]) if not self.poly.is_zero() else Fraction(0)
        return None

    def enclosure(self, bits: int = 64) -> Interval:
        """A certified enclosure of width ``<= 2^-bits`` (a point when rational)."""
        mid, rad = self.ball(bits)
        return Interval(mid - rad, mid + rad) if rad else Interval.point(mid)

    def ball(self, bits: int = 64) -> tuple[Fraction, Fraction]:
        """``(mid, rad)`` of a certified enclosure of width ``<= 2^-bits`` (``rad = 0``
        when rational; a report reads these, not an interval's end points): Horner's
        scheme in Arb balls at θ's enclosure, with working precision and θ's width both
        ``bits`` plus the coefficients' size, since the terms cancel from that size down
        to the value (2000-bit coefficients in the Gauss-6 field: in Fraction intervals
        each enclosure cost 0.25 s)."""
        from flint import arb, arb_poly, ctx, fmpq, fmpz

        r = self.rational()
        if r is not None:
            return r, Fraction(0)
        coeffs = self.coeffs
        width = Fraction(1, 1 << bits)
        # θ's width times the derivative, at most D times the largest term over |θ|
        extra = max(largest_term_bits(self), 1) + self.field.degree.bit_length() + 8
        tb = bits + extra
        while True:
            t = self.field.theta_enclosure(tb)
            prec = tb + max(t.lo.numerator.bit_length(), t.hi.numerator.bit_length()) + 64
            with ctx.workprec(prec):
                # dyadic endpoints with numerators below the precision: exact balls
                theta = arb.union(arb(fmpz(t.lo.numerator)) / fmpz(t.lo.denominator),
                                  arb(fmpz(t.hi.numerator)) / fmpz(t.hi.denominator))
                value = arb_poly([fmpq(c.numerator, c.denominator) for c in coeffs])(theta)
                mid, rad = to_fraction(value.mid()), to_fraction(value.rad())
            if 2 * rad <= width:
                return mid, rad
            tb += max(tb // 2, 32)

    def sign(self) -> int:
        """The exact sign (−1, 0, 1), refining the enclosure until it excludes 0."""
        if self.is_zero():
            return 0
        bits = 64
        while True:
            iv = self.enclosure(bits)
            if iv.lo > 0:
                return 1
            if iv.hi < 0:
                return -1
            bits *= 2

    def _diff_sign(self, y: Any) -> int:
        """sign(self − y), exactly; a float is taken at its exact binary value."""
        if isinstance(y, float):
            y = Fraction(y)
        diff: FieldElement = self - y
        return diff.sign()

    def __lt__(self, y: Any) -> bool:
        return self._diff_sign(y) < 0

    def __le__(self, y: Any) -> bool:
        return self._diff_sign(y) <= 0

    def __gt__(self, y: Any) -> bool:
        return self._diff_sign(y) > 0

    def __ge__(self, y: Any) -> bool:
        return self._diff_sign(y) >= 0

    def __abs__(self) -> "FieldElement":
        return -self if self.sign() < 0 else self

    def __float__(self) -> float:
        return float(self.enclosure(64).mid)

    # ------------------------------------------------------------- text
    def text(self, theta: str | None = None) -> str:
        """A readable exact form: ``1/288 - sqrt(3)/864`` when θ = sqrt(n), otherwise
        ``c0 + c1*θ + c2*θ^2`` with θ written as ``theta`` (default: the field's name, a
        valid entry such as ``root(x^3 - 3*x + 1, 2)``, so the text parses back)."""
        r = self.rational()
        if r is not None:
            return str(r)
        name = theta or self.field.name
        parts: list[tuple[int, str]] = []  # (sign, magnitude text)
        for k, c in enumerate(self.coeffs):
            if c == 0:
                continue
            sign, c = (1 if c > 0 else -1), abs(c)
            if k == 0:
                parts.append((sign, str(c)))
                continue
            power = name if k == 1 else f"{name}^{k}"
            num, den = c.numerator, c.denominator
            mag = power if num == 1 else f"{num}*{power}"
            if den != 1:
                mag += f"/{den}"
            parts.append((sign, mag))
        out = ("-" if parts[0][0] < 0 else "") + parts[0][1]
        for sign, mag in parts[1:]:
            out += (" - " if sign < 0 else " + ") + mag
        return out

    def __str__(self) -> str:
        return self.text()

    def __repr__(self) -> str:
        return f"FieldElement({self.text()})"


def dot(xs: Sequence[Any], ys: Sequence[Any]) -> "FieldElement | None":
    """``Σ x_i·y_i`` with one reduction modulo g for the whole sum, or None unless every
    operand is a :class:`FieldElement` of one field.  In a field of degree 48 the
    reduction costs twice the product itself, and a matrix times a vector (the stability
    function's series, the order conditions) reduces once per entry instead of once per
    product."""
    if not xs or len(xs) != len(ys):
        return None
    field = getattr(xs[0], "field", None)
    if field is None or not all(isinstance(z, FieldElement) and z.field is field for z in (*xs, *ys)):
        return None
    acc = xs[0].poly * ys[0].poly
    for x, y in zip(xs[1:], ys[1:]):
        acc += x.poly * y.poly
    return FieldElement(field, acc % field.g)


def _log2_upper(q: Fraction) -> int:
    """An integer upper bound of ``log₂ |q|`` (q ≠ 0)."""
    return abs(q.numerator).bit_length() - q.denominator.bit_length() + 1


def largest_term_bits(x: "FieldElement") -> int:
    """An upper bound of ``log₂ |c_k σ(θ)^k|`` over the terms of ``x = Σ c_k θ^k`` and
    the conjugates σ(θ), by Fujiwara's bound ``|σ(θ)| ≤ 2 max_k |a_(D−k)|^(1/k)`` on the
    roots of the monic ``g = Σ a_i y^i``: in the field of the six Gauss-6 nodes the
    coefficients have 1 300-bit numerators over 1 236-bit denominators, and the terms
    about 600 bits: that, not the coefficients' sizes, is what enclosing x costs."""
    g = x.field.minpoly
    D = len(g) - 1
    log2_R = 1 + max((_log2_upper(a) / k for k, a in enumerate(reversed(g[:-1]), start=1) if a), default=0)
    return max(math.ceil(_log2_upper(c) + k * max(log2_R, 0)) for k, c in enumerate(x.coeffs[:D]) if c)
