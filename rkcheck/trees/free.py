"""Free (unrooted) trees, enumerated canonically from their centre (definitions §3).

A free tree has one centre or two adjacent ones.  It is generated directly in its
centre-rooted form, so no tree is built twice and none is built only to be discarded:

* **one centre**, radius ``h``: a root carrying a multiset of rooted trees of height
  at most ``h-1`` with at least two of height exactly ``h-1``;
* **two centres**: an edge joining two rooted trees of equal height.  The two halves
  are equal exactly when the tree is **superfluous** (a rooting ``u∘u``), so the
  non-superfluous ones are the pairs of *distinct* halves.

Subtrees come from a :class:`~rkcheck.trees.rooted.RootedTreeTable` whose children bound is
``max_degree - 1`` (every vertex of a branch also has its parent edge), which is how a
degree bound prunes the generation itself.

Every vertex ``v`` of a free tree is described by its **branches**: the rooted trees
hanging from ``v`` along each of its edges, as a key of table ids.  The rooting at
``v`` is the rooted tree whose root carries exactly these branches, so two vertices
give the same rooted tree iff their keys are equal.  Keys are computed by rerooting:
walking from a vertex ``p`` (key ``K``) into the branch ``x``, the new vertex carries
``children(x)`` plus the branch back to ``p``, which is the tree ``K`` minus one ``x``
(a table lookup, never a canonicalisation from scratch).  Siblings with equal ids give
equal keys and equal walks, so each distinct branch is walked once.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator

from rkcheck.trees.rooted import RootedTreeTable, level_sequence_of_forest


@dataclass(frozen=True, slots=True)
class FreeTree:
    """A free tree with its distinct rootings.

    ``rootings[k] = (branches, parity)``: ``branches`` is the key (table ids,
    decreasing) of the rooted tree ``u`` obtained by rooting at some vertex, i.e.
    ``B₋(u)``; ``parity`` is the parity of the distance from the designated root, which
    is the canonical centre.  ``rootings[0]`` is the designated rooting itself.
    """

    vertices: int
    max_degree: int
    bicentral: bool
    rootings: tuple[tuple[tuple[int, ...], int], ...]
    superfluous: bool = False

    @property
    def centre(self) -> tuple[int, ...]:
        """The branches at the designated root (the canonical centre)."""
        return self.rootings[0][0]


def table_for(order: int, max_degree: int | None) -> RootedTreeTable:
    """The rooted-tree table whose trees are the possible branches of conditions up to ``order``."""
    return RootedTreeTable(max(order, 1), None if max_degree is None else max_degree - 1)


class _Forests:
    """Multisets of table trees (keys in decreasing id order) of a given total size,
    restricted to a set of ids; candidates are grouped by size."""

    def __init__(self, table: RootedTreeTable, ids: list[int]):
        self.table = table
        self.by_size: dict[int, list[int]] = {}
        for t in sorted(ids, reverse=True):
            self.by_size.setdefault(table.order[t], []).append(t)

    def multisets(self, total: int, max_count: int | None, min_count: int = 0) -> Iterator[tuple[int, ...]]:
        if total == 0:
            if min_count == 0:
                yield ()
            return
        limit = total if max_count is None else max_count
        if limit < 1 or limit < min_count:
            return
        yield from self._rec(total, limit, min_count, None, ())

    def _rec(self, remaining: int, count_left: int, need: int, max_id: int | None,
             prefix: tuple[int, ...]) -> Iterator[tuple[int, ...]]:
        if remaining == 0:
            if need <= 0:
                yield prefix
            return
        if count_left == 0:
            return
        top = remaining if max_id is None else min(remaining, self.table.order[max_id])
        low = -(-remaining // count_left)  # the biggest part is at least this big
        for r in range(top, low - 1, -1):
            for t in self.by_size.get(r, ()):
                if max_id is not None and t > max_id:
                    continue
                yield from self._rec(remaining - r, count_left - 1, need - 1, t, prefix + (t,))


def _merge(a: tuple[int, ...], b: tuple[int, ...]) -> tuple[int, ...]:
    return tuple(sorted(a + b, reverse=True))


class FreeTreeGenerator:
    """Generates the free trees with ``n`` vertices and maximum degree ``<= max_degree``
    from one shared :class:`RootedTreeTable` (built for ``max_order = n_max - 1``)."""

    def __init__(self, table: RootedTreeTable, max_degree: int | None):
        self.table = table
        self.max_degree = max_degree
        heights: dict[int, list[int]] = {}
        for t in range(len(table)):
            heights.setdefault(table.height[t], []).append(t)
        self.ids_of_height = heights
        self._tall: dict[int, _Forests] = {}
        self._short: dict[int, _Forests] = {}

    def _forests(self, h: int) -> tuple[_Forests, _Forests]:
        """(trees of height exactly h, trees of height < h)."""
        if h not in self._tall:
            self._tall[h] = _Forests(self.table, self.ids_of_height.get(h, []))
            short = [t for k, ids in self.ids_of_height.items() if k < h for t in ids]
            self._short[h] = _Forests(self.table, short)
        return self._tall[h], self._short[h]

    # ------------------------------------------------------------ enumeration

    def free_trees(self, n: int, include_superfluous: bool = False) -> Iterator[FreeTree]:
        """All free trees with ``n`` vertices (non-superfluous unless asked), each once."""
        if n > self.table.max_order + 1:
            raise ValueError(f"table too small for {n} vertices")
        if n == 1:
            yield FreeTree(1, 0, False, (((), 0),))
            return
        yield from self._unicentral(n)
        yield from self._bicentral(n, include_superfluous)

    def _unicentral(self, n: int) -> Iterator[FreeTree]:
        m = self.max_degree
        for h in range(1, (n - 1) // 2 + 1):
            tall, short = self._forests(h - 1)
            for tall_size in range(2 * h, n):
                for tall_key in tall.multisets(tall_size, m, min_count=2):
                    rest = None if m is None else m - len(tall_key)
                    for short_key in short.multisets(n - 1 - tall_size, rest):
                        key = _merge(tall_key, short_key)
                        yield self._with_rootings(n, key, bicentral=False)

    def _bicentral(self, n: int, include_superfluous: bool) -> Iterator[FreeTree]:
        table = self.table
        for r1 in range((n + 1) // 2, n):  # r1 >= r2
            r2 = n - r1
            if r2 < 1:
                continue
            for x in table.ids_of_order(r1):
                for y in table.ids_of_order(r2):
                    if table.height[x] != table.height[y]:
                        continue
                    if r1 == r2 and y > x:
                        continue
                    if x == y:
                        if include_superfluous:
                            key = _merge(table.children[x], (y,))
                            yield FreeTree(n, self._degree_of_pair(x, y), True, ((key, 0),), superfluous=True)
                        continue
                    yield self._bicentral_tree(n, x, y)

    def _degree_of_pair(self, x: int, y: int) -> int:
        return max(self._max_degree_from(_merge(self.table.children[x], (y,))), 1)

    def _bicentral_tree(self, n: int, x: int, y: int) -> FreeTree:
        table = self.table
        kx = _merge(table.children[x], (y,))
        ky = _merge(table.children[y], (x,))
        ls_x = level_sequence_of_forest([table.level_sequence(t) for t in kx])
        ls_y = level_sequence_of_forest([table.level_sequence(t) for t in ky])
        return self._with_rootings(n, kx if ls_x >= ls_y else ky, bicentral=True)

    # --------------------------------------------------------------- rerooting

    def _walk(self, root_key: tuple[int, ...]) -> tuple[dict[tuple[int, ...], int], int, bool]:
        """Distinct rootings reachable from a vertex with branches ``root_key``.

        Walking from a vertex with key K into its branch x, the new vertex carries
        ``children(x)`` plus the branch back, which is K minus one x: a dictionary lookup.
        (Each rooted tree belongs to exactly one free tree, so these lookups are not
        memoised: nothing would ever be reused.)"""
        children = self.table.children
        index = self.table.index
        found: dict[tuple[int, ...], int] = {root_key: 0}
        max_deg = len(root_key)
        superfluous = False
        # (key at vertex, id of the branch that leads back, parity)
        stack: list[tuple[tuple[int, ...], int, int]] = [(root_key, -1, 0)]
        pop, push = stack.pop, stack.append
        while stack:
            key, back, parity = pop()
            p = parity ^ 1
            n = len(key)
            prev = -1
            for i in range(n):
                x = key[i]
                if x == prev:
                    continue  # equal siblings: same rootings, walked once
                prev = x
                if x == back and (i + 1 == n or key[i + 1] != x):
                    continue  # the only branch with this id leads back where we came from
                up = index[key[:i] + key[i + 1:]]
                new_key = tuple(sorted(children[x] + (up,), reverse=True))
                if len(new_key) > max_deg:
                    max_deg = len(new_key)
                seen = found.get(new_key)
                if seen is None:
                    found[new_key] = p
                elif seen != p:
                    superfluous = True
                push((new_key, up, p))
        return found, max_deg, superfluous

    def _max_degree_from(self, root_key: tuple[int, ...]) -> int:
        return self._walk(root_key)[1]

    def _with_rootings(self, n: int, root_key: tuple[int, ...], bicentral: bool) -> FreeTree:
        found, max_deg, superfluous = self._walk(root_key)
        rootings = tuple(found.items())
        return FreeTree(n, max_deg, bicentral, rootings, superfluous)

    # -------------------------------------------------------------- from input

    def from_level_sequence(self, seq: tuple[int, ...]) -> FreeTree:
        """The free tree underlying a rooted tree given by any level sequence, rooted at
        its canonical centre (for ``rkcheck explain``)."""
        adj = _adjacency(seq)
        centres = _centres(adj)
        table = self.table

        def branch_id(v: int, parent: int) -> int:
            return table.lookup(tuple(branch_id(w, v) for w in adj[v] if w != parent))

        keys = [tuple(sorted((branch_id(w, c) for w in adj[c]), reverse=True)) for c in centres]
        if len(keys) == 2 and branch_id(centres[0], centres[1]) == branch_id(centres[1], centres[0]):
            # equal halves across the central edge: a rooting u∘u, no condition
            max_deg = max(len(a) for a in adj)
            return FreeTree(len(seq), max_deg, True, ((keys[0], 0),), superfluous=True)
        if len(keys) == 2:
            ls = [level_sequence_of_forest([table.level_sequence(t) for t in k]) for k in keys]
            key = keys[0] if ls[0] >= ls[1] else keys[1]
        else:
            key = keys[0]
        return self._with_rootings(len(seq), key, bicentral=len(keys) == 2)


def _adjacency(seq: tuple[int, ...]) -> list[list[int]]:
    adj: list[list[int]] = [[] for _ in seq]
    last_at_depth: dict[int, int] = {}
    for v, d in enumerate(seq):
        if d > 1:
            p = last_at_depth[d - 1]
            adj[p].append(v)
            adj[v].append(p)
        last_at_depth[d] = v
    return adj


def _centres(adj: list[list[int]]) -> list[int]:
    """The one or two centres, by peeling leaves."""
    n = len(adj)
    if n <= 2:
        return list(range(n))
    degree = [len(a) for a in adj]
    layer = [v for v in range(n) if degree[v] == 1]
    remaining = n
    while remaining > 2:
        remaining -= len(layer)
        nxt = []
        for v in layer:
            for w in adj[v]:
                degree[w] -= 1
                if degree[w] == 1:
                    nxt.append(w)
        layer = nxt
    return sorted(layer)
