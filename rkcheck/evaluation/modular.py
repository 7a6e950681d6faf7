"""Exact evaluation by residues modulo primes (definitions §5: ``holds`` / ``fails`` with
no digits), for rational tableaux and for tableaux in a number field ``Q(θ)``.

Scaled data.  With ``θ`` an algebraic integer (monic integer minimal polynomial ``g``)
and ``d`` a common denominator, ``Â = d·A`` and ``b̂ = d·b`` have entries in ``Z[θ]``.  The
weights computed from them are ``Φ̂(t) = d^(|t|−1)Φ(t)``, ``â(t) = d^|t| a(t)``,
``ŵ(u) = d^(|u|−1) w(u)``, and the residual ``R`` of a condition with ``n`` vertices gives
the element ``N = (n−1)!·d^(n−1)·R = Σ_u ±((n−1)!/σ(u))·ŵ(u)`` of ``Z[θ]`` (σ(u) divides
``(n−1)!``: it is the order of a group of permutations of the ``n − 1`` non-root vertices).

Channels.  For a prime ``p ∤ d`` over which ``g`` has ``D = deg g`` distinct roots ``r``,
``θ ↦ r`` is a ring homomorphism ``Z[θ] → Z/p``; every weight is computed in int64 numpy
arrays modulo ``p`` (``p < 2^29``, so a row of ``s ≤ 32`` products sums without
overflow).  A nonzero residue proves ``N ≠ 0``: the condition **fails**.

Zero is proven through the norm.  Let ``e`` be the least positive integer with ``e·A`` and
``e·b`` algebraic integers (the *integrality* denominator, from each entry's
characteristic polynomial; ``e | d``, often far smaller: 23 bits against 65 for Gauss-5),
and ``N_e = (n−1)!·e^(n−1)·R = N/(d/e)^(n−1)``, an algebraic integer.  If ``N`` vanishes
at the ``D`` roots modulo ``p``, its ``D`` coefficients are ``≡ 0 (mod p)`` (Vandermonde
modulo p), so ``N = p·N'`` with ``N' ∈ Z[θ]``, and ``N_e/p = N'/(d/e)^(n−1)`` is integral
at every prime (``p ∤ d``): ``p^D`` divides the norm of ``N_e``.  Over a set of such primes,
``N_e ≠ 0`` would force ``|Norm N_e| ≥ (Π p)^D``, while ``|Norm N_e| = Π_j |σ_j(N_e)| ≤
Π_j B_j`` over the ``D`` complex embeddings (bound below, with ``e`` in place of ``d``).
So residues that are all zero with ``log₂ Π p > (1/D) Σ_j log₂ B_j`` prove ``N = 0``: the
condition **holds**.  For Q (D = 1, e = d) this is the familiar ``|N| < Π p``.  The
geometric mean over embeddings, the smaller denominator and the absence of ``‖V⁻¹‖``
make this far cheaper than bounding the coefficients (Gauss-5 to order 10 needs
9 primes instead of 21).

The bound.  In each complex embedding ``σ_j`` (for rationals: the value itself),
``|σ_j(Φ̂(t))_i| ≤ α_j^(|t|−1)`` with ``α_j = max_i Σ_k |σ_j(Â_ik)|``, so
``|σ_j(â(t))| ≤ β_j α_j^(|t|−1)`` (``β_j = Σ_i |σ_j(b̂_i)|``) and
``|σ_j(N)| ≤ B_j = (n−1)!·T·M_j^(n−1)`` with ``T`` the number of terms and
``M_j = max(α_j, β_j, 1)``.  The coefficients of ``N`` are ``V⁻¹`` times its
conjugates (``V`` the Vandermonde matrix of the conjugates of ``θ``), so
``|coefficient| ≤ ‖V⁻¹‖_∞ (n−1)! T M^(n−1)`` with ``M = max_j M_j``; all of it is computed
with exact integers or certified Arb balls, rounded up.

Values.  Residues are kept; the exact residual is rebuilt only when asked for (Chinese
remaindering, Garner's mixed-radix form), so that deciding ``holds``/``fails`` costs
nothing more.  A residual proven zero is 0; a nonzero one in a number field needs its
coefficients, whose bound is larger than the decision's: the missing primes are then
evaluated for that order, once, on first demand.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import Any, Sequence, cast

import numpy as np

#: all roots of a prime run in one pass while at most this many trees are stored (orders
#: up to 10): there numpy's per-call overhead dominates and one pass is 2.5–3× faster than
#: root by root; on larger listings the strided root axis costs more than it saves
#: (measured on Gauss-3/4/5, orders 8–13)
MAX_BATCHED_TREES = 1500

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


# ---------------------------------------------------------------------- the tableau


@dataclass
class ScaledTableau:
    """``Â = d·A`` and ``b̂ = d·b`` over ``Z[θ]``: entries are integer coefficient lists
    (power basis of θ, length D); ``minpoly`` is the monic integer minimal polynomial of
    θ (ascending, length D + 1; ``[0, 1]`` for Q); ``log2_bound(n, terms)`` bounds the
    bits of the coefficients of ``N`` (module docstring)."""

    A: list[list[list[int]]]
    b: list[list[int]]
    d: int
    minpoly: list[int]
    log2_M: float  # upper bound of log2 M
    log2_Vinv: float = 0.0  # upper bound of log2 ‖V⁻¹‖_∞ (0 for Q)
    number_field: Any = None  # the number field of the entries (None: Q)
    theta_scale: int = 1  # λ: the power basis is that of λθ, θ the field's generator
    #: log2 max(α_j, β_j) of the d-scaled data in each complex embedding j (None: Q,
    #: where the one embedding's value is log2_M)
    log2_M_embeddings: list[float] | None = None
    integral_d: int | None = None  # e: the integrality denominator (None: e = d)
    log2_gprime: float | None = None  # upper bound of log2 max_j |g'(σ_j θ)| (None: Q)

    def field_element(self, coeffs: Sequence[int], scale: int) -> Any:
        """``Σ coeffs_k (λθ)^k / scale`` as an element of the number field."""
        lam = self.theta_scale
        return self.number_field([Fraction(int(c) * lam**k, scale) for k, c in enumerate(coeffs)])

    @property
    def degree(self) -> int:
        return len(self.minpoly) - 1

    @property
    def s(self) -> int:
        return len(self.b)

    def coefficient_bits(self, n: int, terms: int) -> int:
        """Bits that bound ``|coefficient of N|`` for a condition with ``n`` vertices and
        ``terms`` terms (rounded up, plus one for the sign)."""
        bits = (n - 1) * self.log2_M + math.log2(math.factorial(n - 1)) + math.log2(max(terms, 1)) + self.log2_Vinv
        return math.ceil(bits) + 2

    def _log2_M_integral(self) -> list[float] | None:
        """``log₂ M_j`` per complex embedding for the data scaled by the integrality
        denominator ``e`` instead of ``d`` (None for Q or without the embeddings' data)."""
        if self.log2_M_embeddings is None or self.integral_d is None:
            return None
        shift = math.log2(self.d) - math.log2(self.integral_d)  # scaling by e instead of d
        return [max(m - shift, 0.0) for m in self.log2_M_embeddings]

    def dual_value_bits(self, n: int, terms: int) -> int | None:
        """Bits that bound the coefficients of ``X = g'(θ)·N_e`` (None without the
        embeddings' data).  ``N_e = N/(d/e)^(n−1)`` is an algebraic integer and
        ``O_K ⊆ Z[θ]/g'(θ)`` (g the minimal polynomial of the algebraic integer θ: the
        dual basis of the power basis under the trace), so ``X ∈ Z[θ]``; its conjugates
        are at most ``max_j |g'(σ_j θ)| · B_j`` with ``e`` in place of ``d``.  In a field of
        high degree this is far below :meth:`coefficient_bits`, which grows with log₂ d
        per vertex (1236 bits for HBVM(6, σ), against log₂ e = 19)."""
        per_embedding = self._log2_M_integral()
        if per_embedding is None or self.log2_gprime is None:
            return None
        top = max(per_embedding)
        bits = ((n - 1) * top + math.log2(math.factorial(n - 1)) + math.log2(max(terms, 1))
                + self.log2_Vinv + self.log2_gprime)
        return math.ceil(bits) + 2

    def decision_bits(self, n: int, terms: int) -> int:
        """Bits ``b`` such that all-zero residues over primes with ``Π p > 2^b`` prove a
        condition with ``n`` vertices and ``terms`` terms zero: ``(1/D) Σ_j log₂ B_j``
        with the integrality denominator (the norm argument of the module docstring)."""
        per_embedding = self._log2_M_integral()
        if per_embedding is None:
            return self.coefficient_bits(n, terms)
        mean = sum(per_embedding) / len(per_embedding)
        bits = (n - 1) * mean + math.log2(math.factorial(n - 1)) + math.log2(max(terms, 1))
        return math.ceil(bits + 1e-6) + 1

    def primes_for(self, bits: int) -> list[tuple[int, list[int]]]:
        """Enough channel primes for coefficients of ``bits`` bits: each (p, roots of
        the minimal polynomial mod p), in a fixed order, with ``Π p > 2^bits``."""
        # the split primes found so far are kept: in a field of degree D only about one
        # prime in D (or in the Galois group's order) splits, and every order asks again
        if not hasattr(self, "_split"):
            self._split: list[tuple[int, list[int]]] = []
            self._scanned = 0
        chosen: list[tuple[int, list[int]]] = []
        total = 0.0
        i = 0
        while total <= bits:
            if i == len(self._split):
                for p in primes(64, self._scanned):
                    roots = self._roots_mod(p)
                    if roots is not None:
                        self._split.append((p, roots))
                self._scanned += 64
                continue
            p, roots = self._split[i]
            chosen.append((p, roots))
            total += math.log2(p)
            i += 1
        return chosen

    def _roots_mod(self, p: int) -> list[int] | None:
        """The D distinct roots of the minimal polynomial modulo p, or None when p
        divides d or the polynomial does not split into distinct linear factors."""
        if self.d % p == 0:
            return None
        if self.degree == 1:
            return [(-self.minpoly[0]) % p]
        from flint import nmod_poly

        f = nmod_poly([c % p for c in self.minpoly], p)
        roots = [int(r) for r, mult in f.roots() if mult == 1]
        return roots if len(roots) == self.degree else None

    def _images(self, p: int, root: int) -> tuple[np.ndarray, np.ndarray]:
        """The entries' images under θ ↦ root (mod p): int64 arrays shaped like A and b."""
        cache = self.__dict__.setdefault("_image_cache", {})
        if p not in cache:
            cache.clear()  # primes are visited one after another: keep one
            roots = self._roots_of(p)
            # all entries at all roots of p as one product (coefficients × powers of the
            # roots) over Python integers: Horner's scheme per entry and root cost 3 s of
            # a 48-degree field's check
            D = self.degree
            coeffs = np.array([[c % p for c in x] for x in [x for row in self.A for x in row] + self.b], dtype=object)
            powers = np.empty((D, len(roots)), dtype=object)
            for j, r in enumerate(roots):
                acc = 1
                for k in range(D):
                    powers[k, j] = acc
                    acc = acc * r % p
            values = (coeffs[:, :D].dot(powers) % p).astype(np.int64)
            s = self.s
            cache[p] = ({r: j for j, r in enumerate(roots)}, values[: s * s].reshape(s, s, -1), values[s * s:])
        index, A, b = cache[p]
        j = index[root]
        return np.ascontiguousarray(A[:, :, j]), np.ascontiguousarray(b[:, j])

    def _roots_of(self, p: int) -> list[int]:
        for q, roots in getattr(self, "_split", ()):
            if q == p:
                return roots
        roots = self._roots_mod(p)
        assert roots is not None, "a channel prime must split the minimal polynomial"
        return roots

    def channel(self, p: int, root: int) -> ModularChannel:
        return ModularChannel(p, *self._images(p, root))

    def roots_channel(self, p: int, roots: Sequence[int]) -> RootsChannel:
        images = [self._images(p, r) for r in roots]
        return RootsChannel(p, np.stack([A for A, _ in images]), np.stack([b for _, b in images]))

    def residues_at(self, listing: Any, p: int, roots: Sequence[int], orders: list[int]) -> dict[int, np.ndarray]:
        """``{n: (conditions, roots) residues}`` of the given orders at one prime: all roots
        in one pass on small listings, else root by root (:data:`MAX_BATCHED_TREES`)."""
        from rkcheck.evaluation.algorithm import condition_sums

        if len(roots) > 1 and listing.first[max(orders)] <= MAX_BATCHED_TREES:
            return condition_sums(listing, self.roots_channel(p, roots), self.s, orders)
        per_root = [condition_sums(listing, self.channel(p, r), self.s, orders) for r in roots]
        return {n: np.stack([sums[n] for sums in per_root], axis=1) for n in orders}


def scaled_rational(A: Sequence[Sequence[Fraction]], b: Sequence[Fraction]) -> ScaledTableau:
    """The scaled data of a rational tableau (D = 1)."""
    d = 1
    for x in [x for row in A for x in row] + list(b):
        d = math.lcm(d, Fraction(x).denominator)
    Ai = [[[int(Fraction(x) * d)] for x in row] for row in A]
    bi = [[int(Fraction(x) * d)] for x in b]
    alpha = max(sum(abs(x[0]) for x in row) for row in Ai)
    beta = sum(abs(x[0]) for x in bi)
    M = max(alpha, beta, 1)
    return ScaledTableau(Ai, bi, d, [0, 1], float(M.bit_length()))


def scaled_field(exact_values: Any) -> ScaledTableau:
    """The scaled data of a tableau with entries in a number field ``Q(θ)``
    (``exact_values``: :meth:`rkcheck.methods.tableau.Tableau.exact_values`).

    ``θ̃ = λθ`` is an algebraic integer (λ the least positive integer that clears the
    denominators of ``λ^D g(x/λ)``); entries are rewritten in the basis of θ̃ and scaled by
    the common denominator ``d``.  ``M`` and ``‖V⁻¹‖_∞`` (module docstring) are bounded
    over every complex embedding with certified Arb/Acb enclosures of the conjugates."""
    field = exact_values.field
    if field is None:
        return scaled_rational(exact_values.A, exact_values.b)
    g = [Fraction(c) for c in field.minpoly]  # monic
    D = len(g) - 1
    from rkcheck.numbers.algebraic import integral_scale

    lam = integral_scale(g)
    minpoly = [int(c * lam ** (D - k)) for k, c in enumerate(g)]
    assert minpoly[-1] == 1 and all(Fraction(c) * lam ** (D - k) == minpoly[k] for k, c in enumerate(g))

    def tilde(x: Any) -> list[Fraction]:
        coeffs = x.coeffs if hasattr(x, "coeffs") else [Fraction(x)] + [Fraction(0)] * (D - 1)
        return [Fraction(c) / lam**k for k, c in enumerate(coeffs)]

    At = [[tilde(x) for x in row] for row in exact_values.A]
    bt = [tilde(x) for x in exact_values.b]
    d = 1
    for v in [v for row in At for v in row] + bt:
        for c in v:
            d = math.lcm(d, c.denominator)
    Ai = [[[int(c * d) for c in v] for v in row] for row in At]
    bi = [[int(c * d) for c in v] for v in bt]

    log2_M, per_embedding = _embedding_bounds(minpoly, Ai, bi)
    vinv = _vandermonde_inverse_norm(minpoly)
    log2_gprime = _log2_derivative_bound(minpoly)
    e = integrality_denominator([x for row in exact_values.A for x in row] + list(exact_values.b), field)
    assert d % e == 0  # d·x ∈ Z[θ̃] ⊂ O_K, so the least e divides d
    return ScaledTableau(Ai, bi, d, minpoly, log2_M + 1e-9, max(math.log2(vinv), 0.0) + 1e-9, field, lam,
                         per_embedding, e, log2_gprime)


@lru_cache(maxsize=8)
def _complex_roots(minpoly: tuple[int, ...], prec: int) -> list[Any]:
    """The complex roots of ``minpoly`` as Acb balls at ``prec`` bits, computed once per
    precision for the three bounds below (use them under the same working precision)."""
    from flint import ctx, fmpz_poly

    with ctx.workprec(prec):
        # python-flint's stubs type complex_roots() as acb; it is a list of (acb, multiplicity)
        return [root for root, _ in cast(list, fmpz_poly(list(minpoly)).complex_roots())]


def _log2_upper(x: Any) -> float:
    """An upper bound of ``log₂ |x|`` for an arb (−1000 for 0): in the log domain, since
    the scaled entries of a field of high degree exceed a float (2^1236 for HBVM(6, 3))."""
    from flint import arb

    u = x.abs_upper()
    if u == 0:
        return -1000.0
    return float((u.log() / arb(2).log()).upper()) + 1e-9


def _embedding_bounds(minpoly: list[int], Ai: list, bi: list) -> tuple[float, list[float]]:
    """``log₂ M`` (``M = max_j M_j``) and ``log₂ max(α_j, β_j)`` per complex embedding
    (module docstring), certified.  The working precision starts at 128 bits and doubles
    while a bound exceeds its ball's lower end by more than one bit: in fields of high
    degree (48 for the six Gauss-6 nodes) the entries' coefficients are large and cancel,
    and 128 bits leave balls too wide to bound anything."""
    from flint import acb, arb, ctx

    prec = 128
    while True:
        with ctx.workprec(prec):
            roots = _complex_roots(tuple(minpoly), prec)

            def conj(v: list[int], r) -> Any:
                acc = acb(0)
                for c in reversed(v):
                    acc = acc * r + c
                return acc

            log2_M = 0.0
            per_embedding = []
            tight = True
            for r in roots:
                sums = [sum((abs(conj(v, r)) for v in row), arb(0)) for row in Ai]
                sums.append(sum((abs(conj(v, r)) for v in bi), arb(0)))
                for x in sums:
                    if not x.is_finite() or (x.abs_upper() > 0 and not x.abs_upper() <= 2 * x.abs_lower()):
                        tight = False
                top = max(_log2_upper(x) for x in sums)
                log2_M = max(log2_M, top)
                per_embedding.append(top)
            if tight or prec >= 1 << 14:
                return log2_M, per_embedding
            prec *= 2


def _log2_derivative_bound(minpoly: list[int]) -> float:
    """An upper bound of ``log₂ max_j |g'(σ_j θ)|`` over the roots of ``g = minpoly``."""
    from flint import acb, ctx, fmpz_poly

    dg = fmpz_poly(minpoly).derivative()
    prec = 128
    while True:
        with ctx.workprec(prec):
            values = [abs(dg(acb(r))) for r in _complex_roots(tuple(minpoly), prec)]
            if all(v.is_finite() for v in values) or prec >= 1 << 14:
                return max(_log2_upper(v) for v in values)
        prec *= 2


def _vandermonde_inverse_norm(minpoly: list[int]) -> float:
    """``‖V⁻¹‖_∞`` for the Vandermonde matrix ``V`` of the roots of ``minpoly``, certified:
    Arb inverts ``V`` only when its balls prove it invertible, so the working precision is
    doubled until they do (128 bits suffice up to degree ~30; the degree-48 field of the
    six Gauss-6 nodes needs more, its conjugates lie close together)."""
    from flint import acb_mat, arb, ctx

    def upper(x: Any) -> float:  # an arb as a float upper bound
        return float(x.abs_upper()) * (1 + 2.0**-40)

    D = len(minpoly) - 1
    prec = 128
    while True:
        with ctx.workprec(prec):
            roots = _complex_roots(tuple(minpoly), prec)
            V = acb_mat([[r**k for k in range(D)] for r in roots])
            try:
                W = V.inv()
            except ZeroDivisionError:
                if prec >= 1 << 14:
                    raise
                prec *= 2
                continue
            return max(upper(sum((abs(W[i, j]) for j in range(D)), arb(0))) for i in range(D))


def integrality_denominator(values: Sequence[Any], field: Any) -> int:
    """The least positive integer ``e`` with ``e·x`` an algebraic integer for every ``x``:
    the lcm over the entries of the least ``λ`` that makes ``λ^m P(X/λ)`` integral, with
    ``P`` the minimal polynomial of ``x`` (of degree m; by Gauss's lemma ``x`` is integral
    exactly when P has integer coefficients)."""
    from rkcheck.numbers.algebraic import integral_scale

    e = 1
    seen = set()
    for x in values:
        x = field(x)
        q = x.rational()
        if q is not None:
            e = math.lcm(e, q.denominator)
            continue
        key = tuple(x.coeffs)
        if key not in seen:
            seen.add(key)
            e = math.lcm(e, integral_scale(x.minimal_polynomial()))
    return e


# ---------------------------------------------------------------------- results


@dataclass
class ExactOrderSums:
    """The residues of every condition of one order, and what they prove.

    ``residues[k, i, j]``: condition k, prime i, root j.  ``scale = (n−1)!·d^(n−1)``
    turns the integer element ``N`` back into the residual ``R`` (of the class
    representative; the caller applies the designated sign)."""

    vertices: int
    residues: np.ndarray
    primes: list[tuple[int, list[int]]]
    scale: int
    tableau: ScaledTableau
    listing: Any = None  # to evaluate more primes when a value needs them
    value_bits: int = 0  # the coefficients' bound: primes beyond the decision's, on demand
    dual: bool = False  # values from g'(θ)·N_e (ScaledTableau.dual_value_bits), not from N

    def __len__(self) -> int:
        return len(self.residues)

    def is_zero(self) -> np.ndarray:
        return ~np.any(self.residues != 0, axis=(1, 2))

    def value(self, k: int) -> Any:
        """The exact residual of condition k: a Fraction (rationals) or a field element."""
        if self.tableau.number_field is not None and not np.any(self.residues[k]):
            return self.tableau.field_element([0], 1)  # proven zero (module docstring)
        self._complete()
        if self.dual:
            return self._dual_value(k)
        coeffs = self._coefficients(k)
        if self.tableau.number_field is None:
            return Fraction(coeffs[0], self.scale)
        return self.tableau.field_element(coeffs, self.scale)

    def _dual_value(self, k: int) -> Any:
        """The residual from the coefficients of ``X = g'(θ)·N_e``
        (:meth:`ScaledTableau.dual_value_bits`): at a root r modulo p, ``X(r) = g'(r)·N(r)/
        (d/e)^(n−1)``; then ``R = X / (g'(θ)·(n−1)!·e^(n−1))``."""
        t = self.tableau
        assert t.integral_d is not None
        D, n = t.degree, self.vertices
        ratio = t.d // t.integral_d
        dg = [k * c for k, c in enumerate(t.minpoly)][1:]
        per_prime = []
        for i, (p, roots) in enumerate(self.primes):
            inv = pow(pow(ratio, n - 1, p), -1, p)
            vals = []
            for j, r in enumerate(roots):
                gp = 0
                for c in reversed(dg):
                    gp = (gp * r + c) % p
                vals.append(int(self.residues[k, i, j]) * gp % p * inv % p)
            per_prime.append(_vandermonde_solve(roots, vals, p))
        mods = [p for p, _ in self.primes]
        X = [_crt_symmetric([pp[c] for pp in per_prime], mods) for c in range(D)]
        scale = math.factorial(n - 1) * t.integral_d ** (n - 1)
        return t.field_element(X, scale) / t.field_element(dg, 1)

    def _complete(self) -> None:
        """Evaluate the primes the coefficients' bound needs beyond the decision's."""
        if self.listing is None or not self.value_bits:
            return
        chosen = self.tableau.primes_for(self.value_bits)
        extra = chosen[len(self.primes):]
        if extra:
            more = np.zeros((len(self.residues), len(extra), self.tableau.degree), dtype=self.residues.dtype)
            for i, (p, roots) in enumerate(extra):
                more[:, i, :] = self.tableau.residues_at(self.listing, p, roots, [self.vertices])[self.vertices]
            self.residues = np.concatenate([self.residues, more], axis=1)
            self.primes = list(self.primes) + list(extra)
        self.value_bits = 0

    def values(self) -> list[Any]:
        """Every condition's exact residual (Garner's algorithm vectorised over the
        conditions: the mixed-radix digits in int64, then one integer per condition)."""
        if self.tableau.degree != 1:
            return [self.value(k) for k in range(len(self.residues))]
        mods = [p for p, _ in self.primes]
        r = self.residues[:, :, 0].astype(np.int64)
        digits: list[np.ndarray] = []
        for i, p in enumerate(mods):
            # x_i = (r_i − (x_0 + x_1 m_0 + …)) / (m_0 … m_{i−1})  (mod p_i)
            acc = np.zeros(len(r), dtype=np.int64)
            weight = 1
            for j in range(i):
                acc = (acc + digits[j] * (weight % p)) % p
                weight *= mods[j]
            inv = pow(weight % p, -1, p)
            digits.append(((r[:, i] - acc) % p) * inv % p)
        total = math.prod(mods)
        out = []
        weights = [math.prod(mods[:i]) for i in range(len(mods))]
        cols = [d.tolist() for d in digits]
        for row in zip(*cols) if cols else [() for _ in range(len(r))]:
            x = sum(d * w for d, w in zip(row, weights))
            out.append(Fraction(x - total if x > total // 2 else x, self.scale))
        return out

    def _coefficients(self, k: int) -> list[int]:
        D = self.tableau.degree
        per_prime = []
        for i, (p, roots) in enumerate(self.primes):
            vals = [int(v) for v in self.residues[k, i, :D]]
            per_prime.append(_vandermonde_solve(roots, vals, p) if D > 1 else vals)
        mods = [p for p, _ in self.primes]
        return [_crt_symmetric([pp[c] for pp in per_prime], mods) for c in range(D)]


def _vandermonde_solve(roots: list[int], values: list[int], p: int) -> list[int]:
    """Coefficients c (mod p) with Σ c_k r^k = value at every root r."""
    from flint import nmod_mat

    D = len(roots)
    V = nmod_mat([[pow(r, k, p) for k in range(D)] for r in roots], p)
    x = V.solve(nmod_mat([[v] for v in values], p))
    return [int(x[i, 0]) for i in range(D)]


def _crt_symmetric(residues: list[int], moduli: list[int]) -> int:
    """The integer in (−Π/2, Π/2] with the given residues (Garner's algorithm)."""
    x, m = 0, 1
    for r, p in zip(residues, moduli):
        t = ((r - x) * pow(m, -1, p)) % p
        x += m * t
        m *= p
    return x - m if x > m // 2 else x


def exact_condition_sums(scaled: ScaledTableau, listing, orders=None, on_pass=None) -> dict[int, ExactOrderSums]:
    """Every condition of the listing (or of the given orders) exactly: residues over
    enough channels for each order's bound.  ``on_pass(done, total)`` after each prime.
    On Ctrl-C, :class:`~rkcheck.evaluation.algorithm.EvaluationInterrupted` carries the
    orders whose primes were all done (low orders need fewer primes: they finish first)."""
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    wanted = sorted(listing.orders if orders is None else orders)
    need = {n: scaled.decision_bits(n, listing.orders[n].max_terms) for n in wanted}
    value_need = {n: scaled.coefficient_bits(n, listing.orders[n].max_terms) for n in wanted}
    dual = {}  # values from g'(θ)·N_e when its bound is the smaller (ScaledTableau.dual_value_bits)
    for n in wanted:
        dual_bits = scaled.dual_value_bits(n, listing.orders[n].max_terms)
        dual[n] = dual_bits is not None and dual_bits < value_need[n]
        if dual_bits is not None and dual[n]:
            value_need[n] = dual_bits
    channels = scaled.primes_for(max(need.values(), default=1))
    D = scaled.degree
    count = {n: 0 for n in wanted}
    cum = 0.0
    for p, _ in channels:
        for n in wanted:
            if cum < need[n]:
                count[n] += 1
        cum += math.log2(p)
    passes = max(count.values(), default=0)
    residues = {n: np.zeros((len(listing.orders[n]), count[n], D), dtype=np.int32) for n in wanted}

    def result(n: int) -> ExactOrderSums:
        more = value_need[n] > need[n]
        return ExactOrderSums(n, residues[n], channels[:count[n]], math.factorial(n - 1) * scaled.d ** (n - 1), scaled,
                              listing if more else None, value_need[n] if more else 0, dual[n])

    done = 0
    try:
        for i, (p, roots) in enumerate(channels[:passes]):
            orders_i = [n for n in wanted if i < count[n]]
            at_p = scaled.residues_at(listing, p, roots, orders_i)
            for n in orders_i:
                residues[n][:, i, :] = at_p[n]
            done = i + 1
            if on_pass is not None:
                on_pass(done, passes)
    except KeyboardInterrupt:
        raise EvaluationInterrupted({n: result(n) for n in wanted if count[n] <= done}) from None
    return {n: result(n) for n in wanted}
