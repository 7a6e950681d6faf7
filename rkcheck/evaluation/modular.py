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
arrays modulo ``p`` (``p < 2^30``, so a row of ``s ≤ 8`` products sums without
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
condition **holds**.  The same holds of ``N/g`` with ``g`` the gcd of the condition's
coefficients ``(n−1)!/σ(u)``, whose bound has W (at most n) in place of ``(n−1)!·T``
(:meth:`ScaledTableau.decision_bits`): the decision needs some 50 bits fewer at 19
vertices.  For Q (D = 1, e = d) this is the familiar ``|N| < Π p``.  The
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

Screening.  A nonzero residue at one prime decides a condition (it fails), and the
conditions of a method that is not energy-preserving nearly all fail; the primes after
the first are needed only for the others.  When the primes take several passes over the
listing, the first pass's residues select the conditions that are zero there, and the
further primes are evaluated for those alone, on the trees their terms need
(:class:`~rkcheck.evaluation.subset.Subset`: Gauss-3 at 19 vertices, five passes over
2.7 million trees become one over 18 thousand), unless they are many (then the passes
go on over the listing).  Every verdict is the same: a zero residue is still proven by
the whole bound below, and the residues left out belong to conditions already decided;
those are evaluated when a value or every residue is asked for.  A listing by centroid
(:mod:`rkcheck.trees.centroid`, exact checks from order 21) is not screened: its walk
costs the same for a few conditions as for all of them.

Listings.  A pass evaluates its channels over the listing it is given
(:meth:`ScaledTableau.residues_at`): the rooted trees' weights of
:mod:`~rkcheck.evaluation.algorithm`, or the centroid sums of
:mod:`~rkcheck.evaluation.centroid`; both give the residues of the same integers ``N``.

Values.  Residues are kept; the exact residual is rebuilt only when asked for (Chinese
remaindering, Garner's mixed-radix form), so that deciding ``holds``/``fails`` costs
nothing more.  A residual proven zero is 0; a nonzero one in a number field needs its
coefficients, whose bound is larger than the decision's: the missing primes are then
evaluated for that order, once, on first demand.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Callable, Iterable

import numpy as np

from rkcheck.evaluation.passes import channel_passes, flat_channels, with_copies
from rkcheck.evaluation.remainders import crt_columns, product
from rkcheck.evaluation.scaled import ScaledTableau
from rkcheck.trees.centroid import CentroidListing, Listing

# ---------------------------------------------------------------------- results


@dataclass
class ExactOrderSums:
    """The residues of every condition of one order, and what they prove.

    ``residues[k, i, j]``: condition k, prime i, root j.  ``scale = (n−1)!·d^(n−1)``
    turns the integer element ``N`` back into the residual ``R`` (of the class
    representative; the caller applies the designated sign).

    Screened evaluations (module docstring) hold in ``screened`` the residues of every
    condition at the first ``full`` primes only, and beyond them those of the conditions
    that are zero there (the others' are 0, unknown: such a condition is decided,
    nonzero, already); ``residues`` evaluates the rest first, as values do."""

    vertices: int
    screened: np.ndarray
    primes: list[tuple[int, list[int]]]
    scale: int
    tableau: ScaledTableau
    listing: Any = None  # to evaluate more primes when a value needs them
    value_bits: int = 0  # the coefficients' bound: primes beyond the decision's, on demand
    dual: bool = False  # values from g'(θ)·N_e (ScaledTableau.dual_value_bits), not from N
    full: int | None = None  # primes known for every condition (None: all)
    #: every order of the same evaluation, by vertices: small ones are completed along
    siblings: dict[int, ExactOrderSums] | None = field(default=None, repr=False, compare=False)

    def __len__(self) -> int:
        return len(self.screened)

    @property
    def residues(self) -> np.ndarray:
        """Every condition's residues at every prime (evaluated now where screened)."""
        _evaluate([(self, list(self.primes))])
        return self.screened

    def is_zero(self) -> np.ndarray:
        result: np.ndarray = ~np.any(self.screened != 0, axis=(1, 2))
        return result

    def value(self, k: int) -> Any:
        """The exact residual of condition k: a Fraction (rationals) or a field element."""
        if self.tableau.number_field is not None and not np.any(self.screened[k]):
            return self.tableau.field_element([0], 1)  # proven zero (module docstring)
        self._complete()
        return self._values_of(slice(k, k + 1))[0]

    def _values_of(self, rows: slice) -> list[Any]:
        """The exact residuals of the conditions ``rows`` (their primes complete)."""
        t = self.tableau
        if not self.dual:
            columns = self._coefficients_of(rows)
            if t.number_field is None:
                return [Fraction(x, self.scale) for x in columns[0]]
            return [t.field_element(list(c), self.scale) for c in zip(*columns)]
        # X = g'(θ)·N_e (ScaledTableau.dual_value_bits): at a root r modulo p, X(r) =
        # g'(r)·N(r)/(d/e)^(n−1); then R = X / (g'(θ)·(n−1)!·e^(n−1))
        assert t.integral_d is not None
        n = self.vertices
        dg = [k * c for k, c in enumerate(t.minpoly)][1:]
        from flint import nmod_poly

        weights = []
        for p, roots in self.primes:
            inv = pow(pow(t.d // t.integral_d, n - 1, p), -1, p)
            g_prime = nmod_poly(dg, p)
            weights.append([int(g_prime(r)) * inv % p for r in roots])
        columns = self._coefficients_of(rows, weights)
        scale = math.factorial(n - 1) * t.integral_d ** (n - 1)
        inverse = t.field_element(dg, 1).inverse()
        return [t.field_element(list(c), scale) * inverse for c in zip(*columns)]

    def _complete(self) -> None:
        """Evaluate the primes the coefficients' bound needs beyond the decision's — in
        the same passes, for the other orders of this evaluation that still need them
        and have no more conditions than the tableau has stages: the passes' cost is
        then forming A's images modulo each prime (a surrogate of hundreds of stages),
        which every order's completion would repeat, and a report reads every order's
        failing values in turn."""
        along = [s for s in (self.siblings or {}).values()
                 if s is not self and len(s) <= self.tableau.s and s._missing()]
        _evaluate([(s, s._chosen()) for s in [self, *along]])
        for s in [self, *along]:
            s.value_bits = 0

    def _chosen(self) -> list[tuple[int, list[int]]]:
        """The primes the exact value needs (the decision's, or the coefficients' bound's)."""
        return self.tableau.primes_for(self.value_bits) if self.value_bits else list(self.primes)

    def _full(self) -> int:
        return len(self.primes) if self.full is None else self.full

    def _missing(self) -> bool:
        return self.listing is not None and len(self._chosen()) > self._full()

    def values(self) -> list[Any]:
        """Every condition's exact residual, the whole order at once
        (:meth:`_coefficients_of`)."""
        if self.tableau.degree == 1:
            return [Fraction(x, self.scale) for x in self.integers()]
        zero = self.is_zero()  # proven zero before the primes for values are added, as in value()
        self._complete()
        nought = self.tableau.field_element([0], 1)
        return [nought if z else v for z, v in zip(zero, self._values_of(slice(None)))]

    def integers(self) -> list[int]:
        """Rationals only: every condition's integer ``N = scale·R`` (Chinese remaindering
        over the primes, the symmetric residue)."""
        assert self.tableau.degree == 1
        self._complete()
        return self._coefficients_of(slice(None))[0]

    def _coefficients_of(self, rows: slice, weights: list[list[int]] | None = None) -> list[list[int]]:
        """For each coefficient of the power basis, its integers for the conditions
        ``rows``: per prime the inverse of the Vandermonde matrix of its roots applied to
        their residues at once (over Q the residues are the coefficient; ``weights[i][j]``
        multiplies those at prime i and root j first), then the Chinese remainder over the
        primes, the symmetric residue."""
        D = self.tableau.degree
        screened = self.screened[rows]
        per_prime = []
        for i, (p, roots) in enumerate(self.primes):
            residues = screened[:, i, :D].astype(np.int64) % p
            if weights is not None:
                residues = residues * np.array(weights[i], dtype=np.int64) % p
            inverse = _vandermonde_inverse(roots, p) if D > 1 else [[1]]
            columns = []
            for c in range(D):
                acc = np.zeros(len(residues), dtype=np.int64)
                for j in range(D):  # residues and entries below 2^30: each step stays below 2^61
                    acc = (acc + residues[:, j] * inverse[c][j]) % p
                columns.append(acc.tolist())
            per_prime.append(columns)
        mods = [p for p, _ in self.primes]
        if not mods:
            return [[0] * len(screened) for _ in range(D)]
        total = product(tuple(mods))
        return [[x - total if x > total // 2 else x for x in crt_columns([pp[c] for pp in per_prime], mods)]
                for c in range(D)]


def _evaluate(parts: list[tuple[ExactOrderSums, list[tuple[int, list[int]]]]]) -> None:
    """Every condition's residues, for each ``(sums, chosen)``, at the primes
    ``chosen`` (which start with its :attr:`~ExactOrderSums.primes`): those screened and
    those not evaluated yet, in one series of passes over the listing for all the
    orders (their primes are prefixes of one sequence)."""
    parts = [(s, chosen) for s, chosen in parts if s.listing is not None and len(chosen) > s._full()]
    if not parts:
        return
    first = parts[0][0]
    start = min(s._full() for s, _ in parts)
    longest = max((chosen for _, chosen in parts), key=len)
    more = {s.vertices: np.zeros((len(s.screened), len(chosen) - s._full(), first.tableau.degree),
                                 dtype=s.screened.dtype) for s, chosen in parts}
    ends = {s.vertices: len(chosen) for s, chosen in parts}

    def orders_for(i: int) -> list[int]:  # a pass's orders: those still short of primes from its first on
        return [n for n in more if start + i < ends[n]]

    for group, at in channel_passes(first.tableau, first.listing, longest[start:], orders_for, max(more)):
        for n, sums in at.items():
            for c, (i, j, _, _) in enumerate(group):
                k = start + i - (ends[n] - more[n].shape[1])
                if 0 <= k < more[n].shape[1]:
                    more[n][:, k, j] = sums[:, c]
    for s, chosen in parts:
        s.screened = np.concatenate([s.screened[:, :s._full()], more[s.vertices]], axis=1)
        s.primes = list(s.primes) + list(chosen[len(s.primes):])
        s.full = None


def _vandermonde_inverse(roots: list[int], p: int) -> list[list[int]]:
    """The inverse modulo p of the Vandermonde matrix ``(r_i^k)`` of distinct roots."""
    from flint import nmod_mat

    D = len(roots)
    inverse = nmod_mat([[pow(r, k, p) for k in range(D)] for r in roots], p).inv()
    return [[int(inverse[c, j]) for j in range(D)] for c in range(D)]


def exact_condition_sums(scaled: ScaledTableau, listing: Listing, orders: Iterable[int] | None = None,
                         on_pass: Callable[[int, int], None] | None = None) -> dict[int, ExactOrderSums]:
    """Every condition of the listing (or of the given orders) exactly: residues over
    enough channels for each order's bound, as many channels per pass over the listing
    as fit (:func:`~rkcheck.evaluation.passes.channel_passes`).  ``on_pass(done, total)`` after each pass that
    completes primes (counted in primes: every root of each done).
    On Ctrl-C, :class:`~rkcheck.evaluation.algorithm.EvaluationInterrupted` carries the
    orders whose primes were all done (low orders need fewer primes: they finish first)."""
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    wanted = sorted(listing.orders if orders is None else orders)
    need, value_need, dual, channels, count = _plan(scaled, listing, wanted)
    D = scaled.degree
    passes = max(count.values(), default=0)
    residues = {n: np.zeros((len(listing.orders[n]), count[n], D), dtype=np.int32) for n in wanted}
    full = dict(count)  # primes evaluated for every condition, per order (fewer when screened)

    def result(n: int) -> ExactOrderSums:
        more = value_need[n] > need[n]
        screened = full[n] < count[n]
        return ExactOrderSums(n, residues[n], channels[:count[n]], math.factorial(n - 1) * scaled.d ** (n - 1), scaled,
                              listing if more or screened else None, value_need[n] if more else 0, dual[n],
                              full[n] if screened else None)

    # every order: perhaps evaluated already, as part of all free trees
    if orders is None and _fill_contained(scaled, listing, count, channels, residues, full):
        if on_pass is not None and passes:
            on_pass(passes, passes)
        return _linked({n: result(n) for n in wanted})
    left = [len(roots) for _, roots in channels[:passes]]  # channels still to come, per prime
    done = 0
    screen = True  # tried once, when the first prime is complete and others remain
    try:
        for group, at in channel_passes(scaled, listing, channels[:passes], lambda i: [n for n in wanted if i < count[n]],
                                        wanted[-1] if wanted else 0):
            _store(residues, count, group, at)
            del at  # not alive while the next pass runs
            for i, *_ in group:
                left[i] -= 1
            finished = next((i for i, k in enumerate(left) if k), len(left))  # primes 0 … finished−1 complete
            if finished > done:
                done = finished
                if on_pass is not None:
                    on_pass(done, passes)
            if screen and 0 < done < passes:
                # the passes still to come (in flight, with a runner) are then not needed:
                # leaving the loop closes them
                screen = False
                if _screened(scaled, listing, channels[:passes], count, done, residues):
                    for n in wanted:
                        full[n] = min(count[n], done)
                    while done < passes:
                        done += 1
                        if on_pass is not None:
                            on_pass(done, passes)
                    break
    except KeyboardInterrupt:
        raise EvaluationInterrupted(_linked({n: result(n) for n in wanted if count[n] <= done})) from None
    out = _linked({n: result(n) for n in wanted})
    if orders is None:
        _remember(scaled, listing, out)
    return out


def _linked(sums: dict[int, ExactOrderSums]) -> dict[int, ExactOrderSums]:
    """The orders of one evaluation, each knowing the others (:meth:`ExactOrderSums._complete`)."""
    for s in sums.values():
        s.siblings = sums
    return sums


def _fill_contained(scaled: ScaledTableau, listing: Listing, count: dict[int, int],
                    channels: list[tuple[int, list[int]]], residues: dict[int, np.ndarray],
                    full: dict[int, int]) -> bool:
    """Whether every order's residues were read off an evaluation of all free trees
    (:func:`_contained`), filling ``residues`` and ``full`` when they were."""
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    try:
        contained = _contained(scaled, listing, count, channels)
    except KeyboardInterrupt:
        raise EvaluationInterrupted({}) from None
    if contained is None:
        return False
    for n, (known, k) in contained.items():
        residues[n], full[n] = known, k
    return True


def _store(residues: dict[int, np.ndarray], count: dict[int, int], group: list[Any], at: dict[int, np.ndarray]) -> None:
    """A pass's sums into the residues: an order keeps those of its own primes, no more."""
    for n, sums in at.items():
        for c, (i, j, _, _) in enumerate(group):
            if i < count[n]:
                residues[n][:, i, j] = sums[:, c]


def _screened(scaled: ScaledTableau, listing: Listing, channels: list[tuple[int, list[int]]],
              count: dict[int, int], done: int, residues: dict[int, np.ndarray]) -> bool:
    """The primes from ``done`` on, for the conditions whose residues at the first
    ``done`` are all zero only (the others are decided: they fail), evaluated on the trees
    their terms need (:class:`~rkcheck.evaluation.subset.Subset`) into ``residues``;
    False, with nothing done, when those conditions are not few."""
    from rkcheck.evaluation.subset import Subset

    if isinstance(listing, CentroidListing):  # its walks cost the same for a few conditions as for all
        return False
    later = [n for n in residues if count[n] > done]
    selected = {n: np.flatnonzero(~np.any(residues[n][:, :done] != 0, axis=(1, 2))) for n in later}
    subset = Subset.build(listing, selected, scaled.s)
    if subset is None:
        return False
    flat, copies = flat_channels(scaled, channels[done:])
    width = scaled.pass_width(subset.channel_bytes())
    for g in range(0, len(flat), width):
        group = flat[g:g + width]
        sums = subset.residues(scaled.channels([(p, r) for _, _, p, r in group]))
        group, sums = with_copies(scaled, group, sums, copies)
        for n, x in sums.items():
            for c, (i, j, _, _) in enumerate(group):
                if done + i < count[n]:
                    residues[n][selected[n], done + i, j] = x[:, c]
    return True


def _plan(scaled: ScaledTableau, listing: Listing,
          wanted: list[int]) -> tuple[dict[int, int], dict[int, int], dict[int, Any], list[Any], dict[int, int]]:
    """Per order: the bits that decide its zero residues (on N/g_k,
    :meth:`ScaledTableau.decision_bits`), the bits its values need, whether those come
    from ``g'(θ)·N_e`` (the smaller bound, :meth:`ScaledTableau.dual_value_bits`); then
    the channel primes, and how many of them each order takes."""
    need = {n: scaled.decision_bits(n, listing.orders[n].max_terms, listing.orders[n].coefficient_weight) for n in wanted}
    value_need = {n: scaled.coefficient_bits(n, listing.orders[n].max_terms) for n in wanted}
    dual = {}
    for n in wanted:
        dual_bits = scaled.dual_value_bits(n, listing.orders[n].max_terms)
        dual[n] = dual_bits is not None and dual_bits < value_need[n]
        if dual_bits is not None and dual[n]:
            value_need[n] = dual_bits
    channels = scaled.primes_for(max(need.values(), default=1))
    count = {n: 0 for n in wanted}
    cum = 0.0
    for p, _ in channels:
        for n in wanted:
            if cum < need[n]:
                count[n] += 1
        cum += math.log2(p)
    return need, value_need, dual, channels, count


def _remember(scaled: ScaledTableau, listing: Listing, sums: dict[int, ExactOrderSums]) -> None:
    """Keep the evaluation of every condition of all free trees on ``scaled``, for the
    listings of lower degrees that a file's claims check next (they share the tableau's
    ScaledTableau; :mod:`rkcheck.evaluation.contained`).  The sums are the check result's
    own: keeping them costs no memory while that result lives."""
    if listing.degree is None and not isinstance(listing, CentroidListing):  # read off by rooted trees
        scaled.__dict__["_all_trees"] = (listing, sums)


def _contained(scaled: ScaledTableau, listing: Listing, count: dict[int, int],
               channels: list[tuple[int, list[int]]]) -> dict[int, tuple[np.ndarray, int]] | None:
    """The residues of every order of ``listing`` read off a kept evaluation of all free
    trees that contains it, or None."""
    kept = scaled.__dict__.get("_all_trees")
    if kept is None or kept[0] is listing or isinstance(listing, CentroidListing):
        return None
    from rkcheck.evaluation.contained import contained_residues

    return contained_residues(kept[0], kept[1], listing, count, channels)
