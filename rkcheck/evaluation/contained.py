"""The residues of a degree-bounded listing read off an evaluation of all free trees.

The free trees of maximum degree ≤ m are some of all free trees, and a condition's
residue is a sum over the rootings of its free tree that does not depend on the listing
that holds it.  So once the exact evaluation of the listing of all Hamiltonians is done
(the main run of ``rkcheck verify --degree none``), the runs a file's claims add for
lower degrees need evaluate nothing: each of their conditions is one of the evaluated
ones, up to a sign.

Nothing is taken from how the smaller listing was built; the correspondence is built,
then checked before a residue is read:

* The trees: every tree of the smaller listing below the top order gets a candidate id
  in the larger one from the generation order of :mod:`rkcheck.trees.table` (without a
  degree bound the trees with n vertices run by their right factor ``v``, and within
  ``v``'s block by the left factor ``u`` in id order), accepted only when every tree's
  two Butcher factors are the images of its own: by induction from τ, the image is
  then the same rooted tree.
* The conditions: the representative rooting ``u ∘ v`` of each condition gets its id
  the same way, checked the same way.  A rooted tree roots one free tree, and a
  condition of either listing is the sum over every rooting of its free tree (each
  rooted tree of a listing lies in exactly one of its conditions,
  :mod:`rkcheck.trees.classes`): the condition of the larger listing holding that
  rooting is the same condition, with the same terms (their numbers are compared too).
* The sign: each listing signs a rooting by the parity of its distance to its own
  representative, so the two residues differ by the sign that the larger listing gives
  the smaller one's representative (its distance to itself is 0).

Then ``N = Σ_u c_u ŵ(u)`` of a condition is that sign times the other's in every
channel: the residues an evaluation of the smaller listing gives, number for number.
Anything that does not check out returns None, and the caller evaluates.
"""

from __future__ import annotations

from typing import Any

import numpy as np


def contained_residues(source: Any, source_sums: dict[int, Any], listing: Any, count: dict[int, int],
                       channels: list[tuple[int, list[int]]]) -> dict[int, tuple[np.ndarray, int]] | None:
    """``{n: ((conditions, count[n], D) residues, full)}`` of ``listing``'s orders, read
    off ``source_sums`` (the :class:`~rkcheck.evaluation.modular.ExactOrderSums` of the
    orders of ``source``, a listing of all free trees at least as high), over the first
    ``count[n]`` of ``channels``, of which the first ``full`` are known for every
    condition and the others for those zero there (screened as in the source); None
    when ``source`` does not contain ``listing`` or lacks the orders or primes it needs,
    or a check fails."""
    if not contains(source, listing) or any(n not in source_sums for n in count):
        return None
    for n, c in count.items():
        primes = source_sums[n].primes
        if len(primes) < c or list(primes[:c]) != list(channels[:c]):
            return None
    if not count:
        return {}
    top = max(count)
    listing.ensure(top)
    ids = tree_map(source, listing, top - 1)
    if ids is None:
        return None
    out = {}
    for n, c in count.items():
        matched = condition_map(source, listing, n, ids)
        if matched is None:
            return None
        where, sign = matched
        known = source_sums[n]
        full = c if known.full is None else min(c, known.full)
        out[n] = (_signed(known.screened[where, :c, :], sign, [p for p, _ in channels[:c]]), full)
    return out


def contains(source: Any, listing: Any) -> bool:
    """Whether ``source`` is a listing of all free trees to at least ``listing``'s order
    (the ids of :func:`tree_map` need one without a degree bound)."""
    return (source.degree is None and listing.degree is not None and listing.degree >= 2
            and source.order >= listing.order)


def _ids_of_products(source: Any, n: int, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The ids in ``source`` (no degree bound) of the trees ``u ∘ v`` with ``n`` vertices,
    given the ids of ``u`` and ``v`` there, from the generation order (module
    docstring); an id that is not such a tree is caught by the caller's check."""
    first = np.asarray(source.first)
    size = np.searchsorted(first, u, side="right") - 1  # vertices of u
    if hasattr(source.right, "searchsorted"):  # a listing's RightFactors: the top order not decoded
        block = source.right.searchsorted(int(first[n]), int(first[n + 1]), v)
    else:
        right = source.right[first[n]:first[n + 1]]
        # v in the factors' own dtype: searchsorted would otherwise convert the whole order
        block = np.searchsorted(right, v.astype(right.dtype), side="left")
    result: np.ndarray = np.minimum(first[n] + block + (u - first[size]), first[n + 1] - 1)
    return result


def tree_map(source: Any, listing: Any, top: int) -> np.ndarray | None:
    """The id in ``source`` of each tree of ``listing`` with at most ``top`` vertices, or
    None unless every one is the same rooted tree, factor by factor."""
    first = listing.first
    ids = np.empty(first[top + 1], dtype=np.int64)
    ids[0] = 0  # τ
    for k in range(2, top + 1):
        lo, hi = first[k], first[k + 1]
        ids[lo:hi] = _ids_of_products(source, k, ids[listing.left[lo:hi]], ids[listing.right[lo:hi]])
    t = slice(1, len(ids))
    if not (np.array_equal(ids[listing.left[t]], source.left[ids[t]])
            and np.array_equal(ids[listing.right[t]], source.right[ids[t]])):
        return None
    return ids


def condition_map(source: Any, listing: Any, n: int, ids: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """For the conditions of ``listing`` with ``n`` vertices: the same condition's index
    in ``source`` and the sign of its residue there (``±1`` per condition), or None
    (module docstring; ``ids``: :func:`tree_map` to ``n − 1`` vertices at least)."""
    mine, theirs = listing.orders[n], source.orders[n]
    u, v = ids[mine.rep_left], ids[mine.rep_right]
    rep = _ids_of_products(source, n, u, v)
    if not (np.array_equal(source.left[rep], u) and np.array_equal(source.right[rep], v)):
        return None
    term = rep - source.first[n]
    where, index = theirs.at(term)
    where = where.astype(np.int64)
    if np.any(where >= len(theirs)) or not np.array_equal(theirs.counts[where], mine.counts):
        return None  # a superfluous tree there, or not the same terms
    if len(where) and np.bincount(where).max() > 1:
        return None  # two conditions on one
    positive = np.array([c > 0 for c in theirs.coefficients], dtype=bool)
    sign = np.where(positive[index], 1, -1).astype(np.int8)
    return where, sign


def _signed(residues: np.ndarray, sign: np.ndarray, moduli: list[int]) -> np.ndarray:
    """``residues`` (conditions × primes × roots, a copy of the source's) with those of
    the conditions whose sign is −1 negated modulo each prime, in place."""
    flip = sign < 0
    if flip.any():
        P = np.array(moduli, dtype=np.int64)[None, :, None]
        residues[flip] = ((P - residues[flip].astype(np.int64)) % P).astype(residues.dtype)
    return residues
