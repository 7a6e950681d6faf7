"""The number context of families: elementary weights and condition sums as exact
polynomials in the parameters (:mod:`rkcheck.numbers.parametric`).

The same algorithm as every other context (:mod:`rkcheck.evaluation.algorithm`) runs
over numpy arrays of FLINT multivariate polynomials (object arrays: numpy's elementwise
products and matrix products call the polynomials' own arithmetic).  Products are
reduced modulo the field's minimal polynomial as they are formed, so degrees in θ stay
below the field degree.
"""

from __future__ import annotations

from fractions import Fraction
from math import factorial
from typing import Any, Callable, Sequence

import numpy as np

from rkcheck.errors import UserError
from rkcheck.numbers.parametric import MAX_PRODUCT_WORK, ParameterRing, object_array
from rkcheck.numbers.room import RoomWatch

#: Terms the stored weights and condition sums of one family check may hold together
#: (50 bytes a term with 30 parameters, about 100 with the temporaries: two gigabytes).
MAX_FAMILY_TERMS = 20_000_000

#: products of terms, and polynomials formed, per slice of the rows of one array
#: operation (about 0.1 s; coefficients of hundreds of digits make a few megabytes of
#: results): the memory left is looked at between slices
SLICE_PRODUCTS = 1_000_000
SLICE_ENTRIES = 4096

_REMEDY = "check a lower order, a degree bound or fewer parameters"


def _terms(x: np.ndarray) -> np.ndarray:
    """The number of terms of each polynomial of ``x``."""
    return np.fromiter((len(v) for v in x.reshape(-1)), dtype=np.int64, count=x.size).reshape(x.shape)


class PolynomialContext:
    """Exact arithmetic on arrays of polynomials over a :class:`ParameterRing`.

    Polynomials in many parameters grow fast with the order (a 5-stage tableau with every
    entry free: 7 GB at order 8), and a product of two of them runs in FLINT's C, where
    neither Ctrl-C nor SIGTERM reaches it: each array operation is refused before it
    would take more than :data:`MAX_PRODUCT_WORK` products of terms, the weights and sums
    kept stay within :data:`MAX_FAMILY_TERMS` terms, and no step starts without the
    memory it may take (:class:`~rkcheck.numbers.room.RoomWatch`: their coefficients
    can take more than their terms)."""

    exact = True

    def __init__(self, ring: ParameterRing, A: Sequence[Sequence[Any]], b: Sequence[Any]):
        self.ring = ring
        self.held = 0  # terms of the weights stored and of the condition sums
        self.room = RoomWatch("the conditions' polynomials", _REMEDY)
        self.s = len(b)
        self.zero, self.unit = ring.constant(0), ring.constant(1)
        self.b = object_array(list(b), (self.s,))
        # a kernel family's A = V C Wᵀ (methods.parametric.KernelMatrix): x Aᵀ = ((x W) Cᵀ) Vᵀ,
        # its n² entries never gathered into a matrix
        factors = getattr(A, "factors", None)
        self.factors = None if factors is None else \
            (factors[2], np.ascontiguousarray(factors[1].T), np.ascontiguousarray(factors[0].T))
        self.A_t = None if self.factors is not None else \
            object_array([A[i][j] for j in range(self.s) for i in range(self.s)], (self.s, self.s))

    def _filled(self, shape: tuple[int, ...], value: Any) -> np.ndarray:
        return object_array([value] * int(np.prod(shape)), shape)

    def _reduced(self, x: np.ndarray) -> np.ndarray:
        if self.ring.minpoly is None:
            return x
        return object_array([self.ring.reduce(v) for v in x.reshape(-1)], x.shape)

    def vectors(self, n: int, s: int) -> np.ndarray:
        return self._filled((n, s), self.zero)

    def scalars(self, n: int) -> np.ndarray:
        return self._filled((n,), self.zero)

    def ones(self, k: int, s: int) -> np.ndarray:
        return self._filled((k, s), self.unit)

    def one(self, k: int) -> np.ndarray:
        return self._filled((k,), self.unit)

    def take(self, x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        result: np.ndarray = x[idx]
        return result

    def put(self, store: np.ndarray, lo: int, x: np.ndarray) -> None:
        self._hold(int(_terms(x).sum()))
        store[lo:lo + len(x)] = x

    def mul(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        per_row = _terms(x) * _terms(y)
        return self._sliced(lambda u, v: self._reduced(u * v), per_row, x, y)

    def matvec(self, x: np.ndarray) -> np.ndarray:
        if self.factors is not None:  # W and V are rational: only C's products need reducing
            W, C_t, V_t = self.factors
            return self._matmul(self._matmul(self._matmul(x, W), C_t, reduce=True), V_t)
        assert self.A_t is not None
        A_t = self.A_t
        return self._sliced(lambda u: self._reduced(u @ A_t), _terms(x) @ _terms(A_t), x)

    def dot(self, x: np.ndarray) -> np.ndarray:
        b = self.b
        return self._sliced(lambda u: self._reduced(u @ b), _terms(x) @ _terms(b), x)

    def _matmul(self, x: np.ndarray, M: np.ndarray, reduce: bool = False) -> np.ndarray:
        return self._sliced(lambda u: self._reduced(u @ M) if reduce else u @ M, _terms(x) @ _terms(M), x)

    def _sliced(self, op: Callable[..., np.ndarray], products: np.ndarray, *arrays: np.ndarray) -> np.ndarray:
        """``op(*arrays)``, over slices of their rows of at most about
        :data:`SLICE_PRODUCTS` products of terms and :data:`SLICE_ENTRIES` results each
        (``products``: each result's, by rows), the memory left looked at before each
        slice: one operation on the weights of an order's trees is most of what the
        order takes."""
        per_row = products.reshape(len(products), -1).sum(axis=1) if products.ndim > 1 else products
        total = int(per_row.sum())
        if total > MAX_PRODUCT_WORK:
            raise UserError(f"the conditions' polynomials grow too large: one step would take about {total:,} "
                            f"products of terms, more than the limit MAX_PRODUCT_WORK = {MAX_PRODUCT_WORK:,}; "
                            + _REMEDY)
        n = len(per_row)
        rows = max(1, SLICE_ENTRIES // max(1, products.size // max(1, n)))
        if n <= 1 or (total <= SLICE_PRODUCTS and n <= rows):
            self.room.step()
            return op(*arrays)
        ends = np.searchsorted(np.cumsum(per_row), np.arange(SLICE_PRODUCTS, total, SLICE_PRODUCTS), side="right")
        bounds = np.unique(np.concatenate([[0], ends, np.arange(rows, n, rows), [n]]))
        parts = []
        for lo, hi in zip(bounds[:-1], bounds[1:]):
            self.room.step()
            parts.append(op(*(a[lo:hi] for a in arrays)))
        return np.concatenate(parts)

    def _hold(self, terms: int) -> None:
        self.held += terms
        if self.held > MAX_FAMILY_TERMS:
            raise UserError(f"the conditions' polynomials grow too large: more than {MAX_FAMILY_TERMS:,} terms "
                            "(the limit MAX_FAMILY_TERMS); " + _REMEDY)

    def sums(self, k: int, n: int) -> np.ndarray:
        return self.scalars(k)

    def add_terms(self, acc: np.ndarray, w_terms: np.ndarray, terms: Any, n: int, i0: int, i1: int) -> None:
        coefficients = [self.ring.constant(c) for c in terms.coefficients]
        grown = 0
        for cond, ci, w in zip(*terms.block(i0, i1), w_terms):
            self.room.step()
            before = len(acc[cond])
            acc[cond] = acc[cond] + coefficients[ci] * w
            grown += len(acc[cond]) - before
        self._hold(grown)

    def finish_sums(self, acc: np.ndarray, k: int, n: int) -> "PolynomialSums":
        scale = self.ring.constant(Fraction(1, factorial(n - 1)))
        return PolynomialSums([self.ring.reduce(acc[i] * scale) for i in range(k)])


class PolynomialSums:
    """The residuals of one order's conditions (class representative's rooting) as
    polynomials: exact, so ``is_zero`` says which vanish identically."""

    def __init__(self, values: list[Any]):
        self.values = values

    def __len__(self) -> int:
        return len(self.values)

    def is_zero(self) -> np.ndarray:
        return np.array([v.is_zero() for v in self.values], dtype=bool)

    def value(self, k: int) -> Any:
        return self.values[k]
