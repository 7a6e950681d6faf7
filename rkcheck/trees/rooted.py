"""Rooted trees: integer ids, level sequences, bracket notation, σ and γ (definitions §2).

Conventions (the same as RootedTrees.jl, so ids can be pasted between tools):

* A rooted tree is written as its **level sequence**: the depth of every vertex in
  depth-first order, the root at depth 1.  The **canonical** level sequence is the
  lexicographically largest one, obtained by listing the subtrees of every vertex in
  non-increasing lexicographic order of their own canonical sequences
  (``[[τ]τ]`` is ``(1, 2, 3, 2)``).
* Bracket notation: ``τ``, ``[τ]``, ``[τ²]``, ``[[τ]τ]``, ... with the subtrees in
  canonical order and repeats written as powers.
* ``σ(τ) = 1``, ``σ([t1^r1 … tp^rp]) = Π r_i! σ(t_i)^r_i`` (symmetry);
  ``γ(τ) = 1``, ``γ(t) = |t| Π γ(t_i)`` (density, for the classical order conditions).

Internally every tree of a :class:`RootedTreeTable` has a small integer **id**; a tree
is its multiset of children, stored as the tuple of child ids in *decreasing id order*
(its ``key``).  Ids grow with the number of vertices, so that order puts bigger
subtrees first.  The table is built by Butcher products ``t = u ∘ v`` (``v`` attached
to the root of ``u``) where ``v`` is the child of ``t`` with the smallest id, which
generates every tree exactly once and gives the recursion
``Φ(t) = Φ(u) ⊙ AΦ(v)`` used by :mod:`rkcheck.evaluation.backends`.  A bound on the number of
children of every vertex is applied *during* generation: trees it excludes are never
built.
"""

from __future__ import annotations

import bisect
from typing import Sequence

TAU = 0  # id of the one-vertex tree τ in every table

_SUPERSCRIPTS = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


class RootedTreeTable:
    """All rooted trees with at most ``max_order`` vertices and at most
    ``max_children`` children at every vertex (None = no bound), with integer ids.

    Per id: ``order`` (vertices), ``children`` (key: child ids, decreasing),
    ``height`` (τ has height 0), ``sigma``, ``gamma``, and the Butcher factors
    ``left``/``right`` with ``t = left ∘ right`` (both -1 for τ).
    """

    def __init__(self, max_order: int, max_children: int | None = None, growable: bool = False):
        if max_order < 1:
            raise ValueError("max_order must be at least 1")
        self.max_order = 1
        self.max_children = max_children
        #: a growable table may gain orders later (:meth:`grow_to`), so weight caches
        #: must keep the intermediate vectors of its top order
        self.growable = growable
        self.order: list[int] = [1]
        self.children: list[tuple[int, ...]] = [()]
        self.height: list[int] = [0]
        self.sigma: list[int] = [1]
        self.gamma: list[int] = [1]
        self.left: list[int] = [-1]
        self.right: list[int] = [-1]
        self.index: dict[tuple[int, ...], int] = {(): TAU}
        # ids of each order form a contiguous range: by_order[n] = range(first, last+1)
        self.first_id: list[int] = [0, 0]  # first_id[n] for n >= 1; sentinel at n = 0
        self._level_sequences: dict[int, tuple[int, ...]] = {TAU: (1,)}
        self._lefts_cache: dict[int, list[tuple[float, int]]] = {}
        self.first_id.append(len(self.order))
        self.grow_to(max_order)

    def grow_to(self, max_order: int) -> None:
        """Add the trees of every order up to ``max_order`` (no-op if already there)."""
        for n in range(self.max_order + 1, max_order + 1):
            self.first_id.pop()  # the sentinel "first id of order max_order + 1"
            self._grow(n)
            self.first_id.append(len(self.order))
            self.max_order = n

    # -------------------------------------------------------------- generation

    def ids_of_order(self, n: int) -> range:
        """The ids of the trees with exactly ``n`` vertices."""
        if n < 1 or n > self.max_order:
            return range(0)
        return range(self.first_id[n], self.first_id[n + 1])

    def _grow(self, n: int) -> None:
        self.first_id.append(len(self.order))
        bound = self.max_children
        if bound == 0:
            return
        # Left factors of each order, sorted by their smallest child id (τ: +inf), so
        # that "smallest child of u >= id of v" is a suffix found by bisection.
        for r in range(n - 1, 0, -1):  # order of the right factor v, big subtrees first
            lefts = self._lefts_by_min_child(n - r)
            mins = [m for m, _ in lefts]
            for v in self.ids_of_order(r):
                for _, u in lefts[bisect.bisect_left(mins, v):]:
                    key = self.children[u] + (v,)
                    if bound is not None and len(key) > bound:
                        continue
                    self._add(key, u, v, n)

    def _lefts_by_min_child(self, n: int) -> list[tuple[float, int]]:
        # cached on the instance (an lru_cache on the method would keep every table alive)
        cached = self._lefts_cache.get(n)
        if cached is not None:
            return cached
        out = []
        for u in self.ids_of_order(n):
            key = self.children[u]
            out.append((key[-1] if key else float("inf"), u))
        out.sort()
        self._lefts_cache[n] = out
        return out

    def _add(self, key: tuple[int, ...], u: int, v: int, n: int) -> None:
        t = len(self.order)
        self.order.append(n)
        self.children.append(key)
        self.height.append(max(self.height[u], self.height[v] + 1))
        self.sigma.append(self.sigma[u] * self.sigma[v] * key.count(v))
        self.gamma.append(self.gamma[u] * self.gamma[v] * n // self.order[u])
        self.left.append(u)
        self.right.append(v)
        self.index[key] = t

    def __len__(self) -> int:
        return len(self.order)

    def factor_arrays(self):
        """numpy arrays (left, right) of the Butcher factors of every id (rebuilt when the
        table has grown), for vectorised weight recursions."""
        import numpy as np

        cached = getattr(self, "_factor_arrays", None)
        if cached is None or len(cached[0]) != len(self.order):
            cached = (np.array(self.left, dtype=np.int64), np.array(self.right, dtype=np.int64))
            self._factor_arrays = cached
        return cached

    # ------------------------------------------------------------------ lookup

    def lookup(self, key: tuple[int, ...]) -> int:
        """Id of the tree whose children are ``key`` (any order); KeyError if absent."""
        return self.index[tuple(sorted(key, reverse=True))]

    def id_of_level_sequence(self, seq: Sequence[int]) -> int:
        """Id of the tree with level sequence ``seq`` (any valid, not only canonical)."""
        return self.lookup_forest(_split_children(tuple(seq)))

    def lookup_forest(self, subtrees: Sequence[tuple[int, ...]]) -> int:
        return self.lookup(tuple(self.id_of_level_sequence(sub) for sub in subtrees))

    # ----------------------------------------------------------------- display

    def level_sequence(self, t: int) -> tuple[int, ...]:
        """Canonical (lexicographically largest) level sequence of tree ``t``."""
        seq = self._level_sequences.get(t)
        if seq is None:
            seq = level_sequence_of_forest([self.level_sequence(c) for c in self.children[t]])
            self._level_sequences[t] = seq
        return seq

    def bracket(self, t: int) -> str:
        """Butcher's bracket notation of tree ``t`` (``[[τ]τ²]``)."""
        return bracket_of_forest([self.level_sequence(c) for c in self.children[t]])


# ---------------------------------------------------------- free functions


def level_sequence_of_forest(subtrees: Sequence[tuple[int, ...]]) -> tuple[int, ...]:
    """Canonical level sequence of the tree whose root carries ``subtrees``
    (each a canonical level sequence with root depth 1)."""
    out = [1]
    for sub in sorted(subtrees, reverse=True):
        out.extend(d + 1 for d in sub)
    return tuple(out)


def bracket_of_forest(subtrees: Sequence[tuple[int, ...]]) -> str:
    """Bracket notation of the tree whose root carries ``subtrees`` (level sequences)."""
    if not subtrees:
        return "τ"
    parts: list[str] = []
    ordered = sorted(subtrees, reverse=True)
    i = 0
    while i < len(ordered):
        j = i
        while j < len(ordered) and ordered[j] == ordered[i]:
            j += 1
        inner = bracket_of_forest(_split_children(ordered[i]))
        parts.append(inner + (str(j - i).translate(_SUPERSCRIPTS) if j - i > 1 else ""))
        i = j
    return "[" + "".join(parts) + "]"


def bracket(seq: Sequence[int]) -> str:
    """Bracket notation of a level sequence (any valid one: it is canonicalised first,
    so every rooting of the same tree prints the same way)."""
    return bracket_of_forest(_split_children(canonical_level_sequence(seq)))


def _split_children(seq: tuple[int, ...]) -> list[tuple[int, ...]]:
    """The subtrees of the root of a level sequence, each re-based to root depth 1."""
    if not seq or seq[0] < 1:
        raise ValueError("a level sequence starts at the root")
    root = seq[0]
    subs: list[tuple[int, ...]] = []
    start = None
    for i in range(1, len(seq)):
        if seq[i] <= root:
            raise ValueError("a level sequence has exactly one vertex at the root's depth")
        if seq[i] == root + 1:
            if start is not None:
                subs.append(tuple(d - root for d in seq[start:i]))
            start = i
        elif seq[i] > seq[i - 1] + 1:
            raise ValueError("a level sequence can go down only one level at a time")
    if start is not None:
        subs.append(tuple(d - root for d in seq[start:]))
    return subs


def children_of_level_sequence(seq: Sequence[int]) -> list[tuple[int, ...]]:
    """Public form of the subtree split: ``B₋(t)`` as level sequences (definitions §2)."""
    return _split_children(tuple(seq))


def canonical_level_sequence(seq: Sequence[int]) -> tuple[int, ...]:
    """The canonical form of any valid level sequence."""
    return level_sequence_of_forest([canonical_level_sequence(s) for s in _split_children(tuple(seq))])


def parse_level_sequence(text: str) -> tuple[int, ...]:
    """Parse ``"1,2,3,2"``, ``"[1, 2, 3, 2]"`` or ``"1 2 3 2"``; raises ValueError."""
    cleaned = text.strip().strip("[]()")
    parts = [p for p in cleaned.replace(",", " ").split() if p]
    if not parts or not all(p.isdigit() for p in parts):
        raise ValueError(f"not a level sequence: {text!r} (expected e.g. 1,2,3,2)")
    seq = tuple(int(p) for p in parts)
    _split_children(seq)  # validates
    if seq[0] != 1:
        raise ValueError("a level sequence starts with the root at depth 1")
    return seq


def sigma_of_forest(branches: Sequence[int], table: RootedTreeTable) -> int:
    """σ of the tree whose root carries the subtrees ``branches`` (ids of ``table``, equal
    ids adjacent, as in a key): Π r_i! σ(t_i)^r_i, accumulated run by run."""
    sigma = table.sigma
    result = 1
    run = 0
    prev = -1
    for b in branches:
        run = run + 1 if b == prev else 1
        prev = b
        result *= sigma[b] * run
    return result

