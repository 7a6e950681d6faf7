"""A level sequence as a graph: the free tree behind a rooted tree's level sequence, its
adjacency lists, its centre or two centres, distances, and its canonical level sequence
from any vertex (definitions §2–§3).  Shared by the explanation of a condition and the
drawing of its tree."""

from __future__ import annotations

from rkcheck.trees.rooted import level_sequence_of_forest


def adjacency(seq: tuple[int, ...]) -> list[list[int]]:
    """The tree of a level sequence as adjacency lists (vertex 0 = the given root)."""
    adj: list[list[int]] = [[] for _ in seq]
    last_at_depth: dict[int, int] = {}
    for v, d in enumerate(seq):
        if d > 1:
            p = last_at_depth[d - 1]
            adj[p].append(v)
            adj[v].append(p)
        last_at_depth[d] = v
    return adj


def rooted_at(adj: list[list[int]], root: int) -> tuple[int, ...]:
    """Canonical level sequence of the tree rooted at ``root``."""
    return level_sequence_of_forest(subtrees_at(adj, root))


def subtrees_at(adj: list[list[int]], root: int) -> list[tuple[int, ...]]:
    """The canonical level sequences of the subtrees of ``root`` in the tree rooted
    there: each vertex's built from its children's, bottom up (one canonical form per
    vertex, not a canonicalisation of a whole sequence at every level)."""
    order, parent = [root], {root: -1}
    for v in order:  # breadth first
        for w in adj[v]:
            if w != parent[v]:
                parent[w] = v
                order.append(w)
    below: dict[int, tuple[int, ...]] = {}
    for v in reversed(order[1:]):
        below[v] = level_sequence_of_forest([below[w] for w in adj[v] if w != parent[v]])
    return [below[w] for w in adj[root]]


def centres(adj: list[list[int]]) -> list[int]:
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


def distances(adj: list[list[int]], source: int) -> list[int]:
    """The number of edges from ``source`` to every vertex (breadth first)."""
    dist = [-1] * len(adj)
    dist[source] = 0
    queue = [source]
    for v in queue:
        for w in adj[v]:
            if dist[w] < 0:
                dist[w] = dist[v] + 1
                queue.append(w)
    return dist


def distinct_rootings(adj: list[list[int]]) -> int:
    """How many distinct rooted trees the rootings at the vertices give (the terms of a
    free tree's condition): each vertex's rooted shape as an interned code — the codes
    of the subtrees below it, then of the rest of the tree above it — in two passes,
    instead of a canonical level sequence per vertex."""
    n = len(adj)
    order, parent = [0], [-1] * n
    for v in order:  # breadth first from vertex 0
        for w in adj[v]:
            if w != parent[v]:
                parent[w] = v
                order.append(w)
    codes: dict[tuple[int, ...], int] = {}

    def intern(children: list[int]) -> int:
        return codes.setdefault(tuple(sorted(children)), len(codes))

    below = [0] * n
    for v in reversed(order):
        below[v] = intern([below[w] for w in adj[v] if w != parent[v]])
    above = [-1] * n  # the rest of the tree seen from v, rooted at v's parent
    shapes = set()
    for v in order:
        kids = [w for w in adj[v] if w != parent[v]]
        mine = [below[w] for w in kids] + ([above[v]] if parent[v] >= 0 else [])
        shapes.add(intern(mine))
        for i, w in enumerate(kids):
            above[w] = intern(mine[:i] + mine[i + 1:])
    return len(shapes)
