"""Conditions named for people, whatever enumerates them: the part of a listing's
interface that reports read (definitions §3).

A listing — by rooted trees (:class:`~rkcheck.trees.listing.ConditionListing`) or by
centroid (:class:`~rkcheck.trees.centroid.CentroidListing`) — says how condition ``k``
of the order with ``n`` vertices is named (:meth:`ConditionNames._describe`: its free
tree, and the sign that turns the residual it evaluates into that of the designated
rooting); this class remembers the names, counts the conditions, and orders them as
every report lists them (by canonical id).
"""

from __future__ import annotations

from typing import Any, Iterator

import numpy as np

from rkcheck.trees.free import FreeTree

#: conditions whose names a listing remembers (about 300 bytes each)
NAMED_CONDITIONS = 1 << 16


class ConditionNames:
    """Names, counts and presentation order of a listing's conditions.  A subclass sets
    ``order``, ``orders`` (vertices → an order with ``len``) and ``_conditions`` (the
    counts by vertices), calls :meth:`_init_names`, and defines :meth:`_describe`."""

    order: int
    orders: Any
    _conditions: tuple[int, ...]

    def _init_names(self) -> None:
        # conditions already named (free tree and designated sign), shared by every
        # tableau checked against this listing: a scan names the same ones file after file
        self._named: dict[tuple[int, int], tuple[FreeTree, int]] = {}
        self._presentations: dict[int, np.ndarray] = {}

    def _describe(self, n: int, k: int) -> tuple[FreeTree, int]:
        """The free tree of condition ``k`` and the sign of :meth:`flip`, worked out."""
        raise NotImplementedError

    # --------------------------------------------------------------- counts

    def __len__(self) -> int:
        return sum(self.counts_by_order().values())

    def counts_by_order(self) -> dict[int, int]:
        """Conditions per energy order ``2 … N`` (vertices − 1), counted, not built."""
        if not self.orders:
            return {k: 0 for k in range(2, self.order + 1)}
        return {k: self._conditions[k + 1] for k in range(2, self.order + 1)}

    # --------------------------------------------------------------- names

    def _name(self, n: int, k: int) -> tuple[FreeTree, int]:
        """:meth:`_describe`, remembered (up to NAMED_CONDITIONS of them: a listing lives
        as long as the process)."""
        named = self._named.get((n, k))
        if named is None:
            named = self._describe(n, k)
            if len(self._named) < NAMED_CONDITIONS:
                self._named[(n, k)] = named
        return named

    def record(self, n: int, k: int) -> FreeTree:
        """Condition ``k`` of the order with ``n`` vertices, for people."""
        return self._name(n, k)[0]

    def flip(self, n: int, k: int) -> int:
        """``±1``: the residual of condition ``k`` for its designated rooting is this sign
        times the residual the evaluation computes (of a representative rooting, or at the
        centroid)."""
        return self._name(n, k)[1]

    def records(self, n: int) -> list[FreeTree]:
        """The conditions with ``n`` vertices in listing order."""
        return [tree for tree, _ in self.named(n)]

    def named(self, n: int) -> list[tuple[FreeTree, int]]:
        """``(free tree, flip)`` of every condition with ``n`` vertices in listing order:
        one naming each, for a reader of a whole order beyond NAMED_CONDITIONS, which
        would otherwise name a condition again for its flip."""
        return [self._name(n, k) for k in range(len(self.orders[n]))] if n in self.orders else []

    def presentation(self, n: int, records: list[FreeTree] | None = None) -> np.ndarray:
        """The ``k`` of the conditions with ``n`` vertices by canonical id (level
        sequence), as every report lists them; ``records``: :meth:`records` of ``n``, when
        the caller has them.  Remembered for orders of at most NAMED_CONDITIONS."""
        got = self._presentations.get(n)
        if got is None:
            recs = self.records(n) if records is None else records
            got = np.array(sorted(range(len(recs)), key=lambda k: recs[k].level_sequence), dtype=np.int64)
            got.flags.writeable = False  # shared by every result read against this listing
            if len(got) <= NAMED_CONDITIONS:
                self._presentations[n] = got
        return got

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
