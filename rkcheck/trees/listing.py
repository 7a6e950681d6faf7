"""The energy conditions up to an order, listed as flat arrays (definitions §3).

A :class:`ConditionListing` for ``(N, m)`` holds what evaluating the conditions needs and
nothing more:

* the Butcher factors ``left``/``right`` of every rooted tree with at most ``N`` vertices
  within the degree bound (the trees whose weights later terms use);
* per number of vertices ``n = 3 … N+1`` an :class:`OrderTerms`: the factors ``(u, v)``
  of every term ``u ∘ v`` sorted by condition, the index of its ``(n−1)!/σ`` among the
  order's distinct values, its sign, and per condition the representative's factors and
  (for two centres) the data that settle the designated rooting.

The trees with ``N + 1`` vertices, the largest set by far (35 million at order 20), are
never stored as a table: they are generated in chunks, classified (:mod:`.classes`) and
kept only as terms, their right factors in 16 bits each (:mod:`.factors`).  Building it is the "listing" cost of a check; it does not depend on
the tableau and is shared by every check of the same ``(N, m)``.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from itertools import groupby
from operator import itemgetter
from typing import Callable, Iterator

import numpy as np

from rkcheck.trees.classes import classify
from rkcheck.trees.counting import condition_counts, listing_size, term_counts
from rkcheck.trees.factors import RightFactors
from rkcheck.trees.free import FreeTree
from rkcheck.trees.naming import ConditionNames
from rkcheck.trees.rooted import bracket_of_runs, level_sequence_of_forest
from rkcheck.trees.stored import ListingStore, from_record, record_key, to_record
from rkcheck.trees.table import TreeTable
from rkcheck.trees.terms import OrderTerms

#: where listings are kept between runs when a listing is not given a store of its own
#: (the CLI sets the user's cache: :func:`use_store`); None: nowhere
_default_store: ListingStore | None = None


def use_store(store: ListingStore | None) -> ListingStore | None:
    """Keep the listings built from now on in ``store`` (None: nowhere); returns the
    previous one.  Listings already in this process's memory are not affected."""
    global _default_store
    previous, _default_store = _default_store, store
    return previous


def current_store() -> ListingStore | None:
    """Where listings built from now on are kept (:func:`use_store`), if anywhere."""
    return _default_store


class _Orders(Mapping[int, OrderTerms]):
    """The listing's orders by vertices: every key is known at once, an order is built
    (or loaded) the first time it is looked up, with every order below it."""

    def __init__(self, listing: "ConditionListing", keys: range):
        self._listing, self._keys = listing, keys
        self._built: dict[int, OrderTerms] = {}

    def __getitem__(self, n: int) -> OrderTerms:
        if n not in self._keys:
            raise KeyError(n)
        if n not in self._built:
            self._listing.ensure(n)
        return self._built[n]

    def __contains__(self, n: object) -> bool:
        return n in self._keys

    def __iter__(self) -> Iterator[int]:
        return iter(self._keys)

    def __len__(self) -> int:
        return len(self._keys)


class ConditionListing(ConditionNames):
    """All energy conditions with ``3 … N+1`` vertices whose free trees have maximum
    degree ``<= degree`` (None: no bound), built order by order as they are asked for.

    ``orders[n]`` builds the conditions with ``n`` vertices and every order below (a
    check that stops at a low order never builds the high ones); :meth:`ensure` does the
    same explicitly.  The counts (``len``, :meth:`counts_by_order`) come from generating
    functions and build nothing.  With a ``store`` each order is read from it when it
    holds a valid record and saved to it when built."""

    def __init__(self, order: int, degree: int | None, store: ListingStore | None = None):
        if order < 1:
            raise ValueError("order must be at least 1")
        if degree is not None and degree < 1:
            raise ValueError("degree must be at least 1")
        self.order = order
        self.degree = degree
        self._store = store if store is not None else _default_store
        self._ls_cache: dict[int, tuple[int, ...]] = {0: (1,)}
        self._bracket_cache: dict[int, str] = {0: "τ"}
        self._init_names()
        self._table: TreeTable | None = None
        self.cache_hits: list[int] = []  # vertices of the orders read from the store
        self.store_notes: list[str] = []  # why the store declined an order (ListingStore.save)
        self.right: np.ndarray | RightFactors  # every tree's right factor, by id
        top = order + 1
        if degree is not None and degree < 2:  # no conditions: only the trees τ and [τ]
            table = TreeTable(order, degree, degree - 1)
            self.first, self.left, self.right = list(table.first), table.left, table.right
            self._right_below = table.right
            self.orders = _Orders(self, range(0))
            self._built = top
            return
        counts = term_counts(top, degree)
        self.first = [0, 0]
        for n in range(1, top + 1):
            self.first.append(self.first[-1] + counts[n])
        self.left = np.empty(self.first[top + 1], dtype=np.int32)
        # the right factors below the top order in a plain array (a tree table grows in
        # it), the top order's set when it is built or read (RightFactors: 16 bits a term)
        self._right_below = np.empty(self.first[top] if top >= 3 else self.first[top + 1], dtype=np.int32)
        self.right = (RightFactors(self._right_below, self.first[top + 1] - self.first[top])
                      if top >= 3 else self._right_below)
        self.left[0] = self._right_below[0] = -1  # τ
        if top >= 2:
            self.left[1] = self._right_below[1] = 0  # [τ] = τ ∘ τ
        self._conditions = condition_counts(top, degree)
        self.orders = _Orders(self, range(3, top + 1))
        self._built = 2

    def __reduce__(self) -> tuple[Callable[[int, int | None], ConditionListing], tuple[int, int | None]]:
        # a listing is determined by (order, degree): send the key, rebuild (cached) there
        return _shared_listing, (self.order, self.degree)

    # --------------------------------------------------------------- building

    def ensure(self, n: int) -> None:
        """Build (or load) every order up to ``n`` vertices."""
        for k in range(self._built + 1, min(n, self.order + 1) + 1):
            self.orders._built[k] = self._build(k)
            self._built = k

    def complete(self) -> "ConditionListing":
        """Every order built; returns the listing."""
        self.ensure(self.order + 1)
        return self

    def _build(self, n: int) -> OrderTerms:
        lo, hi = self.first[n], self.first[n + 1]
        terms = self._load(n)
        if terms is not None:
            # a tree table of the orders below, if any, is grown only when an order is
            # missing from the store (it then regrows through the ones read)
            if n > self.order:
                self._table = None
            self.cache_hits.append(n)
            terms.pack()
            return terms
        table = self._table
        if table is None:  # the first order built here: the table of the orders below, anew
            m = self.degree
            table = self._table = TreeTable(1, root_bound=m, inner_bound=None if m is None else m - 1,
                                            capacity=self.first[self.order + 1], factors=(self.left, self._right_below))
        table.grow_to(min(n, self.order))
        if n <= self.order:
            if table.first[n:n + 2] != [lo, hi]:  # pragma: no cover - counted = generated
                raise AssertionError(f"the tree table disagrees with the counts at {n} vertices")
            terms = classify(table, n)
            right = self._right_below[lo:hi]
        else:  # the top order is never stored in the table: its factors go straight here
            right = np.empty(hi - lo, dtype=np.int32)  # until the record is saved: then 16 bits
            terms = classify(table, n, last=True, factors_out=(self.left[lo:hi], right))
            self._table = None
        if table.left is not self.left:  # pragma: no cover - the capacity is exact
            raise AssertionError("the tree table outgrew its capacity")
        terms.first_id, terms.left, terms.right = lo, None, None
        if self._stored(n):
            assert self._store is not None
            note = self._store.save(record_key(n, self.degree), *to_record(self.left[lo:hi], right, terms))
            if note and note not in self.store_notes:
                self.store_notes.append(note)
        terms.pack()  # after the record: the file keeps the two arrays apart
        if n > self.order:
            self._set_top_right(right)
        return terms

    def _set_top_right(self, right: np.ndarray) -> None:
        """The right factors of the top order, into :attr:`right`."""
        assert isinstance(self.right, RightFactors)
        self.right.set_top(right)

    def _load(self, n: int) -> OrderTerms | None:
        """The order with ``n`` vertices from the store, when it holds a valid record."""
        if not self._stored(n):
            return None
        assert self._store is not None
        lo, hi = self.first[n], self.first[n + 1]
        # the factors are read straight into the listing's arrays (no second copy of the
        # largest order's in memory); a record found invalid leaves them to the build
        top = n > self.order  # its right factors are read apart, then kept in 16 bits
        into = {"left": self.left[lo:hi]} if top else {"left": self.left[lo:hi], "right": self._right_below[lo:hi]}
        got = self._store.load(record_key(n, self.degree), into)
        if got is None:
            return None
        record = from_record(n, lo, hi - lo, self._conditions[n], *got)
        if record is None:
            return None
        left, right, terms = record
        del got, record
        if left is not into["left"]:
            self.left[lo:hi] = left
        if top:
            terms.pack()  # first: the coefficient indices go before the factors are copied
            self._set_top_right(right)
        elif right is not into["right"]:
            self._right_below[lo:hi] = right
        return terms

    def _stored(self, n: int) -> bool:
        """Whether the order with ``n`` vertices is worth a store's file."""
        return self._store is not None and self.first[n + 1] - self.first[n] >= self._store.min_terms

    # --------------------------------------------------------------- counts

    def terms(self) -> int:
        """The terms of every condition (builds the listing)."""
        return sum(t.terms for t in self.orders.values())

    # --------------------------------------------------------------- display

    def _children(self, t: int) -> list[int]:
        out = []
        left, right = self.left, self.right
        while t != 0:
            out.append(int(right[t]))
            t = int(left[t])
        return out

    def tree_level_sequence(self, t: int) -> tuple[int, ...]:
        """Canonical level sequence of the stored tree ``t``."""
        seq = self._ls_cache.get(t)
        if seq is None:
            seq = self._ls_cache[t] = level_sequence_of_forest([self.tree_level_sequence(c) for c in self._children(t)])
        return seq

    def _forest(self, children: list[int]) -> list[tuple[int, ...]]:
        return [self.tree_level_sequence(c) for c in children]

    def tree_bracket(self, t: int) -> str:
        """Butcher's bracket of the stored tree ``t``."""
        text = self._bracket_cache.get(t)
        if text is None:
            text = self._bracket_cache[t] = self._forest_bracket(self._children(t))
        return text

    def _forest_bracket(self, children: list[int]) -> str:
        """The bracket of the tree whose root carries the stored trees ``children``, as
        :func:`~rkcheck.trees.rooted.bracket_of_forest` writes it (larger level sequences
        first, a repeated subtree once with its count), from the subtrees' own brackets:
        a listing names each rooted tree once, not once per condition it is part of."""
        ordered = sorted(((self.tree_level_sequence(c), c) for c in children), reverse=True)
        runs = [list(run) for _, run in groupby(ordered, key=itemgetter(0))]
        return bracket_of_runs((self.tree_bracket(run[0][1]), len(run)) for run in runs)

    def _designated(self, n: int, k: int) -> tuple[tuple[int, ...], list[int], int]:
        """The designated rooting of condition ``k`` (level sequence, the stored trees
        B₋ of its root) and the sign that turns the residual of the representative rooting
        into the residual of the designated one."""
        o = self.orders[n]
        forest = self._children(int(o.rep_left[k])) + [int(o.rep_right[k])]
        seq = level_sequence_of_forest(self._forest(forest))
        if o.tall[k] >= 0:  # two centres: the designated one has the larger level sequence
            other = self._children(int(o.tall[k])) + [int(o.rest[k])]
            other_seq = level_sequence_of_forest(self._forest(other))
            if other_seq > seq:
                return other_seq, other, -1
        return seq, forest, 1

    def _describe(self, n: int, k: int) -> tuple[FreeTree, int]:
        """The free tree of condition ``k`` and the sign of :meth:`flip`."""
        seq, forest, sign = self._designated(n, k)
        o = self.orders[n]
        return FreeTree(seq, self._forest_bracket(forest), int(o.max_degree[k]), int(o.counts[k])), sign

    def term_forests(self, n: int, k: int) -> list[tuple[int, int, list[tuple[int, ...]]]]:
        """(sign relative to the designated rooting, σ(u), B₋(u) as level sequences) for
        every rooting u of condition k, in listing order."""
        import math

        o = self.orders[n]
        flip = self.flip(n, k)
        out = []
        for i in o.terms_of(k):
            u, v = o.factors(int(i), self)
            coef = o.coefficient(int(i))
            sigma = math.factorial(n - 1) // abs(coef)
            out.append((o.sign(i) * flip, sigma, self._forest(self._children(u) + [v])))
        return out


#: a listing with at most this many terms is kept for the process's life (a few MB at
#: most), up to SMALL_LISTINGS_TERMS of them in all: a scan checks each file's claims
#: at several degrees, and with only the last few listings kept it rebuilt the same
#: small ones file after file (a third of a scan of the shipped tableaux)
SMALL_LISTING_TERMS = 1 << 15
SMALL_LISTINGS_TERMS = 1 << 18
_small_listings: dict[tuple[int, int | None], ConditionListing] = {}


@lru_cache(maxsize=4)
def _large_listing(order: int, degree: int | None) -> ConditionListing:
    return ConditionListing(order, degree)


def _shared_listing(order: int, degree: int | None) -> ConditionListing:
    """The process's one listing for ``(order, degree)``: small ones are all kept (up to
    the budget), the last few large ones (each can take gigabytes)."""
    key = (order, degree)
    listing = _small_listings.get(key)
    if listing is not None:
        return listing
    terms = listing_size(order, degree)[1]
    kept = sum(listing_size(*k)[1] for k in _small_listings)
    if terms > SMALL_LISTING_TERMS or kept + terms > SMALL_LISTINGS_TERMS:
        return _large_listing(order, degree)
    listing = _small_listings[key] = ConditionListing(order, degree)
    return listing


def forget_listings() -> None:
    """Drop the shared listings from memory (the next use builds, or loads, them anew)."""
    _small_listings.clear()
    _large_listing.cache_clear()


def condition_listing(order: int, degree: int | None, *, lazy: bool = False) -> ConditionListing:
    """The shared, cached listing for ``(order, degree)`` (a scan reuses it file after
    file), complete — or, with ``lazy``, built order by order as it is used (a check that
    stops at a low order then never builds the high ones)."""
    listing = _shared_listing(order, degree)
    return listing if lazy else listing.complete()
