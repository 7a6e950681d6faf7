"""Number backends: one algorithm, several number contexts (definitions §5).

Every backend answers the same two calls, in the manner of mpmath's ``mp``/``iv``/``fp``:

* :meth:`tree_weights` — the elementary weights ``a(t) = bᵀΦ(t)`` of every tree of a
  :class:`~rkcheck.trees.rooted.RootedTreeTable`, by the recursion (definitions §2)
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
``BallBackend`` (``"ball"``)
    Everything else (square roots, rounded decimals), at ``--dps`` digits.  Fixed-point
    balls: an integer mid-point ``m`` and radius ``r`` at scale ``2^-P`` mean the value
    lies in ``[m-r, m+r]·2^-P``.  This is the arbitrary-precision backend that definitions §5
    calls "mpmath at the working precision": mpmath's ``mpf`` carries no error bound and
    its interval context costs about 2.5× more per product, so rkcheck does its own balls
    on Python integers (what ``mpf`` does internally) with a proven radius.  Additions are exact on integers; every product adds the
    propagated radius and one unit for its rounding, so the enclosure is rigorous by
    construction (no reliance on floating-point rounding modes).
``FloatBackend`` (:mod:`rkcheck.evaluation.float_screen`)
    A float64 screen with its own rounding bound, used for speed comparisons.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Protocol, Sequence

from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.precision import bits_for_dps, entry_bits
from rkcheck.trees.rooted import RootedTreeTable

_ZERO = Fraction(0)
# float inflation factors that keep computed radii upper bounds (see BallBackend)
_UP1 = 1.0 + 2.0**-51
_UP4 = 1.0 + 12 * 2.0**-52


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



class _WeightStore:
    """Per-table store of Φ(t), AΦ(t) and a(t), grown order by order (a caller that stops
    early, like the classical-order check, never pays for higher orders).  Mid-points are
    numpy *object* arrays of Python ints, so the arithmetic stays exact while the loops
    over the trees of one order run in numpy's C code; the ball backend adds float64
    radius arrays (``radii=True``)."""

    def __init__(self, s: int, radii: bool = False) -> None:
        import numpy as np

        self.np = np
        self.radii = radii
        self.done_order = 0
        self.phi_m = np.empty((0, s), dtype=object)
        self.psi_m = np.empty((0, s), dtype=object)
        self.a_m = np.empty(0, dtype=object)
        self.phi_r = np.empty((0, s))
        self.psi_r = np.empty((0, s))
        self.a_r = np.empty(0)

    def grow(self, n: int) -> None:
        np = self.np
        extra = n - len(self.a_m)
        if extra <= 0:
            return
        s = self.phi_m.shape[1]
        self.phi_m = np.concatenate([self.phi_m, np.zeros((extra, s), dtype=object)])
        self.psi_m = np.concatenate([self.psi_m, np.zeros((extra, s), dtype=object)])
        self.a_m = np.concatenate([self.a_m, np.zeros(extra, dtype=object)])
        if self.radii:
            self.phi_r = np.concatenate([self.phi_r, np.zeros((extra, s))])
            self.psi_r = np.concatenate([self.psi_r, np.zeros((extra, s))])
            self.a_r = np.concatenate([self.a_r, np.zeros(extra)])


def _term_multipliers(ctable):
    """(±lcm/σ per term, lcm per condition, vertices − 1 per condition) from the table's
    cached term arrays."""
    arr = ctable.term_arrays
    return arr["mult"], arr["lcm"], arr["size"]


# ------------------------------------------------------------------------ exact


class ExactBackend:
    """Exact rational arithmetic on integer-scaled weights (see module docstring)."""

    name = "exact"
    exact = True

    def __init__(self, A: Sequence[Sequence[Fraction]], b: Sequence[Fraction]):
        import numpy as np

        self.s = len(b)
        den = 1
        for x in [x for row in A for x in row] + list(b):
            den = math.lcm(den, Fraction(x).denominator)
        self.d = den
        self.A = [[int(Fraction(x) * den) for x in row] for row in A]
        self.b = [int(Fraction(x) * den) for x in b]
        self._At = np.array(self.A, dtype=object).T
        self._bv = np.array(self.b, dtype=object)
        # keyed by the table object itself (identity), never by id(): a freed table's id
        # could be reused by a new table and would then return stale weights
        self._caches: dict[RootedTreeTable, _WeightStore] = {}

    def tree_weights(self, table: RootedTreeTable, upto: int | None = None):
        """``â(t) = d^|t| a(t)`` for every id of order <= ``upto`` (default: all), as an
        object array indexed by id."""
        upto = table.max_order if upto is None else upto
        cache = self._caches.get(table)
        if cache is None:
            cache = self._caches[table] = _WeightStore(self.s)
            cache.grow(1)
            ones = cache.np.array([1] * self.s, dtype=object)
            cache.phi_m[0] = ones
            cache.psi_m[0] = ones.dot(self._At)
            cache.a_m[0] = ones.dot(self._bv)
            cache.done_order = 1
        if upto > cache.done_order:
            cache.grow(table.first_id[upto + 1])
            left, right = table.factor_arrays()
            for n in range(cache.done_order + 1, upto + 1):
                lo, hi = table.first_id[n], table.first_id[n + 1]
                if hi > lo:
                    phi = cache.phi_m[left[lo:hi]] * cache.psi_m[right[lo:hi]]
                    cache.phi_m[lo:hi] = phi
                    cache.psi_m[lo:hi] = phi.dot(self._At)
                    cache.a_m[lo:hi] = phi.dot(self._bv)
                cache.done_order = n
        return cache.a_m

    def enclose_terms(self, table: RootedTreeTable, terms: Sequence[Term], scale: int) -> Enclosure:
        """``Σ sign/σ Π a(t)`` exactly; ``scale`` = lcm of the σ of the terms."""
        a = self.tree_weights(table)
        total = 0
        size = None
        for term in terms:
            p = scale // term.sigma
            for t in term.branches:
                p *= int(a[t])
            total += p if term.sign > 0 else -p
            if size is None:
                size = sum(table.order[t] for t in term.branches)
        value = Fraction(total, scale * self.d ** (size or 0))
        return Enclosure(value, Fraction(0), True)

    def enclose_table(self, ctable) -> list[Enclosure]:
        """Every condition of a :class:`~rkcheck.trees.conditions.ConditionTable`, exactly:
        ``lcm·d^(n−1)·R = Σ ±(lcm/σ) Π â(t)``, vectorised over all terms."""
        import numpy as np

        arr = ctable.term_arrays
        mult, lcms, sizes = _term_multipliers(ctable)
        a = np.append(self.tree_weights(ctable.trees), np.array([1], dtype=object))  # -1 pads read 1
        br = arr["branches"]
        p = mult.copy()
        for k, n_k in enumerate(arr["needs"]):
            p[:n_k] = p[:n_k] * a[br[:n_k, k]]
        totals = np.zeros(len(ctable.conditions), dtype=object)
        np.add.at(totals, arr["owner"], p)
        d = self.d
        powers = [d**k for k in range(max(sizes, default=0) + 1)]
        return [
            Enclosure(Fraction(int(t), int(L) * powers[k]) if t else _ZERO, _ZERO, True)
            for t, L, k in zip(totals, lcms, sizes)
        ]

    def weight_minus(self, table: RootedTreeTable, t: int, value: Fraction) -> Enclosure:
        """``a(t) - value`` exactly."""
        a = self.tree_weights(table, table.order[t])
        return Enclosure.of(Fraction(int(a[t]), self.d ** table.order[t]) - value)



# ------------------------------------------------------------------------- ball


def _to_ball(x: Interval, bits: int) -> tuple[int, int]:
    """A fixed-point ball (m, r) at scale 2^-bits enclosing the interval ``x``."""
    lo = x.lo * (1 << bits)
    hi = x.hi * (1 << bits)
    m = math.floor((lo + hi) / 2)
    r = math.ceil(max(hi - m, m - lo))
    return m, r


class BallBackend:
    """Certified fixed-point ball arithmetic at ``bits`` bits (see module docstring).

    Mid-points are exact integers at scale 2^-P: a product is ``(m1·m2) >> P`` (floored,
    less than one unit lost), sums are exact, a dot product is rounded once after its
    exact integer sum.  Radii need no precision, only to be upper bounds, so they are
    float64 numbers of units 2^-P: ``r = |x1|·r2 + |x2|·r1 + r1·r2·2^-P + 1`` with ``|x|``
    a float upper bound of ``|m|·2^-P``; every float operation rounds to nearest, so each
    computed radius is multiplied by ``1 + (2k+4)·2^-52`` for a k-term expression (and
    the magnitudes by ``1 + 2^-51``), which keeps it an upper bound (Higham's γ_k).  The
    big-integer work is then one product per operation, as in exact arithmetic."""

    name = "ball"
    exact = False

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval], bits: int):
        import numpy as np

        self.np = np
        self.s = len(b)
        self.bits = bits
        self.one = 1 << bits
        self._scale = 2.0 ** (-bits)
        self._mag_shift = max(0, bits - 64)
        self._mag_scale = 2.0 ** (self._mag_shift - bits)
        balls_A = [[_to_ball(x, bits) for x in row] for row in A]
        balls_b = [_to_ball(x, bits) for x in b]
        self._Am_t = np.array([[m for m, _ in row] for row in balls_A], dtype=object).T
        self._Ar_t = np.array([[float(r) for _, r in row] for row in balls_A]).T * _UP1 + 1.0
        self._Ax_t = self._mag(self._Am_t)
        self._bm = np.array([m for m, _ in balls_b], dtype=object)
        self._br = np.array([float(r) for _, r in balls_b]) * _UP1 + 1.0
        self._bx = self._mag(self._bm)
        self._dot_up = 1.0 + (2 * self.s + 8) * 2.0**-52
        self._caches: dict[RootedTreeTable, _WeightStore] = {}

    def _mag(self, m):
        """float upper bounds of |m|·2^-P for an object array of integers (shifted down
        first: at hundreds of digits the integers themselves exceed the float range)."""
        np = self.np
        shift = self._mag_shift
        if shift == 0:
            return np.abs(np.asarray(m, dtype=float)) * self._scale * _UP1
        top = (np.abs(m) >> shift) + 1  # rounds the magnitude up
        return np.asarray(top, dtype=float) * self._mag_scale * _UP1

    def _dot(self, xm, xr, Mm, Mr, Mx):
        """Ball (rows of x) @ M: exact integer sums, one floor, radius bound in units."""
        mid = xm.dot(Mm) >> self.bits
        xx = self._mag(xm)
        rad = (xx.dot(Mr) + xr.dot(Mx) + xr.dot(Mr) * self._scale) * self._dot_up + 1.0
        return mid, rad

    def tree_weights(self, table: RootedTreeTable, upto: int | None = None):
        """Balls of ``a(t)`` per id: (mids: object array, radii: float array), units 2^-P."""
        np = self.np
        upto = table.max_order if upto is None else upto
        cache = self._caches.get(table)
        if cache is None:
            cache = self._caches[table] = _WeightStore(self.s, radii=True)
            cache.grow(1)
            ones_m = np.array([self.one] * self.s, dtype=object)
            zeros = np.zeros(self.s)
            cache.phi_m[0], cache.phi_r[0] = ones_m, zeros
            cache.psi_m[0], cache.psi_r[0] = self._dot(ones_m, zeros, self._Am_t, self._Ar_t, self._Ax_t)
            am, ar = self._dot(ones_m, zeros, self._bm, self._br, self._bx)
            cache.a_m[0], cache.a_r[0] = am, ar
            cache.done_order = 1
        if upto > cache.done_order:
            cache.grow(table.first_id[upto + 1])
            left, right = table.factor_arrays()
            P = self.bits
            for n in range(cache.done_order + 1, upto + 1):
                lo, hi = table.first_id[n], table.first_id[n + 1]
                if hi > lo:
                    li, ri = left[lo:hi], right[lo:hi]
                    um, ur = cache.phi_m[li], cache.phi_r[li]
                    vm, vr = cache.psi_m[ri], cache.psi_r[ri]
                    pm = (um * vm) >> P
                    pr = (self._mag(um) * vr + self._mag(vm) * ur + ur * vr * self._scale) * _UP4 + 1.0
                    cache.phi_m[lo:hi], cache.phi_r[lo:hi] = pm, pr
                    cache.psi_m[lo:hi], cache.psi_r[lo:hi] = self._dot(pm, pr, self._Am_t, self._Ar_t, self._Ax_t)
                    cache.a_m[lo:hi], cache.a_r[lo:hi] = self._dot(pm, pr, self._bm, self._br, self._bx)
                cache.done_order = n
        return cache.a_m, cache.a_r

    def _mag_one(self, m: int) -> float:
        shift = self._mag_shift
        return float((abs(m) >> shift) + (1 if shift else 0)) * self._mag_scale * _UP1

    def _ball_of(self, a_m, a_r, t: int) -> tuple[int, float]:
        return int(a_m[t]), float(a_r[t])

    def enclose_terms(self, table: RootedTreeTable, terms: Sequence[Term], scale: int) -> Enclosure:
        a_m, a_r = self.tree_weights(table)
        P, S = self.bits, self._scale
        total_m = 0
        total_r = 0.0
        for term in terms:
            branches = term.branches
            if not branches:
                pm, pr = self.one, 0.0
            else:
                pm, pr = self._ball_of(a_m, a_r, branches[0])
                for t in branches[1:]:
                    qm, qr = self._ball_of(a_m, a_r, t)
                    xm, xq = self._mag_one(pm), self._mag_one(qm)
                    pr = (xm * qr + xq * pr + pr * qr * S) * _UP4 + 1.0
                    pm = (pm * qm) >> P
            k = scale // term.sigma
            total_m += k * pm if term.sign > 0 else -k * pm
            total_r = (total_r + k * pr) * _UP1
        m = total_m // scale
        r = math.ceil(total_r / scale * _UP1) + 1  # divide by scale: round the radius up
        return Enclosure(Fraction(m, self.one), Fraction(r, self.one), False)

    def enclose_table(self, ctable) -> list[Enclosure]:
        """Every condition of a condition table, vectorised over all terms."""
        np = self.np
        arr = ctable.term_arrays
        mult, lcms, _sizes = _term_multipliers(ctable)
        a_m, a_r = self.tree_weights(ctable.trees)
        am = np.append(a_m, np.array([self.one], dtype=object))  # -1 pads read the exact 1
        ar = np.append(a_r, 0.0)
        P, S = self.bits, self._scale
        br = arr["branches"]
        n_terms = br.shape[0]
        pm = np.full(n_terms, self.one, dtype=object)
        pr = np.zeros(n_terms)
        for k, n_k in enumerate(arr["needs"]):
            idx = br[:n_k, k]
            qm, qr = am[idx], ar[idx]
            if k == 0:  # multiplying the exact 1 is exact
                pm[:n_k], pr[:n_k] = qm, qr
                continue
            xm, xr = pm[:n_k], pr[:n_k]
            pr[:n_k] = (self._mag(xm) * qr + self._mag(qm) * xr + xr * qr * S) * _UP4 + 1.0
            pm[:n_k] = (xm * qm) >> P
        n = len(ctable.conditions)
        owner = arr["owner"]
        tm = np.zeros(n, dtype=object)
        np.add.at(tm, owner, mult * pm)
        abs_mult = arr.get("abs_mult_float")
        if abs_mult is None:
            abs_mult = arr["abs_mult_float"] = np.abs(np.asarray(mult, dtype=float)) * _UP1
        counts = arr["counts"]
        tr = np.bincount(owner, weights=abs_mult * pr, minlength=n) * (1.0 + (counts + 4) * 2.0**-52)
        one = self.one
        out = []
        for m, r, L in zip(tm.tolist(), tr.tolist(), lcms.tolist()):
            # divide by lcm: floor the mid-point (< 1 unit), round the radius up (+1 unit)
            out.append(Enclosure(Fraction(m // L, one), Fraction(math.ceil(r / L * _UP1) + 1, one), False))
        return out

    def weight_minus(self, table: RootedTreeTable, t: int, value: Fraction) -> Enclosure:
        a_m, a_r = self.tree_weights(table, table.order[t])
        m, r = self._ball_of(a_m, a_r, t)
        return Enclosure(Fraction(m, self.one) - value, Fraction(math.ceil(r * _UP1), self.one), False)



def make_backend(tableau, dps: int, decimals: str, enclosures=None) -> ExactBackend | BallBackend:
    """Exact arithmetic when the tableau is rational (and decimals are read exactly or
    are all short), else certified balls at ``dps`` digits (definitions §5).  ``enclosures``:
    the entries already enclosed at :func:`entry_bits` (saves enclosing them twice)."""
    if tableau.is_exact(decimals):
        return ExactBackend(tableau.exact_A(), tableau.exact_b())
    A, b = enclosures or tableau.enclosures(entry_bits(dps), decimals)
    return BallBackend(A, b, bits_for_dps(dps))

