"""Exact residues of the conditions of a
:class:`~rkcheck.trees.centroid.CentroidListing`: each free tree evaluated at its
centroid, as a sum over vertices (definitions §3; the scaled integers and channels of
:mod:`rkcheck.evaluation.modular`).

Over vertices.  Rooting the tree at each vertex ``v`` gives every distinct rooting
``|Aut t̄|/σ(u)`` times (orbit–stabiliser), and ``|Aut t̄| = σ(T)`` for the rooting ``T``
at the centroid of a non-superfluous tree (an automorphism fixes the centroid, or for
two centroids the edge between them, whose halves differ).  So, with the signs counted
from the centroid,

    N = Σ_u ±((n−1)!/σ(u))·ŵ(u) = ((n−1)!/σ(T)) · Σ_v (−1)^{d(v)} ŵ(rooting at v),

the same integer element the listing's terms sum to.

Per branch.  For ``v`` in a branch ``c`` of the centroid, the rooting at ``v`` has the
children of ``v`` in ``c`` and the rest of the tree seen from ``v``, so its weight is
linear in the stage vector ``x`` of the rest seen from ``c``'s root: the vertices of
``c`` add ``m(c)ᵀx`` with

    m(τ) = b,    m(c) = w(c)·b − Aᵀ Q(c),    Q(c) = Σ_{children u} m(u) ⊙ Π_{siblings u'} ψ(u').

For a multiset of branches ``F`` at the centroid, with ``P(F) = Π ψ(c)``, ``α(F) = Π a(c)``
and ``Q(F)`` as above, the sum over vertices is ``α(F) − 1ᵀQ(F)``; adding a branch ``c``
gives ``P ⊙ ψ(c)``, ``α·a(c)`` and ``Q ⊙ ψ(c) + m(c) ⊙ P``.  A free tree therefore costs a
few products of stage vectors per branch, whatever its number of rootings, and the
tables of ``Φ, ψ, a, w, Q, m`` cover the branches only.
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

from rkcheck.trees.centroid import Branches, CentroidListing, CentroidOrder

#: residues below 2^30 fit int32 in the states that wait; arithmetic widens to int64
_STORE = np.int32

#: stage entries per waiting tree that a pass over a centroid listing holds (its channels
#: times the stages): RK4's five channels at order 22 held 1.3 GB at the peak
CENTROID_PASS_VALUES = 24


class _Tables:
    """``Φ, ψ, a, w, Q, m`` and ``1/σ`` of every branch in each channel (images ``A``,
    ``b`` of ``Â``, ``b̂`` modulo the channel's prime), tree axis first, channel axis
    second."""

    def __init__(self, branches: Branches, moduli: list[int], A: np.ndarray, b: np.ndarray):
        count, (C, s) = branches.count, b.shape
        self.shape = (C, s)
        p = np.array(moduli, dtype=np.int64)
        pv = p[:, None]
        self.p, self.pv = p, pv
        phi, psi, Q, m = (np.zeros((count, C, s), dtype=np.int64) for _ in range(4))
        a, w = np.zeros((count, C), dtype=np.int64), np.zeros((count, C), dtype=np.int64)
        At = np.ascontiguousarray(np.swapaxes(A, 1, 2))
        for c in range(count):
            if c == 0:
                phi[0], w[0] = 1, 1
            else:
                u, v = branches.left[c], branches.right[c]
                phi[c] = phi[u] * psi[v] % pv
                w[c] = w[u] * a[v] % p
                Q[c] = (Q[u] * psi[v] + m[v] * phi[u]) % pv
            psi[c] = _matvec(A, phi[c], pv)
            a[c] = (b * phi[c] % pv).sum(axis=1) % p
            m[c] = (w[c][:, None] * b - _matvec(At, Q[c], pv)) % pv
        self.phi, self.psi, self.a, self.w, self.Q, self.m = phi, psi, a, w, Q, m
        self.sigma_inv = np.array([[pow(x, -1, q) for q in moduli] for x in branches.sigma], dtype=np.int64)
        runs = 2 * (len(branches.first) - 2) + 1  # copies of one branch at a centroid: at most n − 1
        self.run_inv = np.array([[0] * C] + [[pow(k, -1, q) for q in moduli] for k in range(1, runs + 1)],
                                dtype=np.int64)


def _matvec(M: np.ndarray, x: np.ndarray, pv: np.ndarray) -> np.ndarray:
    """``M[k] @ x[k] mod p_k`` per channel k, each product reduced before it is summed
    (residues below 2^30: a product takes 60 bits, a sum of a few of them int64)."""
    out = np.zeros_like(x)
    for j in range(M.shape[2]):
        out = (out + M[:, :, j] * x[:, j, None]) % pv
    return out


class _Residues:
    """The :class:`~rkcheck.trees.centroid.Builder` of residues: a state is ``(P, Q, α,
    1/σ)`` per partial multiset and channel; complete ones give
    ``N = (n−1)!·σ(T)⁻¹·(α − 1ᵀQ)``."""

    def __init__(self, tables: _Tables, n: int, moduli: list[int], conditions: int):
        self.t = tables
        self.fact = np.array([math.factorial(n - 1) % q for q in moduli], dtype=np.int64)
        # filled in listing order as conditions complete (blocks gathered at the end
        # would hold the order's residues twice at the peak)
        self.out = np.empty((conditions, len(moduli)), dtype=_STORE)
        self.done = 0

    def start(self) -> Any:
        C, s = self.t.shape
        return (np.ones((1, C, s), dtype=_STORE), np.zeros((1, C, s), dtype=_STORE), np.ones((1, C), dtype=_STORE),
                np.ones((1, C), dtype=_STORE))

    def extend(self, state: Any, parent: np.ndarray, branch: np.ndarray, run: np.ndarray) -> Any:
        t = self.t
        P, Q, alpha, sinv = state
        psi = t.psi[branch]
        Pp = P[parent].astype(np.int64)
        P2 = (Pp * psi % t.pv).astype(_STORE)
        Q2 = ((Q[parent] * psi + t.m[branch] * Pp) % t.pv).astype(_STORE)
        del Pp, psi
        alpha2 = (alpha[parent] * t.a[branch] % t.p).astype(_STORE)
        sinv2 = (sinv[parent] * t.sigma_inv[branch] % t.p * t.run_inv[run] % t.p).astype(_STORE)
        return P2, Q2, alpha2, sinv2

    def take(self, state: Any, rows: np.ndarray) -> Any:
        return tuple(x[rows] for x in state)

    def concat(self, states: list[Any]) -> Any:
        return tuple(np.concatenate([x[i] for x in states]) for i in range(4))

    def finish(self, state: Any) -> None:
        t = self.t
        _, Q, alpha, sinv = state
        S = (alpha - Q.sum(axis=2, dtype=np.int64)) % t.p
        self._put(self.fact * sinv % t.p * S % t.p)

    def halves(self, big: np.ndarray, small: np.ndarray) -> None:
        # the centroid is big's root; small hangs from it: P = Φ(big) ⊙ ψ(small) and so on
        t = self.t
        S = (t.w[big] * t.a[small] % t.p
             - ((t.Q[big] * t.psi[small] + t.m[small] * t.phi[big]) % t.pv).sum(axis=2)) % t.p
        sinv = t.sigma_inv[big] * t.sigma_inv[small] % t.p
        self._put(self.fact * sinv % t.p * S % t.p)

    def _put(self, block: np.ndarray) -> None:
        self.out[self.done:self.done + len(block)] = block
        self.done += len(block)

    def residues(self) -> np.ndarray:
        assert self.done == len(self.out), "a walk completes every condition of its order"
        return self.out


def centroid_residues(listing: CentroidListing, moduli: Sequence[int], A: np.ndarray, b: np.ndarray,
                      orders: list[int]) -> dict[int, np.ndarray]:
    """``{n: (conditions, channels) residues}`` of the given orders of ``listing`` in the
    channels with the primes ``moduli`` and images ``A`` (channels × s × s) and ``b``
    (channels × s) of ``Â`` and ``b̂``: ``N`` of each condition at its centroid (the
    listing's flip gives the designated sign)."""
    moduli = list(moduli)
    tables = _Tables(listing.branches, moduli, np.asarray(A, dtype=np.int64) % np.array(moduli)[:, None, None],
                     np.asarray(b, dtype=np.int64) % np.array(moduli)[:, None])
    out = {}
    for n in orders:
        order: CentroidOrder = listing.orders[n]
        builder = _Residues(tables, n, moduli, len(order))
        order.walk(builder)
        out[n] = builder.residues()
    return out
