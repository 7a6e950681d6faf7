"""The energy conditions enumerated by centroid, without a listing of rooted trees
(definitions §3).

A free tree with ``n`` vertices has one centroid — a vertex whose branches have at most
``⌊(n−1)/2⌋`` vertices each — or, for even ``n``, two adjacent ones whose halves have
``n/2`` vertices each.  Rooted at its centroid it is a multiset of *branches*, rooted
trees of at most ``⌊(n−1)/2⌋`` vertices (3 047 of them up to 11), plus, with two
centroids, the pair of halves (equal halves: the superfluous trees, skipped).  So every
condition of an order is a multiset drawn from a small table, and the whole order is
enumerated without the rooted trees of ``n`` vertices that a
:class:`~rkcheck.trees.listing.ConditionListing` lists (267 million at 23 vertices).

With a degree bound ``m`` the branches are the rooted trees whose vertices have at most
``m − 1`` children, and the centroid carries at most ``m`` of them.

:class:`CentroidOrder.walk` drives the enumeration: it decides which branch extends
which partial multiset and leaves the arithmetic to a :class:`Builder` (the evaluation
stage's, or none to name conditions).  The order of the complete multisets is the
order's listing order ``k``; the first walk records, per condition, the chain of
branches it was built from, so that a condition is named from its branches later.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from typing import Any, Iterator, Protocol

import numpy as np

from rkcheck.trees.counting import condition_counts
from rkcheck.trees.free import FreeTree
from rkcheck.trees.graph import (
    adjacency,
    centres,
    distances,
    distinct_rootings,
    subtrees_at,
)
from rkcheck.trees.listing import ConditionListing
from rkcheck.trees.naming import ConditionNames
from rkcheck.trees.rooted import bracket_of_forest, level_sequence_of_forest

#: exact checks to this order and beyond enumerate their conditions by centroid: a
#: listing of rooted trees to order 21 takes some 3 GB, to order 22 over 9 GB (RK4 to
#: order 22 by centroid: 50 s and 1.4 GB, docs/performance.md)
CENTROID_FROM_ORDER = 21

#: rows of one block of new partial multisets: the temporaries of a block stay small
BLOCK = 1 << 17

#: partial multisets with at most this many vertices still to place are completed at
#: once, not held until their turn: they are most of them (at 23 vertices, held, they
#: would take some 3 GB in five channels)
SHALLOW = 4


class Branches:
    """Every rooted tree with at most ``top`` vertices whose vertices have at most
    ``children`` children (None: any), ids by size: tree ``c = u ∘ v`` (``v`` attached
    to ``u``'s root, ``v`` its child with the largest id), with ``run`` the copies of
    ``v`` among ``c``'s children and ``σ(c)``."""

    def __init__(self, top: int, children: int | None):
        self.left, self.right, self.size, self.run, self.sigma = [-1], [-1], [1], [0], [1]
        self.degree = [0]  # children of the root
        first = [0, 0, 1]  # first id with 0, 1, 2, … vertices
        for z in range(2, top + 1):
            for v in range(len(self.size)):  # v: the largest child
                zu = z - self.size[v]
                for u in range(first[zu], first[zu + 1]) if zu >= 1 else ():
                    if (u and self.right[u] > v) or (children is not None and self.degree[u] >= children):
                        continue
                    run = self.run[u] + 1 if u and self.right[u] == v else 1
                    self.left.append(u)
                    self.right.append(v)
                    self.size.append(z)
                    self.run.append(run)
                    self.degree.append(self.degree[u] + 1)
                    self.sigma.append(self.sigma[u] * self.sigma[v] * run)
            first.append(len(self.size))
        self.first = first
        self.count = len(self.size)
        self._sequences: dict[int, tuple[int, ...]] = {0: (1,)}

    def upto(self, z: int) -> int:
        """The number of branches with at most ``z`` vertices."""
        return self.first[min(z, len(self.first) - 2) + 1]

    def children(self, c: int) -> list[int]:
        out = []
        while c > 0:
            out.append(self.right[c])
            c = self.left[c]
        return out

    def level_sequence(self, c: int) -> tuple[int, ...]:
        seq = self._sequences.get(c)
        if seq is None:
            out = [1]
            for child in self.children(c):
                out += [d + 1 for d in self.level_sequence(child)]
            seq = self._sequences[c] = tuple(out)
        return seq


class Builder(Protocol):
    """The arithmetic of a walk: opaque states, one row per partial multiset."""

    def start(self) -> Any:
        """The empty multiset (one row)."""

    def extend(self, state: Any, parent: np.ndarray, branch: np.ndarray, run: np.ndarray) -> Any:
        """Row i: the multiset of row ``parent[i]`` of ``state`` with one more copy of
        ``branch[i]``, which it then holds ``run[i]`` times."""

    def take(self, state: Any, rows: np.ndarray) -> Any: ...

    def concat(self, states: list[Any]) -> Any: ...

    def finish(self, state: Any) -> None:
        """Complete multisets (conditions), in listing order."""

    def halves(self, big: np.ndarray, small: np.ndarray) -> None:
        """Conditions with two centroids, in listing order: halves ``big`` (the root's
        side) and ``small``, distinct, of ``n/2`` vertices each."""


class _Nothing:
    """A builder that computes nothing: a walk that only records the branches."""

    def start(self) -> Any:
        return None

    def extend(self, state: Any, parent: np.ndarray, branch: np.ndarray, run: np.ndarray) -> Any:
        return None

    def take(self, state: Any, rows: np.ndarray) -> Any:
        return None

    def concat(self, states: list[Any]) -> Any:
        return None

    def finish(self, state: Any) -> None:
        pass

    def halves(self, big: np.ndarray, small: np.ndarray) -> None:
        pass


class CentroidOrder:
    """The conditions with ``n`` vertices: their enumeration, and once walked, the
    branches of each.  ``max_terms`` bounds a condition's distinct rootings (at most one
    per vertex); there is no coefficient weight (the bound takes ``(n−1)!`` per term)."""

    coefficient_weight = None

    def __init__(self, n: int, branches: Branches, degree: int | None, count: int):
        self.vertices = n
        self.max_terms = n
        self._branches, self._degree, self._count = branches, degree, count
        self._leaves: tuple[np.ndarray, np.ndarray] | None = None  # per condition: its node, its last branch
        self._nodes: tuple[np.ndarray, np.ndarray] | None = None  # per partial multiset: its parent, its branch

    def __len__(self) -> int:
        return self._count

    def branches_of(self, k: int) -> tuple[list[int], bool]:
        """The branches of condition ``k`` at its centroid, and whether they are two
        halves (two centroids: the root's half first)."""
        if self._leaves is None:
            self.walk(_Nothing())
        leaves, nodes = self._leaves, self._nodes
        assert leaves is not None and nodes is not None
        node, last = int(leaves[0][k]), int(leaves[1][k])
        if node < 0:
            return [-node - 1, last], True
        out = [last]
        parent, branch = nodes
        while node > 0:
            out.append(int(branch[node]))
            node = int(parent[node])
        return out, False

    def walk(self, builder: Builder) -> None:
        """Every condition, built by ``builder`` in listing order (the first walk also
        records each condition's branches)."""
        _Walk(self, builder).run()


class _Walk:
    """One enumeration of an order: partial multisets, largest branch first, wait by the
    vertices still to place (those with at most :data:`SHALLOW` are completed at once)."""

    def __init__(self, order: CentroidOrder, builder: Builder):
        n = order.vertices
        self.order, self.builder, self.b = order, builder, order._branches
        self.cap = (n - 1) // 2 if n % 2 else n // 2 - 1
        self.most = order._degree  # branches at the centroid
        self.record = order._leaves is None
        self.sizes = np.array(self.b.size, dtype=np.int64)
        self.pending: dict[int, list[tuple[Any, ...]]] = {r: [] for r in range(n)}
        # a branch id in the record: 16 bits while they fit (3 047 branches up to 11 vertices)
        self.branch = np.int16 if self.b.count < 1 << 15 else np.int32
        self.nodes: list[tuple[np.ndarray, np.ndarray]] = [(np.array([-1], dtype=np.int32),
                                                             np.array([-1], dtype=self.branch))]
        self.node_count = 1
        self.leaves: list[tuple[np.ndarray, np.ndarray]] = []

    def run(self) -> None:
        n, b = self.order.vertices, self.b
        one = np.zeros(1, dtype=np.int64)
        self.pending[n - 1].append((self.builder.start(), np.array([b.count]), one, one, one.copy()))
        for r in range(n - 1, 0, -1):
            if self.pending[r]:
                parts, self.pending[r] = self.pending[r], []
                controls = tuple(np.concatenate([x[i] for x in parts]) for i in range(1, 5))
                self._expand(r, self.builder.concat([x[0] for x in parts]), *controls)
        if n % 2 == 0:
            self._halves(n // 2)
        if self.record:
            leaves = _joined(self.leaves)
            if len(leaves[0]) != len(self.order):  # pragma: no cover - enumerated = counted
                raise AssertionError(f"{len(leaves[0])} conditions enumerated at {n} vertices, "
                                     f"{len(self.order)} counted")
            self.order._nodes, self.order._leaves = _joined(self.nodes), leaves

    def _expand(self, r: int, state: Any, last: np.ndarray, run: np.ndarray, placed: np.ndarray,
                node: np.ndarray) -> None:
        """Every way to add a branch to the partial multisets ``state`` (``r`` vertices
        still to place; ``last`` their smallest branch, ``run`` its copies, ``placed``
        their branches, ``node`` their ids in the record)."""
        count = np.minimum(last, self.b.upto(min(r, self.cap)) - 1) + 1
        if self.most is not None:
            count[placed >= self.most] = 0
        ends = np.cumsum(count)
        lo = 0
        while lo < len(count):
            start = int(ends[lo - 1]) if lo else 0
            hi = max(int(np.searchsorted(ends, start + BLOCK, side="right")), lo + 1)
            k = count[lo:hi]
            parent = np.repeat(np.arange(lo, hi), k)
            c = np.arange(len(parent)) - np.repeat(np.cumsum(k) - k, k)
            run2 = np.where(last[parent] == c, run[parent] + 1, 1)
            new = self.builder.extend(state, parent, c, run2)
            rem = r - self.sizes[c]
            for r2 in np.flatnonzero(np.bincount(rem, minlength=r)).tolist():  # (np.unique imports numpy.ma)
                rows = np.flatnonzero(rem == r2)
                self._place(r2, self.builder.take(new, rows), c[rows], run2[rows], placed[parent[rows]] + 1,
                            node[parent[rows]])
            lo = hi

    def _place(self, r: int, state: Any, c: np.ndarray, run: np.ndarray, placed: np.ndarray,
               parent_node: np.ndarray) -> None:
        if r == 0:
            self.builder.finish(state)
            if self.record:
                self.leaves.append((parent_node.astype(np.int32), c.astype(self.branch)))
            return
        node = np.arange(self.node_count, self.node_count + len(c))
        if self.record:
            self.nodes.append((parent_node.astype(np.int32), c.astype(self.branch)))
            self.node_count += len(c)
        if r <= SHALLOW:
            self._expand(r, state, c, run, placed, node)
        else:
            self.pending[r].append((state, c, run, placed, node))

    def _halves(self, half: int) -> None:
        ids = np.arange(self.b.first[half], self.b.upto(half))
        i, j = np.triu_indices(len(ids), 1)  # distinct halves: equal ones are superfluous
        big, small = ids[j], ids[i]
        self.builder.halves(big, small)
        if self.record:
            self.leaves.append(((-big - 1).astype(np.int32), small.astype(self.branch)))


def _joined(parts: list[tuple[np.ndarray, np.ndarray]]) -> tuple[np.ndarray, np.ndarray]:
    """A record's blocks of (parent, branch) as two arrays."""
    if not parts:
        return np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.int32)
    return np.concatenate([x[0] for x in parts]), np.concatenate([x[1] for x in parts])


class _Orders(Mapping[int, CentroidOrder]):
    def __init__(self, make: Any, keys: range):
        self._make, self._keys = make, keys
        self._built: dict[int, CentroidOrder] = {}

    def __getitem__(self, n: int) -> CentroidOrder:
        if n not in self._keys:
            raise KeyError(n)
        if n not in self._built:
            self._built[n] = self._make(n)
        return self._built[n]

    def __iter__(self) -> Iterator[int]:
        return iter(self._keys)

    def __len__(self) -> int:
        return len(self._keys)


class CentroidListing(ConditionNames):
    """All energy conditions with ``3 … N+1`` vertices whose free trees have maximum
    degree ``<= degree`` (None: no bound), enumerated by centroid: the same conditions
    as a :class:`~rkcheck.trees.listing.ConditionListing` (in another order ``k`` within
    each order), named the same way, with nothing built before it is walked."""

    def __init__(self, order: int, degree: int | None):
        if order < 1:
            raise ValueError("order must be at least 1")
        if degree is not None and degree < 1:
            raise ValueError("degree must be at least 1")
        self.order, self.degree = order, degree
        top = order + 1
        self.branches = Branches(top // 2, None if degree is None else degree - 1)
        self._conditions = condition_counts(top, degree)
        keys = range(3, top + 1) if degree is None or degree >= 2 else range(0)
        self.orders = _Orders(lambda n: CentroidOrder(n, self.branches, degree, self._conditions[n]), keys)
        self.store_notes: list[str] = []  # nothing is stored: no note
        self.cache_hits: list[int] = []
        self._init_names()

    def __reduce__(self) -> tuple[Any, tuple[int, int | None]]:
        # determined by (order, degree): send the key, walk again there
        return centroid_listing, (self.order, self.degree)

    def ensure(self, n: int) -> None:
        """Nothing to build ahead: an order is enumerated when it is walked."""

    def complete(self) -> "CentroidListing":
        return self

    def _describe(self, n: int, k: int) -> tuple[FreeTree, int]:
        """Condition ``k``'s free tree, and the sign (−1)^d of the distance d from the
        centroid (where it is evaluated) to the designated centre."""
        found, halves = self.orders[n].branches_of(k)
        b = self.branches
        forest = b.children(found[0]) + [found[1]] if halves else found
        adj = adjacency((1,) + tuple(d + 1 for c in forest for d in b.level_sequence(c)))
        at = [(subtrees_at(adj, v), v) for v in centres(adj)]
        seq, subtrees, centre = max((level_sequence_of_forest(subs), subs, v) for subs, v in at)
        tree = FreeTree(seq, bracket_of_forest(subtrees), max(len(a) for a in adj), distinct_rootings(adj))
        return tree, (-1) ** distances(adj, 0)[centre]


@lru_cache(maxsize=2)
def centroid_listing(order: int, degree: int | None) -> CentroidListing:
    """The process's centroid listing for ``(order, degree)``: its record of branches is
    made by the first walk of each order, and kept for the conditions named later."""
    return CentroidListing(order, degree)


#: either enumeration of the conditions: by rooted trees, or by centroid
Listing = ConditionListing | CentroidListing
