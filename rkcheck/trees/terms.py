"""The terms of the energy conditions of one order, as flat arrays (definitions §3).

:func:`rkcheck.trees.classes.classify` builds an :class:`OrderTerms` per number of
vertices; :class:`rkcheck.trees.listing.ConditionListing` keeps them; the evaluation sums
them (:mod:`rkcheck.evaluation.algorithm`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np


class _Factors(Protocol):
    """The Butcher factors of the stored trees (a listing or a tree table)."""

    left: np.ndarray
    right: Any  # int32 ids, or a listing's RightFactors (reads alike)


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
    condition: np.ndarray | None  # int32 condition of each term (None once packed)
    coefficient_index: np.ndarray | None  # int16 into ``coefficients`` (None once packed)
    coefficients: list[int]  # the distinct ±(n−1)!/σ(u) of this order (exact, signed)
    counts: np.ndarray  # int32 terms per condition
    rep_left: np.ndarray  # int32 factors of each condition's representative rooting
    rep_right: np.ndarray
    tall: np.ndarray  # int32: for two centres, the other centre's branch (−1 for one centre)
    rest: np.ndarray  # int32: for two centres, the representative minus that branch
    max_degree: np.ndarray  # int16
    superfluous: int = 0  # free trees of this order left out (equal halves across an edge)
    # condition | coefficient index << condition_bits per term, when :meth:`pack` fitted both
    packed: np.ndarray | None = None
    condition_bits: int = 0

    def __len__(self) -> int:
        return len(self.rep_left)

    @property
    def rows(self) -> int:
        """The terms, superfluous trees included."""
        rows = self.packed if self.packed is not None else self.condition
        assert rows is not None
        return len(rows)

    def block(self, i0: int, i1: int) -> tuple[np.ndarray, np.ndarray]:
        """``(condition, coefficient index)`` of the terms ``i0 … i1 − 1``."""
        return self.conditions(i0, i1), self.coefficient_indices(i0, i1)

    def conditions(self, i0: int, i1: int) -> np.ndarray:
        """The condition of each of the terms ``i0 … i1 − 1``."""
        return self._conditions(slice(i0, i1))

    def coefficient_indices(self, i0: int, i1: int) -> np.ndarray:
        """The index into :attr:`coefficients` of each of the terms ``i0 … i1 − 1``."""
        return self._coefficient_indices(slice(i0, i1))

    def at(self, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(condition, coefficient index)`` of the terms at the positions ``index``."""
        return self._conditions(index), self._coefficient_indices(index)

    def _conditions(self, index: slice | np.ndarray) -> np.ndarray:
        if self.packed is None:
            assert self.condition is not None
            return self.condition[index]
        return (self.packed[index] & np.uint32((1 << self.condition_bits) - 1)).view(np.int32)

    def _coefficient_indices(self, index: slice | np.ndarray) -> np.ndarray:
        if self.packed is None:
            assert self.coefficient_index is not None
            return self.coefficient_index[index]
        return (self.packed[index] >> np.uint32(self.condition_bits)).view(np.int32)

    def pack(self) -> None:
        """Keep each term's condition and coefficient index in one 32-bit word, in place
        of the condition's (the coefficient indices' int16 array goes: a sixth of a
        large listing), when both fit; :meth:`block` reads them back."""
        if self.packed is not None or self.condition is None or self.coefficient_index is None:
            return
        bits = len(self).bit_length()  # conditions 0 … len (the superfluous trees' bin)
        if bits + max(len(self.coefficients) - 1, 0).bit_length() > 32 or self.condition.dtype != np.int32:
            return
        packed = self.condition.view(np.uint32)
        for i in range(0, len(packed), _PACK_CHUNK):
            packed[i:i + _PACK_CHUNK] |= self.coefficient_index[i:i + _PACK_CHUNK].astype(np.uint32) << np.uint32(bits)
        self.packed, self.condition_bits = packed, bits
        self.condition = self.coefficient_index = None

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

    def coefficient(self, i: int) -> int:
        """The signed coefficient ``±(n−1)!/σ`` of term ``i``."""
        return self.coefficients[int(self.coefficient_indices(i, i + 1)[0])]

    def sign(self, i: int) -> int:
        return 1 if self.coefficient(i) > 0 else -1

    def terms_of(self, k: int) -> np.ndarray:
        """The term indices of condition ``k`` (a scan: for explanations, not bulk work)."""
        found = [np.flatnonzero(self.conditions(i, i + _PACK_CHUNK) == k) + i for i in range(0, self.rows, _PACK_CHUNK)]
        return np.concatenate(found) if found else np.zeros(0, dtype=np.intp)


#: terms packed or scanned at once: bounds the temporaries
_PACK_CHUNK = 1 << 22

