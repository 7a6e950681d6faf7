"""The energy conditions of one order as classes of rooted trees (definitions §3).

The terms of the energy condition of a free tree ``t̄`` are its distinct rootings ``u``,
and every rooted tree with ``n`` vertices is a rooting of exactly one free tree.  So the
terms of all conditions with ``n`` vertices are exactly the rooted trees with ``n``
vertices (within the degree bound), and listing the conditions means telling, for every
rooted tree, *which* free tree it roots and the parity of the distance from its root to
the designated centre.  No free tree is built:

* a tree whose deepest branch is at least two deeper than every other branch
  (``h1 − h2 ≥ 2``) has its centre inside that branch: move the root one edge towards it
  (``reroot(t, tall) = tall`` with ``t − tall`` attached — one product lookup);
* ``h1 − h2 = 1``: the root and the child ``tall`` are the two centres; the pair is
  represented by the larger id, and when the two halves are equal (``t − tall = tall``)
  the free tree is superfluous and gives no condition;
* ``h1 = h2``: the root is the centre.

Pointer jumping then takes every tree to its class representative in
``log₂(radius)`` vectorised rounds, with the parity of the path.  The representative is
a centre rooting, but for two centres it is the one with the larger *id*; the
designated rooting of definitions §3 (the larger *level sequence*) is settled only when
a condition is shown (:meth:`ConditionListing.record
<rkcheck.trees.listing.ConditionListing.record>`), flipping the sign of R when needed.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Iterator

import numpy as np

from rkcheck.trees.table import _CHUNK, TreeTable
from rkcheck.trees.terms import OrderTerms


def classify(table: TreeTable, n: int, last: bool = False,
             factors_out: tuple[np.ndarray, np.ndarray] | None = None) -> OrderTerms:
    """The conditions with ``n >= 3`` vertices as an :class:`~rkcheck.trees.terms.OrderTerms`.

    ``n`` may be one above the table's stored orders: its trees are then generated in
    chunks (:meth:`TreeTable.pairs`), classified, and kept only as terms.  ``last``: no
    order follows, so the table is reduced to its factors (:meth:`TreeTable.release`) as
    soon as the classes are known, before the terms are sorted (the memory peak).
    ``factors_out``: where to write the factors of an order beyond the table (a
    listing's own arrays, so that they are not copied there afterwards)."""
    stored = n <= table.max_order
    size = table.count(n) if stored else table.prepare_order(n)
    lo = table.first[n]
    walk = _CentreWalk(lo, size)
    for a, U, V, at in _chunks(table, n, stored, lo, size):
        walk.step(table, a, U, V, at)
    if last:
        table.release()  # from here on only the factors are needed: the memory peak follows
    U_all, V_all = (None, None) if stored else _term_factors(table, n, size, factors_out)
    rep = walk.representatives()
    cls, parity = walk.classes(rep["local"])
    counts = _class_sizes(cls, len(rep["local"]) + 1)[:len(rep["local"])]
    # the sign folds into the coefficient: index 2i is +(n−1)!/σ_i, 2i + 1 is its negative
    coefficient_index = walk.sigma_index
    coefficient_index *= 2
    coefficient_index += parity
    del parity
    return OrderTerms(
        vertices=n,
        first_id=lo if stored else None,
        left=U_all,
        right=V_all,
        condition=cls,
        coefficient_index=coefficient_index,
        coefficients=_signed_coefficients(walk.sigma_of, n, table.sigma_value),
        counts=counts.astype(np.int32),
        superfluous=walk.superfluous,
        rep_left=rep["left"].astype(np.int32),
        rep_right=rep["right"].astype(np.int32),
        tall=rep["tall"].astype(np.int32),
        rest=rep["rest"].astype(np.int32),
        max_degree=rep["max_degree"].astype(np.int16),
    )


def _chunks(table: TreeTable, n: int, stored: bool, lo: int,
            size: int) -> Iterator[tuple[int, np.ndarray, np.ndarray, dict[str, Any]]]:
    """``(offset, U, V, attributes)`` of the trees with n vertices, a chunk at a time:
    slices of the table when stored, else generated pairs."""
    if stored:
        for a in range(0, size, _CHUNK):
            b = min(size, a + _CHUNK)
            sl = slice(lo + a, lo + b)
            at = {k: getattr(table, k)[sl] for k in ("h1", "h2", "tall", "rest", "sigma", "nchild", "inner_max")}
            yield a, table.left[sl], table.right[sl], at
    else:
        a = 0
        for U, V in table.pairs(n):
            yield a, U, V, table.attributes(n, U, V)
            a += len(U)


_REP_KEYS = ("local", "left", "right", "tall", "rest", "max_degree")


class _CentreWalk:
    """One step of every rooting towards the centre of its free tree, with the parity of
    the step; the rootings that do not move are the classes' representatives."""

    def __init__(self, lo: int, size: int):
        self.lo = lo
        self.nxt = np.arange(lo, lo + size, dtype=np.int32)  # one step towards the centre (global ids)
        self.parity = np.zeros(size, dtype=np.int8)
        self.sigma_index = np.empty(size, dtype=np.int16)  # distinct σ per order: a few thousand
        self.sigma_of: dict[int, int] = {}
        self._sigma_sorted = np.zeros(0, dtype=np.int64)  # the keys of sigma_of, sorted
        self._sigma_ids_sorted = np.zeros(0, dtype=np.int16)  # and their indices
        self.parts: list[dict[str, np.ndarray]] = []  # the representatives, found chunk by chunk
        self.superfluous = 0

    def step(self, table: TreeTable, a: int, U: np.ndarray, V: np.ndarray, at: dict[str, np.ndarray]) -> None:
        gap = at["h1"] - at["h2"]
        off = np.flatnonzero(gap >= 1)
        tall, rest = at["tall"][off], at["rest"][off]
        other = table.insert(tall, rest)
        far = gap[off] >= 2
        move = far | (other > self.lo + a + off)  # two centres: the pair goes to the larger id
        self.nxt[a + off[move]] = other[move]
        self.parity[a + off[move]] = 1
        # a representative is a centre rooting that does not move; two equal halves make
        # the free tree superfluous (no condition)
        stays = np.ones(len(gap), dtype=bool)
        stays[off[move]] = False
        superfluous = np.zeros(len(gap), dtype=bool)
        superfluous[off[~far]] = rest[~far] == tall[~far]
        self.superfluous += int(np.count_nonzero(stays & superfluous))
        r = np.flatnonzero(stays & ~superfluous)
        two = gap[r] == 1
        self.parts.append({
            "local": (a + r).astype(np.int32), "left": U[r], "right": V[r],
            "tall": np.where(two, at["tall"][r], -1), "rest": np.where(two, at["rest"][r], -1),
            "max_degree": np.maximum(at["nchild"][r], at["inner_max"][r]),
        })
        self.sigma_index[a:a + len(gap)] = self._sigma_ids(at["sigma"])

    def _sigma_ids(self, sigma: np.ndarray) -> np.ndarray:
        """The index of each σ among the order's distinct values, numbered as they first
        appear (chunk by chunk, ascending within a chunk).  An order has a few hundred
        distinct σ: a binary search in them costs a quarter of sorting every chunk."""
        known, ids = self._sigma_sorted, self._sigma_ids_sorted
        pos = np.searchsorted(known, sigma)
        new = sigma if len(known) == 0 else sigma[known[np.minimum(pos, len(known) - 1)] != sigma]
        if len(new):
            # sorted and deduplicated by hand: np.unique would import numpy.ma (start-up)
            new = np.sort(new)
            for v in new[np.concatenate(([True], new[1:] != new[:-1]))].tolist():
                self.sigma_of.setdefault(v, len(self.sigma_of))
            if len(self.sigma_of) >= 2**14:  # pragma: no cover - far beyond 21 vertices
                raise OverflowError("too many distinct symmetry factors for an int16 index")
            known = self._sigma_sorted = np.array(sorted(self.sigma_of), dtype=np.int64)
            ids = self._sigma_ids_sorted = np.array([self.sigma_of[v] for v in known.tolist()], dtype=np.int16)
            pos = np.searchsorted(known, sigma)
        return ids[pos]

    def representatives(self) -> dict[str, np.ndarray]:
        """The representatives' local ids, factors and shape data, in id order."""
        if not self.parts:
            return {k: np.zeros(0, dtype=np.int32) for k in _REP_KEYS}
        rep = {k: np.concatenate([part[k] for part in self.parts]) for k in _REP_KEYS}
        self.parts = []
        return rep

    def classes(self, reps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Every rooting's class (superfluous trees: one extra bin, ``len(reps)``) and the
        parity of its path to the representative, by pointer jumping.

        In place, a chunk at a time: a chunk reads the (next, parity) pairs of the others
        as they stand, jumped already or not — each is the pair of one step along the
        path, written together — so every pass only shortens paths, until one changes
        nothing: every rooting then points at the end of its path.  No array of the
        order's size is allocated beside the walk's own."""
        nxt, parity = self.nxt, self.parity
        del self.nxt, self.parity  # the walk's arrays are the largest of the order: free early
        nxt -= self.lo
        moved = True
        while moved:
            moved = False
            for a in range(0, len(nxt), _CHUNK):
                here = nxt[a:a + _CHUNK]
                ahead = nxt[here]
                if np.array_equal(ahead, here):
                    continue
                parity[a:a + _CHUNK] ^= parity[here]
                nxt[a:a + _CHUNK] = ahead
                moved = True
        class_of = np.full(len(nxt), len(reps), dtype=np.int32)
        class_of[reps] = np.arange(len(reps), dtype=np.int32)
        for a in range(0, len(nxt), _CHUNK):  # the classes overwrite the pointers
            nxt[a:a + _CHUNK] = class_of[nxt[a:a + _CHUNK]]
        return nxt, parity


def _class_sizes(cls: np.ndarray, bins: int) -> np.ndarray:
    """The rootings per class, counted in chunks (``np.bincount`` widens its input to
    intp: a copy of twice the classes' size at once)."""
    sizes = np.zeros(bins, dtype=np.int64)
    for a in range(0, len(cls), _CHUNK):
        sizes += np.bincount(cls[a:a + _CHUNK], minlength=bins)
    return sizes


def _term_factors(table: TreeTable, n: int, size: int,
                  out: tuple[np.ndarray, np.ndarray] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The factors of the terms of an order beyond the table, generated again (cheaper
    than carrying them through the classification), into ``out`` when given."""
    U_all, V_all = out if out is not None else (np.empty(size, dtype=np.int32), np.empty(size, dtype=np.int32))
    if len(U_all) != size or len(V_all) != size:
        raise ValueError(f"the factor arrays must hold {size} rows")
    a = 0
    for U, V in table.pairs(n):
        U_all[a:a + len(U)], V_all[a:a + len(U)] = U, V
        a += len(U)
    table._lefts_sorted.clear()
    table._block_cache.pop(n, None)
    return U_all, V_all


def _signed_coefficients(sigma_of: dict[int, int], n: int, value_of: Callable[[int], int] = int) -> list[int]:
    """``±(n−1)!/σ`` for every distinct σ: index 2i positive, 2i + 1 negative
    (``value_of``: the exact σ of a key of the table's :attr:`~TreeTable.sigma`)."""
    factorial = math.factorial(n - 1)
    coefficients = [0] * (2 * len(sigma_of))
    for key, i in sigma_of.items():
        value = value_of(key)
        coefficients[2 * i] = factorial // value
        coefficients[2 * i + 1] = -(factorial // value)
    return coefficients
