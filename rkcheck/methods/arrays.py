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
``float`` (also numpy)      by default its **exact binary value**: ``0.1`` is
                            ``3602879701896397/36028797018963968``, not 1/10.  That is
                            the number a float computation used; but a tableau whose
                            entries were rounded to doubles is then checked as the
                            slightly different method it is (AVF-Gauss from floats fails
                            by about 1e-17).  ``floats="shortest"`` takes ``repr(x)``
                            instead (``"0.1"``, ``"0.21132486540518713"``), which the
                            ``auto`` decimals rule reads as the double's rounding
                            interval — still narrower than the errors of a float
                            computation; to check a tableau up to the digits you trust,
                            pass strings: ``f"{x:.15g}"``
``decimal.Decimal``         its decimal text, as a string would be
sympy numbers               ``Rational``/``Integer`` exactly; other constant expressions
                            (``sqrt(3)/6``) through their text; ``Float`` at its exact
                            binary value
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

from rkcheck.errors import TableauError, UserError
from rkcheck.numbers.entries import Entry
from rkcheck.options import DEFAULT_MAX_STAGES

FloatMode = Literal["exact", "shortest"]


def _is_sympy(x: Any) -> bool:
    return type(x).__module__.split(".")[0] == "sympy"


def _float_entry(x: float, floats: FloatMode, place: str) -> tuple[Entry, bool]:
    if not math.isfinite(x):
        raise TableauError(f"{x} is not a finite number", place)
    if floats == "shortest":
        return Entry.parse(repr(float(x))), False
    value = Fraction(x)
    # only worth a warning when the binary value is not the decimal the user sees
    return Entry.of(value), Fraction(repr(float(x))) != value


def _longdouble_entry(x: Any, floats: FloatMode, place: str) -> tuple[Entry, bool]:
    """A numpy extended-precision float: its exact binary value (or, ``shortest``, the
    shortest decimal numpy prints for it), like a float."""
    try:
        value = Fraction(*x.as_integer_ratio())
    except (OverflowError, ValueError, AttributeError):
        raise TableauError(f"{x} is not a finite number", place) from None
    shortest = str(x)
    if floats == "shortest":
        return Entry.parse(shortest), False
    try:
        differs = Fraction(shortest) != value
    except ValueError:
        differs = True
    return Entry.of(value), differs


def entry_of(x: Any, place: str, floats: FloatMode = "exact") -> tuple[Entry, bool]:
    """One value as an :class:`Entry` (see the module docstring for what each type
    means) and whether it was a float whose binary value differs from its decimal."""
    try:
        if isinstance(x, bool):
            raise TableauError("expected a number, got a boolean", place)
        if isinstance(x, str):
            return Entry.parse(x), False
        if isinstance(x, (int, Fraction)):
            return Entry.of(x), False
        if isinstance(x, float):
            return _float_entry(x, floats, place)
        if isinstance(x, Decimal):
            if not x.is_finite():
                raise TableauError(f"{x} is not a finite number", place)
            return Entry.parse(str(x)), False
        if _is_sympy(x):
            if getattr(x, "is_Rational", False):
                return Entry.of(Fraction(int(x.p), int(x.q))), False
            if getattr(x, "is_Float", False):
                if floats == "shortest":
                    return Entry.parse(str(x)), False
                value = _sympy_float_exact(x)
                return Entry.of(value), Fraction(str(x)) != value
            if getattr(x, "is_number", False):
                try:
                    return Entry.parse(str(x)), False
                except UserError:  # cos(pi/18) and the like: exact through its minimal polynomial
                    return Entry.parse(_sympy_root_text(x, place)), False
            raise TableauError(f"expected a number, got the sympy expression {x}", place)
        if hasattr(x, "item") and hasattr(x, "dtype"):  # a numpy scalar
            item = x.item()
            if type(item) is type(x):  # numpy.longdouble: no Python type holds it
                return _longdouble_entry(x, floats, place)
            return entry_of(item, place, floats)
    except UserError as err:
        inner = err.place if err.place and not err.place.startswith(place) else None
        raise TableauError(err.message, f"{place}: {inner}" if inner else (err.place or place)) from None
    raise TableauError(f"expected a number (int, Fraction, str, float), got {type(x).__name__}", place)


def _sympy_root_text(x: Any, place: str) -> str:
    """An algebraic sympy number as ``root(p, k)``: its minimal polynomial over Q and
    which real root it is, counted from the smallest (rkcheck's grammar)."""
    import sympy

    X = sympy.Symbol("x")
    try:
        poly = sympy.Poly(sympy.minimal_polynomial(x, X), X)
    except (NotImplementedError, ValueError, TypeError, AttributeError):
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


def _as_list(value: Any, place: str) -> list[Any]:
    if hasattr(value, "tolist"):  # numpy arrays, sympy matrices
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return list(value)
    raise TableauError(f"expected a list or an array, got {type(value).__name__}", place)


def entries_from_arrays(
    A: Any,
    b: Any,
    c: Any = None,
    *,
    floats: FloatMode = "exact",
    max_stages: int = DEFAULT_MAX_STAGES,
) -> tuple[tuple[tuple[Entry, ...], ...], tuple[Entry, ...], tuple[Entry, ...] | None, list[str]]:
    """The entries of a tableau given as arrays: ``A`` (s×s), ``b`` and optionally ``c``
    (length s), with the warnings the values deserve (``Tableau.from_arrays``, public as
    ``rkcheck.from_arrays``, builds the tableau).

    Values may be ints, Fractions, strings in rkcheck's grammar, floats (``floats="exact"``:
    the exact binary value, the default; ``"shortest"``: ``repr(x)`` read as a rounded
    decimal), Decimals, numpy scalars and arrays, sympy numbers and matrices; see the
    module docstring.  Problems raise :class:`~rkcheck.errors.TableauError` naming the
    place (``A[2][3]``, 1-based like ``a_ij``)."""
    if floats not in ("exact", "shortest"):
        raise TableauError(f"floats must be 'exact' or 'shortest', got {floats!r}", "floats")
    rows = _as_list(A, "A")
    s = len(rows)
    if s == 0:
        raise TableauError("the tableau is empty (A has no rows)", "A")
    if s > max_stages:
        raise TableauError(f"{s} stages exceeds the limit of {max_stages}", "A")
    inexact: list[str] = []

    def entry(x: Any, place: str) -> Entry:
        e, differs = entry_of(x, place, floats)
        if differs:
            inexact.append(place)
        return e

    matrix = []
    for i, row in enumerate(rows, start=1):
        cells = _as_list(row, f"A[{i}]")
        if len(cells) != s:
            raise TableauError(f"row has {len(cells)} entries, expected {s} (A must be square)", f"A[{i}]")
        matrix.append(tuple(entry(x, f"A[{i}][{j}]") for j, x in enumerate(cells, start=1)))

    def vector(value: Any, label: str) -> tuple[Entry, ...]:
        cells = _as_list(value, label)
        if len(cells) != s:
            raise TableauError(f"has {len(cells)} entries, expected {s} (one per stage)", label)
        return tuple(entry(x, f"{label}[{i}]") for i, x in enumerate(cells, start=1))

    b_entries = vector(b, "b")
    c_entries = None if c is None else vector(c, "c")
    warnings = []
    if inexact:
        warnings.append(
            f"{len(inexact)} float entries (first {inexact[0]}) were taken at their exact binary value, which "
            "is not the decimal they print as; pass strings, or floats='shortest', to mean the decimals")
    return tuple(matrix), b_entries, c_entries, warnings
