"""Number backends: one algorithm, several number contexts (SPEC §5).

Every backend answers the same two calls, in the manner of mpmath's ``mp``/``iv``/``fp``:

* :meth:`tree_weights` — the elementary weights ``a(t) = bᵀΦ(t)`` of every tree of a
  :class:`~rkcheck.trees.RootedTreeTable`, by the recursion (SPEC §2)
  ``Φ(τ) = 1``, ``Φ(u∘v) = Φ(u) ⊙ AΦ(v)``, memoised per tree id and per table, so each
  weight is computed once and shared by all the conditions that use it;
* :meth:`enclose_terms` — enclosures of sums ``Σ sign/σ · Π a(t_k)``, the shape of
  every energy condition (and, with one factor, of ``a(t) − 1/γ(t)``).

Backends:

``ExactBackend``
    Rational tableaux.  ``A`` and ``b`` are scaled to one common denominator ``d``;
    then ``â(t) = d^|t| a(t)`` and ``Φ̂(t) = d^(|t|-1) Φ(t)`` are integers, and a
    condition on ``n`` vertices times ``lcm(σ) d^(n-1)`` is an integer sum.  Verdicts
    are exact: ``holds`` or ``fails``.
``BallBackend``
    Everything else (square roots, rounded decimals).  Fixed-point balls: an integer
    mid-point ``m`` and radius ``r`` at scale ``2^-P`` mean the value lies in
    ``[m-r, m+r]·2^-P``.  Additions are exact on integers; every product adds the
    propagated radius and one unit for its rounding, so the enclosure is rigorous by
    construction (no reliance on floating-point rounding modes).
``FloatBackend`` (:mod:`rkcheck.screen`)
    A float64 screen with its own rounding bound, used for speed comparisons.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Protocol, Sequence

from .intervals import Interval
from .trees import RootedTreeTable

LOG2_10 = math.log2(10)
GUARD_BITS = 32


@dataclass(frozen=True, slots=True)
class Enclosure:
    """``mid ± rad`` with rational end points; ``exact`` means ``rad == 0`` by construction."""

    mid: Fraction
    rad: Fraction
    exact: bool

    def contains_zero(self) -> bool:
        return abs(self.mid) <= self.rad

    @staticmethod
    def of(x: Fraction) -> "Enclosure":
        return Enclosure(Fraction(x), Fraction(0), True)


class Term(Protocol):
    sign: int
    sigma: int
    branches: tuple[int, ...]


class Backend(Protocol):
    name: str
    exact: bool

    def tree_weights(self, table: RootedTreeTable, upto: int | None = None) -> object: ...

    def enclose_terms(self, table: RootedTreeTable, terms: Sequence[Term], scale: int) -> Enclosure: ...

    def weight_minus(self, table: RootedTreeTable, t: int, value: Fraction) -> Enclosure: ...

    def enclose_scalar(self, x: Interval | Fraction) -> Enclosure: ...


def bits_for_dps(dps: int) -> int:
    """Working bits for ``dps`` decimal digits, plus guard bits for the rounding of long sums."""
    return math.ceil(dps * LOG2_10) + GUARD_BITS


class _WeightCache:
    """Per-table memo of weights, grown order by order (so a caller that stops early,
    like the classical-order check, never pays for higher orders)."""

    def __init__(self) -> None:
        self.done_order = 0
        self.phi: list = []  # Φ(t) per id (backend representation), None when not needed
        self.psi: list = []  # AΦ(t) per id
        self.a: list = []  # a(t) per id


# ------------------------------------------------------------------------ exact


class ExactBackend:
    """Exact rational arithmetic on integer-scaled weights (see module docstring)."""

    name = "exact"
    exact = True

    def __init__(self, A: Sequence[Sequence[Fraction]], b: Sequence[Fraction]):
        self.s = len(b)
        den = 1
        for x in [x for row in A for x in row] + list(b):
            den = math.lcm(den, Fraction(x).denominator)
        self.d = den
        self.A = [[int(Fraction(x) * den) for x in row] for row in A]
        self.b = [int(Fraction(x) * den) for x in b]
        # sparse rows: explicit tableaux are mostly zeros
        self._rows = [[(j, a) for j, a in enumerate(row) if a] for row in self.A]
        self._bnz = [(i, x) for i, x in enumerate(self.b) if x]
        # keyed by the table object itself (identity), never by id(): a freed table's id
        # could be reused by a new table and would then return stale weights
        self._caches: dict[RootedTreeTable, _WeightCache] = {}

    def _matvec(self, x: list[int]) -> list[int]:
        return [sum(a * x[j] for j, a in row) for row in self._rows]

    def tree_weights(self, table: RootedTreeTable, upto: int | None = None) -> list[int]:
        """``â(t) = d^|t| a(t)`` for every id of order <= ``upto`` (default: all)."""
        upto = table.max_order if upto is None else upto
        cache = self._caches.get(table)
        if cache is None:
            cache = self._caches[table] = _WeightCache()
            ones = [1] * self.s
            cache.phi.append(ones)
            cache.psi.append(self._matvec(ones))
            cache.a.append(sum(x for _, x in self._bnz))
            cache.done_order = 1
        top = table.max_order
        for n in range(cache.done_order + 1, upto + 1):
            # trees of the top order are never a factor of another tree (unless the table grows)
            keep_phi = keep_psi = n < top or table.growable
            for t in table.ids_of_order(n):
                pu = cache.phi[table.left[t]]
                pv = cache.psi[table.right[t]]
                phi = [x * y for x, y in zip(pu, pv)]
                cache.a.append(sum(x * phi[i] for i, x in self._bnz))
                cache.phi.append(phi if keep_phi else None)
                cache.psi.append(self._matvec(phi) if keep_psi else None)
            cache.done_order = n
        return cache.a

    def enclose_terms(self, table: RootedTreeTable, terms: Sequence[Term], scale: int) -> Enclosure:
        """``Σ sign/σ Π a(t)`` exactly; ``scale`` = lcm of the σ of the terms."""
        a = self._caches[table].a
        total = 0
        size = None
        for term in terms:
            p = scale // term.sigma
            for t in term.branches:
                p *= a[t]
            total += p if term.sign > 0 else -p
            if size is None:
                size = sum(table.order[t] for t in term.branches)
        value = Fraction(total, scale * self.d ** (size or 0))
        return Enclosure(value, Fraction(0), True)

    def weight_minus(self, table: RootedTreeTable, t: int, value: Fraction) -> Enclosure:
        """``a(t) - value`` exactly."""
        a = self.tree_weights(table, table.order[t])
        return Enclosure.of(Fraction(a[t], self.d ** table.order[t]) - value)

    def enclose_scalar(self, x: Interval | Fraction) -> Enclosure:
        if isinstance(x, Interval):
            assert x.is_point
            x = x.lo
        return Enclosure.of(x)


# ------------------------------------------------------------------------- ball


def _to_ball(x: Interval, bits: int) -> tuple[int, int]:
    """A fixed-point ball (m, r) at scale 2^-bits enclosing the interval ``x``."""
    lo = x.lo * (1 << bits)
    hi = x.hi * (1 << bits)
    m = math.floor((lo + hi) / 2)
    r = math.ceil(max(hi - m, m - lo))
    return m, r


class BallBackend:
    """Certified fixed-point ball arithmetic at ``bits`` bits (see module docstring)."""

    name = "mpmath"
    exact = False

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval], bits: int):
        self.s = len(b)
        self.bits = bits
        self.one = 1 << bits
        self.A = [[_to_ball(x, bits) for x in row] for row in A]
        self.b = [_to_ball(x, bits) for x in b]
        self._rows = [[(j, m, r) for j, (m, r) in enumerate(row) if m or r] for row in self.A]
        self._bnz = [(i, m, r) for i, (m, r) in enumerate(self.b) if m or r]
        # keyed by the table object itself (identity), never by id(): a freed table's id
        # could be reused by a new table and would then return stale weights
        self._caches: dict[RootedTreeTable, _WeightCache] = {}

    def _mul(self, m1: int, r1: int, m2: int, r2: int) -> tuple[int, int]:
        P = self.bits
        # floor for the mid-point costs < 1 unit; the radius is rounded up: +2 in all
        return (m1 * m2) >> P, ((abs(m1) * r2 + abs(m2) * r1 + r1 * r2) >> P) + 2

    def _dot(self, coeffs: list[tuple[int, int, int]], xm: list[int], xr: list[int]) -> tuple[int, int]:
        P = self.bits
        sm = 0
        sr = 0
        for j, m, r in coeffs:
            xmj = xm[j]
            xrj = xr[j]
            sm += m * xmj
            sr += abs(m) * xrj + abs(xmj) * r + r * xrj
        # one rounding for the whole exact integer sum
        return sm >> P, (sr >> P) + 2

    def tree_weights(self, table: RootedTreeTable, upto: int | None = None) -> list[tuple[int, int]]:
        upto = table.max_order if upto is None else upto
        cache = self._caches.get(table)
        if cache is None:
            cache = self._caches[table] = _WeightCache()
            ones_m, ones_r = [self.one] * self.s, [0] * self.s
            cache.phi.append((ones_m, ones_r))
            cache.psi.append(self._matvec(ones_m, ones_r))
            cache.a.append(self._dot(self._bnz, ones_m, ones_r))
            cache.done_order = 1
        top = table.max_order
        P = self.bits
        for n in range(cache.done_order + 1, upto + 1):
            keep = n < top or table.growable
            for t in table.ids_of_order(n):
                um, ur = cache.phi[table.left[t]]
                vm, vr = cache.psi[table.right[t]]
                pm = [(x * y) >> P for x, y in zip(um, vm)]
                pr = [((abs(x) * ry + abs(y) * rx + rx * ry) >> P) + 2 for x, rx, y, ry in zip(um, ur, vm, vr)]
                cache.a.append(self._dot(self._bnz, pm, pr))
                cache.phi.append((pm, pr) if keep else None)
                cache.psi.append(self._matvec(pm, pr) if keep else None)
            cache.done_order = n
        return cache.a

    def _matvec(self, xm: list[int], xr: list[int]) -> tuple[list[int], list[int]]:
        out_m, out_r = [], []
        for row in self._rows:
            m, r = self._dot(row, xm, xr)
            out_m.append(m)
            out_r.append(r)
        return out_m, out_r

    def enclose_terms(self, table: RootedTreeTable, terms: Sequence[Term], scale: int) -> Enclosure:
        a = self._caches[table].a
        P = self.bits
        total_m = 0
        total_r = 0
        for term in terms:
            branches = term.branches
            if not branches:
                pm, pr = self.one, 0
            else:
                pm, pr = a[branches[0]]
                for t in branches[1:]:
                    qm, qr = a[t]
                    pm, pr = (pm * qm) >> P, ((abs(pm) * qr + abs(qm) * pr + pr * qr) >> P) + 2
            k = scale // term.sigma
            total_m += k * pm if term.sign > 0 else -k * pm
            total_r += k * pr
        # divide by scale: floor the mid-point (<1 unit), round the radius up
        m = total_m // scale
        r = -(-total_r // scale) + 1
        return Enclosure(Fraction(m, self.one), Fraction(r, self.one), False)

    def weight_minus(self, table: RootedTreeTable, t: int, value: Fraction) -> Enclosure:
        a = self.tree_weights(table, table.order[t])
        m, r = a[t]
        return Enclosure(Fraction(m, self.one) - value, Fraction(r, self.one), False)

    def enclose_scalar(self, x: Interval | Fraction) -> Enclosure:
        if not isinstance(x, Interval):
            x = Interval.point(x)
        return Enclosure(x.mid, x.rad, False)


def make_backend(tableau, dps: int, decimals: str) -> ExactBackend | BallBackend:
    """Exact arithmetic when the tableau is rational (and decimals are read exactly or
    are all short), else certified balls at ``dps`` digits (SPEC §5)."""
    if tableau.is_exact(decimals):
        return ExactBackend(tableau.exact_A(), tableau.exact_b())
    bits = bits_for_dps(dps)
    A, b = tableau.enclosures(bits + 8, decimals)
    return BallBackend(A, b, bits)

