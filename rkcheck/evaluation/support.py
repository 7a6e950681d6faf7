"""Number contexts run only where a weight may be nonzero (the tableau's pattern of zeros).

A weight is *structurally zero* when it is zero for every tableau with the same zero
entries: ``Φ(u∘v)_i`` when ``Φ(u)_i`` or ``ψ(v)_i`` is, ``ψ_i = Σ_j a_ij Φ_j`` when every
``a_ij Φ_j`` has a zero factor, ``a = Σ_j b_j Φ_j`` likewise, ``w(u∘v)`` when ``w(u)`` or
``a(v)`` is.  Such a weight is exactly 0 at every point of a box whose zero entries are
points (an interval entry is never zero here), so it adds exactly nothing to any sum and
its derivatives are 0.  An explicit tableau has most of its weights structurally zero
(RK4: 96 % of those of the trees with 17 vertices), and a context that stores and
multiplies them all spends most of its time on zeros.

:class:`SupportContext` wraps any context of :mod:`~rkcheck.evaluation.algorithm`'s
kernel and hands it only the rows that may be nonzero.  A value is ``(flags, inner)``:
the flags (one per row, or per row and stage for vectors) say where the weight may be
nonzero, and the inner context's value holds the rows with a flag set, in order (a
gather only notes where they are stored: an operation reads the rows it keeps).  A store
keeps the flags of every tree and, for the trees with one set, their row in a compact
inner store.  The inner context computes every kept row exactly as it would in
a full pass (same operations on the same values): only rows that are exactly zero are
left out.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
import numpy.typing as npt

from rkcheck.evaluation.balls import take_rows


def zero_pattern(A: Sequence[Sequence[Any]], b: Sequence[Any]) -> tuple[np.ndarray, np.ndarray]:
    """(A's, b's entries that are exactly zero) from entries that compare with 0 (exact
    numbers, or intervals that are the point 0)."""
    return (np.array([[_is_zero(x) for x in row] for row in A], dtype=bool),
            np.array([_is_zero(x) for x in b], dtype=bool))


def _is_zero(x: Any) -> bool:
    point = getattr(x, "is_point", None)
    if point is not None:  # an interval: zero only as the point 0
        return bool(point) and x.lo == 0
    return bool(x == 0)


def reach_pattern(nonzero: npt.ArrayLike) -> np.ndarray:
    """The pattern :func:`may_be_nonzero` reads for the products ``x Mᵀ``, from the
    entries of M (outputs × inputs) that may be nonzero: column j, output i, as 0/1
    floats."""
    return np.ascontiguousarray(np.asarray(nonzero, dtype=np.float32).T)


def may_be_nonzero(flags: np.ndarray, pattern: np.ndarray) -> np.ndarray:
    """Where ``x Mᵀ`` may be nonzero, given where ``x`` may be (``flags``, bool, the inputs
    on the last axis): where some input that may be nonzero meets an entry of M that may
    be (``pattern``: :func:`reach_pattern`).  A product of 0/1 floats, exact (each sum
    counts at most s ones, far below 2^24) — numpy's integer products run without BLAS,
    about five times slower."""
    result: np.ndarray = (flags.astype(np.float32) @ pattern) > 0
    return result


class _Store:
    """Flags of every row, each flagged row's place in the compact inner store, and
    how many places are taken (filled in the order of :meth:`SupportContext.put`)."""

    __slots__ = ("flags", "place", "inner", "count")

    def __init__(self, flags: np.ndarray, inner: Any):
        self.flags = flags
        self.place = np.zeros(len(flags), dtype=np.int64)
        self.inner = inner
        self.count = 0

    @property
    def nbytes(self) -> int:
        """The memory of a full store (what callers size their choices by): the compact
        inner store takes at most this."""
        return int(self.flags.nbytes + self.place.nbytes + _nbytes(self.inner))


def _nbytes(value: Any) -> int:
    if isinstance(value, (tuple, list)):
        return sum(_nbytes(v) for v in value)
    return int(getattr(value, "nbytes", 0))


def _rows(flags: np.ndarray) -> np.ndarray:
    """Whether each row has a flag set (its stages or-ed together for vectors): a row of
    2, 4 or 8 flags read as one unsigned integer (a bool is one byte, 0 or 1), which is
    nonzero exactly when one of them is set; other widths column by column."""
    if flags.ndim == 1:
        return flags
    word = _WORDS.get(flags.shape[1])
    if word is not None and flags.dtype == np.bool_ and flags.flags.c_contiguous:
        result: np.ndarray = flags.view(word).reshape(-1) != 0
        return result
    out = flags[:, 0].copy()
    for j in range(1, flags.shape[1]):
        out |= flags[:, j]
    return out


#: unsigned integers as wide as a row of 2, 4 or 8 flags
_WORDS = {2: np.uint16, 4: np.uint32, 8: np.uint64}


class _Stored:
    """The flagged rows of a gather, not yet read: their trees' ids in a store.  Only the rows
    an operation keeps are read (:meth:`SupportContext._inner`) — a product ``w(u)·a(v)``
    keeps the rows where both factors may be nonzero, often far fewer than either's."""

    __slots__ = ("store", "ids")

    def __init__(self, store: _Store, ids: np.ndarray):
        self.store, self.ids = store, ids


class _TermRows:
    """The terms ``i0 … i1 − 1`` of an order restricted to some of them (``rows``): what
    :meth:`block` gives an inner context's ``add_terms``; every other attribute (the
    coefficients and the caches contexts keep on them) is the order's own."""

    def __init__(self, terms: Any, i0: int, i1: int, rows: np.ndarray):
        object.__setattr__(self, "_parts", (terms, i0, i1, rows))
        object.__setattr__(self, "_block", None)

    def block(self, lo: int, hi: int) -> Any:
        terms, i0, i1, rows = self._parts
        if self._block is None:  # read once for the contexts of a pair
            cond, idx = terms.block(i0, i1)
            object.__setattr__(self, "_block", (cond[rows], idx[rows]))
        cond, idx = self._block
        return (cond, idx) if (lo, hi) == (0, len(rows)) else (cond[lo:hi], idx[lo:hi])

    @property
    def all_terms(self) -> Any:
        """The order's own terms, for what a context keeps per order (all its terms)."""
        return self._parts[0]

    def positions(self, lo: int, hi: int) -> np.ndarray:
        """The places among the order's terms of the rows ``lo … hi − 1`` given here, for
        a context's arrays of one entry per term of the order."""
        _, i0, _, rows = self._parts
        result: np.ndarray = i0 + rows[lo:hi]
        return result

    def __getattr__(self, name: str) -> Any:
        return getattr(self._parts[0], name)

    def __setattr__(self, name: str, value: Any) -> None:
        setattr(self._parts[0], name, value)


class SupportContext:
    """The inner context run on the rows that may be nonzero only (module docstring)."""

    exact = False

    def __init__(self, inner: Any, A_zero: np.ndarray, b_zero: np.ndarray):
        self.inner = inner
        self._A_t = reach_pattern(~A_zero)
        self._b = reach_pattern(~b_zero[None, :])[:, 0]

    @property
    def width(self) -> int:
        return getattr(self.inner, "width", 1)

    # ------------------------------------------------------------- storage

    def vectors(self, n: int, s: int) -> Any:
        return _Store(np.zeros((n, s), dtype=bool), self.inner.vectors(n, s))

    def scalars(self, n: int) -> Any:
        return _Store(np.zeros(n, dtype=bool), self.inner.scalars(n))

    def ones(self, k: int, s: int) -> Any:
        return np.ones((k, s), dtype=bool), self.inner.ones(k, s)

    def one(self, k: int) -> Any:
        return np.ones(k, dtype=bool), self.inner.one(k)

    def take(self, store: _Store, idx: np.ndarray) -> Any:
        flags = take_rows(store.flags, idx)
        return flags, _Stored(store, idx[_rows(flags)])

    def _inner(self, x: Any, keep: np.ndarray | None = None) -> Any:
        """The inner value of ``x``'s flagged rows, or of those of them that ``keep`` (a
        mask over them) keeps."""
        inner = x[1]
        if isinstance(inner, _Stored):
            ids = inner.ids if keep is None else inner.ids[keep]
            return self.inner.take(inner.store.inner, inner.store.place[ids])
        return inner if keep is None else self.inner.take(inner, np.flatnonzero(keep))

    def put(self, store: _Store, lo: int, x: Any) -> None:
        flags, inner = x[0], self._inner(x)
        rows = _rows(flags)
        k = int(np.count_nonzero(rows))
        if store.count + k > len(store.flags):
            raise AssertionError("support context: a store was written twice")
        store.flags[lo:lo + len(flags)] = flags
        store.place[lo:lo + len(flags)][rows] = np.arange(store.count, store.count + k)
        if k:
            self.inner.put(store.inner, store.count, inner)
        store.count += k

    # ------------------------------------------------------------- arithmetic

    def _kept(self, x: Any, flags: np.ndarray) -> Any:
        """The inner value of the rows of ``x`` that ``flags`` (a subset of x's) keeps."""
        keep = _rows(flags)[_rows(x[0])]
        return self._inner(x, None if keep.all() else keep)

    def mul(self, x: Any, y: Any) -> Any:
        flags = x[0] & y[0]
        return flags, self.inner.mul(self._kept(x, flags), self._kept(y, flags))

    def matvec(self, x: Any) -> Any:
        flags = may_be_nonzero(x[0], self._A_t)
        return flags, self.inner.matvec(self._kept(x, flags))

    def dot(self, x: Any) -> Any:
        flags = may_be_nonzero(x[0], self._b)
        return flags, self.inner.dot(self._kept(x, flags))

    # ------------------------------------------------------------- condition sums

    def sums(self, k: int, n: int) -> Any:
        return self.inner.sums(k, n)

    def add_terms(self, acc: Any, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        """The terms that may be nonzero only: the others add exactly 0."""
        rows = np.flatnonzero(w_terms[0])
        if len(rows):
            self.inner.add_terms(acc, self._inner(w_terms), _TermRows(terms, i0, i1, rows), n, 0, len(rows))

    def finish_sums(self, acc: Any, k: int, n: int) -> Any:
        return self.inner.finish_sums(acc, k, n)

    def selected_sums(self, part: Any) -> Any:
        return self.inner.selected_sums(part)

    def add_selected(self, acc: Any, w_terms: Any, part: Any, t0: int, t1: int) -> None:
        """The selected terms that may be nonzero only, as :meth:`add_terms`."""
        rows = np.flatnonzero(w_terms[0])
        if len(rows):
            self.inner.add_selected(acc, self._inner(w_terms), _SelectedRows(part, t0 + rows), 0, len(rows))

    def finish_selected(self, acc: Any, part: Any) -> Any:
        return self.inner.finish_selected(acc, part)


class _SelectedRows:
    """Some of the selected terms of a :class:`~rkcheck.evaluation.subset.Subset`'s order
    (``rows``), read as that order's selected terms are: their conditions and coefficient
    indices; the order and its selected conditions are the part's own."""

    def __init__(self, part: Any, rows: np.ndarray):
        self.terms, self.conditions = part.terms, part.conditions
        self.condition, self.coefficient = part.condition[rows], part.coefficient[rows]
