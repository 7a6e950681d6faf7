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

    Weights are kept only as far as later terms need them: ``Φ`` and ``ψ`` for trees
    with at most ``top − 2`` vertices, ``a`` and ``w`` up to ``top − 1``, where ``top`` is
    the largest number of vertices asked for.  ``on_order(n, sums)`` is called as soon as
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


def _weights_and_sums(listing: ConditionListing, ctx: NumberContext, s: int, wanted: list[int],
                      out: dict[int, Any], on_order: Callable[[int, Any], None] | None) -> None:
    top = wanted[-1]
    first = listing.first
    n_a = first[top]  # trees with <= top − 1 vertices
    n_phi = first[max(top - 1, 2)]  # trees with <= top − 2 vertices
    phi = ctx.vectors(n_phi, s)
    psi = ctx.vectors(n_phi, s)
    a = ctx.scalars(n_a)
    w = ctx.scalars(n_a)
    phi0 = ctx.ones(1, s)
    ctx.put(phi, 0, phi0)
    ctx.put(psi, 0, ctx.matvec(phi0))
    ctx.put(a, 0, ctx.dot(phi0))
    ctx.put(w, 0, ctx.one(1))
    left, right = listing.left, listing.right
    chunk = max(_TERM_CHUNK // getattr(ctx, "width", 1), 1)  # several channels per row: fewer rows
    for n in range(2, top + 1):
        lo, hi = first[n], first[n + 1] if n + 1 < len(first) else first[n]
        for a0 in range(lo, hi if n < top else lo, chunk):  # weights of the trees with n vertices
            a1 = min(hi, a0 + chunk)
            U, V = left[a0:a1], right[a0:a1]
            ctx.put(w, a0, ctx.mul(ctx.take(w, U), ctx.take(a, V)))
            phi_n = ctx.mul(ctx.take(phi, U), ctx.take(psi, V))
            ctx.put(a, a0, ctx.dot(phi_n))
            if n < top - 1:
                ctx.put(phi, a0, phi_n)
                ctx.put(psi, a0, ctx.matvec(phi_n))
            del phi_n
        if n == top - 1:  # the trees with top vertices need only w and a: free Φ and ψ first
            phi = psi = None
        terms = listing.orders.get(n) if n in wanted else None
        if terms is not None:
            acc = ctx.sums(len(terms) + 1, n)  # the extra bin collects superfluous trees
            for t0 in range(0, len(terms.condition), chunk):
                t1 = min(len(terms.condition), t0 + chunk)
                if terms.first_id is not None and n < top:  # their weights w are stored
                    w_terms = ctx.take(w, np.arange(terms.first_id + t0, terms.first_id + t1))
                else:  # w(u ∘ v) = w(u)·a(v), from the factors
                    if terms.first_id is not None:
                        U, V = left[terms.first_id + t0:terms.first_id + t1], right[terms.first_id + t0:terms.first_id + t1]
                    else:
                        assert terms.left is not None and terms.right is not None  # top order: factors kept
                        U, V = terms.left[t0:t1], terms.right[t0:t1]
                    w_terms = ctx.mul(ctx.take(w, U), ctx.take(a, V))
                ctx.add_terms(acc, w_terms, terms, n, t0, t1)
            out[n] = ctx.finish_sums(acc, len(terms), n)
            if on_order is not None:
                on_order(n, out[n])


#: rows per block of the kernel: small enough that a block's temporaries stay in the
#: processor's caches (the evaluation is bound by memory traffic, not arithmetic: blocks
#: of 2^14 rows ran RK4 and Gauss-3 at order 16 15–20 % faster than blocks of 2^20),
#: large enough that numpy's cost per call stays small
_TERM_CHUNK = 1 << 14
