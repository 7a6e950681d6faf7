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

import numpy as np

from rkcheck.trees.table import _CHUNK, TreeTable
from rkcheck.trees.terms import OrderTerms


def classify(table: TreeTable, n: int, last: bool = False) -> OrderTerms:
    """The conditions with ``n >= 3`` vertices as an :class:`~rkcheck.trees.terms.OrderTerms`.

    ``n`` may be one above the table's stored orders: its trees are then generated in
    chunks (:meth:`TreeTable.pairs`), classified, and kept only as terms.  ``last``: no
    order follows, so the table is reduced to its factors (:meth:`TreeTable.release`) as
    soon as the classes are known, before the terms are sorted (the memory peak)."""
    stored = n <= table.max_order
    size = table.count(n) if stored else table.prepare_order(n)
    lo = table.first[n]
    nxt = np.arange(lo, lo + size, dtype=np.int32)  # one step towards the centre (global ids)
    parity = np.zeros(size, dtype=np.int8)
    sigma_index = np.empty(size, dtype=np.int16)  # distinct σ per order: a few thousand
    sigma_of: dict[int, int] = {}
    rep_parts: list[dict[str, np.ndarray]] = []  # the representatives, found chunk by chunk
    n_superfluous = 0

    def chunks():
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

    for a, U, V, at in chunks():
        gap = at["h1"] - at["h2"]
        off = np.flatnonzero(gap >= 1)
        tall, rest = at["tall"][off], at["rest"][off]
        other = table.insert(tall, rest)
        far = gap[off] >= 2
        move = far | (other > lo + a + off)  # two centres: the pair goes to the larger id
        nxt[a + off[move]] = other[move]
        parity[a + off[move]] = 1
        # a representative is a centre rooting that does not move; two equal halves make
        # the free tree superfluous (no condition)
        stays = np.ones(len(gap), dtype=bool)
        stays[off[move]] = False
        superfluous = np.zeros(len(gap), dtype=bool)
        superfluous[off[~far]] = rest[~far] == tall[~far]
        n_superfluous += int(np.count_nonzero(stays & superfluous))
        r = np.flatnonzero(stays & ~superfluous)
        two = gap[r] == 1
        rep_parts.append({
            "local": (a + r).astype(np.int32), "left": U[r], "right": V[r],
            "tall": np.where(two, at["tall"][r], -1), "rest": np.where(two, at["rest"][r], -1),
            "max_degree": np.maximum(at["nchild"][r], at["inner_max"][r]),
        })
        values, inverse = np.unique(at["sigma"], return_inverse=True)
        ids = np.array([sigma_of.setdefault(int(v), len(sigma_of)) for v in values], dtype=np.int32)
        if len(sigma_of) >= 2**14:  # pragma: no cover - far beyond 21 vertices
            raise OverflowError("too many distinct symmetry factors for an int16 index")
        sigma_index[a:a + len(gap)] = ids[inverse]
    if last:
        table.release()  # from here on only the factors are needed: the memory peak follows
    U_all = V_all = None
    if not stored:  # the factors of the terms, generated again (cheaper than carrying them)
        U_all = np.empty(size, dtype=np.int32)
        V_all = np.empty(size, dtype=np.int32)
        a = 0
        for U, V in table.pairs(n):
            U_all[a:a + len(U)], V_all[a:a + len(U)] = U, V
            a += len(U)
        table._lefts_sorted.clear()
        table._block_cache.pop(n, None)
    rep = {k: np.concatenate([part[k] for part in rep_parts]) for k in rep_parts[0]} if rep_parts else None
    del rep_parts
    reps = rep["local"] if rep else np.zeros(0, dtype=np.int32)
    nxt -= lo
    while True:  # pointer jumping: every tree to its representative, with the parity
        jumped = nxt[nxt]
        if np.array_equal(jumped, nxt):
            break
        parity ^= parity[nxt]
        nxt = jumped
    del jumped
    class_of = np.full(size, len(reps), dtype=np.int32)  # superfluous trees: one extra bin
    class_of[reps] = np.arange(len(reps), dtype=np.int32)
    cls = class_of[nxt]
    del class_of, nxt
    counts = np.bincount(cls, minlength=len(reps) + 1)[:len(reps)]
    # the sign folds into the coefficient: index 2i is +(n−1)!/σ_i, 2i + 1 is its negative
    coefficient_index = sigma_index
    coefficient_index *= 2
    coefficient_index += parity
    del parity
    empty = np.zeros(0, dtype=np.int32)
    factorial = math.factorial(n - 1)
    coefficients = [0] * (2 * len(sigma_of))
    for value, i in sigma_of.items():
        coefficients[2 * i] = factorial // value
        coefficients[2 * i + 1] = -(factorial // value)
    return OrderTerms(
        vertices=n,
        first_id=lo if stored else None,
        left=U_all,
        right=V_all,
        condition=cls,
        coefficient_index=coefficient_index,
        coefficients=coefficients,
        counts=counts.astype(np.int32),
        superfluous=n_superfluous,
        rep_left=(rep["left"] if rep else empty).astype(np.int32),
        rep_right=(rep["right"] if rep else empty).astype(np.int32),
        tall=(rep["tall"] if rep else empty).astype(np.int32),
        rest=(rep["rest"] if rep else empty).astype(np.int32),
        max_degree=(rep["max_degree"] if rep else empty).astype(np.int16),
    )
