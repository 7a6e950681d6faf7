"""The number model: what a tableau entry *is* (definitions §5).

An :class:`Entry` keeps exactly what the file said (its text and parsed expression) and
knows three facts about it:

* its exact rational value at face value, when it has one (integers, fractions,
  decimal literals, and roots of rational squares);
* whether it involves a square root of a non-square (then it is algebraic and is
  evaluated by outward-rounded interval arithmetic at the working precision);
* whether it contains a *rounded* decimal literal (definitions §5: "some number within half a
  unit of its last digit"; see :data:`rkcheck.numbers.grammar.ROUNDED_MIN_DIGITS`).

Named constants (the ``[constants]`` table) are shared by all entries of one tableau
through a :class:`Constants` table, so ``r3 = "sqrt(3)"`` is evaluated once per
precision, however often it is used.
"""

from __future__ import annotations

import copyreg
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Mapping, Protocol

from rkcheck.errors import UserError
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode


class Constants:
    """The ``[constants]`` table of one tableau: name -> expression, resolved lazily.

    Constants may use other constants in any order; unknown names and cycles are
    reported at construction, naming the constant (``constants.r5: unknown name 'q'``).
    """

    def __init__(self, definitions: Mapping[str, ex.Expr] | None = None):
        self.definitions: dict[str, ex.Expr] = dict(definitions or {})
        self._order = self._topological_order()
        self._exact: dict[str, Fraction | None] | None = None
        self._enclosures: dict[tuple[int, DecimalsMode, bool], dict[str, Interval]] = {}
        self._rounded: dict[str, int | None] = {}  # fewest digits of its rounded decimals, through others too
        self._decimal: dict[str, bool] = {}
        self._root_decimal: dict[str, ex.Num | None] = {}  # a decimal in a root's polynomial, through others too
        for name in self._order:
            node = self.definitions[name]
            used = {n.name for n in xp.names(node)}
            self._root_decimal[name] = self.root_decimal(node)  # the constants it uses came before
            self._decimal[name] = any(lit.is_decimal for lit in xp.literals(node)) or any(
                self._decimal[u] for u in used
            )
            digits = [lit.digits for lit in xp.literals(node) if lit.digits is not None and lit.is_rounded_decimal]
            digits += [d for u in used if (d := self._rounded[u]) is not None]
            self._rounded[name] = min(digits) if digits else None

    def _topological_order(self) -> list[str]:
        """The constants in an order where each comes after those it uses (depth first,
        with an explicit stack: a chain of thousands of constants needs no recursion)."""
        order: list[str] = []
        state: dict[str, int] = {}  # 1 = on the current path, 2 = done
        for root in self.definitions:
            if state.get(root) == 2:
                continue
            path: list[str] = [root]
            state[root] = 1
            pending = [iter(xp.names(self.definitions[root]))]
            while pending:
                used = next(pending[-1], None)
                if used is None:
                    done = path.pop()
                    pending.pop()
                    state[done] = 2
                    order.append(done)
                    continue
                if used.name not in self.definitions:
                    raise UserError(f"unknown name {used.name!r} at column {used.column}", f"constants.{path[-1]}")
                if state.get(used.name) == 2:
                    continue
                if state.get(used.name) == 1:
                    cycle = " -> ".join(path[path.index(used.name):] + [used.name])
                    raise UserError(f"constants refer to each other in a cycle: {cycle}", f"constants.{path[0]}")
                state[used.name] = 1
                path.append(used.name)
                pending.append(iter(xp.names(self.definitions[used.name])))
        return order

    @property
    def order(self) -> list[str]:
        """The constants' names, each after those it uses."""
        return list(self._order)

    def check_names(self, node: ex.Expr) -> None:
        """Raise for a name in ``node`` that is not a constant of this table."""
        for used in xp.names(node):
            if used.name not in self.definitions:
                known = ", ".join(sorted(self.definitions)) or "none defined"
                raise UserError(f"unknown constant {used.name!r} at column {used.column} (constants: {known})")

    def exact_values(self) -> dict[str, Fraction | None]:
        if self._exact is None:
            values: dict[str, Fraction | None] = {}
            for name in self._order:
                try:
                    values[name] = xp.evaluate_exact(self.definitions[name], values)
                except UserError as err:
                    raise err.located(f"constants.{name}") from None
            self._exact = values
        return self._exact

    def enclosures(self, bits: int, decimals: DecimalsMode, centre: bool = False) -> dict[str, Interval]:
        """Every constant enclosed under the decimals mode (``centre``: at the centre of
        its literals' box, :func:`~rkcheck.numbers.expressions.enclose`)."""
        key = (bits, decimals, centre)
        if key not in self._enclosures:
            values: dict[str, Interval] = {}
            for name in self._order:
                try:
                    values[name] = xp.enclose(self.definitions[name], bits, decimals, values, centre)
                except UserError as err:
                    raise err.located(f"constants.{name}") from None
            self._enclosures[key] = values
        return self._enclosures[key]

    def is_rounded(self, name: str) -> bool:
        return self._rounded[name] is not None

    def rounded_digits(self, name: str) -> int | None:
        """The fewest significant digits among the rounded decimals ``name`` depends on,
        directly or through other constants (None: it depends on none)."""
        return self._rounded[name]

    def root_decimal(self, node: ex.Expr) -> ex.Num | None:
        """A decimal literal inside a ``root(p, k)`` polynomial of ``node``, itself or
        through these constants (None: there is none)."""
        return next(iter(xp.root_decimals(node)), None) or next(
            (lit for u in xp.names(node) if u.name in self.definitions and (lit := self._root_decimal[u.name]) is not None),
            None)

    def has_decimal(self, name: str) -> bool:
        return self._decimal[name]

    def uses_decimal(self, node: ex.Expr) -> bool:
        """Whether the expression ``node`` has a decimal literal, itself or through one of
        these constants."""
        return any(lit.is_decimal for lit in xp.literals(node)) or any(
            self.has_decimal(u.name) for u in xp.names(node) if u.name in self.definitions)


class TableauEntry(Protocol):
    """What a tableau and its checks read of a coefficient: an :class:`Entry` as written,
    or a coefficient computed by a family
    (:class:`~rkcheck.methods.families.ComputedEntry`, which has no expression ``node``)."""

    @property
    def text(self) -> str: ...
    @property
    def exact(self) -> Fraction | None: ...
    @property
    def uses_sqrt(self) -> bool: ...
    @property
    def rounded_digits(self) -> int | None: ...
    @property
    def bare_number(self) -> bool: ...
    @property
    def is_rational(self) -> bool: ...
    @property
    def is_rounded(self) -> bool: ...
    def is_box(self, decimals: DecimalsMode) -> bool: ...
    def enclosure(self, bits: int, decimals: DecimalsMode = ...) -> Interval: ...
    def is_zero(self) -> bool: ...


@dataclass(frozen=True)
class Entry:
    """One coefficient of a tableau, as written, with its exact value when it has one."""

    text: str
    node: ex.Expr = field(repr=False, compare=False)
    constants: Constants = field(repr=False, compare=False)
    exact: Fraction | None = field(repr=False)  # its text says it (repr of a long rational raises past 4 300 digits)
    uses_sqrt: bool
    rounded_digits: int | None  # fewest significant digits among its rounded decimal literals
    bare_number: bool = False  # written as a bare TOML/JSON number, not a string
    has_decimal: bool = False  # a nonzero decimal literal, itself or through a constant (float64 mode)
    # its literal nodes are shared with the other entries that say so, each one number in
    # all of them (a kernel's, at a surrogate's nodes); else its own, even where a reader
    # built entries of equal text from one parse
    shares_literals: bool = field(default=False, compare=False)
    # a decimal literal inside a root(p, k) polynomial (read exactly there), if any
    root_decimal: Any = field(default=None, compare=False, repr=False)

    @staticmethod
    def parse(text: str, constants: Constants | None = None, bare_number: bool = False) -> "Entry":
        """Parse an entry; raises :class:`UserError` with the column of the problem."""
        return Entry.from_node(text, ex.parse(text), constants, bare_number)

    @staticmethod
    def from_node(text: str, node: ex.Expr, constants: Constants | None = None, bare_number: bool = False,
                  shares_literals: bool = False) -> "Entry":
        """The entry of a parsed ``node`` whose text is ``text``; ``shares_literals``: its
        nodes are another expression's (a kernel's at a surrogate's nodes), whose
        literals are one number in every entry that holds them."""
        constants = constants or Constants()
        constants.check_names(node)
        used = {n.name for n in xp.names(node)}
        rounded = [lit.digits for lit in xp.literals(node) if lit.digits is not None and lit.is_rounded_decimal]
        # a constant counts with the fewest digits it depends on (s = "1 - r", r a decimal)
        rounded += [d for u in used if (d := constants.rounded_digits(u)) is not None]
        rounded_digits = min(rounded) if rounded else None
        exact = xp.evaluate_exact(node, constants.exact_values())
        # sqrt of a non-square is the only source of irrationals: an entry without an
        # exact value is algebraic; sqrt(9/4) stays rational.
        return Entry(text, node, constants, exact, exact is None, rounded_digits, bare_number,
                     constants.uses_decimal(node), shares_literals, constants.root_decimal(node))

    @staticmethod
    def of(value: Fraction | int) -> "Entry":
        """An exact entry from a rational number (used by generators and tests)."""
        value = Fraction(value)
        if max(value.numerator.bit_length(), value.denominator.bit_length()) < 10_000:
            return Entry.parse(str(value))
        # str() refuses integers of more than 4300 digits, gmpy2 writes any; the entry's
        # own length limit then applies, as to the text of a file
        import gmpy2

        n, d = gmpy2.mpz(value.numerator), gmpy2.mpz(value.denominator)
        return Entry.parse(f"{n}" if d == 1 else f"{n}/{d}")

    @property
    def is_rational(self) -> bool:
        return self.exact is not None

    @property
    def is_rounded(self) -> bool:
        return self.rounded_digits is not None

    def is_box(self, decimals: DecimalsMode) -> bool:
        """Whether the entry stands for an interval of numbers, not one number, under the
        decimals mode (definitions §5.2; :meth:`rkcheck.numbers.grammar.Num.interval`)."""
        decimals = DecimalsMode(decimals)
        if self.root_decimal is not None and self.root_decimal.interval(decimals) is not None:
            # a root's polynomial has exact numbers: a decimal there that stands for an
            # interval would be read at face value, and a verdict could claim too much
            raise UserError(f"root(p, k): the polynomial's numbers are exact, but {self.root_decimal.text} stands "
                            f"for an interval (--decimals {decimals.value}); write it as a fraction, or check with "
                            "--decimals exact")
        if decimals is DecimalsMode.FLOAT64:
            return self.has_decimal
        if decimals.rounds:
            return self.is_rounded
        return False

    def enclosure(self, bits: int, decimals: DecimalsMode = DecimalsMode.EXACT) -> Interval:
        """A rigorous enclosure at ``bits`` bits under the decimals mode of definitions §5;
        by default the entry at face value, like :meth:`Tableau.exact_values` (a check
        reads entries through its own :class:`~rkcheck.numbers.reading.Reading`)."""
        decimals = DecimalsMode(decimals)
        if self.exact is not None and not self.is_box(decimals):
            return Interval.point(self.exact)
        return xp.enclose(self.node, bits, decimals, self.constants.enclosures(bits, decimals))

    def centre(self, bits: int, decimals: DecimalsMode) -> Interval:
        """The entry at the centre of its box of inputs — each literal at the middle of
        the numbers it stands for (:meth:`~rkcheck.numbers.grammar.Num.centre`) — at
        ``bits`` bits: its face value unless a literal is a double's rounding interval."""
        decimals = DecimalsMode(decimals)
        if not self.is_box(decimals):
            return self.enclosure(bits)
        return xp.enclose(self.node, bits, decimals, self.constants.enclosures(bits, decimals, True), True)

    def is_zero(self) -> bool:
        """Certainly zero at face value (used for the explicit/implicit structure)."""
        return self.exact == 0


# ------------------------------------------------------------------ pickling

# An entry's expression can be a tree thousands of levels deep (a sum of a thousand
# square roots leans left); pickle walks objects recursively and fails on it, and a scan
# worker sends its results by pickle.  Each tree is therefore pickled as its nodes in
# post-order, flat, and rebuilt with an explicit stack.


def _record(node: ex.Expr) -> tuple[Any, ...]:
    if isinstance(node, ex.Num):
        return ("N", node.value, node.text, node.digits, node.last_digit_exponent)
    if isinstance(node, ex.Name):
        return ("V", node.name, node.column)
    if isinstance(node, ex.Unary):
        return ("U", node.op)
    if isinstance(node, ex.Binary):
        return ("B", node.op, node.column)
    if isinstance(node, ex.Power):
        return ("P", node.column)
    assert isinstance(node, ex.Call)
    return ("C", node.func, len(node.args), node.column)


def _rebuild(flat: list[tuple[Any, ...]]) -> ex.Expr:
    stack: list[ex.Expr] = []
    for kind, *f in flat:
        if kind == "N":
            stack.append(ex.Num(*f))
        elif kind == "V":
            stack.append(ex.Name(*f))
        elif kind == "U":
            stack.append(ex.Unary(f[0], stack.pop()))
        elif kind == "B":
            right, left = stack.pop(), stack.pop()
            stack.append(ex.Binary(f[0], left, right, f[1]))
        elif kind == "P":
            exponent, base = stack.pop(), stack.pop()
            stack.append(ex.Power(base, exponent, f[0]))
        else:
            func, n, column = f
            args = tuple(stack[len(stack) - n:])
            del stack[len(stack) - n:]
            stack.append(ex.Call(func, args, column))
    return stack[0]


def _reduce_expr(node: Any) -> tuple[Any, tuple[list[tuple[Any, ...]]]]:
    flat: list[tuple[Any, ...]] = []
    xp.fold(node, lambda n, _: flat.append(_record(n)), xp.children)
    return _rebuild, (flat,)


for _cls in (ex.Num, ex.Name, ex.Unary, ex.Binary, ex.Power, ex.Call):
    copyreg.pickle(_cls, _reduce_expr)
