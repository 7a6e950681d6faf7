"""The terms of the energy conditions of one order, as flat arrays (definitions §3).

:func:`rkcheck.trees.classes.classify` builds an :class:`OrderTerms` per number of
vertices; :class:`rkcheck.trees.listing.ConditionListing` keeps them; the evaluation sums
them (:mod:`rkcheck.evaluation.algorithm`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np


class _Factors(Protocol):
    """The Butcher factors of the stored trees (a listing or a tree table)."""

    left: np.ndarray
    right: np.ndarray


@dataclass
class OrderTerms:
    """The conditions with ``vertices`` vertices.  Its terms are the rooted trees with
    that many vertices, in id order: term ``i`` is the tree ``first_id + i`` (orders kept
    in the table) or the product ``left[i] ∘ right[i]`` (the top order); it belongs to
    condition ``condition[i]`` (``len(self)`` for the terms of superfluous trees, which
    are left out) with the coefficient ``coefficients[coefficient_index[i]]``."""

    vertices: int
    first_id: int | None
    left: np.ndarray | None  # int32 factors u, v of each term u ∘ v (top order only)
    right: np.ndarray | None
    condition: np.ndarray  # int32 condition of each term
    coefficient_index: np.ndarray  # int16 into ``coefficients``
    coefficients: list[int]  # the distinct ±(n−1)!/σ(u) of this order (exact, signed)
    counts: np.ndarray  # int32 terms per condition
    rep_left: np.ndarray  # int32 factors of each condition's representative rooting
    rep_right: np.ndarray
    tall: np.ndarray  # int32: for two centres, the other centre's branch (−1 for one centre)
    rest: np.ndarray  # int32: for two centres, the representative minus that branch
    max_degree: np.ndarray  # int16
    superfluous: int = 0  # free trees of this order left out (equal halves across an edge)

    def __len__(self) -> int:
        return len(self.rep_left)

    @property
    def order(self) -> int:
        return self.vertices - 1

    @property
    def terms(self) -> int:
        return int(self.counts.sum())

    @property
    def max_terms(self) -> int:
        return int(self.counts.max(initial=1))

    @property
    def coefficient_weight(self) -> int:
        """``W``, a bound on ``Σ_u |c_u| / g_k`` for every condition k of this order, with
        ``c_u = ±(n−1)!/σ(u)`` the coefficients of its terms and ``g_k`` their gcd:
        ``Σ_u c_u w(u) = g_k · Σ_u (c_u/g_k) w(u)``, and ``g_k`` divides ``(n−1)!``, a
        unit modulo any prime above n, so the integer after ``g_k`` decides a condition's
        zero residues and is at most ``W`` times the largest weight.

        ``W = n``: the terms of a condition are the rootings of one free tree, one per
        orbit O of its automorphism group on the vertices, and ``σ(u)`` is the stabiliser
        of the root, ``|Aut|/|O|``; so ``c_u = K·|O|`` with ``K = (n−1)!/|Aut|``, the gcd
        is ``K·m`` (m the gcd of the orbit sizes: ``K·m`` is an integer combination of
        the ``c_u``) and ``Σ_u |c_u|/g_k = n/m ≤ n``, where ``(n−1)!`` times the terms
        is 2^57 at 19 vertices.  (A free tree with one centre has an orbit of size one,
        so no order does better than n.)"""
        return self.vertices

    def factors(self, i: int, tables: "_Factors") -> tuple[int, int]:
        """(u, v) of term ``i`` (``tables``: the listing whose trees it indexes)."""
        if self.first_id is not None:
            t = self.first_id + i
            return int(tables.left[t]), int(tables.right[t])
        assert self.left is not None and self.right is not None  # the top order keeps its factors
        return int(self.left[i]), int(self.right[i])

    def sign(self, i: int) -> int:
        return 1 if self.coefficients[int(self.coefficient_index[i])] > 0 else -1

    def terms_of(self, k: int) -> np.ndarray:
        """The term indices of condition ``k`` (a scan: for explanations, not bulk work)."""
        return np.flatnonzero(self.condition == k)

