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

from functools import lru_cache
from typing import Iterator

from rkcheck.trees.classes import classify
from rkcheck.trees.free import FreeTree
from rkcheck.trees.rooted import bracket_of_forest, level_sequence_of_forest
from rkcheck.trees.table import TreeTable
from rkcheck.trees.terms import OrderTerms


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

    def _designated(self, n: int, k: int) -> tuple[tuple[int, ...], list[tuple[int, ...]], int]:
        """The designated rooting of condition ``k`` (level sequence, the forest B₋ of
        its root) and the sign that turns the residual of the representative rooting
        into the residual of the designated one."""
        o = self.orders[n]
        forest = self._forest(self._children(int(o.rep_left[k])) + [int(o.rep_right[k])])
        seq = level_sequence_of_forest(forest)
        if o.tall[k] >= 0:  # two centres: the designated one has the larger level sequence
            other = self._forest(self._children(int(o.tall[k])) + [int(o.rest[k])])
            other_seq = level_sequence_of_forest(other)
            if other_seq > seq:
                return other_seq, other, -1
        return seq, forest, 1

    def record(self, n: int, k: int) -> FreeTree:
        """Condition ``k`` of the order with ``n`` vertices, for people."""
        seq, forest, _ = self._designated(n, k)
        o = self.orders[n]
        return FreeTree(seq, bracket_of_forest(forest), int(o.max_degree[k]), int(o.counts[k]))

    def flip(self, n: int, k: int) -> int:
        """``±1``: the residual of condition ``k`` for its designated rooting is this sign
        times the residual of the representative the evaluation computes."""
        return self._designated(n, k)[2]

    def records(self, n: int) -> list[FreeTree]:
        """The conditions with ``n`` vertices in listing order."""
        return [self.record(n, k) for k in range(len(self.orders[n]))] if n in self.orders else []

    def sorted_conditions(self) -> Iterator[tuple[int, int, FreeTree]]:
        """``(vertices, k, free tree)`` of every condition, by vertices and then canonical
        id (``k``: its position in the listing's order)."""
        for n in sorted(self.orders):
            records = self.records(n)
            for k in sorted(range(len(records)), key=lambda k: records[k].level_sequence):
                yield n, k, records[k]

    def sorted_records(self) -> Iterator[FreeTree]:
        """Every condition for people, by vertices and then canonical id."""
        return (tree for _, _, tree in self.sorted_conditions())

    def term_forests(self, n: int, k: int) -> list[tuple[int, int, list[tuple[int, ...]]]]:
        """(sign relative to the designated rooting, σ(u), B₋(u) as level sequences) for
        every rooting u of condition k, in listing order."""
        import math

        o = self.orders[n]
        flip = self.flip(n, k)
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




