"""The scalars of the tableau-level algebra: exact numbers, or certified intervals.

The algebra on the s×s tableau itself — stage reduction, the AVF and line-integral
tests, the stability function, symplecticity, symmetry — is written once, generically,
over three kinds of scalar (definitions §5):

* ``Fraction`` — an exact rational tableau;
* an exact algebraic number (``rkcheck.numbers.algebraic.FieldElement``: ``+ − × ÷``
  with ints and Fractions, ``is_zero()``, ``enclosure(bits)``, ``text(style)``) — an
  exact tableau with roots;
* :class:`~rkcheck.numbers.intervals.Interval` — everything else (rounded decimals,
  families computed at a working precision): a rigorous enclosure.

A zero test on an exact scalar is ``holds`` or ``fails``; on an interval it is
``holds to D digits`` (the enclosure contains 0) or ``fails`` (it excludes 0), so no
interval result is ever a false ``fails``.  Constants enter through :func:`const`, which
lifts a rational to the kind of its neighbour (intervals do not mix with Fractions).
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from typing import Any, Iterator, Sequence

from rkcheck.evaluation.values import TableauValues
from rkcheck.numbers.algebraic import dot as field_dot
from rkcheck.numbers.centred import Centred
from rkcheck.numbers.formatting import decimal_string, radius_string
from rkcheck.numbers.intervals import Interval
from rkcheck.verdicts import FAILS, HOLDS, Verdict, classify_interval

#: A tableau value: an exact ``Fraction``, an exact number-field element or a certified
#: ``Interval``.  Typed ``Any``: the kinds mix in arithmetic (``Fraction * Interval``),
#: which the union would reject because Fraction's stubs accept only numbers.
Scalar = Any
Matrix = list[list[Scalar]]
Vector = list[Scalar]


# ------------------------------------------------------------------ the tableau's values


#: a box with at most this many entries that are not points (decimal entries, say) is
#: carried in mean value form (:mod:`rkcheck.numbers.centred`), so that a quantity nonzero
#: on the whole box is found so; above, in plain intervals (sound, but a product such as
#: b(1 − b) near 0 may then only "hold to digits").  Each product costs a float interval
#: product per entry: a dense 5-stage tableau (30 entries) stays within a tenth of a
#: second, the 42 entries of HBVM(6, 2) in 60 digits took 0.3 s more than plain intervals
MAX_CENTRED_INPUTS = 32


def values_from_enclosures(A: list[list[Interval]], b: list[Interval], exact: bool) -> tuple[Matrix, Vector]:
    """Exact Fractions when the enclosures are exact points, else the intervals: in mean
    value form around their mid-points, up to :data:`MAX_CENTRED_INPUTS` of them."""
    if exact and all(x.is_point for row in A for x in row) and all(x.is_point for x in b):
        return [[x.lo for x in row] for row in A], [x.lo for x in b]
    s = len(b)
    flat = [tidy(x) for row in A for x in row] + [tidy(x) for x in b]
    if sum(not x.is_point for x in flat) <= MAX_CENTRED_INPUTS:
        flat = Centred.inputs(flat)
    return [flat[i * s:(i + 1) * s] for i in range(s)], flat[s * s:]


#: bits kept below the width of an interval when its end points are rounded outwards
GUARD_BITS = 64


def tidy(x: Scalar) -> Scalar:
    """An interval with its end points rounded outwards to ``GUARD_BITS`` bits below its
    own width (a relative widening of at most 2^-64), so that long computations do not
    carry end points of thousands of bits; other scalars unchanged."""
    if not isinstance(x, Interval) or x.is_point:
        return x
    width = x.hi - x.lo
    bits = max(GUARD_BITS, width.denominator.bit_length() - width.numerator.bit_length() + GUARD_BITS)
    return x.round_out(bits)


def tableau_values(values: TableauValues) -> tuple[Matrix, Vector]:
    """The best scalars for a tableau: exact (rational or algebraic) when the reading
    makes its entries exact numbers, else their enclosures."""
    if values.exact is not None:
        return [list(row) for row in values.exact.A], list(values.exact.b)
    return values_from_enclosures(values.A, values.b, False)


# ------------------------------------------------------------------------ the kinds


def is_interval(x: Scalar) -> bool:
    return isinstance(x, Interval)


def is_exact(x: Scalar) -> bool:
    return not isinstance(x, Interval)


def const(q: Fraction | int, like: Scalar) -> Scalar:
    """The rational ``q`` as a scalar of the same kind as ``like``."""
    return Interval.point(Fraction(q)) if isinstance(like, Interval) else Fraction(q)


def verdict(x: Scalar) -> Verdict:
    """Is ``x`` zero?  ``holds``/``fails`` for exact scalars; for an interval
    ``holds to D digits`` when it contains 0 (``holds`` for the point 0), else ``fails``."""
    if isinstance(x, Interval):
        return classify_interval(x, False)
    if isinstance(x, (Fraction, int)):
        return Verdict(HOLDS) if x == 0 else Verdict(FAILS)
    return Verdict(HOLDS) if x.is_zero() else Verdict(FAILS)


def certainly_nonzero(x: Scalar) -> bool:
    return verdict(x).state == FAILS


def enclosure(x: Scalar, bits: int = 128) -> Interval:
    """A rigorous rational interval around ``x``."""
    if isinstance(x, Interval):
        return x
    if isinstance(x, (Fraction, int)):
        return Interval.point(Fraction(x))
    out: Interval = x.enclosure(bits)
    return out


def approx_text(x: Scalar, sig: int) -> str:
    """``x`` to ``sig`` significant digits, as text (exact decimal rounding of an
    enclosure's mid-point: no float, so no overflow at any magnitude)."""
    from rkcheck.numbers.formatting import decimal_string

    return decimal_string(Fraction(enclosure(x, 64 + 4 * sig).mid), sig)


def rational(x: Scalar) -> Fraction | None:
    """``x`` as a Fraction when it is an exact rational, else None."""
    if isinstance(x, (Fraction, int)):
        return Fraction(x)
    if isinstance(x, Interval):
        return None
    r = getattr(x, "rational", None)
    return r() if r is not None else None


def text(x: Scalar, sig: int = 12) -> str:
    """``x`` for people: ``p/q`` (with a decimal when it is not short), the exact algebraic
    text, or ``mid ± radius`` for an interval."""
    q = rational(x)
    if q is not None:
        dec = decimal_string(q, sig)
        if _beyond_text(q):
            return f"≈ {dec}"
        s = str(q)
        if s == dec:
            return s
        return f"{s} = {dec}" if Fraction(dec) == q else f"{s} ≈ {dec}"
    if isinstance(x, Interval):
        if x.is_point:
            return decimal_string(x.lo, sig)
        return f"{decimal_string(x.mid, sig)} ± {radius_string(x.rad)}"
    exact, approx_text = exact_text(x), decimal_string(x.enclosure(64).mid, sig)
    # a field element of a large field has a page-long exact text: the decimal then
    # stands alone (the zero test behind it was exact all the same)
    return f"{exact} ≈ {approx_text}" if len(exact) <= MAX_EXACT_TEXT else f"≈ {approx_text}"


#: longest exact algebraic text printed beside its decimal
MAX_EXACT_TEXT = 60


def _beyond_text(q: Fraction) -> bool:
    """Whether ``q`` has an integer of more digits than Python writes as text in this
    process (``sys.get_int_max_str_digits``: the CLI raises it, a library leaves it)."""
    import sys

    limit = sys.get_int_max_str_digits()
    bits = max(q.numerator.bit_length(), q.denominator.bit_length())
    return limit > 0 and bits * 0.30103 > limit - 1


def exact_text(x: Scalar) -> str:
    """The exact text of an exact scalar (Fraction ``p/q`` or the field element's own)."""
    q = rational(x)
    if q is not None:
        return str(q)
    render = getattr(x, "text", None)
    return render() if render is not None else str(x)


def certainly_larger(x: Scalar, y: Scalar) -> bool:
    """``|x| > |y|`` for certain (exactly for rationals, else by enclosures at 128 bits):
    of two entries equal in size, or too close to tell, neither is larger."""
    qx, qy = rational(x), rational(y)
    if qx is not None and qy is not None:
        return abs(qx) > abs(qy)
    ex, ey = enclosure(x, 128), enclosure(y, 128)
    low = Fraction(0) if ex.contains_zero() else min(abs(ex.lo), abs(ex.hi))
    return low > max(abs(ey.lo), abs(ey.hi))


# ------------------------------------------------------------- vectors and matrices


def total(xs: Sequence[Scalar], like: Scalar) -> Scalar:
    """The sum (``0`` of the kind of ``like`` for none)."""
    acc = const(0, like)
    for x in xs:
        acc = acc + x
    return tidy(acc)


def row_sums(A: Matrix, like: Scalar) -> Vector:
    return [total(row, like) for row in A]


def matvec(A: Matrix, v: Vector, like: Scalar) -> Vector:
    return [dot(row, v, like) for row in A]


def dot(u: Vector, v: Vector, like: Scalar) -> Scalar:
    fast = field_dot(u, v)  # number-field entries: one reduction for the whole sum
    if fast is not None:
        return tidy(fast)
    return total([x * y for x, y in zip(u, v)], like)


def sample(A: Matrix, b: Vector) -> Scalar:
    """A scalar of the tableau's kind (for :func:`const`)."""
    return b[0] if b else (A[0][0] if A else Fraction(0))


def poly_at(coeffs: Sequence[Fraction], x: Scalar) -> Scalar:
    """The rational polynomial ``coeffs`` (ascending powers) at ``x`` (Horner)."""
    acc = const(0, x)
    for c in reversed(coeffs):
        acc = tidy(acc * x + const(c, x))  # intervals: end points stay near their width
    return acc


def power(x: Scalar, k: int) -> Scalar:
    if isinstance(x, Interval):
        return x.power(k)
    acc = const(1, x)
    for _ in range(k):
        acc = acc * x
    return acc


def quadrature_residual(b: Vector, c: Vector, k: int) -> Scalar:
    """``Σ b_i c_i^(k−1) − 1/k`` (definitions §2)."""
    like = b[0]
    return total([bi * power(ci, k - 1) for bi, ci in zip(b, c)], like) - const(Fraction(1, k), like)


def quadrature_residuals(b: Vector, c: Vector) -> Iterator[Scalar]:
    """``Σ b_i c_i^(k−1) − 1/k`` for k = 1, 2, … (as far as the caller reads).  Exact
    scalars keep ``b_i c_i^(k−1)`` from one k to the next, one product per node and k
    where each power anew took k (a continuous method's surrogate has dozens of nodes),
    and so do values in mean value form, whose products keep the dependency; plain
    intervals take each power on its own, the tighter enclosure."""
    like = b[0]
    if any(isinstance(x, Interval) and not isinstance(x, Centred) and not x.is_point for x in (*b, *c)):
        yield from (quadrature_residual(b, c, k) for k in itertools.count(1))
        return
    terms = list(b)
    for k in itertools.count(1):
        yield total(terms, like) - const(Fraction(1, k), like)
        terms = [t * ci for t, ci in zip(terms, c)]
