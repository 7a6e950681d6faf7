"""The a-priori float screen: float64 mid-points with one error bound per order, not per
value (definitions §5).

:class:`~rkcheck.evaluation.balls.FloatContext` carries a radius beside every mid-point
and bounds each operation's rounding as it goes: four matrix products per ``matvec``,
six operations per product.  This context carries, beside the mid-points ``x̂``, the
same weights evaluated on the entries' absolute values, ``x̄`` — two channels of plain
float arithmetic, one ``matmul`` or one product for both — and bounds every rounding at
once, by the standard analysis of a polynomial evaluated in floating point (Higham,
*Accuracy and Stability of Numerical Algorithms*, §3):

* every weight is a sum of monomials in the entries; each operation multiplies the
  monomials flowing through it by ``(1 + δ)`` with ``|δ| ≤ u = 2^−53`` (a sum of two
  floats whose result is subnormal is exact; a product that underflows errs by at most
  ``2^−1075 ≤ u·2^−1022``, which the absolute channel bounds relatively — below — so
  each operation is counted with ``2u``);
* along any monomial of a condition with ``n`` vertices in an ``s``-stage tableau at most
  ``d = (n − 1)(s + 1) + 2 + c`` operations round: ``Φ`` of a tree with ``m`` vertices
  at most ``(m − 1)(s + 1)`` (a product, and a matrix–vector product of ``s`` terms, per
  vertex), ``w`` as many, the coefficient ``c/(n−1)!`` and its product two, and the
  condition's sum of at most ``c`` terms ``c``;
* the entries themselves are floats within a relative ``ε = 2^−52`` of the tableau's
  (checked exactly; a zero entry must be exact), and each monomial has at most ``n``
  of them.

So the computed residual ``R̂`` and the computed absolute sum ``S̄`` of a condition bound
the true residual: ``|R̂ − R| ≤ κ_n·S̄`` with
``κ_n = ((1 + 2u)^d (1 + ε)^n − 1) / (1 − 2u)^d``.  The bound needs the absolute channel
free of underflow and overflow, which :meth:`ScreenContext.create` checks once from the
entries: every nonzero monomial lies between ``m^n/(n−1)!`` and ``M^n`` (``m`` the
smallest nonzero entry, ``M`` the largest absolute row sum of ``A`` and ``b``, both
capped at 1), so when those stay within ``2^±1000`` no absolute value is subnormal and
none overflows.  When a check fails the context is not made, and the certified balls
evaluate every condition, as before.

A value is a ``(2, rows[, s])`` array: channel 0 the mid-points, channel 1 the absolute
values.  The screen may say ``fails`` (``|R̂| > κ_n·S̄``, rounded against it); it never
says ``holds``: :func:`rkcheck.evaluation.screened.screened_sums` evaluates the conditions
it leaves open in the certified balls.  Before balls of P fixed-point bits its radii are
widened by a bound on theirs (:meth:`ScreenContext.floor`): a residual too small for
the balls to tell from 0 is left to them, so that the verdicts are the balls'.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Sequence

import numpy as np

from rkcheck.evaluation.balls import ETA, FloatSums, U, _float_coefficients
from rkcheck.numbers.intervals import Interval

#: the entries' floats are within this relative distance of the entries (checked)
EPSILON = 2.0**-52
#: the absolute channel stays within 2^±this (no subnormal, no overflow)
_RANGE = 1000


def _float_entry(x: Interval) -> float | None:
    """The float of an entry, or None when it is not within a relative ``EPSILON`` of
    every point of the entry's interval (a zero float only for an exact zero)."""
    mid = (x.lo + x.hi) / 2
    try:
        f = float(mid)
    except OverflowError:
        return None
    if not math.isfinite(f):
        return None
    g = Fraction(f)
    if max(abs(x.hi - g), abs(g - x.lo)) > abs(g) * Fraction(EPSILON):
        return None
    return f


class ScreenContext:
    """The float screen with a-priori bounds (module docstring), for conditions with up
    to ``vertices`` vertices."""

    exact = False

    @classmethod
    def create(cls, A: Sequence[Sequence[Interval]], b: Sequence[Interval], vertices: int,
               ball_bits: int | None = None) -> ScreenContext | None:
        """The screen for these entries, or None when an entry is not a float within
        ``EPSILON`` or the absolute channel could leave ``2^±1000`` (module docstring).
        ``ball_bits``: the fixed-point precision of the balls behind the screen, whose
        resolution widens its radii (:meth:`floor`)."""
        floats = [_float_entry(x) for row in [*A, b] for x in row]
        if any(x is None for x in floats) or not any(floats):
            return None
        s = len(b)
        flat = np.array(floats, dtype=float)
        Am, bm = flat[:s * s].reshape(s, s), flat[s * s:]
        smallest = min(1.0, float(np.abs(flat[flat != 0]).min()))
        largest = max(1.0, float(np.abs(Am).sum(axis=1).max(initial=0)), float(np.abs(bm).sum()))
        n = vertices
        low = n * math.log2(smallest) - math.lgamma(n) / math.log(2) - 1
        high = n * math.log2(largest) + 1
        if low < -_RANGE or high > _RANGE:
            return None
        return cls(Am, bm, largest, ball_bits)

    def __init__(self, A: np.ndarray, b: np.ndarray, growth: float = 1.0, ball_bits: int | None = None):
        self.s = len(b)
        self.growth = growth  # ≥ every absolute row sum of A and Σ|b|, and ≥ 1
        self.unit = 0.0 if ball_bits is None else 2.0**-ball_bits
        self.M_t = np.ascontiguousarray(np.stack([A.T, np.abs(A).T]))  # (2, s, s): x Aᵀ and |x| |A|ᵀ
        self.b2 = np.ascontiguousarray(np.stack([b, np.abs(b)])[:, :, None])  # (2, s, 1)
        self._abs_coef: dict[int, tuple[Any, np.ndarray]] = {}

    def kappa(self, n: int, count: int) -> float:
        """``κ_n`` for conditions of ``n`` vertices with at most ``count`` terms, rounded
        up generously (its own float evaluation errs far less than the factor 1 + 2^−20)."""
        d = self._roundings(n, count)
        grow = math.expm1(d * math.log1p(2 * U) + n * math.log1p(EPSILON))
        return grow / math.exp(d * math.log1p(-2 * U)) * (1 + 2.0**-20)

    def floor(self, n: int, count: int) -> float:
        """A bound, with a margin of 2^20, on the radius the fixed-point balls behind the
        screen give a condition of ``n`` vertices with at most ``count`` terms: a unit
        2^−P for each of its d roundings and terms, grown by the weights' magnitudes (at
        most ``growth^n``).  The screen's radii are widened by it, so that the screen
        decides a condition only where the balls would decide it too — a residual
        smaller than the balls' resolution is theirs to judge (they say "holds to D
        digits" where they cannot exclude 0)."""
        # growth^n ≤ 2^1000: create checked it
        return self.unit * self._roundings(n, count) * (count + 1) * self.growth ** n * 2.0**20

    def _roundings(self, n: int, count: int) -> int:
        """``d``: the roundings along any monomial of a condition of ``n`` vertices with
        at most ``count`` terms (module docstring)."""
        return (n - 1) * (self.s + 1) + 2 + count

    # ------------------------------------------------------------- kernel

    def vectors(self, n: int, s: int) -> Any:
        return np.zeros((2, n, s))

    def scalars(self, n: int) -> Any:
        return np.zeros((2, n))

    def ones(self, k: int, s: int) -> Any:
        return np.ones((2, k, s))

    def one(self, k: int) -> Any:
        return np.ones((2, k))

    def take(self, x: Any, idx: np.ndarray) -> Any:
        return np.take(x, idx, axis=1)

    def put(self, store: Any, lo: int, x: Any) -> None:
        store[:, lo:lo + x.shape[1]] = x

    def mul(self, x: Any, y: Any) -> Any:
        return x * y

    def matvec(self, x: Any) -> Any:
        return np.matmul(x, self.M_t)

    def dot(self, x: Any) -> Any:
        return np.matmul(x, self.b2)[..., 0]

    def sums(self, k: int, n: int) -> Any:
        return [np.zeros((2, k)), 1]  # the bins, the most terms of a condition

    def add_terms(self, acc: Any, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        """Add ``(c/(n−1)!)·ŵ`` and ``|c/(n−1)!|·w̄`` of the terms ``i0 … i1−1`` to their
        conditions' bins."""
        cond, idx = terms.block(i0, i1)
        coef, absolute = self._coefficients(terms, n)
        w_terms[0] *= coef[idx]
        w_terms[1] *= absolute[idx]
        bins = acc[0]
        np.add.at(bins[0], cond, w_terms[0])
        np.add.at(bins[1], cond, w_terms[1])
        acc[1] = max(acc[1], terms.max_terms)

    def finish_sums(self, acc: Any, k: int, n: int) -> FloatSums:
        """The residuals ``R̂ ± κ_n·S̄`` (the product rounded up), the radii widened by the
        balls' resolution (:meth:`floor`) when the screen stands before balls."""
        bins, count = acc
        rad = bins[1][:k] * (self.kappa(n, count) * (1 + 4 * U)) + ETA
        return FloatSums(bins[0][:k], rad + self.floor(n, count) if self.unit else rad)

    def _coefficients(self, terms: Any, n: int) -> tuple[np.ndarray, np.ndarray]:
        cached = self._abs_coef.get(n)
        if cached is None or cached[0] is not terms:
            coef = _float_coefficients(terms, n)
            cached = self._abs_coef[n] = (terms, np.abs(coef))
        return _float_coefficients(terms, n), cached[1]
