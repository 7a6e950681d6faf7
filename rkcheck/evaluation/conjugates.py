"""Channels that repeat one another: the images of a tableau at two roots of the same
prime that differ only by a relabelling of the stages.

Every quantity the exact evaluation computes — ``Φ``, ``ψ = AΦ``, ``a = bᵀΦ``, ``w`` and
the condition sums (:mod:`rkcheck.evaluation.algorithm`) — is a polynomial in the
entries that a simultaneous permutation of the stages (``A ↦ PAPᵀ``, ``b ↦ Pb``) leaves
unchanged: the stage vectors are permuted and every scalar is a sum over all stages.
The identity holds in any commutative ring, so in ``Z/p`` too: when the images
``(A', b')`` at a root ``r'`` are a stage permutation of the images ``(A, b)`` at a root
``r`` of the same prime, the residues at ``r'`` *are* those at ``r``, and the channel of
``r'`` need not be evaluated.

This is how a Galois symmetry of the tableau shows up modulo ``p``: the conjugate of a
collocation tableau is the same tableau with its nodes reordered (Gauss–Legendre over
``Q(√15)``: ``√15 ↦ −√15`` swaps the first and last node), so half of Gauss-3's channels
repeat the other half, and an HBVM tableau over the splitting field of its nodes can
repeat one channel at every root of a prime.  Nothing is assumed: each permutation
found is checked entry by entry on the images, and a root without one is evaluated.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

import numpy as np

#: assignments tried for all the roots of one prime before giving up (the roots left
#: are evaluated): stages with equal signatures (rows and columns as multisets) are few
#: in practice, and the search stays bounded for tableaux where they are not
MAX_TRIES = 20_000


def repeated_channels(A: np.ndarray, b: np.ndarray) -> list[int]:
    """For the images ``A[:, :, j]``, ``b[:, j]`` at the roots ``j`` of one prime: the
    root whose channel gives root j's residues — j itself, or an earlier root whose
    images are a stage permutation of j's (checked entry by entry)."""
    D = b.shape[1]
    source = list(range(D))
    kept: list[int] = []  # roots evaluated so far (their own source)
    signatures = [_signatures(A[:, :, j], b[:, j]) for j in range(D)]
    shapes = [Counter(sig) for sig in signatures]
    budget = [MAX_TRIES]  # shared by every search of this prime
    for j in range(D):
        for k in kept:
            if shapes[j] != shapes[k] or budget[0] <= 0:
                continue
            perm = _permutation(A[:, :, k], b[:, k], A[:, :, j], b[:, j], signatures[k], signatures[j], budget)
            if perm is not None:
                source[j] = k
                break
        else:
            kept.append(j)
    return source


def _signatures(A: np.ndarray, b: np.ndarray) -> list[tuple[Any, ...]]:
    """Per stage, what a relabelling of the stages cannot change: its weight, its
    diagonal entry, and its row and column as multisets."""
    return [(int(b[i]), int(A[i, i]), tuple(sorted(A[i].tolist())), tuple(sorted(A[:, i].tolist())))
            for i in range(len(b))]


def is_stage_permutation(A: np.ndarray, b: np.ndarray, A2: np.ndarray, b2: np.ndarray, perm: list[int]) -> bool:
    """``A2[π(i), π(l)] = A[i, l]`` and ``b2[π(i)] = b[i]`` for every i, l."""
    idx = np.asarray(perm)
    return bool(np.array_equal(A2[np.ix_(idx, idx)], A) and np.array_equal(b2[idx], b))


def _permutation(A: np.ndarray, b: np.ndarray, A2: np.ndarray, b2: np.ndarray,
                 sig: list[tuple[Any, ...]], sig2: list[tuple[Any, ...]], budget: list[int]) -> list[int] | None:
    """A permutation π of the stages with ``(A2, b2)`` the images of ``(A, b)`` under it
    (:func:`is_stage_permutation`), or None: a depth-first search over the stages of equal
    signature, each partial assignment checked on the entries it fixes, within
    ``budget[0]`` assignments (spent)."""
    s = len(b)
    candidates = [[m for m in range(s) if sig2[m] == sig[i]] for i in range(s)]
    order = sorted(range(s), key=lambda i: len(candidates[i]))  # the most constrained first
    perm = [-1] * s
    used = [False] * s

    def extend(depth: int) -> bool:
        if depth == s:
            return True
        i = order[depth]
        for m in candidates[i]:
            if used[m]:
                continue
            budget[0] -= 1
            if budget[0] < 0:
                return False
            if all(A2[m, perm[l]] == A[i, l] and A2[perm[l], m] == A[l, i] for l in order[:depth]):
                perm[i], used[m] = m, True
                if extend(depth + 1):
                    return True
                perm[i], used[m] = -1, False
        return False

    if not extend(0) or not is_stage_permutation(A, b, A2, b2, perm):
        return None
    return perm
