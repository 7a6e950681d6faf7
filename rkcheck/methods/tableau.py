"""The Butcher tableau ``(A, b, c)`` of definitions §1, as entries of the number model.

A :class:`Tableau` is immutable data: the coefficients and a name.  What a file says
about the method besides them (description, references, claims, ``[check]`` options,
line numbers, warnings) is a :class:`MethodInfo`; how the entries are read for one
check (exact, a box of decimals, enclosures) is decided by
:class:`~rkcheck.evaluation.values.TableauValues`.  No file I/O here (that is
:mod:`rkcheck.io.loader`) and no B-series (that is :mod:`rkcheck.evaluation`).  Every
B-series quantity uses the row sums ``A·1``; a given ``c`` is only compared with them.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any, Callable, Mapping, Protocol, Sequence

from rkcheck.errors import TableauError, UserError
from rkcheck.methods.arrays import FloatMode, entries_from_arrays
from rkcheck.numbers.algebraic import NotAlgebraic, NumberField
from rkcheck.numbers.entries import Constants, Entry, TableauEntry
from rkcheck.numbers.field_builder import field_of
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode
from rkcheck.options import DEFAULT_MAX_STAGES


@dataclass(frozen=True)
class MethodInfo:
    """What a file says about a method besides its coefficients.

    ``check``: the validated ``[check]`` options; ``expect``: the ``[expect]`` table as
    written and ``claims`` its parsed claims (:class:`~rkcheck.methods.claims.Claim`);
    ``lines``: where keys were written (``"tableau"``, ``"expect.avf"`` -> line);
    ``family``: the ``[family]`` parameters of a generated method; ``constants``: the
    ``[constants]`` table the entries may name; ``continuous``: see below."""

    description: str = ""
    references: tuple[str, ...] = ()
    source: str = "<memory>"
    check: Mapping[str, Any] = field(default_factory=dict)
    expect: Mapping[str, Any] = field(default_factory=dict)
    claims: tuple[Any, ...] = ()
    warnings: tuple[str, ...] = ()
    lines: Mapping[str, int] = field(default_factory=dict)
    family: Mapping[str, Any] | None = None
    constants: Constants = field(default_factory=Constants)
    #: a surrogate tableau's :class:`~rkcheck.methods.continuous.Surrogate`: the
    #: continuous-stage method whose B-series it carries, and how far
    continuous: Any = None

    def replace(self, **changes: Any) -> "MethodInfo":
        return dataclasses.replace(self, **changes)


class ExactValues:
    """A tableau's entries exactly, in one number field (``field`` None: rationals).

    A family in node form (``nodes``, a :class:`~rkcheck.methods.node_form.NodeForm`)
    has its conditions computed over Q (:mod:`rkcheck.evaluation.split_nodes`); with an
    ``algebra`` (:class:`~rkcheck.methods.node_algebra.NodeAlgebra`) its properties too,
    and then ``load`` builds the field and the entries in it only when something reads
    them (:meth:`entries`)."""

    def __init__(self, field: NumberField | None, A: list[list[Any]] | None, b: list[Any] | None,
                 c: list[Any] | None, nodes: Any = None, algebra: Any = None,
                 load: Callable[[], tuple[NumberField, list[list[Any]], list[Any]]] | None = None):
        self.c, self.nodes, self.algebra = c, nodes, algebra
        self._load = load
        self._built: tuple[NumberField | None, list[list[Any]], list[Any]] | str | None = (
            None if load is not None else (field, A or [], b or []))

    def entries(self) -> tuple[NumberField | None, list[list[Any]], list[Any]] | None:
        """``(field, A, b)``, built on first use; None when the field exceeds its limits
        (possible only for a family in node form, which needs no field to be checked)."""
        if self._built is None:
            assert self._load is not None
            try:
                self._built = self._load()
            except NotAlgebraic as err:
                self._built = str(err)
        return None if isinstance(self._built, str) else self._built

    def _entries(self) -> tuple[NumberField | None, list[list[Any]], list[Any]]:
        found = self.entries()
        if found is None:
            raise NotAlgebraic(str(self._built))
        return found

    @property
    def field(self) -> NumberField | None:
        return self._entries()[0]

    @property
    def A(self) -> list[list[Any]]:
        return self._entries()[1]

    @property
    def b(self) -> list[Any]:
        return self._entries()[2]

    @property
    def is_rational(self) -> bool:
        """Every entry rational (never true of a family in node form)."""
        return self.nodes is None and self.field is None

    def weight_sum(self) -> Any:
        """``Σ b_j`` exactly (over Q from the node form, without the field)."""
        if self.algebra is not None:
            return self.algebra.weight_sum()
        return sum(self.b)


class FamilyCoefficient(Protocol):
    """An entry computed by a method family (:class:`~rkcheck.methods.families.ComputedEntry`):
    the family knows its coefficients exactly when its nodes have closed forms."""

    def family_values(self) -> tuple[ExactValues | None, str | None]: ...


@dataclass(frozen=True)
class Tableau:
    """An s-stage Runge–Kutta method; ``c`` is None when the file left it out.  Its entries
    are :class:`~rkcheck.numbers.entries.Entry` objects, or the coefficients a family
    computes (:class:`FamilyCoefficient`)."""

    A: tuple[tuple[TableauEntry, ...], ...]
    b: tuple[TableauEntry, ...]
    c: tuple[TableauEntry, ...] | None = None
    name: str = "unnamed tableau"
    info: MethodInfo = field(default_factory=MethodInfo, compare=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):  # a report writes it as text, a catalogue sorts by it
            raise TableauError(f"expected a string, got {type(self.name).__name__}", "name")

    # ------------------------------------------------------------- construction

    @staticmethod
    def from_values(
        A: Sequence[Sequence[Fraction | int | str]],
        b: Sequence[Fraction | int | str],
        c: Sequence[Fraction | int | str] | None = None,
        name: str = "unnamed tableau",
        info: MethodInfo | None = None,
    ) -> "Tableau":
        """Build a tableau from rationals or entry strings (for generators and tests)."""

        def entry(x: Fraction | int | str) -> Entry:
            return Entry.parse(x) if isinstance(x, str) else Entry.of(x)

        return Tableau(
            A=tuple(tuple(entry(x) for x in row) for row in A),
            b=tuple(entry(x) for x in b),
            c=None if c is None else tuple(entry(x) for x in c),
            name=name,
            info=info or MethodInfo(),
        )

    @staticmethod
    def from_arrays(A: Any, b: Any, c: Any = None, *, name: str = "unnamed tableau", floats: FloatMode = "shortest",
                    max_stages: int = DEFAULT_MAX_STAGES) -> "Tableau":
        """A tableau from arrays of ints, Fractions, strings, floats, numpy or sympy values
        (what each means: :mod:`rkcheck.methods.arrays`); also ``rkcheck.from_arrays``."""
        A_, b_, c_, warnings = entries_from_arrays(A, b, c, floats=floats, max_stages=max_stages)
        return Tableau(A_, b_, c_, name, MethodInfo(source=name, warnings=tuple(warnings)))

    def replace(self, **changes: Any) -> "Tableau":
        """A copy with some fields changed (``name``, ``info``, entries)."""
        return dataclasses.replace(self, **changes)

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

    def is_box(self, decimals: DecimalsMode) -> bool:
        """Some entry of A or b stands for an interval of numbers under the decimals mode
        (definitions §5.2): the tableau is a box of tableaux, judged jointly."""
        decimals = DecimalsMode(decimals)
        found = False
        n = self.stages * (self.stages + 1)  # A and b: c is a check of A·1, not an input of the conditions
        for place, e in zip(self.entry_places()[:n], self.entries()[:n]):
            try:  # every entry: one that cannot be read under the mode is named, with its file
                found = e.is_box(decimals) or found
            except UserError as err:
                raise err.located(place, self.info.source or None) from None
        return found

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

    # ------------------------------------------------------------------- values

    @cached_property
    def _exactness(self) -> ExactValues | str:
        """The entries at face value in one number field, or why they have none."""
        if self.is_rational:
            c = None if self.c is None or any(e.exact is None for e in self.c) else [e.exact for e in self.c]
            return ExactValues(None, [[e.exact for e in row] for row in self.A], [e.exact for e in self.b], c)
        entries = self.entries()
        computed = [e for e in entries if not isinstance(e, Entry)]
        if computed:
            family: FamilyCoefficient = computed[0]  # type: ignore[assignment]
            values, reason = family.family_values()
            return values if values is not None else reason or "the coefficients are computed numerically"
        try:
            found = field_of([e.node for e in entries], self.info.constants.definitions)  # type: ignore[attr-defined]
        except NotAlgebraic as err:
            return str(err)
        except UserError as err:  # the square root of a negative number: name the entry and the file
            raise err.located(self._place_of_error(entries), self.info.source or None) from None
        s = self.stages
        v = found.values
        A = [v[i * s:(i + 1) * s] for i in range(s)]
        return ExactValues(found.field, A, v[s * s:s * s + s], v[s * s + s:] if self.c is not None else None)

    def entry_places(self) -> list[str]:
        """The places of :meth:`entries`, in their order: ``A[i][j]`` row by row, ``b[i]``,
        then ``c[i]`` (1-based)."""
        s = self.stages
        places = [f"A[{i + 1}][{j + 1}]" for i in range(s) for j in range(s)] + [f"b[{i + 1}]" for i in range(s)]
        return places + [f"c[{i + 1}]" for i in range(s)]

    def _place_of_error(self, entries: list[Any]) -> str | None:
        """The first entry (``A[i][j]``, ``b[i]``, ``c[i]``) that fails on its own."""
        for place, e in zip(self.entry_places(), entries):
            try:
                field_of([e.node], self.info.constants.definitions)
            except UserError:
                return place
            except NotAlgebraic:
                continue
        return None

    def exact_values(self) -> ExactValues | None:
        """The entries at face value, exactly, in one number field
        (:mod:`rkcheck.numbers.algebraic`; computed once); None when they are not exact
        numbers (computed coefficients without closed form, or a field beyond the degree
        limit: :attr:`exact_reason` says why).  Whether a check may use them — decimals
        may stand for a box of inputs — is decided by its reading."""
        found = self._exactness
        return found if isinstance(found, ExactValues) else None

    @property
    def exact_reason(self) -> str | None:
        """Why :meth:`exact_values` is None (None when it is not)."""
        found = self._exactness
        return found if isinstance(found, str) else None

    def exact_A(self) -> list[list[Any]]:
        """A exactly at face value: Fractions, or field elements for algebraic entries."""
        values = self.exact_values()
        assert values is not None, self.exact_reason
        return values.A

    def exact_b(self) -> list[Any]:
        values = self.exact_values()
        assert values is not None, self.exact_reason
        return values.b

    def enclosures(self, bits: int, decimals: DecimalsMode) -> tuple[list[list[Interval]], list[Interval]]:
        """Rigorous enclosures of A and b at ``bits`` bits (definitions §5)."""
        decimals = DecimalsMode(decimals)

        def enclosed(e: Any, place: str) -> Interval:
            try:
                result: Interval = e.enclosure(bits, decimals)
                return result
            except UserError as err:  # an entry that cannot be enclosed: name it and the file
                raise err.located(place if not err.place else None, self.info.source or None) from None

        A = [[enclosed(e, f"A[{i}][{j}]") for j, e in enumerate(row, start=1)] for i, row in enumerate(self.A, start=1)]
        b = [enclosed(e, f"b[{i}]") for i, e in enumerate(self.b, start=1)]
        return A, b
