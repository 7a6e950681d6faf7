"""The residues of a few conditions, from the weights of the trees their terms need only.

After one pass over the whole listing modulo a first prime, every condition whose residue
there is not zero is decided (it fails, :mod:`rkcheck.evaluation.modular`); the further
primes that prove the others zero are needed for those others only.  They are usually
few (the conditions a method satisfies: 10 of 317 955 at 19 vertices for Gauss-3), and
their terms need the weights of few trees: the factors of each term, the factors of those
and so on (18 thousand trees of 2.7 million there).  :class:`Subset` finds them once and
evaluates them in any channels, by the same recurrences as a pass over the listing
(:mod:`rkcheck.evaluation.algorithm`), so every residue is the one that pass gives.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from rkcheck.evaluation.protocols import SubsetContext

#: rows of a level of trees, or of terms, computed at once (as in the full pass)
_CHUNK = 1 << 14

#: terms' conditions read at once when selecting them (bounds the temporaries)
_SCAN = 1 << 18


@dataclass
class _OrderPart:
    """The selected terms of one order: factor positions in the subset's trees, the
    coefficient index of each term, its condition among the selected ones, and those
    conditions' indices in the order."""

    terms: Any  # the order's OrderTerms (its coefficients)
    left: np.ndarray  # positions of u in Subset.trees, per term u ∘ v
    right: np.ndarray  # positions of v
    coefficient: np.ndarray
    condition: np.ndarray  # 0 … conditions − 1
    selected: np.ndarray  # the selected conditions, sorted: condition i is selected[i]
    _own: "SelectedTerms | None" = None

    @property
    def conditions(self) -> int:
        return len(self.selected)

    @property
    def own_terms(self) -> "SelectedTerms":
        """These terms read as an order of their own (cached)."""
        if self._own is None:
            self._own = SelectedTerms(self)
        return self._own


class SelectedTerms:
    """The selected terms of one order read as an order's terms of their own, their
    conditions renumbered: what :func:`~rkcheck.evaluation.digit_sums.multipliers` reads,
    so that the digit balls plan the sums of the selected conditions without planning
    the whole order's."""

    def __init__(self, part: _OrderPart):
        self.part = part
        self.vertices = int(part.terms.vertices)
        self.coefficients = part.terms.coefficients
        self.rows = len(part.condition)
        self.counts = np.bincount(part.condition, minlength=part.conditions)

    def __len__(self) -> int:
        return self.part.conditions

    def block(self, i0: int, i1: int) -> tuple[np.ndarray, np.ndarray]:
        return self.conditions(i0, i1), self.part.coefficient[i0:i1]

    def conditions(self, i0: int, i1: int) -> np.ndarray:
        return self.part.condition[i0:i1].astype(np.intp)


class Subset:
    """The trees and terms of the conditions ``selected`` (``{vertices: sorted condition
    indices}``) of ``listing``: :meth:`build` returns None when they are not few (more
    than ``1/share`` of the orders' terms or of the trees below them), where a pass over
    the listing costs less than gathering them and their arrays would add to its peak
    memory (about 30 bytes a term)."""

    def __init__(self, trees: np.ndarray, levels: list[tuple[int, int, np.ndarray, np.ndarray]],
                 orders: dict[int, _OrderPart], s: int):
        self.trees = trees  # sorted tree ids (τ first): the closure under Butcher factors
        self.levels = levels  # (lo, hi, left positions, right positions) per number of vertices ≥ 2
        self.orders = orders
        self.s = s

    @staticmethod
    def build(listing: Any, selected: dict[int, np.ndarray], s: int, share: int = 32) -> "Subset | None":
        first = listing.first
        # the terms counted before any is gathered: when they are many, nothing is spent
        picked = sum(int(listing.orders[n].counts[c].sum(dtype=np.int64)) for n, c in selected.items())
        if picked * share > sum(listing.orders[n].rows for n in selected) and picked > _CHUNK:
            return None
        mark = np.zeros(first[max(selected) if selected else 2], dtype=bool)
        mark[0] = True  # τ
        chosen: dict[int, tuple[Any, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = {}
        for n, conditions in selected.items():
            terms = listing.orders[n]
            where = np.full(len(terms) + 1, -1, dtype=np.int32)  # the superfluous bin stays out
            where[conditions] = np.arange(len(conditions), dtype=np.int32)
            index = np.concatenate([np.flatnonzero(where[terms.conditions(i, min(i + _SCAN, terms.rows))] >= 0) + i
                                    for i in range(0, terms.rows, _SCAN)] or [np.zeros(0, dtype=np.intp)])
            condition, coefficient = terms.at(index)
            if terms.first_id is not None:  # the trees themselves: their factors in the listing
                u, v = listing.left[terms.first_id + index], listing.right[terms.first_id + index]
            else:
                assert terms.left is not None and terms.right is not None
                u, v = terms.left[index], terms.right[index]
            mark[u] = mark[v] = True
            chosen[n] = (terms, u, v, coefficient, where[condition], np.asarray(conditions))
        for k in range(len(first) - 2, 1, -1):  # every tree's factors, from the largest trees down
            lo, hi = first[k], min(first[k + 1], len(mark))
            if lo >= hi:
                continue
            ids = np.flatnonzero(mark[lo:hi]) + lo
            mark[listing.left[ids]] = mark[listing.right[ids]] = True
        trees = np.flatnonzero(mark)
        if len(trees) * share > len(mark) and len(trees) > _CHUNK:
            return None
        def position(ids: np.ndarray) -> np.ndarray:  # in ``trees`` (int32: a term's share of memory)
            return np.searchsorted(trees, ids).astype(np.int32)

        levels = []
        for k in range(2, len(first) - 1):
            lo, hi = (int(x) for x in np.searchsorted(trees, [first[k], first[k + 1]]))
            if hi > lo:
                ids = trees[lo:hi]
                levels.append((lo, hi, position(listing.left[ids]), position(listing.right[ids])))
        orders = {n: _OrderPart(terms, position(u), position(v), coefficient, condition, conditions)
                  for n, (terms, u, v, coefficient, condition, conditions) in chosen.items()}
        return Subset(trees, levels, orders, s)

    def channel_bytes(self) -> int:
        """Memory one channel takes (its weights, int32)."""
        return 4 * len(self.trees) * (2 * self.s + 2)

    def residues(self, ctx: SubsetContext) -> dict[int, Any]:
        """``{n: sums of the selected conditions}`` in ``ctx``: residues ``(selected
        conditions, channels)`` in the channels of a
        :class:`~rkcheck.evaluation.channels.PrimeChannels`, balls in the certified
        contexts."""
        size = len(self.trees)
        phi, psi, a, w = ctx.vectors(size, self.s), ctx.vectors(size, self.s), ctx.scalars(size), ctx.scalars(size)
        one = ctx.ones(1, self.s)  # τ, at position 0
        ctx.put(phi, 0, one)
        ctx.put(psi, 0, ctx.matvec(one))
        ctx.put(a, 0, ctx.dot(one))
        ctx.put(w, 0, ctx.one(1))
        for lo, hi, left, right in self.levels:  # by vertices: a tree's factors are done before it
            for c0 in range(lo, hi, _CHUNK):
                c1 = min(hi, c0 + _CHUNK)
                u, v = left[c0 - lo:c1 - lo], right[c0 - lo:c1 - lo]
                ctx.put(w, c0, ctx.mul(ctx.take(w, u), ctx.take(a, v)))
                x = ctx.mul(ctx.take(phi, u), ctx.take(psi, v))
                ctx.put(a, c0, ctx.dot(x))
                ctx.put(phi, c0, x)
                ctx.put(psi, c0, ctx.matvec(x))
        out = {}
        for n, part in self.orders.items():
            acc = ctx.selected_sums(part)
            for t0 in range(0, len(part.left), _CHUNK):
                t1 = min(t0 + _CHUNK, len(part.left))
                w_terms = ctx.mul(ctx.take(w, part.left[t0:t1]), ctx.take(a, part.right[t0:t1]))
                ctx.add_selected(acc, w_terms, part, t0, t1)
            out[n] = ctx.finish_selected(acc, part)
        return out
