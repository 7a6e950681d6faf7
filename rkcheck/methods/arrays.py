"""A tableau from arrays of Python, numpy or sympy numbers (``Tableau.from_arrays``).

What a value means (definitions §5) — the one thing to know when building a tableau
from arrays:

==========================  ==============================================================
``int``, ``Fraction``       that exact rational
``str``                     an entry in rkcheck's grammar (``"1/4 - sqrt(3)/6"``), exactly
                            as in a file: decimals with ≥ 6 significant digits are read
                            by the decimals rule of the check (definitions §5; default
                            ``auto``: within half a unit of the last digit, or half an
                            ulp for the shortest ``repr`` of a double)
``float`` (also numpy)      by default (``floats="shortest"``) the decimal it prints as,
                            ``repr(x)`` (``"0.1"``, ``"0.16666666666666666"``), read as
                            that literal in a file is: the ``auto`` decimals rule widens
                            a shortest repr to the double's rounding interval, so RK4 in
                            floats reaches classical order 4 to 15 digits, exactly as
                            ``rkcheck verify`` says of the ``json.dumps`` of the same
                            floats.  ``floats="exact"`` takes the **exact binary value**
                            instead (``0.1`` is ``3602879701896397/36028797018963968``):
                            the number a float computation used, so a tableau rounded to
                            doubles is checked as the slightly different method it is
                            (AVF-Gauss from floats fails by about 1e-17).  Reading a
                            float whose two readings differ warns
                            (:class:`~rkcheck.errors.RkcheckWarning`).  To check a
                            tableau up to the digits you trust, pass strings:
                            ``f"{x:.15g}"``.  A numpy ``float32``, ``float16`` or
                            ``longdouble`` is a decimal whose half unit in the last
                            digit covers the reals that round to it in its own
                            precision (a float32 1/12 reads ``0.0833333``, not the
                            ``0.083333336`` it prints as, which excludes 1/12)
``decimal.Decimal``         its decimal text, as a string would be
sympy numbers               ``Rational``/``Integer`` exactly; other constant expressions
                            (``sqrt(3)/6``) through their text; a ``Float`` of 53 bits
                            as the double it is, a longer one by its text
                            (``floats="exact"``: its exact binary value)
==========================  ==============================================================

``A`` may be a list of rows, a numpy 2-D array or a sympy ``Matrix``; ``b`` and ``c``
lists or 1-D arrays.  ``c`` is optional (the check always uses ``A·1``; a given ``c``
is only compared with it, definitions §1).
"""

from __future__ import annotations

import math
from decimal import Decimal
from fractions import Fraction
from typing import Any, Literal

from rkcheck.errors import TableauError, UserError, warn
from rkcheck.numbers.entries import Entry
from rkcheck.options import DEFAULT_MAX_STAGES, MAX_STAGES_RANGE, parse_int_in

FloatMode = Literal["exact", "shortest"]
#: how a float was read where its two readings (the decimal it prints as, its binary
#: value) differ: as a decimal, or at its exact binary value (None: they agree)
DECIMAL, BINARY = "decimal", "binary"


def _is_sympy(x: Any) -> bool:
    return type(x).__module__.split(".")[0] == "sympy"


def _float_entry(x: float, floats: FloatMode, place: str) -> tuple[Entry, str | None]:
    if not math.isfinite(x):
        raise TableauError(f"{x} is not a finite number", place)
    text = repr(float(x))
    # only worth a warning when the two readings differ: the binary value is not the
    # decimal the user sees (0.1), or the decimal stands for an interval (0.16666666666666666)
    entry = Entry.parse(text) if floats == "shortest" else Entry.of(Fraction(x))
    return entry, _reading(Fraction(text) != Fraction(x) or Entry.parse(text).is_rounded, floats)


def _reading(differs: bool, floats: FloatMode) -> str | None:
    return None if not differs else (BINARY if floats == "exact" else DECIMAL)


def _longdouble_entry(x: Any, floats: FloatMode, place: str) -> tuple[Entry, str | None]:
    """A numpy extended-precision float: its exact binary value, or (``shortest``) a
    decimal whose rounding reading covers the reals that round to it
    (:func:`_covering_decimal`)."""
    try:
        value = Fraction(*x.as_integer_ratio())
    except (OverflowError, ValueError, AttributeError):
        raise TableauError(f"{x} is not a finite number", place) from None
    return _own_precision_entry(x, value, floats)


def _own_precision_entry(x: Any, value: Fraction, floats: FloatMode) -> tuple[Entry, str | None]:
    """A numpy float of another precision than a double's (float16, float32, longdouble),
    exactly ``value``: at ``shortest``, the decimal of :func:`_covering_decimal`, which the
    ``auto`` and ``rounded`` decimals rules read as covering every real that rounds to
    ``x`` in its own precision (its printed decimal would cover only half a unit of its
    last digit, several times less: a float32 1/12 would then exclude 1/12)."""
    import numpy as np

    if value == 0:
        return Entry.of(value), None
    if floats == "exact":
        return Entry.of(value), (BINARY if Fraction(str(x)) != value else None)
    spacing = max(value - _neighbour(x, -np.inf), _neighbour(x, np.inf) - value)  # both: the larger
    text = _covering_decimal(value, spacing / 2)
    if text is None:  # fewer digits than a rounded decimal has: its exact value, and a warning
        return Entry.of(value), BINARY
    entry = Entry.parse(text)
    return entry, (DECIMAL if Fraction(text) != value or entry.is_rounded else None)


def _neighbour(x: Any, towards: float) -> Fraction:
    """The next float of ``x``'s own type towards ±inf; past the largest one, as far
    beyond it as the float below is beneath it (the rounding interval's other half)."""
    import numpy as np

    def exact(y: Any) -> Fraction:
        return Fraction(*y.item().as_integer_ratio()) if y.dtype.itemsize > 8 else Fraction(float(y))

    y = np.nextafter(x, np.asarray(towards, dtype=x.dtype))
    if np.isfinite(y):
        return exact(y)
    return 2 * exact(x) - exact(np.nextafter(x, np.asarray(-towards, dtype=x.dtype)))


def _covering_decimal(value: Fraction, radius: Fraction) -> str | None:
    """The decimal of the most significant digits (at least ROUNDED_MIN_DIGITS) whose half
    unit in the last digit covers ``[value − radius, value + radius]``, or None."""
    from rkcheck.numbers.formatting import decimal_digits, decimal_string
    from rkcheck.numbers.grammar import ROUNDED_MIN_DIGITS

    for sig in range(40, ROUNDED_MIN_DIGITS - 1, -1):
        n, e = decimal_digits(value, sig)
        d = (-1 if value < 0 else 1) * Fraction(n) * Fraction(10) ** (e - sig + 1)
        if abs(d - value) + radius <= Fraction(1, 2) * Fraction(10) ** (e - sig + 1):
            return decimal_string(d, sig, keep_zeros=True)
    return None


def entry_of(x: Any, place: str, floats: FloatMode = "shortest") -> tuple[Entry, str | None]:
    """One value as an :class:`Entry` (see the module docstring for what each type
    means) and, for a float whose readings (shortest repr, exact binary value) differ,
    which was taken (:data:`DECIMAL` or :data:`BINARY`; None otherwise)."""
    try:
        if isinstance(x, bool):
            raise TableauError("expected a number, got a boolean", place)
        if isinstance(x, str):
            return Entry.parse(x), None
        if isinstance(x, (int, Fraction)):
            return Entry.of(x), None
        if isinstance(x, float):
            return _float_entry(x, floats, place)
        if isinstance(x, Decimal):
            if not x.is_finite():
                raise TableauError(f"{x} is not a finite number", place)
            return Entry.parse(str(x)), None
        if _is_sympy(x):
            if getattr(x, "is_Rational", False):
                return Entry.of(Fraction(int(x.p), int(x.q))), None
            if getattr(x, "is_Float", False):
                if getattr(x, "_prec", None) == 53:  # a double: read as the float it is
                    return _float_entry(float(x), floats, place)
                value, shown = _sympy_float_exact(x), Entry.parse(str(x))
                differs = Fraction(str(x)) != value or shown.is_rounded
                return (shown if floats == "shortest" else Entry.of(value)), _reading(differs, floats)
            if getattr(x, "is_number", False):
                try:
                    return Entry.parse(str(x)), None
                except UserError:  # cos(pi/18) and the like: exact through its minimal polynomial
                    return Entry.parse(_sympy_root_text(x, place)), None
            raise TableauError(f"expected a number, got the sympy expression {x}", place)
        if hasattr(x, "item") and hasattr(x, "dtype"):  # a numpy scalar
            if getattr(x, "ndim", 0) >= 1:  # an array where a number belongs: A of three axes, b of two
                shape = "×".join(str(n) for n in x.shape)
                raise TableauError(f"expected a number, got an array of shape {shape}", place)
            if getattr(x.dtype, "kind", "") == "f" and x.dtype.itemsize < 8:
                return _narrow_float_entry(x, floats, place)
            item = x.item()
            if type(item) is type(x):  # numpy.longdouble: no Python type holds it
                return _longdouble_entry(x, floats, place)
            return entry_of(item, place, floats)
    except UserError as err:
        inner = err.place if err.place and not err.place.startswith(place) else None
        raise TableauError(err.message, f"{place}: {inner}" if inner else (err.place or place)) from None
    raise TableauError(f"expected a number (int, Fraction, str, float), got {type(x).__name__}", place)


def _narrow_float_entry(x: Any, floats: FloatMode, place: str) -> tuple[Entry, str | None]:
    """A numpy float32 (or float16) as a decimal covering its own rounding interval
    (:func:`_own_precision_entry`), or its exact binary value."""
    if not math.isfinite(float(x)):
        raise TableauError(f"{x} is not a finite number", place)
    return _own_precision_entry(x, Fraction(float(x)), floats)  # widening to a double is exact


def _sympy_root_text(x: Any, place: str) -> str:
    """An algebraic sympy number as ``root(p, k)``: its minimal polynomial over Q and
    which real root it is, counted from the smallest (rkcheck's grammar)."""
    import sympy

    X = sympy.Symbol("x")
    from sympy.polys.polyerrors import BasePolynomialError

    try:
        poly = sympy.Poly(sympy.minimal_polynomial(x, X), X)
    except (BasePolynomialError, NotImplementedError, ValueError, TypeError, AttributeError):  # pi, oo, zoo, nan
        raise TableauError(f"{x} is not an algebraic number rkcheck can take exactly", place) from None
    if poly.degree() > 100 or not x.is_real:
        raise TableauError(f"{x}: its minimal polynomial is out of reach (degree {poly.degree()})", place)
    roots = poly.real_roots()
    value = sympy.N(x, 60)
    k = min(range(len(roots)), key=lambda i: abs(sympy.N(roots[i], 60) - value)) + 1
    terms = []
    for (power,), coeff in poly.terms():
        c = sympy.Rational(coeff)
        terms.append(f"({c.p}/{c.q})*x^{power}" if c.q != 1 else f"({c.p})*x^{power}")
    return f"root({' + '.join(terms)}, {k})"


def _sympy_float_exact(x: Any) -> Fraction:
    """The exact binary value of a sympy Float (its mantissa and exponent)."""
    import mpmath

    man, exp = mpmath.mpf(x._mpf_).man_exp
    return Fraction(int(man)) * (Fraction(2) ** int(exp))


def refuse_masked(value: Any, place: str) -> None:
    """A numpy masked array with masked cells is refused: they hold whatever was there,
    not entries."""
    mask = getattr(value, "mask", None)
    if hasattr(value, "dtype") and mask is not None and bool(getattr(mask, "any", lambda: mask)()):
        raise TableauError("a masked array with masked entries: give every entry", place)


def as_list(value: Any, place: str) -> list[Any]:
    refuse_masked(value, place)
    if hasattr(value, "dtype") and getattr(value, "ndim", 0) >= 1:  # a numpy array: its own scalars
        value = list(value)  # (tolist() would widen float32 to float and print its binary noise)
    elif hasattr(value, "tolist"):  # sympy matrices
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return list(value)
    raise TableauError(f"expected a list or an array, got {type(value).__name__}", place)


def as_vector(value: Any, place: str) -> list[Any]:
    """A vector's cells: a list, a 1-D array, or a sympy vector — a matrix of one column
    (or row); numpy has 1-D arrays for vectors, and a 2-D one is refused cell by cell."""
    shape = getattr(value, "shape", None)
    if not hasattr(value, "dtype") and shape is not None and len(shape) == 2 and 1 in shape:
        value = [value[i, 0] if shape[1] == 1 else value[0, i] for i in range(max(shape))]
    return as_list(value, place)


def entries_from_arrays(
    A: Any,
    b: Any,
    c: Any = None,
    *,
    floats: FloatMode = "shortest",
    max_stages: int = DEFAULT_MAX_STAGES,
) -> tuple[tuple[tuple[Entry, ...], ...], tuple[Entry, ...], tuple[Entry, ...] | None, list[str]]:
    """The entries of a tableau given as arrays: ``A`` (s×s), ``b`` and optionally ``c``
    (length s), with the warnings the values deserve (``Tableau.from_arrays``, public as
    ``rkcheck.from_arrays``, builds the tableau).

    Values may be ints, Fractions, strings in rkcheck's grammar, floats
    (``floats="shortest"``, the default: ``repr(x)``, read like that literal in a file;
    ``"exact"``: the exact binary value), Decimals, numpy scalars and arrays, sympy
    numbers and matrices; see the module docstring.  Floats whose readings differ are
    warned about (:class:`~rkcheck.errors.RkcheckWarning`, and in the warnings).
    Problems raise :class:`~rkcheck.errors.TableauError` naming the place
    (``A[2][3]``, 1-based like ``a_ij``)."""
    if floats not in ("exact", "shortest"):
        raise TableauError(f"floats must be 'exact' or 'shortest', got {floats!r}", "floats")
    parse_int_in(max_stages, MAX_STAGES_RANGE, "max_stages")  # as load() and loads() refuse it
    rows = as_list(A, "A")
    s = len(rows)
    if s == 0:
        raise TableauError("the tableau is empty (A has no rows)", "A")
    if s > max_stages:
        raise TableauError(f"{s} stages exceeds the limit of {max_stages} (raise it with max_stages=)", "A")
    inexact: list[tuple[str, Entry, str]] = []

    def entry(x: Any, place: str) -> Entry:
        e, reading = entry_of(x, place, floats)
        if reading is not None:
            inexact.append((place, e, reading))
        return e

    matrix = []
    for i, row in enumerate(rows, start=1):
        cells = as_list(row, f"A[{i}]")
        if len(cells) != s:
            raise TableauError(f"row has {len(cells)} entries, expected {s} (A must be square)", f"A[{i}]")
        matrix.append(tuple(entry(x, f"A[{i}][{j}]") for j, x in enumerate(cells, start=1)))

    def vector(value: Any, label: str) -> tuple[Entry, ...]:
        cells = as_vector(value, label)
        if len(cells) != s:
            raise TableauError(f"has {len(cells)} entries, expected {s} (one per stage)", label)
        return tuple(entry(x, f"{label}[{i}]") for i, x in enumerate(cells, start=1))

    b_entries = vector(b, "b")
    c_entries = None if c is None else vector(c, "c")
    warnings = _float_warnings(inexact, floats)
    for w in warnings:
        warn(w)
    return tuple(matrix), b_entries, c_entries, warnings


def _float_warnings(inexact: list[tuple[str, Entry, str]], floats: FloatMode) -> list[str]:
    """One warning per way floats were read where the two readings differ: as a decimal
    (:data:`DECIMAL`), or at their exact binary value (:data:`BINARY`)."""
    out = []
    decimal = [(p, e) for p, e, how in inexact if how == DECIMAL]
    if decimal:
        place, first = decimal[0]
        out.append(f"{len(decimal)} float entries (first {place} = {first.text}) were read as a decimal, which "
                   "stands for the reals that round to the float (decimals 'auto') or for that decimal exactly (0.1 "
                   "is not the double 0.1); floats='exact' takes their exact binary values")
    binary = [p for p, _, how in inexact if how == BINARY]
    if binary and floats == "exact":
        out.append(f"{len(binary)} float entries (first {binary[0]}) were taken at their exact binary value, which is "
                   "not the decimal they print as; pass strings, or floats='shortest' (the default), to mean the "
                   "decimals")
    elif binary:
        out.append(f"{len(binary)} float entries (first {binary[0]}) were taken at their exact binary value: they "
                   "have fewer digits than a rounded decimal (definitions §5), so no decimal stands for the reals "
                   "that round to them; pass strings to mean decimals")
    return out
