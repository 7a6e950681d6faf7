"""Prime channels of the exact evaluation: arithmetic modulo a prime ``p`` (rationals) or
modulo ``p`` at a root of the minimal polynomial (number fields), on numpy int64 arrays.
:class:`PrimeChannels` runs many channels in one pass over the listing (the exact
route); :class:`ModularChannel` is a single one (order conditions, and the reference
the batched pass is tested against).  Why primes decide exactly:
:mod:`rkcheck.evaluation.modular`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

PRIME_BITS = 30  # residues fit int32; products of two are below 2^60, and sums of SLICE of them below 2^63
#: stages summed at once in ``x Aᵀ`` and ``x b`` before a reduction (8 products below 2^60 each)
SLICE = 8
#: above SLICE stages and up to SPLIT_STAGES, :class:`PrimeChannels` multiplies in float64
#: with the tableau's residues in halves of HALF_BITS (sums below 2^30 · 2^15 · 256 = 2^53)
HALF_BITS = 15
HALF_MASK = (1 << HALF_BITS) - 1
SPLIT_STAGES = 1 << (53 - PRIME_BITS - HALF_BITS)
#: the images of A and b one pass of channels holds: a surrogate of 300 stages needs
#: 500 channels of 0.7 MB each, which in one pass took a gigabyte; passes are then
#: narrowed to this much (a tableau of a few stages is never narrowed by it)
IMAGE_PASS_BYTES = 64 << 20
#: bytes per entry and channel of those images at their peak: each channel's images,
#: then stacked, reduced and transposed (:class:`PrimeChannels`); or, while the pass
#: runs, the transposed images and their float halves
IMAGE_BYTES_PER_ENTRY = 32
_PRIME_LIMIT = 1 << PRIME_BITS


def image_bytes(stages: int) -> int:
    """What one channel's images of A and b take at their peak."""
    return IMAGE_BYTES_PER_ENTRY * (stages * stages + stages)


def held_image_bytes(stages: int) -> int:
    """What one channel's images of A take while its context lives: the transposed
    residues, and their float halves where the products go through them."""
    halves = SLICE < stages <= SPLIT_STAGES
    return (8 + (16 if halves else 0)) * stages * stages


def channels_per_image_pass(stages: int) -> int:
    """How many channels' images of a tableau of ``stages`` stages one pass may hold
    within :data:`IMAGE_PASS_BYTES` (at least one)."""
    return max(1, IMAGE_PASS_BYTES // image_bytes(stages))


def is_prime(n: int) -> bool:
    """Deterministic Miller–Rabin for n < 3.3·10^24 (bases 2 … 41), far beyond the 30-bit
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


#: primes the first window below a limit holds at least
_FIRST_WINDOW = 4096

#: the primes found below each limit so far, largest first: a smaller count is a prefix
_FOUND: dict[int, tuple[int, ...]] = {}


def _primes_below(limit: int, count: int) -> tuple[int, ...]:
    """The ``count`` largest primes below ``limit`` (deterministic), largest first (all of
    them when there are fewer)."""
    known = _FOUND.get(limit, ())
    if len(known) >= count:
        return known[:count]
    # a window sieved at once: a Miller–Rabin test per odd number cost ~10 µs each,
    # 0.2 s for the thousands of primes of a field of high degree.  Primes near 2^30 are
    # ~21 apart: the first window nearly always suffices, a short one is doubled.  A
    # window costs about the same whatever its width (the loop over the primes below
    # √limit), so the first is wide enough for the counts that follow (checks ask for
    # 64, then 128, 256 … primes)
    span = 32 * max(count, _FIRST_WINDOW) + 1024
    while True:
        lo = max(limit - span, 0)
        found = _sieve_window(lo, limit)[::-1]
        if len(found) >= count or lo == 0:
            _FOUND[limit] = tuple(int(q) for q in found)
            return _FOUND[limit][:count]
        span *= 2


def _sieve_window(lo: int, hi: int) -> np.ndarray:
    """The primes ``lo <= q < hi``, ascending: the window's multiples of every prime up to
    √hi struck out (a segmented sieve of Eratosthenes)."""
    root = math.isqrt(max(hi - 1, 0))
    small = np.ones(root + 1, dtype=bool)
    small[:2] = False
    for k in range(2, math.isqrt(root) + 1):
        if small[k]:
            small[k * k::k] = False
    window = np.ones(hi - lo, dtype=bool)
    window[:max(0, 2 - lo)] = False  # 0 and 1
    for k in np.flatnonzero(small).tolist():
        start = max(k * k, (lo + k - 1) // k * k)  # below k², a multiple has a smaller factor
        window[start - lo::k] = False
    return np.flatnonzero(window) + lo


def primes(count: int, skip: int = 0) -> tuple[int, ...]:
    """Primes below 2^30, largest first, in a fixed order (``skip`` them first)."""
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
        self._coef_cache: dict[int, tuple[Any, ...]] = {}
        self.A_t = np.ascontiguousarray(A.T % p)
        self.b = b % p
        self.s = len(b)

    # Stored weights are residues below 2^30: int32 halves the memory; arithmetic
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
        result: np.ndarray = x[idx].astype(np.int64)
        return result

    def put(self, store: np.ndarray, lo: int, x: np.ndarray) -> None:
        store[lo:lo + len(x)] = x

    def mul(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        z = x * y
        z %= self.p
        result: np.ndarray = z
        return result

    def matvec(self, x: np.ndarray) -> np.ndarray:
        if self.s <= SLICE:
            z = x @ self.A_t
            z %= self.p
            result: np.ndarray = z
            return result
        z = np.zeros((len(x), self.s), dtype=np.int64)
        for k in range(0, self.s, SLICE):
            z += (x[:, k:k + SLICE] @ self.A_t[k:k + SLICE]) % self.p
            z %= self.p
        return z

    def dot(self, x: np.ndarray) -> np.ndarray:
        if self.s <= SLICE:
            z = x @ self.b
            z %= self.p
            result: np.ndarray = z
            return result
        return _chunked_dot(x, self.b, self.p)

    def sums(self, k: int, n: int) -> np.ndarray:
        # float64 bins: a condition sums at most 21 residues below 2^30 (< 2^35), far
        # inside the 2^53 integers a double holds exactly, and bincount is fast
        return np.zeros(k, dtype=np.float64)

    def add_terms(self, acc: np.ndarray, w_terms: np.ndarray, terms: Any, n: int, i0: int, i1: int) -> None:
        """Add ``((n−1)!/σ)·(±ŵ)`` modulo p of terms i0 … i1−1 to their conditions' bins."""
        p = self.p
        cond, idx = terms.block(i0, i1)
        w_terms *= self._coefficients(terms, n)[idx]
        w_terms %= p
        acc += np.bincount(cond, weights=w_terms, minlength=len(acc))

    def finish_sums(self, acc: np.ndarray, k: int, n: int) -> np.ndarray:
        """The residues of N per condition (the extra bin dropped)."""
        return acc[:k].astype(np.int64) % self.p

    def _coefficients(self, terms: Any, n: int) -> np.ndarray:
        cached = self._coef_cache.get(n)
        if cached is None or cached[0] is not terms:
            cached = (terms, np.array([c % self.p for c in terms.coefficients], dtype=np.int64))  # signs as residues
            self._coef_cache[n] = cached
        result: np.ndarray = cached[1]
        return result


class PrimeChannels:
    """Several channels in one pass: channel ``k`` computes modulo ``P[k]`` with the images
    ``A[k]``, ``b[k]`` of the tableau (distinct primes, the roots of one prime, or both).

    Every array has a leading channel axis (vectors ``(K, n, s)``, scalars ``(K, n)``), so
    each arithmetic call runs over long contiguous rows, and a block of rows costs one
    call per operation for all channels: the tree ids, factors, conditions and
    coefficient indices are read once per pass instead of once per channel.  Results are
    the same residues, bit for bit, as one :class:`ModularChannel` pass per channel."""

    exact = True

    def __init__(self, moduli: list[int], A: np.ndarray, b: np.ndarray):
        # A: (K, s, s), b: (K, s) — the images of Â and b̂ in each channel
        self.width = len(moduli)
        self.P = np.array(moduli, dtype=np.int64)
        self.s = b.shape[1]
        self.A_t = np.ascontiguousarray(np.transpose(np.asarray(A, dtype=np.int64) % self.P[:, None, None], (0, 2, 1)))
        self.b = np.ascontiguousarray((np.asarray(b, dtype=np.int64) % self.P[:, None])[:, :, None])  # (K, s, 1)
        self._P2, self._P3 = self.P[:, None], self.P[:, None, None]
        self._coef_cache: dict[int, tuple[Any, ...]] = {}

    def vectors(self, n: int, s: int) -> np.ndarray:
        return np.zeros((self.width, n, s), dtype=np.int32)

    def scalars(self, n: int) -> np.ndarray:
        return np.zeros((self.width, n), dtype=np.int32)

    def ones(self, k: int, s: int) -> np.ndarray:
        return np.ones((self.width, k, s), dtype=np.int64)

    def one(self, k: int) -> np.ndarray:
        return np.ones((self.width, k), dtype=np.int64)

    def take(self, x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return np.take(x, idx, axis=1).astype(np.int64)

    def put(self, store: np.ndarray, lo: int, x: np.ndarray) -> None:
        store[:, lo:lo + x.shape[1]] = x

    def _reduce(self, z: np.ndarray) -> np.ndarray:
        z %= self._P3 if z.ndim == 3 else self._P2
        return z

    def mul(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return self._reduce(x * y)

    def _product(self, x: np.ndarray, M: np.ndarray) -> np.ndarray:
        """``x[k] @ M[k]`` per channel modulo ``P[k]``, in slices of SLICE stages (a sum
        of SLICE products of residues stays below 2^63)."""
        if self.s <= SLICE:
            return self._reduce(np.matmul(x, M))
        if self.s <= SPLIT_STAGES:
            return self._split_product(x, *self._halves(M))
        z = np.zeros(x.shape[:2] + M.shape[2:], dtype=np.int64)
        for k in range(0, self.s, SLICE):
            z += self._reduce(np.matmul(x[:, :, k:k + SLICE], M[:, k:k + SLICE]))
            self._reduce(z)
        return z

    def _halves(self, M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``M = 2^15·high + low`` with both halves below 2^15, as float64 (kept per matrix)."""
        cache = self.__dict__.setdefault("_half_cache", {})
        got = cache.get(id(M))
        if got is None:
            got = cache[id(M)] = (M, (M >> HALF_BITS).astype(np.float64), (M & HALF_MASK).astype(np.float64))
        return got[1], got[2]

    def _split_product(self, x: np.ndarray, high: np.ndarray, low: np.ndarray) -> np.ndarray:
        """``x @ M`` modulo P with ``M`` in two halves of 15 bits, each product in float64:
        a residue times a half is below 2^45, and a sum of at most SPLIT_STAGES of them
        below 2^53, so every partial sum is an integer a double holds exactly, in any
        order of summation — the result is the exact one, from BLAS instead of
        numpy's integer loops (three times faster at 33 stages)."""
        xf = x.astype(np.float64)
        z = self._reduce(np.matmul(xf, high).astype(np.int64))
        z <<= HALF_BITS
        z += np.matmul(xf, low).astype(np.int64)
        return self._reduce(z)

    def matvec(self, x: np.ndarray) -> np.ndarray:
        return self._product(x, self.A_t)

    def dot(self, x: np.ndarray) -> np.ndarray:
        return self._product(x, self.b)[:, :, 0]

    def sums(self, k: int, n: int) -> "_Bins":
        return _Bins(self.width, k)

    def add_terms(self, acc: "_Bins", w_terms: np.ndarray, terms: Any, n: int, i0: int, i1: int) -> None:
        """Add ``((n−1)!/σ)·(±ŵ)`` modulo each channel's prime to the conditions' bins."""
        w_terms *= np.take(self._coefficients(terms, n), terms.coefficient_indices(i0, i1), axis=1)
        acc.add(self._reduce(w_terms), terms, i0, i1)

    def finish_sums(self, acc: "_Bins", k: int, n: int) -> np.ndarray:
        """The residues per condition and channel, ``(k, K)``."""
        return (acc.total()[:, :k].astype(np.int64) % self._P2).T

    def selected_sums(self, part: Any) -> np.ndarray:
        """Bins for the selected conditions of ``part`` (a
        :class:`~rkcheck.evaluation.subset.Subset`'s order), whose terms come in any
        order: float64, exact (at most 21 residues below 2^30 a condition)."""
        return np.zeros((self.width, part.conditions), dtype=np.float64)

    def add_selected(self, acc: np.ndarray, w_terms: np.ndarray, part: Any, t0: int, t1: int) -> None:
        """Add ``((n−1)!/σ)·(±ŵ)`` of the selected terms ``t0 … t1−1`` of ``part``
        modulo each channel's prime to the bins ``acc``."""
        terms = part.terms
        w_terms *= np.take(self._coefficients(terms, terms.vertices), part.coefficient[t0:t1], axis=1)
        w = self._reduce(w_terms).astype(np.float64)
        cond = part.condition[t0:t1].astype(np.intp)
        for c in range(self.width):
            acc[c] += np.bincount(cond, weights=w[c], minlength=acc.shape[1])

    def finish_selected(self, acc: np.ndarray, part: Any) -> np.ndarray:
        """The residues per condition and channel, ``(k, K)``."""
        return (acc.astype(np.int64) % self._P2).T

    def _coefficients(self, terms: Any, n: int) -> np.ndarray:
        cached = self._coef_cache.get(n)
        if cached is None or cached[0] is not terms:
            table = np.array([[c % p for c in terms.coefficients] for p in self.P.tolist()], dtype=np.int64)
            cached = self._coef_cache[n] = (terms, table)  # signs as residues
        result: np.ndarray = cached[1]
        return result


class _Bins:
    """The condition sums of every channel, in int64 (a condition sums at most 21
    residues below 2^30: exact).  Each block of terms is added where it lands
    (``np.add.at``): no buffer of terms, no pass over every bin per call — at the top
    orders a block is far smaller than the millions of conditions it lands in, and
    binning runs of blocks with ``np.bincount`` held a run, its conditions widened to
    intp and a full array of bins besides the sums (about 50 MB at 21 vertices)."""

    def __init__(self, width: int, k: int):
        self.sums = np.zeros((width, k), dtype=np.int64)
        # channel c's bins start at c·k in the flat sums: one call adds every channel
        self._offsets = (np.arange(width, dtype=np.intp) * k)[:, None] if width > 1 else None

    def add(self, w: np.ndarray, terms: Any, i0: int, i1: int) -> None:
        """The residues ``w`` (channels × terms, int64) of the terms ``i0 … i1 − 1`` of
        ``terms`` (an :class:`~rkcheck.trees.terms.OrderTerms`)."""
        cond = terms.conditions(i0, i1)
        if self._offsets is None:
            np.add.at(self.sums[0], cond, w[0])
        else:
            np.add.at(self.sums.reshape(-1), (cond + self._offsets).reshape(-1), w.reshape(-1))

    def total(self) -> np.ndarray:
        return self.sums


def _chunked_dot(x: np.ndarray, b: np.ndarray, p: int) -> np.ndarray:
    z = np.zeros(len(x), dtype=np.int64)
    for k in range(0, len(b), SLICE):
        z += (x[:, k:k + SLICE] @ b[k:k + SLICE]) % p
        z %= p
    return z
