"""A free tree drawn from a level sequence, for people who would rather look than decode
``1,2,3,3,2,2``.

:func:`draw` reads the tree off the level sequence (vertex ``i`` hangs from the last
vertex before it one level up), finds its centre or two centres by peeling leaves, and
lays it out from the designated centre (definitions §3: for two centres the one whose
rooting has the larger level sequence), children in canonical order (largest subtree
first).  The result knows which vertices are centres and which one is the root of the
rooting given, and renders as Unicode lines (one vertex per line, ``tree``-style guides)
or as coordinates for a picture (leaves one unit apart, each parent above the middle of
its children).  Nothing here is computed from anything but the level sequence.
"""

from __future__ import annotations

from dataclasses import dataclass

from rkcheck.trees.graph import adjacency, centres
from rkcheck.trees.rooted import canonical_level_sequence

VERTEX = "●"


def _subtrees(adj: list[list[int]], top: int) -> tuple[dict[int, int], dict[int, tuple[int, ...]]]:
    """Parents and canonical level sequences of every subtree, the tree hanging from ``top``."""
    parent, order = {top: -1}, [top]
    for v in order:  # breadth first: each vertex after its parent
        for w in adj[v]:
            if w != parent[v]:
                parent[w] = v
                order.append(w)
    canon: dict[int, tuple[int, ...]] = {}
    for v in reversed(order):  # children before parents
        kids = sorted((canon[w] for w in adj[v] if w != parent[v]), reverse=True)
        canon[v] = (1,) + tuple(level + 1 for kid in kids for level in kid)
    return parent, canon


@dataclass(frozen=True)
class TreeDrawing:
    """A free tree laid out from its designated centre.  Vertices are numbered in the
    order they are drawn (depth first from the top, larger subtrees first): ``parent``
    and ``depth`` (0 at the top) of each, the ``centres``, the ``root`` of the rooting
    given (vertex 0 of ``given``), and ``x`` positions for a picture."""

    given: tuple[int, ...]
    parent: tuple[int, ...]
    depth: tuple[int, ...]
    centres: tuple[int, ...]
    root: int
    x: tuple[float, ...]

    @property
    def vertices(self) -> int:
        return len(self.parent)

    @property
    def edges(self) -> list[tuple[int, int]]:
        """(parent, child) for every edge."""
        return [(p, v) for v, p in enumerate(self.parent) if p >= 0]

    def children(self, v: int) -> list[int]:
        return [w for w, p in enumerate(self.parent) if p == v]

    def labels(self, v: int, mark_root: bool = True) -> list[str]:
        """What a vertex is: ``centre`` and/or ``root`` (of the rooting given)."""
        out = ["centre"] if v in self.centres else []
        return out + (["root"] if mark_root and v == self.root else [])

    def lines(self, mark_root: bool = True) -> list[str]:
        """One line per vertex, ``tree``-style: the top vertex, then each child indented
        four columns under its parent (``├── ``, ``└── `` and ``│`` guides), each vertex
        ``●`` followed by its labels."""
        out = []
        for v in range(self.vertices):
            chain = []  # v and its ancestors below the top, from the top down
            w = v
            while self.parent[w] >= 0:
                chain.append(w)
                w = self.parent[w]
            chain.reverse()
            guides = ""
            for k, u in enumerate(chain):
                last = self.children(self.parent[u])[-1] == u
                if k < len(chain) - 1:
                    guides += "    " if last else "│   "
                else:
                    guides += "└── " if last else "├── "
            label = ", ".join(self.labels(v, mark_root))
            out.append(f"{guides}{VERTEX}{' ' + label if label else ''}")
        return out


def draw(seq: tuple[int, ...] | list[int]) -> TreeDrawing:
    """The drawing of the free tree of level sequence ``seq`` (any rooting of it)."""
    seq = tuple(seq)
    adj = adjacency(seq)
    middle = centres(adj)
    top = max(middle, key=lambda c: canonical_level_sequence(_subtrees(adj, c)[1][c]))
    parent, canon = _subtrees(adj, top)
    order: list[int] = []  # the given vertices in drawing order
    stack = [top]
    while stack:
        v = stack.pop()
        order.append(v)
        kids = sorted((w for w in adj[v] if w != parent[v]), key=lambda w: canon[w])  # largest last: popped first
        stack.extend(kids)
    index = {v: k for k, v in enumerate(order)}
    parents = tuple(-1 if parent[v] < 0 else index[parent[v]] for v in order)
    depth: list[int] = []
    for k, p in enumerate(parents):
        depth.append(0 if p < 0 else depth[p] + 1)
    return TreeDrawing(seq, parents, tuple(depth), tuple(sorted(index[c] for c in middle)), index[0],
                       _layout(parents))


def _layout(parents: tuple[int, ...]) -> tuple[float, ...]:
    """x of every vertex: leaves at 0, 1, 2, … in drawing order, a parent above the
    middle of its first and last child (vertices are in depth-first order)."""
    children: list[list[int]] = [[] for _ in parents]
    for v, p in enumerate(parents):
        if p >= 0:
            children[p].append(v)
    x = [0.0] * len(parents)
    next_leaf = 0
    for v in range(len(parents)):  # leaves in depth-first order
        if not children[v]:
            x[v] = float(next_leaf)
            next_leaf += 1
    for v in reversed(range(len(parents))):  # children come after their parent
        if children[v]:
            x[v] = (x[children[v][0]] + x[children[v][-1]]) / 2
    return tuple(x)
