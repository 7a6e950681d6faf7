"""The condition sums of the int64-digit balls (:mod:`rkcheck.evaluation.limbs`,
definitions §5): the exact mid-point sums ``Σ c·w`` of an order, accumulated digit by
digit, and the order's :class:`DigitBallSums`, judged without a Python integer per
condition.

A condition's coefficients ``c = ±(n−1)!/σ`` share a divisor ``g_k`` with ``c/g_k`` a
small integer (:func:`multipliers`), so ``Σ c·w = g_k·Σ (c/g_k)·w`` is summed as small
multiples of the weights' digits, uncarried, in float64 — exact — and carried once per
order.  The judging (``|mid| > rad``, a bound on ``|mid| + rad``) runs on a float
estimate of each ``|mid|`` with a rigorous relative error, exactly (Python integers)
only where the estimate cannot decide; the mid-points as Python integers are built
when asked for.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from rkcheck.evaluation.balls import BallSums, exceeds_scaled
from rkcheck.numbers.enclosure import Enclosure


class DigitSums:
    """The condition sums of one order: per condition and digit position the float64
    sum of the terms' ``m·digit`` (exact integers), and the radius sums.  Terms are
    gathered in runs of many blocks (digits as int32, their multipliers as int8) and
    binned at once: ``np.bincount`` costs the number of conditions on every call, and at
    the top orders a block of terms is far smaller than the conditions it lands in."""

    def __init__(self, L: int, k: int):
        self.digits, self.radii = np.zeros((L, k)), np.zeros(k)
        run = min(max(k, _MIN_RUN), _MAX_RUN)
        self._w, self._wm, self._wc = np.empty((L, run), dtype=np.int32), np.empty(run, dtype=np.int8), \
            np.empty(run, dtype=np.intp)
        self._r, self._rc = np.empty(run), np.empty(run, dtype=np.intp)
        self._nw = self._nr = 0
        self.terms = None  # the order's terms (their divisors scale the sums)

    def add_digits(self, digits: np.ndarray, mult: np.ndarray, cond: np.ndarray) -> None:
        """The digits ``(L, m)`` (each below 2^31 in magnitude) of terms with the
        multipliers ``mult`` in the conditions ``cond``."""
        m = len(cond)
        if self._nw + m > self._w.shape[1]:
            self._flush_digits()
        if m > self._w.shape[1]:
            self._w = np.empty((len(self._w), m), dtype=np.int32)
            self._wm, self._wc = np.empty(m, dtype=np.int8), np.empty(m, dtype=np.intp)
        lo, self._nw = self._nw, self._nw + m
        self._w[:, lo:self._nw] = digits
        self._wm[lo:self._nw] = mult
        self._wc[lo:self._nw] = cond

    def radius_room(self, cond: np.ndarray) -> np.ndarray:
        """Room for the radii of terms of the conditions ``cond``."""
        m = len(cond)
        if self._nr + m > len(self._r):
            self._flush_radii()
        if m > len(self._r):
            self._r, self._rc = np.empty(m), np.empty(m, dtype=np.intp)
        self._rc[self._nr:self._nr + m] = cond
        self._nr += m
        return self._r[self._nr - m:self._nr]

    def _flush_digits(self) -> None:
        n, k = self._nw, self.digits.shape[1]
        if n:
            cond, mult = self._wc[:n], self._wm[:n]
            for p in range(len(self.digits)):  # m·digit: exact in float64 (multipliers checks)
                self.digits[p] += np.bincount(cond, weights=np.multiply(self._w[p, :n], mult, dtype=np.float64),
                                              minlength=k)
        self._nw = 0

    def _flush_radii(self) -> None:
        n = self._nr
        if n:
            # one term after another into its bin: every radius is then the same sum, in the
            # same order, whatever else is binned with it (a subset's balls are the pass's)
            np.add.at(self.radii, self._rc[:n], self._r[:n])
        self._nr = 0

    def totals(self) -> tuple[np.ndarray, np.ndarray]:
        """The digit sums ``(L, k)`` and radius sums; the runs' buffers are released."""
        self._flush_digits()
        self._flush_radii()
        self._w = np.empty((len(self._w), 0), dtype=np.int32)  # (a slice would keep them)
        self._wm, self._wc = np.empty(0, dtype=np.int8), np.empty(0, dtype=np.intp)
        self._r, self._rc = np.empty(0), np.empty(0, dtype=np.intp)
        return self.digits, self.radii


#: terms binned at once (at least, and at most): runs at least as long as the conditions
#: are many keep bincount's cost per term bounded, and the run's buffer small
_MIN_RUN = 1 << 14
_MAX_RUN = 1 << 18


def multipliers(terms: Any, beta: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(per term ``m = c/g_k`` as int8, per coefficient ``|c|`` as float64, per condition
    ``g_k``), once per order's terms, ``g_k`` a common divisor of the coefficients of
    condition ``k``.

    The terms of a condition are the rootings of one free tree, one per orbit O of its
    automorphisms, with ``c = ±K·|O|`` (:attr:`~rkcheck.trees.terms.OrderTerms.coefficient_weight`):
    ``g_k = K = Σ|c|/n`` (:func:`_orbit_divisors`) when it divides every coefficient —
    then ``Σ|m| = n`` exactly — else their gcd (``Σ|m|`` counted).  Every partial sum of
    ``m·digit`` (digits below 2^β in magnitude) is below ``Σ|m|·2^β``; that bound is
    checked against 2^53 (float64 integers) and against what :meth:`LimbBallContext.to_ints`
    takes after the carries (``2^(62−β)``, the top digit below ``Σ|m|·2^(β−4) + Σ|m| + 1``)."""
    cached = getattr(terms, "_digit_multipliers", None)
    if cached is None:
        coef = terms.coefficients
        wide = max(map(abs, coef), default=0) >= 2**62  # beyond int64: Python integers
        exact = np.array(coef, dtype=object).astype(object if wide else np.int64)
        g = None if wide else _orbit_divisors(terms, exact)
        mult = None if g is None else _quotients(terms, exact, g)
        weight = float(terms.vertices)
        if mult is None:  # not the orbit structure: the gcd of each condition's coefficients
            g = np.zeros(len(terms) + 1, dtype=exact.dtype)
            for t0 in range(0, terms.rows, _PLAN_CHUNK):  # in chunks: small temporaries
                cond, idx = terms.block(t0, min(terms.rows, t0 + _PLAN_CHUNK))
                np.gcd.at(g, cond, np.abs(exact[idx]))
            mult = _quotients(terms, exact, g)
            weight = _largest_weight(terms, mult) if mult is not None else math.inf
        if mult is None or weight * 2.0**beta > 2.0**53 or weight * 2.0 ** (beta - 4) + weight + 1 >= 2.0 ** (62 - beta):
            raise ArithmeticError("certified digits: the coefficients of a condition are too large for exact sums")
        assert g is not None
        cached = (mult, np.abs(np.array(coef, dtype=object).astype(float)), g)
        terms._digit_multipliers = cached
    return cached


def _orbit_divisors(terms: Any, exact: np.ndarray) -> np.ndarray | None:
    """``Σ|c|/n`` per condition (``n`` vertices; 2^62, which divides no coefficient,
    where it is not an integer, and for the superfluous trees' bin), the sums exact in
    int64 where every condition's sum is below 2^63 (``n`` times the largest ``|c|``: up
    to 20 vertices), else in float64 as two halves of 31 bits; None when a condition has
    so many terms that they might not be."""
    k1, n = len(terms) + 1, terms.vertices
    if len(terms) and int(terms.counts.max()) > n:
        return None
    cabs = np.abs(exact)
    if n * int(cabs.max(initial=0)) < _INT64_SUMS:
        # exact in int64, and numpy's unbuffered add.at costs the terms alone, where a
        # bincount per chunk costs every condition of the order (nine tenths of the time)
        whole = np.zeros(k1, dtype=np.int64)
        for t0 in range(0, terms.rows, _PLAN_CHUNK):
            cond, idx = terms.block(t0, min(terms.rows, t0 + _PLAN_CHUNK))
            np.add.at(whole, cond, cabs[idx])
        q, r = np.divmod(whole[:-1], n)
        return _divisors(q, r, k1)
    halves = [(cabs >> 31).astype(np.float64), (cabs & (2**31 - 1)).astype(np.float64)]
    sums = [np.zeros(k1) for _ in halves]
    for t0 in range(0, terms.rows, _PLAN_CHUNK):
        cond, idx = terms.block(t0, min(terms.rows, t0 + _PLAN_CHUNK))
        for total, half in zip(sums, halves):
            total += np.bincount(cond, weights=half[idx], minlength=k1)
    # Σ|c| divided by n; in halves (at most n terms per condition, halves below 2^31: both
    # sums below n·2^31, exact) Σ|c| = 2^31·S_hi + S_lo is divided in two steps, within int64
    q, r = np.divmod(sums[0][:-1].astype(np.int64), n)
    q2, r = np.divmod((r << 31) + sums[1][:-1].astype(np.int64), n)
    return _divisors((q << 31) + q2, r, k1)


def _divisors(q: np.ndarray, r: np.ndarray, k1: int) -> np.ndarray:
    """The divisors ``q = Σ|c|/n`` where the division left no remainder ``r`` (2^62
    elsewhere, and for the superfluous trees' bin)."""
    divisors = np.full(k1, 2**62, dtype=np.int64)
    divisors[:-1] = np.where((r == 0) & (q > 0), q, 2**62)
    return divisors


def _quotients(terms: Any, exact: np.ndarray, g: np.ndarray) -> np.ndarray | None:
    """``c/g_k`` per term as int8 (0 for the superfluous trees, whose bin is dropped), or
    None when some ``g_k`` does not divide a coefficient of condition ``k`` or a quotient
    exceeds int8."""
    k = len(terms)
    mult = np.zeros(terms.rows, dtype=np.int8)
    safe = np.where(g == 0, 2**62, g) if g.dtype != object else np.where(g == 0, 1, g)
    for t0 in range(0, terms.rows, _PLAN_CHUNK):
        t1 = min(terms.rows, t0 + _PLAN_CHUNK)
        cond, idx = terms.block(t0, t1)
        m, rest = np.divmod(exact[idx], safe[cond])
        if len(cond) and cond.max() >= k:  # the superfluous trees' terms: not divided, multiplier 0
            real = cond < k
            rest *= real
            m *= real
        if np.any(rest) or len(m) and max(-int(m.min()), int(m.max())) > 127:
            return None
        mult[t0:t1] = m
    return mult


def _largest_weight(terms: Any, mult: np.ndarray) -> float:
    """The largest ``Σ|m|`` over the terms of a condition."""
    weight = np.zeros(len(terms) + 1)
    for t0 in range(0, terms.rows, _PLAN_CHUNK):
        cond = terms.conditions(t0, min(terms.rows, t0 + _PLAN_CHUNK))
        weight += np.bincount(cond, weights=np.abs(mult[t0:t0 + len(cond)].astype(np.float64)), minlength=len(weight))
    return float(weight.max(initial=0))


#: terms per chunk when the multipliers of an order are computed: the chunk's temporaries
#: (a dozen arrays of its length) stay below a few MB — chunks of 2^18 terms cost a check
#: of decimal RK4 at order 16 a sixth of its page faults and 15 MB of its peak memory
_PLAN_CHUNK = 1 << 16
#: int64 sums of nonnegative terms stay exact below this
_INT64_SUMS = 2**63


def digits_to_ints(digits: np.ndarray, beta: int) -> np.ndarray:
    """The integers ``Σ_j d_j 2^(β·j)`` of int64 digits ``(n, K)`` (any K, each digit
    below 2^(62−β) in magnitude), as Python ints (an object array)."""
    d = digits.astype(np.int64)
    if d.shape[1] % 2:
        d = np.concatenate([d, np.zeros((d.shape[0], 1), dtype=np.int64)], axis=1)
    # pairs of digits first, in int64: |d_0 + d_1·2^β| < 2^(62−β)·(1 + 2^β) < 2^63
    pairs = d[:, 0::2] + (d[:, 1::2] << beta)
    out = pairs[:, -1].astype(object)
    for q in range(pairs.shape[1] - 2, -1, -1):
        out = (out << (2 * beta)) + pairs[:, q].astype(object)
    return out


#: the relative error of :meth:`DigitBallSums._magnitudes` is below γ_(L+1) (L ≤ 40
#: digits): 2^−45 leaves room for the rounding of the comparisons themselves
_REL = 2.0**-45


class DigitBallSums(BallSums):
    """:class:`~rkcheck.evaluation.balls.BallSums` of the digit balls:
    ``mid_k = g_k·N_k`` with ``N_k = Σ_j d_jk 2^(β·j)`` (``digits``: ``(L, k)`` int64,
    carried: each digit but the last in [0, 2^β)) and ``g_k`` the condition's divisor.

    ``|mid|`` is estimated in float64 (:meth:`_magnitudes`, relative error below 2^−45);
    :meth:`excludes_zero` decides from it where the margin allows and exactly elsewhere,
    and :meth:`magnitude_bound` is the one of ``BallSums`` — the same float, computed
    exactly from ``|mid|`` — wherever ``|mid| < 2^59`` or the ball contains 0 (where the
    bound gives a verdict's digits), and the estimate rounded up elsewhere."""

    def __init__(self, digits: np.ndarray, divisors: np.ndarray, rads: np.ndarray, bits: int, beta: int,
                 factorial: int):
        self.digits, self.divisors, self.beta = digits, divisors, beta
        self.rads, self.bits, self.shift, self.factorial = rads, bits, 0, factorial
        self._mids: np.ndarray | None = None
        self._mags: np.ndarray | None = None
        self._excludes: np.ndarray | None = None

    def __len__(self) -> int:
        return int(self.digits.shape[1])

    @property
    def mids(self) -> np.ndarray:  # type: ignore[override]
        """The mid-points as Python integers (built on first use)."""
        if self._mids is None:
            self._mids = self._integers(np.arange(len(self)))
        return self._mids

    def _integers(self, cols: np.ndarray) -> np.ndarray:
        ints = digits_to_ints(np.ascontiguousarray(np.take(self.digits, cols, axis=1).T), self.beta)
        result: np.ndarray = ints * self.divisors[cols].astype(object)
        return result

    def enclosure(self, k: int) -> Enclosure:
        if self._mids is not None:
            return super().enclosure(k)
        m = sum(int(d) << (self.beta * j) for j, d in enumerate(self.digits[:, k].tolist())) * int(self.divisors[k])
        f = self.factorial
        return Enclosure(Fraction(m, f << self.bits), Fraction(float(self.rads[k])) / (f << self.shift), False)

    def _magnitudes(self) -> np.ndarray:
        """Floats within a relative 2^−45 of ``|mid|``: the digits of ``|N|`` (those of
        −N carried again where N < 0: all nonnegative), summed from the top in float64
        (each step ``f·2^β + d`` rounds once, every term nonnegative: γ_(L−1)), times
        ``g`` (rounded once, and the product once: γ_(L+1) in all)."""
        if self._mags is None:
            # −N where N < 0, as a product by each column's sign (indexing the negative columns
            # goes entry by entry)
            d = self.digits * np.where(self.digits[-1] < 0, -1, 1)
            mask = (1 << self.beta) - 1
            c = np.zeros(d.shape[1], dtype=np.int64)
            for j in range(len(d) - 1):  # floor carries: every digit but the last in [0, 2^β)
                v = d[j]
                v += c
                c = v >> self.beta
                v &= mask
            d[-1] += c
            f = d[-1].astype(np.float64)
            for j in range(len(d) - 2, -1, -1):
                f *= 2.0**self.beta
                f += d[j]
            self._mags = f * self.divisors.astype(np.float64)
        return self._mags

    def _limit(self) -> np.ndarray:
        return self.rads * 2.0 ** (self.bits - self.shift)  # rad in units of 2^−P (inf: no claim)

    def excludes_zero(self) -> np.ndarray:
        """|mid| > rad, exactly: from the estimate where it is more than 2^−45 away from
        the radius (the products by 1 ± 2^−45 round once more, covered), by Python
        integers elsewhere."""
        if self._excludes is None:
            mags, limit = self._magnitudes(), self._limit()
            out = mags * (1 - _REL) > limit
            unsure = np.flatnonzero(~out & (mags * (1 + _REL) > limit))
            if len(unsure):
                out[unsure] = np.abs(self._integers(unsure)) > limit[unsure]
            self._excludes = out
        return self._excludes.copy()

    def exceeds(self, t: np.ndarray) -> np.ndarray:
        """:meth:`BallSums.exceeds`, ``|mid| > t·2^P`` exactly: from the estimate where it
        is more than 2^−45 away from ``t·2^P`` (as :meth:`excludes_zero`), by Python
        integers elsewhere — building every mid-point costs a check of decimal RK4 a tenth
        of its time.  ``t·2^P`` is exact as a float (P ≥ 0), or infinite past float64's
        range, where ``t·2^P`` exceeds every finite ``|mid|·(1 + 2^−45)``."""
        ok = np.isfinite(t)
        with np.errstate(over="ignore"):
            limit = np.ldexp(np.where(ok, t, 0.0), self.bits)
        mags = self._magnitudes()
        out = ok & (mags * (1 - _REL) > limit)
        unsure = np.flatnonzero(ok & ~out & ~(mags * (1 + _REL) < limit))
        if len(unsure):
            out[unsure] = exceeds_scaled(np.abs(self._integers(unsure)), t[unsure], self.bits)
        result: np.ndarray = out
        return result

    def magnitude_bound(self) -> np.ndarray:
        """:meth:`BallSums.magnitude_bound`'s bound: ``((|m| >> e) + 1)·2^(e−P)`` with
        ``e = max(bitlen(|m|) − 60, 0)``, exactly, where ``|m| < 2^59`` (``e = 0``:
        ``|m|`` in int64) or the ball contains 0 (Python integers: few); elsewhere — the
        ball excludes 0, the verdict has no digits — ``|m|·(1 + 2^−45)`` rounded up."""
        if not len(self):
            return np.zeros(0)
        mags = self._magnitudes()
        mid_up = mags * (1 + _REL)  # >= |m| (the product's rounding covered)
        small = np.flatnonzero(mid_up < 2.0**59)  # |m| < 2^59 certainly
        if len(small) and self.divisors.dtype != object:
            exact = self._small_integers(small)
            mid_up[small] = (exact + 1).astype(np.float64)  # the rounding of the Python ints' float()
        elif len(small):
            mid_up[small] = self._top_bits(self._integers(small))
        wide = np.setdiff1d(np.flatnonzero(~self.excludes_zero()), small, assume_unique=True)
        if len(wide):
            mid_up[wide] = self._top_bits(self._integers(wide))
        with np.errstate(over="ignore"):  # past float64: an infinite bound is still a bound
            mid_up = np.ldexp(mid_up, -self.bits)  # the exponents e − P (e applied in _top_bits)
            bound: np.ndarray = (mid_up + np.ldexp(np.asarray(self.rads, dtype=float), -self.shift)) \
                / float(self.factorial) * (1 + 2.0**-50) + _ETA
        return bound

    def _small_integers(self, cols: np.ndarray) -> np.ndarray:
        """``|m|`` of the given conditions, known to be below 2^59, in int64: Horner's
        partial values from the top digit are ``⌊N/2^(β·j)⌋``, no larger than |N|, and
        ``g·|N| = |m|``: nothing overflows."""
        d = np.take(self.digits, cols, axis=1)
        n = d[-1].copy()
        for j in range(len(d) - 2, -1, -1):
            n <<= self.beta
            n += d[j]
        result: np.ndarray = np.abs(n) * self.divisors[cols]
        return result

    def _top_bits(self, ints: np.ndarray) -> np.ndarray:
        """``((|m| >> e) + 1)·2^e`` as floats (e = max(bitlen − 60, 0)), as
        :meth:`BallSums.magnitude_bound` rounds them."""
        m = np.abs(ints)
        e = np.maximum(_bit_length(m).astype(np.int64) - 60, 0)
        top = ((m >> e.astype(object)) + 1).astype(float)
        with np.errstate(over="ignore"):
            result: np.ndarray = np.ldexp(top, e)
            return result


_bit_length = np.frompyfunc(int.bit_length, 1, 1)
_ETA = 2.0**-1074
