"""A family's order conditions as exact polynomials in its parameters.

Every energy condition of definitions §3 (one per free tree, residual of the designated
rooting) and every classical order condition ``a(t) − 1/γ(t)`` (definitions §2) of a
method whose entries are polynomials (:mod:`rkcheck.numbers.parametric`) is itself a
polynomial.  Computed by the same algorithm as numeric checks, over the polynomial
context (:mod:`rkcheck.evaluation.polynomial`).

A condition *vanishes identically* when its polynomial is zero: it holds for every value
of the parameters.  The *generic* order is the largest order whose conditions all vanish
identically; the first conditions that do not are the ones that carve out exceptional
parameter values (where the order is higher).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

import numpy as np

from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.polynomial import PolynomialContext
from rkcheck.numbers.parametric import ParameterRing
from rkcheck.properties.orders import TreeWeights
from rkcheck.trees.listing import condition_listing
from rkcheck.trees.rooted import bracket_of_forest
from rkcheck.trees.table import TreeTable


@dataclass(frozen=True)
class PolynomialCondition:
    """One condition of a family: what it is (``kind`` ``energy`` or ``classical``), the
    tree (canonical level sequence and bracket), its order, and its residual as a
    polynomial over the family's ring."""

    kind: str
    level_sequence: tuple[int, ...]
    bracket: str
    order: int
    polynomial: Any

    @property
    def id(self) -> str:
        return ",".join(map(str, self.level_sequence))

    @property
    def vanishes(self) -> bool:
        """Zero for every value of the parameters."""
        return bool(self.polynomial.is_zero())

    @property
    def degree(self) -> int:
        """Total degree in the parameters (θ, the field generator, not counted)."""
        return parameter_degree(self.polynomial, self.polynomial.context().names())

    @property
    def label(self) -> str:
        return f"{self.kind} {self.id} {self.bracket}"


def parameter_degree(p: Any, names: Sequence[str]) -> int:
    """Total degree of ``p`` in the parameters (-1 for zero)."""
    from rkcheck.numbers.parametric import THETA

    skip = [i for i, n in enumerate(names) if n == THETA]
    degrees = [sum(int(e) for i, e in enumerate(m) if i not in skip) for m in p.monoms()]
    return max(degrees, default=-1)


def energy_conditions(ring: ParameterRing, A: Sequence[Sequence[Any]], b: Sequence[Any], order: int,
                      degree: int | None) -> list[PolynomialCondition]:
    """The energy conditions with 3 … order+1 vertices (free trees of maximum degree
    ≤ ``degree``), by vertices and canonical id."""
    listing = condition_listing(order, degree)
    sums = condition_sums(listing, PolynomialContext(ring, A, b), len(b))
    out = []
    for n, k, tree in listing.sorted_conditions():
        value = sums[n].value(k)
        if listing.flip(n, k) < 0:
            value = -value
        out.append(PolynomialCondition("energy", tree.level_sequence, tree.bracket, n - 1, value))
    return out


def classical_conditions(ring: ParameterRing, A: Sequence[Sequence[Any]], b: Sequence[Any],
                         order: int) -> list[PolynomialCondition]:
    """``a(t) − 1/γ(t)`` for every rooted tree with 1 … order vertices."""
    table = TreeTable(1)
    ctx = PolynomialContext(ring, A, b)
    weights = TreeWeights(ctx, len(b))
    out = []
    for p in range(1, order + 1):
        table.grow_to(p)
        ids = np.arange(table.first[p], table.first[p + 1])
        a = weights.extend(table, p)
        for t, value, g in zip(ids, a, table.gamma(ids)):
            residual = ring.reduce(value - ring.constant(Fraction(1, int(g))))
            forest = [table.level_sequence(c) for c in table.children(int(t))]
            out.append(PolynomialCondition("classical", table.level_sequence(int(t)), bracket_of_forest(forest),
                                           p, residual))
    return sorted(out, key=lambda c: (c.order, c.level_sequence))


def quadrature_conditions(ring: ParameterRing, A: Sequence[Sequence[Any]], b: Sequence[Any],
                          reach: int | None = None) -> list[PolynomialCondition]:
    """``Σ bᵢ cᵢ^(k−1) − 1/k`` for k = 1 … 2s (c = A·1): the rule (b, c) integrates
    polynomials of degree < k exactly.  ``reach``: for a kernel family's surrogate, exact
    for trees of up to ``reach`` vertices, k goes to ``reach`` only (the condition of k is
    the elementary weight of the bush with k vertices; past it the surrogate's rule is not
    the kernel's)."""
    s = len(b)
    row_sums = getattr(A, "row_sums", None)  # a kernel family's A, through its factors
    c = row_sums() if row_sums is not None else [sum(row[1:], row[0]) for row in A]
    out = []
    for k in range(1, (2 * s if reach is None else reach) + 1):
        total = ring.constant(0)
        for bi, ci in zip(b, c):
            total = total + bi * ci ** (k - 1)
        label = "Σ b_i" if k == 1 else f"Σ b_i c_i^{k - 1}"
        out.append(PolynomialCondition("quadrature", (k,), label, k, ring.reduce(total - ring.constant(Fraction(1, k)))))
    return out


def generic_order(conditions: Sequence[PolynomialCondition], checked: int) -> tuple[int, list[PolynomialCondition]]:
    """The largest order whose conditions all vanish identically (``checked`` when all
    do), and the conditions of the next order that do not (the exceptional values)."""
    for c in conditions:
        if not c.vanishes:
            first = [d for d in conditions if d.order == c.order and not d.vanishes]
            return c.order - 1, first
    return checked, []


@dataclass(frozen=True)
class FamilyConditions:
    """A family's conditions as polynomials (definitions §2–3): the energy conditions up
    to ``order`` for polynomial Hamiltonians of degree ≤ ``degree`` and, when asked for,
    the classical conditions up to ``classical_order``; the generic orders and the first
    conditions that do not vanish identically."""

    family: Any
    degree: int | None
    order: int
    energy: list[PolynomialCondition]
    classical_order_checked: int | None = None
    classical: list[PolynomialCondition] | None = None
    quadrature: list[PolynomialCondition] | None = None

    def __repr__(self) -> str:
        return (f"<FamilyConditions of {self.family.name!r}: {len(self.energy)} energy conditions to order "
                f"{self.order}, generic energy order {self.energy_order}>")

    @property
    def energy_order(self) -> int:
        """The energy order for generic parameter values."""
        return generic_order(self.energy, self.order)[0]

    @property
    def exceptional(self) -> list[PolynomialCondition]:
        """The first energy conditions that do not vanish identically: their zeros are the
        parameter values where the energy order is higher."""
        return generic_order(self.energy, self.order)[1]

    @property
    def energy_order_all(self) -> bool:
        """Every order, for every parameter value: degree 1 has no condition, and every
        method preserves linear energy (:mod:`rkcheck.properties.linear`)."""
        return self.degree == 1

    @property
    def energy_order_everywhere(self) -> bool:
        """Whether the generic energy order is that of every parameter value: a condition
        of the next order is a nonzero constant, which no value makes vanish (or there is
        no condition at all)."""
        return self.energy_order_all or any(c.degree == 0 for c in self.exceptional)

    @property
    def fails_everywhere(self) -> Any:
        """The first energy condition that is a nonzero constant — it fails for every
        parameter value, so no member reaches its order — or None."""
        return next((c for c in self.exceptional if c.degree == 0 and not c.vanishes), None)

    @property
    def classical_order(self) -> int | None:
        """The classical order for generic parameter values (None: not computed)."""
        if self.classical is None or self.classical_order_checked is None:
            return None
        return generic_order(self.classical, self.classical_order_checked)[0]

    @property
    def quadrature_order(self) -> int | None:
        """The order of the quadrature rule (b, A·1) for generic parameter values (at least
        this when it is :attr:`quadrature_checked` for a family of kernels: their rules
        have no largest order)."""
        if self.quadrature is None:
            return None
        return generic_order(self.quadrature, len(self.quadrature))[0]

    @property
    def quadrature_checked(self) -> int | None:
        """The largest k of the quadrature conditions (2s, or for a family of kernels the
        largest tree its surrogate reads exactly)."""
        return None if self.quadrature is None else len(self.quadrature)


def family_conditions(family: Any, degree: int | None, order: int,
                      classical_order: int | None = None) -> FamilyConditions:
    """The conditions of a :class:`~rkcheck.methods.parametric.Family`."""
    family = family.covering(max(order + 1, classical_order or 0))
    energy = energy_conditions(family.ring, family.A, family.b, order, degree)
    classical = None
    if classical_order is not None:
        classical = classical_conditions(family.ring, family.A, family.b, classical_order)
    quadrature = quadrature_conditions(family.ring, family.A, family.b, family.reach)
    return FamilyConditions(family, degree, order, energy, classical_order, classical, quadrature)
