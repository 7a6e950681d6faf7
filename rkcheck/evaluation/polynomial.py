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
from typing import Any, Sequence

import numpy as np

from rkcheck.numbers.parametric import ParameterRing, object_array


class PolynomialContext:
    """Exact arithmetic on arrays of polynomials over a :class:`ParameterRing`."""

    exact = True

    def __init__(self, ring: ParameterRing, A: Sequence[Sequence[Any]], b: Sequence[Any]):
        self.ring = ring
        self.s = len(b)
        self.zero, self.unit = ring.constant(0), ring.constant(1)
        self.b = object_array(list(b), (self.s,))
        # a kernel family's A = V C Wᵀ (methods.parametric.KernelMatrix): x Aᵀ = ((x W) Cᵀ) Vᵀ,
        # its n² entries never gathered into a matrix
        factors = getattr(A, "factors", None)
        self.factors = None if factors is None or ring.minpoly is not None else \
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
        store[lo:lo + len(x)] = x

    def mul(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return self._reduced(x * y)

    def matvec(self, x: np.ndarray) -> np.ndarray:
        if self.factors is not None:
            W, C_t, V_t = self.factors
            result: np.ndarray = ((x @ W) @ C_t) @ V_t
            return result
        return self._reduced(x @ self.A_t)

    def dot(self, x: np.ndarray) -> np.ndarray:
        return self._reduced(x @ self.b)

    def sums(self, k: int, n: int) -> np.ndarray:
        return self.scalars(k)

    def add_terms(self, acc: np.ndarray, w_terms: np.ndarray, terms: Any, n: int, i0: int, i1: int) -> None:
        coefficients = [self.ring.constant(c) for c in terms.coefficients]
        for cond, ci, w in zip(*terms.block(i0, i1), w_terms):
            acc[cond] = acc[cond] + coefficients[ci] * w

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
