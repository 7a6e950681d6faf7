"""A tableau scaled to integers for the exact evaluation: the common denominator, the
number field's minimal polynomial and integrality denominator, and the size bounds that
say how many primes decide a condition (:mod:`rkcheck.evaluation.modular`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

import numpy as np

from rkcheck.evaluation.centroid import CENTROID_PASS_VALUES, centroid_residues
from rkcheck.evaluation.channels import (
    ModularChannel,
    PrimeChannels,
    channels_per_image_pass,
    primes,
)
from rkcheck.evaluation.conjugates import repeated_channels
from rkcheck.evaluation.field_bounds import (
    embedding_bounds,
    integrality_denominator,
    log2_derivative_bound,
    vandermonde_inverse_norm,
)
from rkcheck.numbers.polynomials import integer_coefficients
from rkcheck.trees.centroid import CentroidListing

#: the weights one pass holds (:meth:`ScaledTableau.channels_per_pass`) may take this much
#: memory: channels run together while their weights fit, so that on small listings the
#: cost of each numpy call is shared (a field's 80 channels at order 10–12: 1.5–4× faster);
#: on larger ones a pass per channel is faster (RK4 at orders 16–18: 10–20 %), its hot
#: weights (the small subtrees every product reads) staying in the caches
PASS_BYTES = 8 << 20


#: How many primes the exact route may try in search of those over which the field splits
#: (about one in the order of its Galois group does; a field of degree 20 from entries
#: of 300 digits needed minutes of search): beyond it the check stops with one line.
MAX_PRIMES_SCANNED = 30_000

#: coefficients of at least this many bits are reduced modulo the channel primes through
#: their limbs, LIMB_BATCH primes at once (below, Python's % on each is as fast)
LIMB_MIN_BITS = 512
LIMB_BATCH = 64


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

    def __getstate__(self) -> dict[str, Any]:
        # the evaluation kept for the claims' runs (modular._remember) stays here: a pass
        # sent to a worker needs the tableau, not every residue of a finished check
        state = dict(self.__dict__)
        state.pop("_all_trees", None)
        state.pop("_flat", None)  # the coefficients again, in one list: rebuilt on use
        state.pop("_limbs", None)  # and their limbs, with the residues of a batch of primes
        state.pop("_residue_batch", None)
        return state

    def field_element(self, coeffs: Sequence[int], scale: int) -> Any:
        """``Σ coeffs_k (λθ)^k / scale`` as an element of the number field."""
        from flint import fmpq_poly

        lam = self.theta_scale  # an integer: the numerators over one denominator, no Fractions
        return self.number_field(fmpq_poly([int(c) * lam**k for k, c in enumerate(coeffs)], scale))

    @property
    def degree(self) -> int:
        return len(self.minpoly) - 1

    @property
    def s(self) -> int:
        return len(self.b)

    def coefficient_bits(self, n: int, terms: int, weight: int | None = None) -> int:
        """Bits that bound ``|coefficient of N|`` for a condition with ``n`` vertices and
        ``terms`` terms (rounded up, plus one for the sign); with ``weight`` (the order's
        :attr:`~rkcheck.trees.terms.OrderTerms.coefficient_weight` W), those of ``N/g_k``
        instead, which decide zero residues as well (:meth:`decision_bits`)."""
        bits = (n - 1) * self.log2_M + _log2_weight(n, terms, weight) + self.log2_Vinv
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

    def decision_bits(self, n: int, terms: int, weight: int | None = None) -> int:
        """Bits ``b`` such that all-zero residues over primes with ``Π p > 2^b`` prove a
        condition with ``n`` vertices and ``terms`` terms zero: ``(1/D) Σ_j log₂ B_j``
        with the integrality denominator (the norm argument of the module docstring).

        With ``weight`` W (:attr:`~rkcheck.trees.terms.OrderTerms.coefficient_weight`) the
        bound is that of ``N/g_k``, ``g_k`` the gcd of the condition's coefficients
        ``(n−1)!/σ(u)``: W times the largest weight instead of ``(n−1)!`` times the terms
        (2^4 against 2^57 at 19 vertices).  ``N/g_k`` is an algebraic integer (the
        coefficients divided by ``g_k`` are integers), and ``g_k`` divides ``(n−1)!``, so
        it is a unit modulo every channel prime (``p > 2^28 > n``): the residues of
        ``N`` are zero exactly when those of ``N/g_k`` are, and the argument applies to
        ``N/g_k`` unchanged.  Values still need :meth:`coefficient_bits` of ``N``."""
        per_embedding = self._log2_M_integral()
        if per_embedding is None:
            return self.coefficient_bits(n, terms, weight)
        mean = sum(per_embedding) / len(per_embedding)
        bits = (n - 1) * mean + _log2_weight(n, terms, weight)
        return math.ceil(bits + 1e-6) + 1

    def primes_for(self, bits: int) -> list[tuple[int, list[int]]]:
        """Enough channel primes for coefficients of ``bits`` bits: each (p, roots of
        the minimal polynomial mod p), in a fixed order, with ``Π p > 2^bits``."""
        # the split primes found so far are kept: in a field of degree D only about one
        # prime in D (or in the Galois group's order) splits, and every order asks again
        if not hasattr(self, "_split"):
            self._split: list[tuple[int, list[int]]] = []
            self._split_roots: dict[int, list[int]] = {}  # the same, by prime (looked up per channel)
            self._scanned = 0
        chosen: list[tuple[int, list[int]]] = []
        total = 0.0
        i = 0
        while total <= bits:
            if i == len(self._split):
                if self._scanned >= MAX_PRIMES_SCANNED:
                    from rkcheck.errors import UserError

                    raise UserError(_too_few_primes(self.degree, len(self._split), self._scanned, bits))
                for p in primes(64, self._scanned):
                    roots = self._roots_mod(p)
                    if roots is not None:
                        self._split.append((p, roots))
                        self._split_roots[p] = roots
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

        if not self._splits_generators(p):
            return None
        f = nmod_poly([c % p for c in self.minpoly], p)
        # f splits into distinct linear factors exactly when it divides the squarefree
        # x^p − x, i.e. x^p ≡ x (mod f): a few dozen squarings modulo f, where finding the
        # roots of a polynomial that does not split (all but about one prime in D) cost
        # 3 ms each at degree 48 — 2.3 s of an HBVM(6, 3) check
        x = nmod_poly([0, 1], p)
        if x.pow_mod(p, f) != x:
            return None
        roots = [int(r) for r, mult in f.roots() if mult == 1]
        return roots if len(roots) == self.degree else None

    def _splits_generators(self, p: int) -> bool:
        """False when p certainly does not split the field completely: a generator's
        minimal polynomial (of low degree: the Gauss-6 nodes' degree 6 against θ's 48)
        does not split into distinct linear factors modulo p.  p splits completely in the
        field only if it does in every subfield Q(γ), and for p prime to the discriminant
        and leading coefficient of γ's integral polynomial that is its splitting into
        distinct linear factors (Dedekind); at other primes the generator says nothing.
        A filter only: the minimal polynomial's own test still decides."""
        from flint import fmpz_poly, nmod_poly

        tests = self.__dict__.get("_generator_tests")
        if tests is None:
            tests = self.__dict__["_generator_tests"] = []
            for f in getattr(self.number_field, "generator_polynomials", ()):
                if len(f) - 1 < 2 or len(f) - 1 >= self.degree:
                    continue  # rational, or no cheaper than θ's own test
                z = fmpz_poly(integer_coefficients(f))
                tests.append((list(map(int, z.coeffs())), int(z.discriminant()) * int(z.coeffs()[-1])))
        for coeffs, bad in tests:
            if bad % p == 0:
                continue
            w = nmod_poly([c % p for c in coeffs], p)
            x = nmod_poly([0, 1], p)
            if x.pow_mod(p, w) != x:
                return False
        return True

    def _images(self, p: int, root: int) -> tuple[np.ndarray, np.ndarray]:
        """The entries' images under θ ↦ root (mod p): int64 arrays shaped like A and b."""
        cache = self.__dict__.setdefault("_image_cache", {})
        if p not in cache:
            cache.clear()  # primes are visited one after another: keep one
            roots = self._roots_of(p)
            # all entries at all roots of p as one sum of products (coefficients × powers
            # of the roots), reduced after each of the D steps so that int64 holds it
            # (p < 2^31): Horner's scheme per entry and root would cost 3 s of a 48-degree
            # field's check, and one list of residues per entry most of a rational one's
            D = self.degree
            coeffs = self._flat_residues(p).reshape(-1, D)
            values: np.ndarray = np.zeros((len(coeffs), len(roots)), dtype=np.int64)
            power = np.ones(len(roots), dtype=np.int64)
            r = np.array(roots, dtype=np.int64) % p
            for k in range(D):
                values = (values + coeffs[:, k, None] * power[None, :]) % p
                power = power * r % p
            s = self.s
            cache[p] = ({r: j for j, r in enumerate(roots)}, values[: s * s].reshape(s, s, -1), values[s * s:])
        index, A, b = cache[p]
        j = index[root]
        return np.ascontiguousarray(A[:, :, j]), np.ascontiguousarray(b[:, j])

    def _flat_residues(self, p: int) -> np.ndarray:
        """Every entry's coefficients modulo ``p``.  Large coefficients (a surrogate
        tableau's, thousands of digits) are reduced through their limbs for a batch of
        the split primes at once (:class:`~rkcheck.evaluation.remainders.LimbResidues`):
        one big-integer division per coefficient and prime took most of such a check."""
        flat = self._flat_coefficients()
        wide = self.__dict__.get("_wide")
        if wide is None:  # decided once, not at every prime
            wide = self.__dict__["_wide"] = max((abs(c).bit_length() for c in flat), default=0) >= LIMB_MIN_BITS
        if not wide:
            return np.fromiter((c % p for c in flat), dtype=np.int64, count=len(flat))
        batch = self.__dict__.setdefault("_residue_batch", {})
        if p not in batch:
            from rkcheck.evaluation.remainders import LimbResidues

            limbs = self.__dict__.get("_limbs")
            if limbs is None:
                limbs = self.__dict__["_limbs"] = LimbResidues(flat)
            split = [q for q, _ in getattr(self, "_split", [])]
            start = split.index(p) if p in split else 0
            moduli = split[start:start + LIMB_BATCH] if p in split else [p]
            batch.clear()  # primes are visited in order: keep one batch
            batch.update(zip(moduli, limbs.modulo(moduli).T))
        result: np.ndarray = batch[p]
        return result

    def _flat_coefficients(self) -> list[int]:
        """Every entry's D coefficients (A row by row, then b), in one list."""
        flat = self.__dict__.get("_flat")
        if flat is None:
            flat = self.__dict__["_flat"] = [c for x in [x for row in self.A for x in row] + self.b
                                             for c in list(x) + [0] * (self.degree - len(x))]
        return flat

    def channel_sources(self, p: int) -> list[int]:
        """Per root of ``p`` (in the order of its roots): the root whose channel gives the
        same residues — itself, or an earlier root whose images are a stage permutation
        of its own (:mod:`rkcheck.evaluation.conjugates`)."""
        known = self.__dict__.setdefault("_source_cache", {})
        if p not in known:
            roots = self._roots_of(p)
            if len(roots) == 1:
                known[p] = [0]
            else:
                self._images(p, roots[0])  # fills the image cache with every root of p
                _, A, b = self.__dict__["_image_cache"][p]
                known[p] = repeated_channels(A, b)
        found: list[int] = known[p]
        return found

    def _roots_of(self, p: int) -> list[int]:
        known: list[int] | None = getattr(self, "_split_roots", {}).get(p)
        if known is not None:
            return known
        roots = self._roots_mod(p)
        assert roots is not None, "a channel prime must split the minimal polynomial"
        return roots

    def channel(self, p: int, root: int) -> ModularChannel:
        return ModularChannel(p, *self._images(p, root))

    def channels(self, pairs: Sequence[tuple[int, int]]) -> PrimeChannels:
        """One context for the channels ``(p, root)`` in ``pairs``, in that order."""
        return PrimeChannels([p for p, _ in pairs], *self._stacked_images(pairs))

    def _stacked_images(self, pairs: Sequence[tuple[int, int]]) -> tuple[np.ndarray, np.ndarray]:
        """The images of ``Â`` (channels × s × s) and ``b̂`` (channels × s) in the channels
        ``(p, root)`` of ``pairs``."""
        images = [self._images(p, r) for p, r in pairs]
        return np.stack([A for A, _ in images]), np.stack([b for _, b in images])

    def channels_per_pass(self, listing: Any, top: int) -> int:
        """How many channels one pass over the listing evaluates for orders up to ``top``
        vertices within :data:`PASS_BYTES` (at least one): Φ and ψ of the trees with up to
        ``top − 2`` vertices, a and w up to ``top − 1``, 4 bytes each per channel
        (:meth:`pass_width`)."""
        if isinstance(listing, CentroidListing):  # a few stage vectors per channel and waiting tree
            return min(channels_per_image_pass(self.s), max(1, CENTROID_PASS_VALUES // self.s))
        first = listing.first
        trees_a = first[min(top, len(first) - 1)]
        trees_phi = first[min(max(top - 1, 2), len(first) - 1)]
        return self.pass_width(4 * (2 * trees_phi * self.s + 2 * trees_a))

    def pass_width(self, channel_bytes: int) -> int:
        """How many channels one pass evaluates when each holds ``channel_bytes`` of
        weights: as many as fit in :data:`PASS_BYTES`, and whose images of the tableau
        fit (:func:`~rkcheck.evaluation.channels.channels_per_image_pass`); at least one."""
        return min(channels_per_image_pass(self.s), max(1, PASS_BYTES // max(channel_bytes, 1)))

    def residues_at(self, listing: Any, pairs: Sequence[tuple[int, int]], orders: list[int]) -> dict[int, np.ndarray]:
        """``{n: (conditions, channels) residues}`` of the given orders in the channels
        ``(p, root)`` of ``pairs``, all in one pass."""
        if isinstance(listing, CentroidListing):
            return centroid_residues(listing, [p for p, _ in pairs], *self._stacked_images(pairs), orders)
        from rkcheck.evaluation.algorithm import condition_sums

        return condition_sums(listing, self.channels(pairs), self.s, orders)


def _too_few_primes(degree: int, split: int, scanned: int, bits: int) -> str:
    """Why the primes ran out: too few split in the field, or, over Q (where every
    prime serves), the numbers are too large for any count of them within the limit."""
    if degree == 1 or (scanned and split == scanned):
        return (f"the entries are too large for exact arithmetic: their conditions' values take about {bits:,} "
                f"bits, more than the first {scanned:,} primes cover (the limit MAX_PRIMES_SCANNED); write them "
                "smaller, or check a lower --order")
    return (f"exact arithmetic needs primes over which the entries' number field (degree {degree}) splits, and "
            f"only {split} of the first {scanned:,} primes do (the limit MAX_PRIMES_SCANNED); use --arithmetic ball")


def _log2_weight(n: int, terms: int, weight: int | None) -> float:
    """log₂ of the coefficients' share of a condition's bound: ``(n−1)!`` times the terms,
    or the order's coefficient weight W when given (:meth:`ScaledTableau.decision_bits`)."""
    if weight is None:
        return math.log2(math.factorial(n - 1)) + math.log2(max(terms, 1))
    return math.log2(max(weight, 1))


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
    from rkcheck.numbers.minimal import integral_scale

    lam = integral_scale(g)
    minpoly = [int(c * lam ** (D - k)) for k, c in enumerate(g)]
    assert minpoly[-1] == 1 and all(Fraction(c) * lam ** (D - k) == minpoly[k] for k, c in enumerate(g))

    def tilde(x: Any) -> list[Fraction]:
        coeffs = getattr(x, "coeffs", None) or [Fraction(x)] + [Fraction(0)] * (D - 1)
        return [Fraction(c) / lam**k for k, c in enumerate(coeffs)]

    At = [[tilde(x) for x in row] for row in exact_values.A]
    bt = [tilde(x) for x in exact_values.b]
    d = 1
    for v in [v for row in At for v in row] + bt:
        for c in v:
            d = math.lcm(d, c.denominator)
    Ai = [[[int(c * d) for c in v] for v in row] for row in At]
    bi = [[int(c * d) for c in v] for v in bt]

    # first: the entries' minimal polynomials need the conjugates at the highest precision,
    # which the bounds then reuse
    e = integrality_denominator([x for row in exact_values.A for x in row] + list(exact_values.b), field)
    log2_M, per_embedding = embedding_bounds(minpoly, Ai, bi)
    vinv = vandermonde_inverse_norm(minpoly)
    log2_gprime = log2_derivative_bound(minpoly)
    assert d % e == 0  # d·x ∈ Z[θ̃] ⊂ O_K, so the least e divides d
    return ScaledTableau(Ai, bi, d, minpoly, log2_M + 1e-9, max(math.log2(vinv), 0.0) + 1e-9, field, lam,
                         per_embedding, e, log2_gprime)
