"""Prime channels of the exact evaluation: arithmetic modulo one prime ``p`` (rationals)
or modulo ``p`` at the roots of the minimal polynomial (number fields), on numpy int64
arrays — one :class:`~rkcheck.evaluation.protocols.NumberContext` per prime and root.
Why primes decide exactly: :mod:`rkcheck.evaluation.modular`.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

PRIME_BITS = 29  # products of two residues and sums of 32 of them stay below 2^63
_PRIME_LIMIT = 1 << PRIME_BITS


def is_prime(n: int) -> bool:
    """Deterministic Miller–Rabin for n < 3.3·10^24 (bases 2 … 41), far beyond the 29-bit
    primes used here; no library import on the start-up path."""
    if n < 2:
        return False
    small = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41)
    if n in small:
        return True
    if any(n % p == 0 for p in small):
        return False
    d, r = n - 1, 0
    while d % 2 == 0:
        d //= 2
        r += 1
    for a in small:
        x = pow(a, d, n)
        if x in (1, n - 1):
            continue
        for _ in range(r - 1):
            x = x * x % n
            if x == n - 1:
                break
        else:
            return False
    return True


@lru_cache(maxsize=4)
def _primes_below(limit: int, count: int) -> tuple[int, ...]:
    """The ``count`` largest primes below ``limit`` (deterministic)."""
    out: list[int] = []
    q = limit - 1
    while len(out) < count:
        if is_prime(q):
            out.append(q)
        q -= 2 if q % 2 else 1
    return tuple(out)


def primes(count: int, skip: int = 0) -> tuple[int, ...]:
    """Primes below 2^29, largest first, in a fixed order (``skip`` them first)."""
    size = 64
    while size < count + skip:
        size *= 2
    return _primes_below(_PRIME_LIMIT, size)[skip:skip + count]


# ---------------------------------------------------------------------- one channel


class ModularChannel:
    """The arithmetic of one channel: int64 numpy arrays of residues modulo ``p``."""

    exact = True

    def __init__(self, p: int, A: np.ndarray, b: np.ndarray):
        self.p = p
        self._coef_cache: dict[int, tuple] = {}
        self.A_t = np.ascontiguousarray(A.T % p)
        self.b = b % p
        self.s = len(b)

    # Stored weights are residues below 2^29: int32 halves the memory; arithmetic
    # widens to int64 (a product of two residues needs 58 bits).
    def vectors(self, n: int, s: int) -> np.ndarray:
        return np.zeros((n, s), dtype=np.int32)

    def scalars(self, n: int) -> np.ndarray:
        return np.zeros(n, dtype=np.int32)

    def ones(self, k: int, s: int) -> np.ndarray:
        return np.ones((k, s), dtype=np.int64)

    def one(self, k: int) -> np.ndarray:
        return np.ones(k, dtype=np.int64)

    def take(self, x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return x[idx].astype(np.int64)

    def put(self, store: np.ndarray, lo: int, x: np.ndarray) -> None:
        store[lo:lo + len(x)] = x

    def mul(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        z = x * y
        z %= self.p
        return z

    def matvec(self, x: np.ndarray) -> np.ndarray:
        if self.s <= 32:
            z = x @ self.A_t
            z %= self.p
            return z
        z = np.zeros((len(x), self.s), dtype=np.int64)
        for k in range(0, self.s, 32):
            z += (x[:, k:k + 32] @ self.A_t[k:k + 32]) % self.p
            z %= self.p
        return z

    def dot(self, x: np.ndarray) -> np.ndarray:
        if self.s <= 32:
            z = x @ self.b
            z %= self.p
            return z
        return _chunked_dot(x, self.b, self.p)

    def sums(self, k: int, n: int) -> np.ndarray:
        # float64 bins: a condition sums at most 21 residues below 2^29 (< 2^34), far
        # inside the 2^53 integers a double holds exactly, and bincount is fast
        return np.zeros(k, dtype=np.float64)

    def add_terms(self, acc: np.ndarray, w_terms: np.ndarray, terms, n: int, i0: int, i1: int) -> None:
        """Add ``((n−1)!/σ)·(±ŵ)`` modulo p of terms i0 … i1−1 to their conditions' bins."""
        p = self.p
        w_terms *= self._coefficients(terms, n)[terms.coefficient_index[i0:i1]]
        w_terms %= p
        acc += np.bincount(terms.condition[i0:i1], weights=w_terms, minlength=len(acc))

    def finish_sums(self, acc: np.ndarray, k: int, n: int) -> np.ndarray:
        """The residues of N per condition (the extra bin dropped)."""
        return acc[:k].astype(np.int64) % self.p

    def _coefficients(self, terms, n: int) -> np.ndarray:
        cached = self._coef_cache.get(n)
        if cached is None or cached[0] is not terms:
            cached = (terms, np.array([c % self.p for c in terms.coefficients], dtype=np.int64))  # signs as residues
            self._coef_cache[n] = cached
        return cached[1]


class RootsChannel(ModularChannel):
    """All ``R`` roots of one prime at once: the channels ``θ ↦ r_1 … r_R`` modulo the same
    ``p`` share every index operation, so they run as one pass over arrays with a leading
    root axis — vectors ``(R, n, s)``, scalars ``(R, n)`` — instead of ``R`` passes (the
    per-call overhead of numpy dominates at the sizes of a field check).  Results are
    the same residues, bit for bit, as ``R`` separate :class:`ModularChannel` passes."""

    def __init__(self, p: int, A: np.ndarray, b: np.ndarray):
        # A: (R, s, s), b: (R, s) — the images of Â and b̂ under each root
        self.p = p
        self._coef_cache = {}
        self.R = self.width = A.shape[0]
        self.A_t = np.ascontiguousarray(np.transpose(A, (0, 2, 1)) % p)  # x @ Aᵀ per root
        self.b = np.ascontiguousarray((b % p)[:, :, None])  # (R, s, 1)
        self.s = b.shape[1]

    def vectors(self, n: int, s: int) -> np.ndarray:
        return np.zeros((self.R, n, s), dtype=np.int32)

    def scalars(self, n: int) -> np.ndarray:
        return np.zeros((self.R, n), dtype=np.int32)

    def ones(self, k: int, s: int) -> np.ndarray:
        return np.ones((self.R, k, s), dtype=np.int64)

    def one(self, k: int) -> np.ndarray:
        return np.ones((self.R, k), dtype=np.int64)

    def take(self, x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return x[:, idx].astype(np.int64)

    def put(self, store: np.ndarray, lo: int, x: np.ndarray) -> None:
        store[:, lo:lo + x.shape[1]] = x

    def _product(self, x: np.ndarray, M: np.ndarray) -> np.ndarray:
        """``x @ M`` per root modulo p, in slices of 32 stages (no int64 overflow)."""
        if self.s <= 32:
            z = x @ M
            z %= self.p
            return z
        z = np.zeros(x.shape[:2] + M.shape[2:], dtype=np.int64)
        for k in range(0, self.s, 32):
            z += (x[:, :, k:k + 32] @ M[:, k:k + 32]) % self.p
            z %= self.p
        return z

    def matvec(self, x: np.ndarray) -> np.ndarray:
        return self._product(x, self.A_t)

    def dot(self, x: np.ndarray) -> np.ndarray:
        return self._product(x, self.b)[:, :, 0]

    def sums(self, k: int, n: int) -> np.ndarray:
        return np.zeros((self.R, k), dtype=np.float64)

    def add_terms(self, acc: np.ndarray, w_terms: np.ndarray, terms, n: int, i0: int, i1: int) -> None:
        p = self.p
        w_terms *= self._coefficients(terms, n)[terms.coefficient_index[i0:i1]]
        w_terms %= p
        cond = terms.condition[i0:i1]
        for r in range(self.R):
            acc[r] += np.bincount(cond, weights=w_terms[r], minlength=acc.shape[1])

    def finish_sums(self, acc: np.ndarray, k: int, n: int) -> np.ndarray:
        """The residues per condition and root, ``(k, R)``."""
        return (acc[:, :k].astype(np.int64) % self.p).T


def _chunked_dot(x: np.ndarray, b: np.ndarray, p: int) -> np.ndarray:
    z = np.zeros(len(x), dtype=np.int64)
    for k in range(0, len(b), 32):
        z += (x[:, k:k + 32] @ b[k:k + 32]) % p
        z %= p
    return z
