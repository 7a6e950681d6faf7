"""A level sequence as a graph: the free tree behind a rooted tree's level sequence, its
adjacency lists, its centre or two centres, distances, and its canonical level sequence
from any vertex (definitions §2–§3).  Shared by the explanation of a condition and the
drawing of its tree."""

from __future__ import annotations

from rkcheck.trees.rooted import canonical_level_sequence


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
    order, depth, parent = [], {root: 1}, {root: -1}
    stack = [root]
    while stack:  # depth-first, iteratively: the sequence is canonicalised afterwards
        v = stack.pop()
        order.append(v)
        for w in reversed(adj[v]):
            if w != parent[v]:
                parent[w], depth[w] = v, depth[v] + 1
                stack.append(w)
    return canonical_level_sequence([depth[v] for v in order])


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
