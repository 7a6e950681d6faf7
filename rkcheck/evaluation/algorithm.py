"""One algorithm for every number context: elementary weights and condition sums.

Over a :class:`~rkcheck.trees.table.TreeTable`, order by order (definitions §2):

* ``Φ(τ) = 1``, ``Φ(u ∘ v) = Φ(u) ⊙ ψ(v)`` with ``ψ = AΦ``, and ``a = bᵀΦ``;
* ``w(t) = a(B₋(t)) = Π_{c child of t} a(c)``, i.e. ``w(u ∘ v) = w(u) · a(v)``;
* the energy condition of a class of rootings (:mod:`rkcheck.trees.classes`) is
  ``Σ_u (−1)^κ w(u)/σ(u)`` (definitions §3): one product per rooted tree.

Only what later orders need is computed: ``ψ`` up to order ``N − 1``, ``Φ`` and ``a`` up
to ``N``, ``w`` up to ``N + 1`` (the trees with ``N + 1`` vertices are terms only).  A
*context* (:class:`~rkcheck.evaluation.protocols.NumberContext`) supplies the arithmetic
on whole arrays, like mpmath's ``mp``/``iv``/``fp`` contexts behind one set of calls; its
values are opaque to this module.  The kernel:

``vectors(n, s)`` / ``scalars(n)``   storage for n values
``ones(k, s)``, ``one(k)``            the weights of τ
``take(x, idx)``                      gather (numpy fancy indexing)
``put(store, lo, x)``                 store a block of rows
``mul(x, y)``                         elementwise product (vectors or scalars)
``matvec(x)``, ``dot(x)``             ``x Aᵀ`` and ``x b`` row by row
``sums(k, n)``, ``add_terms(acc, w, terms, n, i0, i1)``, ``finish_sums(acc, k, n)``
                                      accumulate ``Σ ±w/σ`` of the terms ``i0 … i1−1`` of an
                                      :class:`OrderTerms` into its k condition sums

The result of ``class_sums`` is whatever the context reports a residual with (residues
modulo a prime, balls, float balls).
"""

from __future__ import annotations

from typing import Any, Callable, Iterable

import numpy as np

from rkcheck.evaluation.protocols import NumberContext
from rkcheck.trees.listing import ConditionListing


class EvaluationInterrupted(KeyboardInterrupt):
    """Ctrl-C during an evaluation; ``finished`` holds the orders that were complete."""

    def __init__(self, finished: dict[int, Any]):
        super().__init__()
        self.finished = finished


def condition_sums(
    listing: ConditionListing,
    ctx: NumberContext,
    s: int,
    orders: Iterable[int] | None = None,
    on_order: Callable[[int, Any], None] | None = None,
) -> dict[int, Any]:
    """``{vertices: class sums}`` for the conditions with the given numbers of vertices
    (default: all of the listing's), in increasing order.

    Weights are stored only where later terms use them many times (``a`` and ``w`` for
    trees with at most ``top − 2`` vertices, ``top`` the largest number of vertices asked
    for; :class:`_Weights`); the others are computed where they are used.  ``on_order(n, sums)`` is called as soon as
    an order is done, so that callers can stream (report, stop early)."""
    wanted = sorted(listing.orders if orders is None else orders)
    out: dict[int, Any] = {}
    if not wanted:
        return out
    listing.ensure(wanted[-1])  # a streamed listing builds its orders on demand: the factors first
    try:
        _weights_and_sums(listing, ctx, s, wanted, out, on_order)
    except KeyboardInterrupt:
        raise EvaluationInterrupted(out) from None
    return out


def store_weights(listing: ConditionListing, ctx: NumberContext, s: int, top: int) -> None:
    """Compute and store the weights that the conditions with ``top`` vertices are made
    of — ``Φ`` and ``ψ`` up to ``top − 2`` vertices, ``a`` and ``w`` up to ``top − 1`` —
    every one of them once, for a context that inspects the weights rather than sums
    them (the pattern of zeros of :mod:`~rkcheck.evaluation.box`)."""
    listing.ensure(top)
    weights = _Weights(listing, ctx, s, top - 2, top - 1)
    chunk = max(_TERM_CHUNK // getattr(ctx, "width", 1), 1)
    for n in range(2, top):
        weights.compute_order(n, listing.first[n], listing.first[n + 1], chunk)


def _weights_and_sums(listing: ConditionListing, ctx: NumberContext, s: int, wanted: list[int],
                      out: dict[int, Any], on_order: Callable[[int, Any], None] | None) -> None:
    top = wanted[-1]
    first = listing.first
    phi_vertices = _phi_vertices(listing, ctx, s, top)
    late_a = _a_before_top(listing, ctx, s, top, phi_vertices)
    # w of the trees with top − 2 vertices: used only as the bushes' left factors, then
    weights = _Weights(listing, ctx, s, phi_vertices, *((top - 1, top - 3) if late_a else (top - 2, top - 2)))
    chunk = max(_TERM_CHUNK // getattr(ctx, "width", 1), 1)  # several channels per row: fewer rows
    for n in range(2, top + 1):
        if n <= top - 2:  # the weights of the trees with n vertices, stored as far as kept
            weights.compute_order(n, first[n], first[n + 1], chunk)
        if late_a and n == top:  # before the largest order's sums: a of the trees below, then no Φ, ψ
            weights.shrink_phi(first[phi_vertices], chunk)
            weights.compute_a(first[top - 1], first[top], chunk)
            weights.release_phi()
        terms = listing.orders.get(n) if n in wanted else None
        if terms is None:
            continue
        acc = ctx.sums(len(terms) + 1, n)  # the extra bin collects superfluous trees
        for t0 in range(0, terms.rows, chunk):
            t1 = min(terms.rows, t0 + chunk)
            if terms.first_id is not None:  # the trees themselves: w stored, or from their factors
                w_terms = weights.get("w", slice(terms.first_id + t0, terms.first_id + t1))
            else:  # the top order: w(u ∘ v) = w(u)·a(v), from the factors kept with the terms
                assert terms.left is not None and terms.right is not None
                w_terms = ctx.mul(weights.get("w", terms.left[t0:t1]), weights.get("a", terms.right[t0:t1]))
            ctx.add_terms(acc, w_terms, terms, n, t0, t1)
        out[n] = ctx.finish_sums(acc, len(terms), n)
        if on_order is not None:
            on_order(n, out[n])


def _phi_vertices(listing: ConditionListing, ctx: NumberContext, s: int, top: int) -> int:
    """Up to how many vertices ``Φ`` and ``ψ`` are stored for conditions up to ``top``
    vertices: ``top − 2`` (each weight computed once), or ``top − 3`` when those of the
    trees with ``top − 2`` vertices would take more than :data:`RECOMPUTE_BYTES` — they are
    then computed a second time where the trees with ``top − 1`` vertices need them."""
    first = listing.first
    if top < 4 or top - 1 >= len(first):
        return top - 2
    trees = int(first[top - 1] - first[top - 2])
    return top - 3 if 2 * trees * _nbytes(ctx.vectors(1, s)) > RECOMPUTE_BYTES else top - 2


def _a_before_top(listing: ConditionListing, ctx: NumberContext, s: int, top: int, phi_vertices: int) -> bool:
    """Whether ``a`` of the trees with ``top − 1`` vertices is computed and stored before
    the sums of the trees with ``top`` vertices, so that ``Φ`` and ``ψ`` are released
    first: those sums need nothing else of them (every tree with ``top − 1`` vertices is
    a right factor once, in ``τ ∘ v``, and a left one only as the bush), and these
    scalars take less memory than the vectors released, or the swap is not made."""
    first = listing.first
    if top < 4 or top >= len(first):
        return False
    scalars = int(first[top] - first[top - 1]) * _nbytes(ctx.scalars(1))
    vectors = 2 * int(first[phi_vertices + 1]) * _nbytes(ctx.vectors(1, s))
    return scalars < vectors


def _nbytes(value: Any) -> int:
    """Bytes of a context's value (an array, or nested tuples of arrays)."""
    if isinstance(value, (tuple, list)):
        return sum(_nbytes(v) for v in value)
    return int(getattr(value, "nbytes", 0))


#: Φ and ψ of the trees with ``top − 2`` vertices are stored up to this many bytes, and
#: computed twice above: recomputing them cost the exact evaluation of RK4 at order 18
#: about 6 % of its time (they would take 40 MB there, one prime at a time), storing them
#: took certified balls 220 MB of their 850 MB
RECOMPUTE_BYTES = 128 << 20


class _Weights:
    """The elementary weights of the trees up to ``top`` vertices: those that later orders
    use many times stored, the others computed from their factors when asked.

    A tree with ``top − 1`` vertices enters the trees with ``top`` vertices only as
    ``τ ∘ v`` (and the bush as ``u ∘ τ``: the right factor is the child with the largest
    id), and one with ``top − 2`` vertices enters those with ``top − 1`` the same way.
    So ``a`` and ``w`` are stored up to ``top − 2`` vertices, ``Φ`` and ``ψ`` up to
    ``top − 2`` or ``top − 3`` (:func:`_phi_vertices`); a larger tree's weight is computed
    from its factors where a term needs it, once per tree (twice for ``Φ`` and ``ψ`` of
    the trees with ``top − 2`` vertices when they are not stored; ``a`` of the trees with
    ``top − 1`` vertices is stored before the last order when that lets ``Φ`` and ``ψ``
    go, :func:`_a_before_top`) — by the same operations
    on the same values as when it was stored, so every value is the same, bit for bit.
    (Storing them all took most of a certified check's memory: ``Φ`` and ``ψ`` of the
    trees with ``top − 2`` vertices and ``a`` and ``w`` of those with ``top − 1`` are
    nine tenths of what was stored.)"""

    def __init__(self, listing: ConditionListing, ctx: NumberContext, s: int, phi_vertices: int,
                 a_vertices: int, w_vertices: int | None = None):
        """Storage for ``Φ`` and ``ψ`` of the trees with at most ``phi_vertices`` vertices,
        for ``a`` of those with at most ``a_vertices`` and for ``w`` of those with at most
        ``w_vertices`` (default ``a_vertices``; τ at least).  :meth:`compute_order` fills
        every order up to ``phi_vertices + 1``; ``a`` beyond it, :meth:`compute_a`."""
        first = listing.first
        self.ctx, self.s = ctx, s
        self.left, self.right = listing.left, listing.right
        w_vertices = a_vertices if w_vertices is None else w_vertices
        n_phi, n_a, n_w = (first[max(k + 1, 2)] for k in (phi_vertices, a_vertices, w_vertices))
        self.limit = {"phi": n_phi, "psi": n_phi, "a": n_a, "w": n_w}
        self.store = {"phi": ctx.vectors(n_phi, s), "psi": ctx.vectors(n_phi, s),
                      "a": ctx.scalars(n_a), "w": ctx.scalars(n_w)}
        phi0 = ctx.ones(1, s)
        ctx.put(self.store["phi"], 0, phi0)
        ctx.put(self.store["psi"], 0, ctx.matvec(phi0))
        ctx.put(self.store["a"], 0, ctx.dot(phi0))
        ctx.put(self.store["w"], 0, ctx.one(1))

    def compute_order(self, n: int, lo: int, hi: int, chunk: int) -> None:
        """Compute and store the weights of the trees ``lo … hi − 1`` (those with ``n``
        vertices): ``a`` always, ``w``, ``Φ`` and ``ψ`` when they are kept."""
        ctx, store = self.ctx, self.store
        keep_phi = hi <= self.limit["phi"]
        keep_w = hi <= self.limit["w"]
        for a0 in range(lo, hi, chunk):
            a1 = min(hi, a0 + chunk)
            U, V = self.left[a0:a1], self.right[a0:a1]
            if keep_w:
                ctx.put(store["w"], a0, ctx.mul(ctx.take(store["w"], U), ctx.take(store["a"], V)))
            phi_n = ctx.mul(ctx.take(store["phi"], U), ctx.take(store["psi"], V))
            ctx.put(store["a"], a0, ctx.dot(phi_n))
            if keep_phi:
                ctx.put(store["phi"], a0, phi_n)
                ctx.put(store["psi"], a0, ctx.matvec(phi_n))
            del phi_n

    def compute_a(self, lo: int, hi: int, chunk: int) -> None:
        """Compute and store ``a`` of the trees ``lo … hi − 1`` (within the stored ``a``),
        their ``Φ`` from their factors, stored or computed."""
        ctx = self.ctx
        for a0 in range(lo, hi, chunk):
            a1 = min(hi, a0 + chunk)
            ctx.put(self.store["a"], a0, ctx.dot(self.get("phi", slice(a0, a1))))

    def shrink_phi(self, rows: int, chunk: int) -> None:
        """Keep ``Φ`` of the first ``rows`` trees only (``ψ`` stays): for ``a`` of the
        trees with ``top − 1`` vertices, a tree with ``top − 3`` vertices is a left factor
        only when its children are the smallest trees (a handful, computed from their
        factors), while its ψ enters every ``τ ∘ v``.  Φ(τ) stays whatever ``rows``: it
        has no factors to be computed from."""
        rows = max(rows, 1)
        if rows >= self.limit["phi"]:
            return
        ctx, old = self.ctx, self.store["phi"]
        kept = ctx.vectors(rows, self.s)
        for a0 in range(0, rows, chunk):
            ctx.put(kept, a0, ctx.take(old, np.arange(a0, min(rows, a0 + chunk))))
        self.store["phi"], self.limit["phi"] = kept, rows

    def release_phi(self) -> None:
        """Drop the stored ``Φ`` and ``ψ``: later orders need only ``a`` and ``w``, and
        any use of them now fails rather than computing them from nothing."""
        self.store["phi"] = self.store["psi"] = None

    def get(self, kind: str, ids: np.ndarray | slice) -> Any:
        """The weights ``kind`` (``"phi"``, ``"psi"``, ``"a"`` or ``"w"``) of the trees
        ``ids`` (an array of ids, or a slice of consecutive ones): gathered where
        stored, computed from the factors elsewhere."""
        ctx, limit = self.ctx, self.limit[kind]
        if isinstance(ids, slice):  # consecutive trees: their factors are slices, not gathers
            if ids.stop <= limit:
                return ctx.take(self.store[kind], np.arange(ids.start, ids.stop))
            if ids.start >= limit:
                return self._from_factors(kind, ids)
            ids = np.arange(ids.start, ids.stop)
        computed = ids >= limit
        k = int(np.count_nonzero(computed))
        if k == 0:
            return ctx.take(self.store[kind], ids)
        if k == len(ids):
            return self._from_factors(kind, ids)
        # both kinds in one block: stored ones first, then computed, then put in place
        kept = ~computed
        both = ctx.vectors(len(ids), self.s) if kind in ("phi", "psi") else ctx.scalars(len(ids))
        ctx.put(both, 0, ctx.take(self.store[kind], ids[kept]))
        ctx.put(both, len(ids) - k, self._from_factors(kind, ids[computed]))
        place = np.empty(len(ids), dtype=np.intp)
        place[kept] = np.arange(len(ids) - k)
        place[computed] = np.arange(len(ids) - k, len(ids))
        return ctx.take(both, place)

    def _from_factors(self, kind: str, ids: np.ndarray | slice) -> Any:
        ctx = self.ctx
        if kind == "w":  # w(u ∘ v) = w(u)·a(v)
            return ctx.mul(self.get("w", self.left[ids]), self.get("a", self.right[ids]))
        if kind == "a":
            return ctx.dot(self.get("phi", ids))
        if kind == "psi":
            return ctx.matvec(self.get("phi", ids))
        return ctx.mul(self.get("phi", self.left[ids]), self.get("psi", self.right[ids]))


#: rows per block of the kernel: small enough that a block's temporaries stay in the
#: processor's caches (the evaluation is bound by memory traffic, not arithmetic: blocks
#: of 2^14 rows ran RK4 and Gauss-3 at order 16 15–20 % faster than blocks of 2^20),
#: large enough that numpy's cost per call stays small
_TERM_CHUNK = 1 << 14
