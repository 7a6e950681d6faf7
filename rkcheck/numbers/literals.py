"""The entries of a tableau as functions of the decimal literals they are written with:
their derivatives along each literal, enclosed over the literals' whole box
(definitions §5.2).

A rounded decimal literal stands for an interval of numbers.  When one literal feeds
several entries — a constant ``a = "0.6666669"`` used in ``A`` and in
``b = 1 − 1/(2a)`` — the entries do not vary independently: the tableaux the file allows
are the image ``x(Λ)`` of the box ``Λ`` of its literals, much thinner than the box of
the entries' own enclosures.  Along the literals the mean value form reads

    R(x(λ)) − R(x(λ̃)) = Σ_l  Σ_e ∂R/∂x_e(x(ξ)) · ∂x_e/∂λ_l(ξ) · (λ_l − λ̃_l)

for some ``ξ`` on the segment from the face values ``λ̃``; ``x(ξ)`` lies in the entries'
box, where :mod:`~rkcheck.evaluation.slopes` encloses ``∂R/∂x_e``, and this module
encloses ``∂x_e/∂λ_l`` over ``Λ``: forward-mode differentiation of each entry's
expression in exact interval arithmetic, through the constants it names.

A literal is identified by where it is written: a constant's literal is shared by every
entry that names the constant (directly or through other constants), an entry's own
literal is its own — two entries written alike are two numbers, as definitions §5 reads
them, even where a reader built them from one parse — and a kernel's literal is one
number in every entry of its surrogate tableau (entries that say they share their nodes,
``Entry.shares_literals``).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Mapping, Sequence

from rkcheck.numbers import expressions as xp
from rkcheck.numbers.grammar import Binary, Call, Expr, Name, Num, Power, Unary
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode

#: a literal: its position among the box literals met, in the order they are met
Literal = int

_ZERO = Interval.point(0)


@dataclass(frozen=True)
class _Slope:
    """A value over the box of literals and its derivative along each literal it depends
    on (by the literal's number)."""

    value: Interval
    grad: Mapping[Literal, Interval]


class Unbounded(Exception):
    """A derivative that cannot be bounded on the box (a square root whose argument
    reaches 0)."""


@dataclass(frozen=True)
class LiteralBox:
    """The Jacobian of some entries along the box literals they are written with, some
    literal occurring more than once among them: ``rows[e]`` maps a literal's number
    ``l`` to an enclosure of ``∂x_e/∂λ_l`` over the literals' box (literals the entry
    does not use are absent: 0), ``radii[l]`` is ``max |λ_l − λ̃_l|`` over the literal's
    interval, ``λ̃_l`` its centre (:meth:`~rkcheck.numbers.grammar.Num.centre`)."""

    radii: tuple[Fraction, ...]
    rows: tuple[Mapping[Literal, Interval], ...]


def literal_box(entries: Sequence[Any], bits: int, decimals: DecimalsMode) -> LiteralBox | None:
    """The Jacobian of ``entries`` along their box literals under the decimals mode,
    square roots enclosed to ``bits`` bits; None when no literal occurs twice among them
    (their own box is then the literals' image, to first order), when an entry has no
    expression (a family's computed coefficient) or a derivative is unbounded on the
    box."""
    mode = DecimalsMode(decimals)
    if any(getattr(entry, "node", None) is None for entry in entries) or not _some_literal_twice(entries, mode):
        return None
    literals = _Literals(mode)
    constants: dict[int, dict[str, _Slope]] = {}
    slopes = []
    try:
        for k, entry in enumerate(entries):
            table = entry.constants
            if id(table) not in constants:
                constants[id(table)] = _constant_slopes(table, bits, literals)
            slopes.append(_slope(entry.node, _owner(entry, k), bits, constants[id(table)], literals))
    except Unbounded:
        return None
    return LiteralBox(tuple(literals.radii), tuple(s.grad for s in slopes))


def _owner(entry: Any, k: int) -> Any:
    """Where the entry's own literals are written: the entry itself (the ``k``-th), or
    the nodes the entries that share their literals hold."""
    return "shared" if getattr(entry, "shares_literals", False) else k


def _some_literal_twice(entries: Sequence[Any], mode: DecimalsMode) -> bool:
    """Whether a box literal occurs more than once among the entries' expressions (through
    the constants they name too): counted on the expressions, before any arithmetic."""
    tables: dict[int, dict[str, dict[Any, int]]] = {}
    seen: dict[Any, int] = {}
    for k, entry in enumerate(entries):
        table = entry.constants
        if id(table) not in tables:
            tables[id(table)] = _constant_uses(table, mode)
        for key, count in _uses(entry.node, _owner(entry, k), mode, tables[id(table)]).items():
            seen[key] = seen.get(key, 0) + count
            if seen[key] > 1:
                return True
    return False


def _constant_uses(table: Any, mode: DecimalsMode) -> dict[str, dict[Any, int]]:
    out: dict[str, dict[Any, int]] = {}
    for name in table.order:
        out[name] = _uses(table.definitions[name], ("constants", id(table)), mode, out)
    return out


def _uses(node: Expr, owner: Any, mode: DecimalsMode, constants: Mapping[str, Mapping[Any, int]]) -> dict[Any, int]:
    """How often each box literal occurs in ``node`` (its own written in ``owner``)."""
    counts: dict[Any, int] = {}
    for n in xp.walk(node):
        used: Mapping[Any, int] = {}
        if isinstance(n, Num) and n.interval(mode) is not None:
            used = {(owner, id(n)): 1}
        elif isinstance(n, Name) and n.name in constants:
            used = constants[n.name]
        for key, c in used.items():
            counts[key] = counts.get(key, 0) + c
    return counts


class _Literals:
    """The box literals met so far, numbered by their nodes (kept alive here, so that
    their ids stay theirs), with their radii about their face values."""

    def __init__(self, mode: DecimalsMode):
        self.mode = mode
        self.index: dict[tuple[Any, int], Literal] = {}
        self.nodes: list[Num] = []
        self.radii: list[Fraction] = []

    def slope(self, n: Num, owner: Any) -> "_Slope":
        """The literal ``n`` written in ``owner`` (a constants table, an entry, or the
        nodes entries share)."""
        box = n.interval(self.mode)
        if box is None:
            return _Slope(Interval.point(n.value), {})
        lit = self.index.get((owner, id(n)))
        if lit is None:
            lit = self.index[owner, id(n)] = len(self.nodes)
            self.nodes.append(n)
            self.radii.append((box[1] - box[0]) / 2)  # about its centre (Num.centre), as the box's centre takes it
        return _Slope(Interval(*box), {lit: Interval.point(1)})


def _constant_slopes(table: Any, bits: int, literals: _Literals) -> dict[str, _Slope]:
    """Every constant of ``table`` as a slope, each after those it names."""
    out: dict[str, _Slope] = {}
    for name in table.order:
        out[name] = _slope(table.definitions[name], ("constants", id(table)), bits, out, literals)
    return out


def _slope(node: Expr, owner: Any, bits: int, constants: Mapping[str, _Slope], literals: _Literals) -> _Slope:
    """``node``'s value and derivatives over the literals' box, its own literals
    written in ``owner``."""

    def combine(n: Expr, vals: list[_Slope]) -> _Slope:
        if isinstance(n, Num):
            return literals.slope(n, owner)
        if isinstance(n, Name):
            return constants[n.name]
        if isinstance(n, Unary):
            v = vals[0]
            return _Slope(-v.value, {k: -d for k, d in v.grad.items()})
        if isinstance(n, Call):
            return _call(n, vals, bits)
        if isinstance(n, Power):
            return _power(vals[0], vals[1])
        assert isinstance(n, Binary)
        return _binary(n.op, vals[0], vals[1])

    result: _Slope = xp.fold(node, combine)
    return result


def _combination(p: Interval, du: Mapping[Literal, Interval], q: Interval,
                 dv: Mapping[Literal, Interval]) -> dict[Literal, Interval]:
    """``p·du + q·dv`` along every literal of either."""
    out: dict[Literal, Interval] = {}
    for k in du.keys() | dv.keys():
        out[k] = p * du.get(k, _ZERO) + q * dv.get(k, _ZERO)
    return out


def _binary(op: str, u: _Slope, v: _Slope) -> _Slope:
    one = Interval.point(1)
    if op == "+":
        return _Slope(u.value + v.value, _combination(one, u.grad, one, v.grad))
    if op == "-":
        return _Slope(u.value - v.value, _combination(one, u.grad, -one, v.grad))
    if op == "*":
        return _Slope(u.value * v.value, _combination(v.value, u.grad, u.value, v.grad))
    # d(u/v) = (du − (u/v)·dv)/v; the entry's enclosure has excluded 0 from v already
    q, inverse = u.value / v.value, v.value.reciprocal()
    return _Slope(q, _combination(inverse, u.grad, -(q * inverse), v.grad))


def _power(base: _Slope, exponent: _Slope) -> _Slope:
    """``base^k`` for the exact integer ``k`` that the entry's enclosure has checked."""
    k = int(exponent.value.lo)
    value = base.value.power(k)
    if k == 0 or not base.grad:
        return _Slope(value, {})
    factor = Interval.point(k) * base.value.power(k - 1)
    return _Slope(value, {lit: factor * d for lit, d in base.grad.items()})


def _call(n: Call, vals: list[_Slope], bits: int) -> _Slope:
    if n.func == "root":  # its polynomial's coefficients are exact: a number, no literal
        return _Slope(xp.root_enclosure(n, vals[0].value.lo, bits), {})
    v = vals[0]
    value = v.value.sqrt(bits)
    if not v.grad:
        return _Slope(value, {})
    if value.lo <= 0:
        raise Unbounded
    half_inverse = (Interval.point(2) * value).reciprocal()
    return _Slope(value, {lit: half_inverse * d for lit, d in v.grad.items()})


__all__ = ["Literal", "LiteralBox", "literal_box"]
