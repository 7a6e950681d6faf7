"""The energy conditions up to an order, listed as flat arrays (definitions §3).

A :class:`ConditionListing` for ``(N, m)`` holds what evaluating the conditions needs and
nothing more:

* the Butcher factors ``left``/``right`` of every rooted tree with at most ``N`` vertices
  within the degree bound (the trees whose weights later terms use);
* per number of vertices ``n = 3 … N+1`` an :class:`OrderTerms`: the factors ``(u, v)``
  of every term ``u ∘ v`` sorted by condition, the index of its ``(n−1)!/σ`` among the
  order's distinct values, its sign, and per condition the representative's factors and
  (for two centres) the data that settle the designated rooting.

The trees with ``N + 1`` vertices, the largest set by far (35 million at order 20), are
never stored as a table: they are generated in chunks, classified (:mod:`.classes`) and
kept only as terms.  Building it is the "listing" cost of a check; it does not depend on
the tableau and is shared by every check of the same ``(N, m)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from rkcheck.trees.classes import classify
from rkcheck.trees.rooted import bracket_of_forest, level_sequence_of_forest
from rkcheck.trees.table import TreeTable


@dataclass
class OrderTerms:
    """The conditions with ``vertices`` vertices.  Its terms are the rooted trees with
    that many vertices, in id order: term ``i`` is the tree ``first_id + i`` (orders kept
    in the table) or the product ``left[i] ∘ right[i]`` (the top order); it belongs to
    condition ``condition[i]`` (``len(self)`` for the terms of superfluous trees, which
    are left out) with the coefficient ``coefficients[coefficient_index[i]]``."""

    vertices: int
    first_id: int | None
    left: np.ndarray | None  # int32 factors u, v of each term u ∘ v (top order only)
    right: np.ndarray | None
    condition: np.ndarray  # int32 condition of each term
    coefficient_index: np.ndarray  # int16 into ``coefficients``
    coefficients: list[int]  # the distinct ±(n−1)!/σ(u) of this order (exact, signed)
    counts: np.ndarray  # int32 terms per condition
    rep_left: np.ndarray  # int32 factors of each condition's representative rooting
    rep_right: np.ndarray
    tall: np.ndarray  # int32: for two centres, the other centre's branch (−1 for one centre)
    rest: np.ndarray  # int32: for two centres, the representative minus that branch
    max_degree: np.ndarray  # int16
    superfluous: int = 0  # free trees of this order left out (equal halves across an edge)

    def __len__(self) -> int:
        return len(self.rep_left)

    @property
    def order(self) -> int:
        return self.vertices - 1

    @property
    def terms(self) -> int:
        return int(self.counts.sum())

    @property
    def max_terms(self) -> int:
        return int(self.counts.max(initial=1))

    def factors(self, i: int, listing: "ConditionListing") -> tuple[int, int]:
        """(u, v) of term ``i``."""
        if self.first_id is not None:
            t = self.first_id + i
            return int(listing.left[t]), int(listing.right[t])
        assert self.left is not None and self.right is not None  # the top order keeps its factors
        return int(self.left[i]), int(self.right[i])

    def sign(self, i: int) -> int:
        return 1 if self.coefficients[int(self.coefficient_index[i])] > 0 else -1

    def terms_of(self, k: int) -> np.ndarray:
        """The term indices of condition ``k`` (a scan: for explanations, not bulk work)."""
        return np.flatnonzero(self.condition == k)


@dataclass
class ConditionRecord:
    """One condition for people: canonical id (the designated rooting's level sequence,
    definitions §3), bracket, vertices, max degree and number of terms.  ``flip`` is the
    sign that turns the residual computed from the representative into the residual of
    the designated rooting."""

    level_sequence: tuple[int, ...]
    bracket: str
    vertices: int
    max_degree: int
    rootings: int
    flip: int
    order_index: int  # position within its order

    @property
    def id(self) -> str:
        return ",".join(map(str, self.level_sequence))

    @property
    def order(self) -> int:
        return self.vertices - 1


class ConditionListing:
    """All energy conditions with ``3 … N+1`` vertices whose free trees have maximum
    degree ``<= degree`` (None: no bound)."""

    def __init__(self, order: int, degree: int | None):
        if order < 1:
            raise ValueError("order must be at least 1")
        if degree is not None and degree < 1:
            raise ValueError("degree must be at least 1")
        self.order = order
        self.degree = degree
        root_bound = None if degree is None else degree
        inner_bound = None if degree is None else degree - 1
        table = TreeTable(max(order, 1), root_bound, inner_bound)
        self.orders: dict[int, OrderTerms] = {}
        if degree is None or degree >= 2:
            for n in range(3, order + 2):
                self.orders[n] = classify(table, n, last=n == order + 1)
        self.first = list(table.first)
        self.left = table.left
        self.right = table.right
        self._ls_cache: dict[int, tuple[int, ...]] = {0: (1,)}

    def __reduce__(self):
        # a listing is determined by (order, degree): send the key, rebuild (cached) there
        return condition_listing, (self.order, self.degree)

    # --------------------------------------------------------------- counts

    def __len__(self) -> int:
        return sum(len(t) for t in self.orders.values())

    def counts_by_order(self) -> dict[int, int]:
        """Conditions per energy order ``2 … N`` (vertices − 1)."""
        return {k: len(self.orders[k + 1]) if k + 1 in self.orders else 0 for k in range(2, self.order + 1)}

    def terms(self) -> int:
        return sum(t.terms for t in self.orders.values())

    # --------------------------------------------------------------- display

    def _children(self, t: int) -> list[int]:
        out = []
        left, right = self.left, self.right
        while t != 0:
            out.append(int(right[t]))
            t = int(left[t])
        return out

    def tree_level_sequence(self, t: int) -> tuple[int, ...]:
        """Canonical level sequence of the stored tree ``t``."""
        seq = self._ls_cache.get(t)
        if seq is None:
            seq = self._ls_cache[t] = level_sequence_of_forest([self.tree_level_sequence(c) for c in self._children(t)])
        return seq

    def _forest(self, children: list[int]) -> list[tuple[int, ...]]:
        return [self.tree_level_sequence(c) for c in children]

    def record(self, n: int, k: int) -> ConditionRecord:
        """Condition ``k`` of the order with ``n`` vertices, for people."""
        o = self.orders[n]
        forest = self._forest(self._children(int(o.rep_left[k])) + [int(o.rep_right[k])])
        seq = level_sequence_of_forest(forest)
        flip = 1
        if o.tall[k] >= 0:  # two centres: the designated one has the larger level sequence
            other = self._forest(self._children(int(o.tall[k])) + [int(o.rest[k])])
            other_seq = level_sequence_of_forest(other)
            if other_seq > seq:
                seq, forest, flip = other_seq, other, -1
        return ConditionRecord(seq, bracket_of_forest(forest), n, int(o.max_degree[k]),
                               int(o.counts[k]), flip, k)

    def records(self, n: int) -> list[ConditionRecord]:
        """The conditions with ``n`` vertices in listing order."""
        return [self.record(n, k) for k in range(len(self.orders[n]))] if n in self.orders else []

    def sorted_records(self):
        """Every condition for people, by vertices and then canonical id (a generator)."""
        for n in sorted(self.orders):
            yield from sorted(self.records(n), key=lambda r: r.level_sequence)

    def term_forests(self, n: int, k: int) -> list[tuple[int, int, list[tuple[int, ...]]]]:
        """(sign relative to the designated rooting, σ(u), B₋(u) as level sequences) for
        every rooting u of condition k, in listing order."""
        import math

        o = self.orders[n]
        flip = self.record(n, k).flip
        out = []
        for i in o.terms_of(k):
            u, v = o.factors(int(i), self)
            coef = o.coefficients[int(o.coefficient_index[i])]
            sigma = math.factorial(n - 1) // abs(coef)
            out.append((o.sign(i) * flip, sigma, self._forest(self._children(u) + [v])))
        return out


@lru_cache(maxsize=4)
def condition_listing(order: int, degree: int | None) -> ConditionListing:
    """The shared, cached listing for ``(order, degree)`` (a scan reuses it file after
    file)."""
    return ConditionListing(order, degree)




