"""The Butcher tableau ``(A, b, c)`` of definitions §1, as entries of the number model.

A :class:`Tableau` is pure data: no file I/O (that is :mod:`rkcheck.io.loader`) and no
B-series (that is :mod:`rkcheck.evaluation.backends`).  Every B-series quantity uses the row sums
``A·1``; a given ``c`` is only compared with them (:func:`consistency_warnings`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Callable, Sequence

from rkcheck.numbers.entries import Constants, Entry, TableauEntry
from rkcheck.numbers.intervals import Interval, interval_sum


@dataclass
class Tableau:
    """An s-stage Runge–Kutta method; ``c`` is None when the file left it out.  Its entries
    are :class:`~rkcheck.numbers.entries.Entry` objects, or for a family the coefficients
    the family computes (then ``family_exact`` gives them exactly when it can)."""

    A: tuple[tuple[TableauEntry, ...], ...]
    b: tuple[TableauEntry, ...]
    c: tuple[TableauEntry, ...] | None = None
    name: str = "unnamed tableau"
    description: str = ""
    references: tuple[str, ...] = ()
    source: str = "<memory>"
    check: dict[str, Any] = field(default_factory=dict)
    expect: dict[str, Any] = field(default_factory=dict)
    family: dict[str, Any] | None = None
    warnings: list[str] = field(default_factory=list)
    lines: dict[str, int] = field(default_factory=dict)  # "tableau", "expect.avf", ... -> line
    constants: Constants = field(default_factory=Constants)
    claims: list = field(default_factory=list)  # parsed [expect] (rkcheck.energy.claims.Claim)
    exact_reason: str | None = field(default=None, repr=False, compare=False)
    _exact_values: dict = field(default_factory=dict, repr=False, compare=False)
    # a family's coefficients exactly: () -> (ExactValues or None, why not)
    family_exact: Callable[[], tuple[ExactValues | None, str | None]] | None = field(
        default=None, repr=False, compare=False)

    # ------------------------------------------------------------- construction

    @staticmethod
    def from_values(
        A: Sequence[Sequence[Fraction | int | str]],
        b: Sequence[Fraction | int | str],
        c: Sequence[Fraction | int | str] | None = None,
        name: str = "unnamed tableau",
        **kwargs: Any,
    ) -> "Tableau":
        """Build a tableau from rationals or entry strings (for generators and tests)."""

        def entry(x: Fraction | int | str) -> Entry:
            return Entry.parse(x) if isinstance(x, str) else Entry.of(x)

        return Tableau(
            A=tuple(tuple(entry(x) for x in row) for row in A),
            b=tuple(entry(x) for x in b),
            c=None if c is None else tuple(entry(x) for x in c),
            name=name,
            **kwargs,
        )

    @staticmethod
    def from_arrays(A: Any, b: Any, c: Any = None, **kwargs: Any) -> "Tableau":
        """A tableau from arrays of ints, Fractions, strings, floats, numpy or sympy values
        (what each means: :mod:`rkcheck.methods.arrays`); ``rkcheck.from_arrays``."""
        from rkcheck.methods.arrays import from_arrays

        return from_arrays(A, b, c, **kwargs)

    # ----------------------------------------------------------------- structure

    @property
    def stages(self) -> int:
        return len(self.b)

    def entries(self) -> list[TableauEntry]:
        out = [e for row in self.A for e in row] + list(self.b)
        return out + list(self.c or ())

    @property
    def is_rational(self) -> bool:
        """Every entry of A and b is an exact rational at face value."""
        return all(e.is_rational for row in self.A for e in row) and all(e.is_rational for e in self.b)

    @property
    def uses_sqrt(self) -> bool:
        return any(e.uses_sqrt for e in self.entries())

    @property
    def rounded_digits(self) -> int | None:
        """Fewest significant digits of a rounded decimal in A or b (None: no rounded decimals)."""
        digits = [e.rounded_digits for row in self.A for e in row if e.rounded_digits is not None]
        digits += [e.rounded_digits for e in self.b if e.rounded_digits is not None]
        return min(digits) if digits else None

    def is_exact(self, decimals: str) -> bool:
        """True when the check runs in exact arithmetic (definitions §5): no entry is a box
        under ``decimals``, and the entries are rationals or elements of a number field
        (:meth:`exact_values`)."""
        if self.is_box(decimals):
            return False
        return self.is_rational or self.exact_values(decimals) is not None

    def is_box(self, decimals: str) -> bool:
        """Some entry of A or b stands for an interval of numbers under the decimals mode
        (definitions §5.2): the tableau is a box of tableaux, judged jointly."""
        return any(e.is_box(decimals) for row in self.A for e in row) or any(e.is_box(decimals) for e in self.b)

    def exact_values(self, decimals: str = "rounded"):
        """The entries exactly, in one number field (:mod:`rkcheck.numbers.algebraic`):
        an object with ``.field`` (None for Q) and ``.A``, ``.b``, ``.c`` (``c`` None when
        the file left it out) as Fractions or field elements; None when the entries are
        not exact numbers (a box of inputs under ``decimals``, computed coefficients,
        or a field beyond the degree limit: then ``exact_reason`` says why)."""
        key = not self.is_box(decimals)
        if key not in self._exact_values:
            self._exact_values[key] = _exact_values(self) if key else None
        return self._exact_values[key]

    @property
    def structure(self) -> str:
        """``explicit``, ``diagonally implicit`` or ``implicit`` (by entries that are exactly 0)."""
        s = self.stages
        upper_zero = all(self.A[i][j].is_zero() for i in range(s) for j in range(i + 1, s))
        if not upper_zero:
            return "implicit"
        if all(self.A[i][i].is_zero() for i in range(s)):
            return "explicit"
        return "diagonally implicit"

    def number_kind(self, decimals: str = "auto") -> str:
        if self.family is not None and not self.is_rational:
            return "computed by its family at the working precision"
        if self.uses_sqrt:
            return "algebraic (square roots)"
        digits = self.rounded_digits
        if decimals == "float64" and self.is_box(decimals):
            return "decimals read as binary64 doubles (each within half an ulp)"
        if digits is not None and decimals in ("rounded", "auto"):
            return f"decimals rounded to their last digit (>= {digits} significant digits)"
        return "exact rational"

    # ------------------------------------------------------------------- values

    def exact_A(self) -> list[list[Any]]:
        """A exactly: Fractions, or field elements for algebraic entries (is_exact)."""
        if self.is_rational:
            return [[e.exact for e in row] for row in self.A]
        values = self.exact_values("exact")
        assert values is not None
        return values.A

    def exact_b(self) -> list[Any]:
        if self.is_rational:
            return [e.exact for e in self.b]
        values = self.exact_values("exact")
        assert values is not None
        return values.b

    def enclosures(self, bits: int, decimals: str) -> tuple[list[list[Interval]], list[Interval]]:
        """Rigorous enclosures of A and b at ``bits`` bits (definitions §5)."""
        A = [[e.enclosure(bits, decimals) for e in row] for row in self.A]
        b = [e.enclosure(bits, decimals) for e in self.b]
        return A, b


@dataclass
class ExactValues:
    """A tableau's entries in one number field (``field`` None: rationals)."""

    field: Any
    A: list[list[Any]]
    b: list[Any]
    c: list[Any] | None


def _exact_values(tab: Tableau) -> ExactValues | None:
    if tab.is_rational:
        c = None if tab.c is None or any(e.exact is None for e in tab.c) else [e.exact for e in tab.c]
        return ExactValues(None, tab.exact_A(), tab.exact_b(), c)
    entries = tab.entries()
    nodes = [e.node for e in entries if isinstance(e, Entry)]
    if len(nodes) < len(entries):  # computed by a family
        exact = tab.family_exact
        values, reason = exact() if exact is not None else (None, None)
        if values is None:
            tab.exact_reason = reason or "the coefficients are computed numerically by the family"
        return values
    from rkcheck.numbers.algebraic import NotAlgebraic, field_of

    try:
        found = field_of(nodes, tab.constants.definitions)
    except NotAlgebraic as err:
        tab.exact_reason = str(err)
        return None
    s = tab.stages
    v = found.values
    A = [v[i * s:(i + 1) * s] for i in range(s)]
    b = v[s * s:s * s + s]
    c = v[s * s + s:] if tab.c is not None else None
    return ExactValues(found.field, A, b, c)


def consistency_warnings(tab: Tableau, bits: int, decimals: str) -> list[str]:
    """definitions §1 warnings: a given ``c`` that differs from ``A·1``, and ``Σb ≠ 1``.

    A difference is reported only when it is certain (its enclosure excludes 0);
    differences within the rounding of decimal input are not warnings.
    """
    out: list[str] = []
    A, b = tab.enclosures(bits, decimals)
    if tab.c is not None:
        bad = []
        for i, (row, ci) in enumerate(zip(A, tab.c), start=1):
            diff = ci.enclosure(bits, decimals) - interval_sum(row)
            if not diff.contains_zero():
                bad.append(f"c[{i}] - (A·1)[{i}] = {float(diff.mid):.3g}")
        if bad:
            out.append("c differs from the row sums A·1 (the check uses A·1): " + "; ".join(bad))
    sb = interval_sum(b)
    if not (sb - Interval.point(1)).contains_zero():
        out.append(f"Σb = {float(sb.mid):.17g} ≠ 1: the method is inconsistent (not even order 1)")
    return out
