"""A tableau's numbers for one check: what kind they are, exactly or as enclosures.

:class:`TableauValues` is computed once per check from a tableau and a
:class:`~rkcheck.numbers.reading.Reading` (definitions §5), and everything that needs
the tableau's numbers reads them here: the number kind (exact rationals, a number field,
a box of decimal inputs, coefficients computed numerically), the exact values or the
reason there are none, the certified enclosures at the reading's precision, the
arithmetic the conditions are evaluated in, and — built on first use, because in a
number field of high degree it takes seconds — the scaled data of the modular route.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from fractions import Fraction
from functools import cached_property
from typing import Any

from rkcheck.errors import UserError
from rkcheck.evaluation.scaled import ScaledTableau, scaled_field, scaled_rational
from rkcheck.evaluation.split_nodes import scaled_nodes
from rkcheck.methods.tableau import ExactValues, Tableau
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.formatting import decimal_exponent, decimal_string, exact_string
from rkcheck.numbers.intervals import Interval, interval_sum
from rkcheck.numbers.reading import Arithmetic, DecimalsMode, Reading


class NumberKind(StrEnum):
    """What the entries of a tableau are under a reading."""

    RATIONAL = "rational"  # exact rationals
    ALGEBRAIC = "algebraic"  # exact, in a number field
    BOX = "box"  # decimals that stand for intervals: a box of tableaux
    NUMERIC = "numeric"  # no exact values (computed coefficients, a field too large)

    @property
    def is_exact(self) -> bool:
        return self in (NumberKind.RATIONAL, NumberKind.ALGEBRAIC)


class Backend(StrEnum):
    """The arithmetic the conditions are evaluated in."""

    EXACT = "exact"  # residues modulo primes: holds / fails
    BALL = "ball"  # certified balls: holds to D digits / fails


@dataclass(frozen=True)
class TableauValues:
    """The numbers of one tableau under one reading; each fact is computed on first use
    and kept (the exact values of a tableau in a field of high degree take seconds)."""

    tableau: Tableau
    reading: Reading

    @staticmethod
    def of(tableau: Tableau, reading: Reading) -> "TableauValues":
        return TableauValues(tableau, reading)

    @cached_property
    def kind(self) -> NumberKind:
        if self.tableau.is_box(self.reading.decimals):
            return NumberKind.BOX
        exact = self.tableau.exact_values()
        if exact is None:
            return NumberKind.NUMERIC
        return NumberKind.RATIONAL if exact.is_rational else NumberKind.ALGEBRAIC

    @property
    def exact(self) -> ExactValues | None:
        """The exact values, when the reading makes the entries exact numbers."""
        return self.tableau.exact_values() if self.kind.is_exact else None

    @property
    def reason(self) -> str | None:
        """Why there are no exact values (kind NUMERIC)."""
        return self.tableau.exact_reason if self.kind is NumberKind.NUMERIC else None

    @cached_property
    def _enclosures(self) -> tuple[list[list[Interval]], list[Interval]]:
        return self.tableau.enclosures(self.reading.entry_bits, self.reading.decimals)

    @property
    def A(self) -> list[list[Interval]]:
        """Enclosures of A at the reading's entry bits."""
        return self._enclosures[0]

    @property
    def b(self) -> list[Interval]:
        return self._enclosures[1]

    @cached_property
    def literal_chain(self) -> Any:
        """The interval entries' derivatives along their decimal literals
        (:class:`~rkcheck.evaluation.slopes.LiteralChain`), where some literal occurs more
        than once among them (a constant used in several entries): the box is then judged
        along the literals (definitions §5.2); None otherwise, the entries' own box being
        the literals' image already (to first order)."""
        from rkcheck.evaluation.slopes import LiteralChain
        from rkcheck.numbers.literals import literal_box

        tab, s = self.tableau, self.tableau.stages
        in_A, in_b = self.varies
        entries = [tab.A[i][j] for i in range(s) for j in range(s) if in_A[i][j]]
        entries += [tab.b[i] for i in range(s) if in_b[i]]
        box = literal_box(entries, self.reading.entry_bits, self.reading.decimals)
        return None if box is None else LiteralChain.of(box)

    @cached_property
    def varies(self) -> tuple[list[list[bool]], list[bool]]:
        """Which entries of A and b stand for intervals of inputs (a rounded decimal in
        them, or in a constant they use): the directions of a box.  An exact irrational
        entry (``sqrt(3)``) is one number, enclosed, not a direction."""
        decimals = self.reading.decimals
        return ([[e.is_box(decimals) for e in row] for row in self.tableau.A],
                [e.is_box(decimals) for e in self.tableau.b])

    def at(self, dps: int) -> "TableauValues":
        """The same tableau read at another working precision (the exact values are the
        tableau's own, computed once)."""
        return TableauValues(self.tableau, self.reading.at(dps))

    @property
    def backend(self) -> Backend:
        """Exact when the entries allow it and balls were not asked for, else balls;
        ``--arithmetic exact`` on data that is not exact is a user error."""
        if self.reading.arithmetic is Arithmetic.EXACT and not self.kind.is_exact:
            raise UserError("--arithmetic exact: the entries are not exact numbers (rounded decimals or "
                            "coefficients without a closed form); use auto or ball")
        if self.kind.is_exact and self.reading.arithmetic is not Arithmetic.BALL:
            return Backend.EXACT
        return Backend.BALL

    @property
    def stages(self) -> int:
        return self.tableau.stages

    @cached_property
    def scaled(self) -> ScaledTableau:
        """The exact data of the modular route (an exact reading only)."""
        assert self.exact is not None, "the modular route needs exact values"
        if self.exact.nodes is not None:  # rational conditions: no field arithmetic for them
            return scaled_nodes(self.exact.nodes)
        if self.exact.field is None:
            return scaled_rational(self.exact.A, self.exact.b)
        return scaled_field(self.exact)

    # ------------------------------------------------------------------ reports

    def describe(self) -> str:
        """The number kind for people: ``exact rational``, ``algebraic (square roots)``, …"""
        tab, decimals = self.tableau, self.reading.decimals
        if tab.info.family is not None and not tab.is_rational:
            return "computed by its family at the working precision"
        if tab.uses_sqrt:
            kind = "algebraic (roots)" if _uses_root(tab) else "algebraic (square roots)"
            # not silently in balls: say which limit kept them from being exact
            return kind if self.kind is not NumberKind.NUMERIC else f"{kind}, not exact: {self.reason}"
        digits = tab.rounded_digits
        if decimals is DecimalsMode.FLOAT64 and self.kind is NumberKind.BOX:
            return "decimals read as binary64 doubles (each within half an ulp)"
        if digits is not None and decimals.rounds:
            return f"decimals rounded to their last digit (>= {digits} significant digits)"
        return "exact rational"

    def consistency_warnings(self) -> list[str]:
        """definitions §1 warnings: a given ``c`` that differs from ``A·1``, and ``Σb ≠ 1``.

        Exact entries are compared exactly (without enclosing them: an exact check needs
        no enclosures).  Otherwise a difference is reported only when it is certain (its
        enclosure excludes 0); differences within the rounding of decimal input are not
        warnings.  The values shown are exact, from the entries as written, when they have
        exact values."""
        exact = self.exact
        rows, total = _exact_differences(exact) if exact is not None else self._certain_differences()
        if exact is not None and rows and self._c_rounded():  # c's decimals stand for intervals
            rows = self._certain_rows()
        out: list[str] = []
        if rows:
            out.append("c differs from the row sums A·1 (the check uses A·1): "
                       + "; ".join(f"c[{i}] - (A·1)[{i}] = {text}" for i, text in rows))
        if total is not None:
            out.append(f"Σb = {total} ≠ 1: the method is inconsistent (not even order 1)")
        return out

    def _c_rounded(self) -> bool:
        """A given ``c`` with decimals that the reading takes as intervals (exact A and b
        beside it are then compared with them as intervals)."""
        c = self.tableau.c
        return c is not None and any(ci.is_box(self.reading.decimals) for ci in c)

    def _certain_rows(self) -> list[tuple[int, str]]:
        """The rows i with ``c_i ≠ (A·1)_i`` where the enclosures prove it, each with the
        text of its difference."""
        tab, face = self.tableau, self.tableau.exact_values()
        rows: list[tuple[int, str]] = []
        if tab.c is None:
            return rows
        for i, (row, ci) in enumerate(zip(self.A, tab.c), start=1):
            diff = ci.enclosure(self.reading.entry_bits, self.reading.decimals) - interval_sum(row)
            if not diff.contains_zero():
                exact = None if face is None or face.c is None else face.c[i - 1] - sum(face.A[i - 1])
                rows.append((i, _value_text(diff, exact)))
        return rows

    def _certain_differences(self) -> tuple[list[tuple[int, str]], str | None]:
        """The rows i with ``c_i ≠ (A·1)_i`` and the text of each difference, and that of
        ``Σb`` when it is not 1, where the entries' enclosures prove it."""
        face = self.tableau.exact_values()
        rows = self._certain_rows()
        sb = interval_sum(self.b)
        if (sb - Interval.point(1)).contains_zero():
            return rows, None
        return rows, _value_text(sb, None if face is None else face.weight_sum())


def _exact_differences(exact: ExactValues) -> tuple[list[tuple[int, str]], str | None]:
    """:meth:`TableauValues._certain_differences` for exact values: decided exactly,
    shown exactly."""
    rows = []
    if exact.c is not None:
        diffs = [(i, ci - sum(row)) for i, (row, ci) in enumerate(zip(exact.A, exact.c), start=1)]
        rows = [(i, _exact_text(d)) for i, d in diffs if d != 0]
    sb = exact.weight_sum()
    return rows, None if sb == 1 else _exact_text(sb)


def _exact_text(x: Any) -> str:
    return exact_string(x) if isinstance(x, (Fraction, int)) else x.text()


def _uses_root(tab: Tableau) -> bool:
    """Some entry (or a constant it names) takes a root of a polynomial, not only ``sqrt``."""
    nodes = [getattr(e, "node", None) for e in tab.entries()] + list(tab.info.constants.definitions.values())
    return any(isinstance(n, ex.Call) and n.func == "root" for node in nodes if node is not None for n in xp.walk(node))


def _value_text(x: Interval, exact: Any = None) -> str:
    """A value as the entries say it exactly (``0.99``, ``1/3``, a field element's
    text), else its enclosure's certified leading digits — never through a binary float."""
    if exact is not None:
        return _exact_text(exact)
    if x.is_point:
        return exact_string(x.lo)
    rad = (x.hi - x.lo) / 2
    sig = decimal_exponent(x.mid) - decimal_exponent(rad) if x.mid and rad else 1
    return "≈" + decimal_string(x.mid, min(max(sig, 1), 20))
