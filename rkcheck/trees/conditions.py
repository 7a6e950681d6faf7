"""The energy conditions of definitions §3 (seed, Theorem 2 restricted to degree ≤ m).

For an order ``N`` and a degree bound ``m`` (None = all Hamiltonians) the conditions
are the non-superfluous free trees ``t̄`` with ``3 <= |t̄| <= N+1`` and maximum vertex
degree ``<= m``, one per tree, each

    R(t̄) = Σ_{u ∈ π⁻¹(t̄)} (−1)^κ(t,u) / σ(u) · a(B₋(u))

with ``t`` the rooting at the canonical centre.  A :class:`ConditionTable` holds the
conditions as pure combinatorics (no numbers): each term is a sign, ``σ(u)`` and the
ids of the trees of ``B₋(u)``, so that every backend evaluates them from one shared
table of elementary weights ``a(t)``.  Tables are built once per ``(N, m)`` and
process (:func:`condition_table`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache
from math import lcm
from typing import NamedTuple

from rkcheck.trees.free import FreeTree, FreeTreeGenerator, table_for
from rkcheck.trees.rooted import (
    RootedTreeTable,
    bracket_of_forest,
    level_sequence_of_forest,
    sigma_of_forest,
)


class Term(NamedTuple):
    """One rooting ``u`` of a condition: ``sign/σ(u) · Π_{t ∈ B₋(u)} a(t)``.

    A NamedTuple rather than a frozen dataclass: a million of them are built at order 16
    and tuple construction is several times cheaper."""

    sign: int
    sigma: int
    branches: tuple[int, ...]  # table ids of B₋(u)


@dataclass(frozen=True)
class EnergyCondition:
    """The condition of one non-superfluous free tree (terms: designated rooting first)."""

    index: int
    vertices: int
    max_degree: int
    terms: tuple[Term, ...]
    table: RootedTreeTable

    @property
    def order(self) -> int:
        """The energy order this condition belongs to: ``|t̄| - 1``."""
        return self.vertices - 1

    @cached_property
    def level_sequence(self) -> tuple[int, ...]:
        """Canonical id (definitions §3): level sequence of the rooting at the canonical centre."""
        return self.term_level_sequence(self.terms[0])

    @property
    def id(self) -> str:
        return ",".join(map(str, self.level_sequence))

    @property
    def bracket(self) -> str:
        return self.term_bracket(self.terms[0])

    @cached_property
    def denominator(self) -> int:
        """lcm of the σ(u): ``R · denominator`` has integer coefficients."""
        return lcm(*(t.sigma for t in self.terms))

    def term_level_sequence(self, term: Term) -> tuple[int, ...]:
        return level_sequence_of_forest([self.table.level_sequence(b) for b in term.branches])

    def term_bracket(self, term: Term) -> str:
        return bracket_of_forest([self.table.level_sequence(b) for b in term.branches])


def condition_from_free_tree(index: int, tree: FreeTree, table: RootedTreeTable) -> EnergyCondition:
    terms = tuple(
        Term(-1 if parity else 1, sigma_of_forest(branches, table), branches)
        for branches, parity in tree.rootings
    )
    return EnergyCondition(index, tree.vertices, tree.max_degree, terms, table)


class ConditionTable:
    """All energy conditions up to order ``N`` for degree ``<= m``, in a fixed order:
    by number of vertices, then in generation order (deterministic)."""

    def __init__(self, order: int, degree: int | None):
        if order < 1:
            raise ValueError("order must be at least 1")
        if degree is not None and degree < 1:
            raise ValueError("degree must be at least 1")
        self.order = order
        self.degree = degree
        self.trees = table_for(order, degree)
        self.generator = FreeTreeGenerator(self.trees, degree)
        conditions: list[EnergyCondition] = []
        for n in range(3, order + 2):
            if degree is not None and degree < 2:
                break  # m = 1: every tree with 3 vertices has a vertex of degree 2
            for tree in self.generator.free_trees(n):
                conditions.append(condition_from_free_tree(len(conditions), tree, self.trees))
        self.conditions = conditions

    def __len__(self) -> int:
        return len(self.conditions)

    def counts_by_order(self) -> dict[int, int]:
        counts = {k: 0 for k in range(2, self.order + 1)}
        for c in self.conditions:
            counts[c.order] += 1
        return counts

    def condition_for_level_sequence(self, seq: tuple[int, ...]) -> EnergyCondition:
        """The condition of the free tree underlying ``seq`` (any rooting of it)."""
        return condition_from_free_tree(-1, self.generator.from_level_sequence(seq), self.trees)

    @cached_property
    def term_arrays(self):
        """Arrays over all terms of all conditions for the vectorised backends, built once
        per table.  Terms are sorted by decreasing number of factors, so that factor k is
        needed exactly by the first ``needs[k]`` rows.  Keys: ``owner`` (condition index),
        ``coef`` (sign/σ as float), ``mult`` (±lcm/σ, exact ints), ``branches`` (ids padded
        with -1), ``needs``, ``counts`` (terms per condition), ``lcm`` and ``size``
        (lcm of the σ and vertices − 1, per condition)."""
        import numpy as np

        owner: list[int] = []
        rows: list[tuple[int, ...]] = []
        signs: list[int] = []
        sigmas: list[int] = []
        lcms: list[int] = []
        for i, c in enumerate(self.conditions):
            lcms.append(c.denominator)
            for t in c.terms:
                owner.append(i)
                rows.append(t.branches)
                signs.append(t.sign)
                sigmas.append(t.sigma)
        arity = np.fromiter((len(r) for r in rows), dtype=np.int64, count=len(rows))
        order = np.argsort(-arity, kind="stable")  # within an arity, condition order is kept
        width = int(arity.max()) if len(rows) else 0
        pad = (-1,) * width
        branches = np.array([r + pad[len(r):] for r in rows], dtype=np.int64).reshape(len(rows), width)[order]
        owner_a = np.array(owner, dtype=np.int64)[order]
        sign_a = np.array(signs, dtype=np.int64)[order]
        sigma_o = np.array(sigmas, dtype=object)[order]
        lcm_a = np.array(lcms, dtype=object)
        mult = sign_a.astype(object) * (lcm_a[owner_a] // sigma_o)
        arity = arity[order]
        return {
            "owner": owner_a,
            "coef": sign_a / sigma_o.astype(float),
            "mult": mult,
            "branches": branches,
            "needs": [int((arity > k).sum()) for k in range(width)],
            "counts": np.bincount(owner_a, minlength=len(self.conditions)),
            "lcm": lcm_a,
            "size": [c.vertices - 1 for c in self.conditions],
        }


@lru_cache(maxsize=8)
def condition_table(order: int, degree: int | None) -> ConditionTable:
    """The shared, cached :class:`ConditionTable` for ``(order, degree)``."""
    return ConditionTable(order, degree)
