"""The energy order of a family over a grid of parameter values (``rkcheck sweep``).

The conditions are computed once as exact polynomials
(:mod:`rkcheck.energy.family_conditions`) and evaluated at every grid point exactly:
grid points are rationals (``"beta=-1:1:41"``: 41 equally spaced rationals from −1 to 1,
ends included), so a condition vanishes at a point exactly when its value is zero —
over Q(θ) after reduction by θ's minimal polynomial.  No float takes part.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

from rkcheck.errors import UserError
from rkcheck.numbers import expressions as xp
from rkcheck.numbers.formatting import exact_string

#: At most this many grid points in one sweep (each costs one exact evaluation of every
#: condition polynomial).
MAX_SWEEP_POINTS = 100_000
#: At most this many values along one parameter.
MAX_GRID_VALUES = 10_001


def _rational(text: str, place: str) -> Fraction:
    """A grid value: a rational number in the entries' grammar (``-1``, ``3/4``, ``0.25``,
    ``1e-3``, ``2^-4``) read at face value — a decimal is the rational it writes."""
    try:
        value = xp.rational_text_value(text)
    except UserError as err:
        raise UserError(f"{text.strip()!r}: {err.message}", place) from None
    if value is None:
        raise UserError(f"expected a rational number such as -1, 3/4, 0.25 or 1e-3, got {text!r}", place)
    return value


def parse_grid(spec: str) -> tuple[str, list[Fraction]]:
    """``"name=lo:hi:n"`` → the n equally spaced rationals from lo to hi (n ≥ 2), or
    ``"name=value"`` → one value."""
    name, sep, rest = spec.partition("=")
    name = name.strip()
    if not sep or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
        raise UserError(f"expected name=lo:hi:n or name=value, got {spec!r}", "--grid")
    parts = rest.split(":")
    if len(parts) == 1:
        return name, [_rational(parts[0], "--grid")]
    if len(parts) != 3:
        raise UserError(f"expected name=lo:hi:n (three fields), got {spec!r}", "--grid")
    lo, hi = _rational(parts[0], "--grid"), _rational(parts[1], "--grid")
    try:
        n = int(parts[2])
    except ValueError:
        raise UserError(f"the number of values must be a whole number, got {parts[2]!r}", "--grid") from None
    if not 2 <= n <= MAX_GRID_VALUES:
        raise UserError(f"expected 2 to {MAX_GRID_VALUES} values (MAX_GRID_VALUES), got {n} in {spec!r}", "--grid")
    if hi <= lo:
        raise UserError(f"the grid must go upwards (lo < hi), got {spec!r}", "--grid")
    step = (hi - lo) / (n - 1)
    return name, [lo + k * step for k in range(n)]


@dataclass
class Sweep:
    """The energy order (capped at ``order``) at every point of the grid: ``axes`` the
    parameter names with their values, ``orders[k]`` the order at the k-th point of the
    product of the axes (the last axis fastest)."""

    family: Any
    degree: int | None
    order: int
    generic: int
    axes: list[tuple[str, list[Fraction]]]
    orders: list[int]

    def __repr__(self) -> str:
        # each axis by its ends and count: a grid's values may be long rationals (repr of
        # one past 4 300 digits raises) and many
        axes = ", ".join(f"{n} = {exact_string(v[0])}…{exact_string(v[-1])} ({len(v)})" if v else f"{n} = ()"
                         for n, v in self.axes)
        return f"<Sweep of {self.family!r}: {axes}; degree {self.degree}, order ≤ {self.order}, generic {self.generic}>"

    def points(self) -> list[dict[str, Fraction]]:
        names = [n for n, _ in self.axes]
        return [dict(zip(names, values)) for values in itertools.product(*(v for _, v in self.axes))]


def sweep(family: Any, grids: Sequence[str], degree: int | None, order: int) -> Sweep:
    """The energy order of ``family`` at each point of the grids (every parameter needs a
    grid or a single value)."""
    from rkcheck.energy.family_conditions import energy_conditions, generic_order

    axes = [parse_grid(g) for g in grids]
    names = [n for n, _ in axes]
    for n in names:
        if n not in family.parameters:
            raise UserError(f"unknown parameter {n!r} (the parameters are {', '.join(family.parameters)})", "--grid")
    if len(set(names)) != len(names):
        raise UserError("a parameter has two grids", "--grid")
    missing = [p for p in family.parameters if p not in names]
    if missing:
        raise UserError(f"no grid or value for the parameter {missing[0]} (--grid {missing[0]}=VALUE fixes it)",
                        "--grid")
    total = 1
    for _, v in axes:
        total *= len(v)
    if total > MAX_SWEEP_POINTS:
        raise UserError(f"{total} grid points exceed the limit MAX_SWEEP_POINTS = {MAX_SWEEP_POINTS}", "--grid")
    family = family.covering(order + 1)  # a kernel family's surrogate, for trees up to order + 1 vertices
    conds = energy_conditions(family.ring, family.A, family.b, order, degree)
    generic = generic_order(conds, order)[0]
    out = Sweep(family, degree, order, generic, axes, [])
    live = [c for c in conds if not c.vanishes]
    for point in out.points():
        out.orders.append(_order_at(family.ring, live, point, order))
    return out


def _order_at(ring: Any, live: list[Any], point: dict[str, Fraction], order: int) -> int:
    """The energy order at one point: one less than the order of the first condition
    that does not vanish there (conditions come by order)."""
    from flint import fmpq

    values = {n: fmpq(v.numerator, v.denominator) for n, v in point.items()}
    for c in live:
        if ring.field is None:
            if c.polynomial(*(values[n] for n in ring.variables)) != 0:
                return int(c.order) - 1
        elif not ring.is_zero(c.polynomial.subs(values)):
            return int(c.order) - 1
    return order
