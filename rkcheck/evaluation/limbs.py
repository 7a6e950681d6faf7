"""Certified balls whose mid-points are multi-digit fixed-point numbers in integer arrays
(definitions §5): the faster form of :class:`~rkcheck.evaluation.balls.BallContext` for
working precisions up to a few hundred bits (:func:`~rkcheck.evaluation.backends.certified_context`
chooses).

A value is a ball ``m·2^−P ± r`` as in :class:`~rkcheck.evaluation.balls.BallContext`,
but the mid-point ``m = Σ_j d_j·2^(β·j)`` is held as ``L = F + 1`` *digits* ``d_j`` of
``β ≤ 30`` bits in the last axis of an int32 array (``P = F·β ≥`` the working bits; digit
``F`` is the integer part, signed; the others lie in ``[0, 2^β)``).  ``β`` is the widest
such that ``s·L`` digit products sum below ``2^62``: every digit convolution (an
elementwise product) and every digit matrix product (``x Aᵀ``, ``x b``) is exact in
int64, vectorised over the values of a block, then carried exactly.  A product keeps the
positions from ``F − 1`` up: the dropped ones (nonnegative) and the floored carry put its
mid-point within ``e_mul`` units ``2^−P`` below the exact product of the mid-points
(about ``F`` units, bounded in ``__init__``), a matrix product row within ``e_dot``.  The
radius is that of :class:`~rkcheck.evaluation.balls.BallContext` (``|x₁|r₂ + |x₂|r₁ +
r₁r₂``, floats inflated by Higham's γ) plus ``e`` units: every ball still contains every
exact value.

Only for data whose values stay small: the integer digit holds ``|x| < 2^(β−4)``.  With
``α`` the largest row sum of ``|A|`` and ``β_b = Σ|b_j|``, every weight (Φ, ψ, a, w) of a
tree with ``n`` vertices is at most ``M^n``, ``M = max(1, α)·max(1, β_b)`` (induction on
``Φ(u∘v) = Φ(u)⊙AΦ(v)``, ``w(u∘v) = w(u)·bᵀΦ(v)``): :meth:`LimbBallContext.create` builds
the context only when ``M^vertices`` fits, and every product checks its magnitude bounds
anyway.  The condition sums ``Σ c·w`` are exact: each weight's digits times the small
integer ``c/g_k`` (``g_k`` a divisor of the coefficients of condition k), summed per
condition and digit in float64 and carried once per order
(:mod:`rkcheck.evaluation.digit_sums`, which also judges them).

Measured (dense 4-stage tableau, 50 digits, β = 28, L = 9, A/B in one session): about
30 % less time than the Python-integer balls at orders 14, 16 and 18, and 26–30 % less
peak memory (digits stored as int32: 36 bytes a mid-point against about 64).  The digit
convolution costs about as much as a 200-bit Python product; the gain is in the matrix
products (16 products and 4 shifts of Python integers per row) and the smaller gathers.
float64 digits with BLAS products were slower (two carry passes per product, BLAS
threads on small matrices).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from rkcheck.evaluation.balls import _UP1, _UP4, _ball_at, summed_radii, take_rows
from rkcheck.evaluation.digit_sums import (
    DigitBallSums,
    DigitSums,
    digits_to_ints,
    multipliers,
)
from rkcheck.evaluation.limb_store import STORE, LimbStore, copy_digits
from rkcheck.evaluation.support import may_be_nonzero, reach_pattern
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.intervals import Interval

#: int64 sums of digit products stay below this (exact, no overflow)
_EXACT = 2.0**62
#: rows per block of the digit arithmetic (its temporaries stay in the cache)
_BLOCK = 8192


def _layout(bits: int, s: int) -> tuple[int, int] | None:
    """(β, F): the widest digits such that ``s·L`` digit products sum exactly in int64."""
    for beta in range(30, 15, -1):
        frac = -(-bits // beta)
        limbs = frac + 1
        if max(s, 1) * limbs * 2.0 ** (2 * beta) <= _EXACT:
            return beta, frac
    return None


class LimbBallContext:
    """Certified balls with int64 digit mid-points (module docstring).  A value is
    (digits ``(..., L)``, radii, magnitude bounds ``≥ |m·2^−P|``, codes): a code says
    what is known of the mid-point — :data:`_ZERO` (a product with a zero factor, a
    matrix product whose nonzero entries meet only zeros), :data:`_ONE` (exactly 1: the
    weights of τ, and their products), else :data:`_ANY` — so that the digit arithmetic
    of those rows is skipped: most weights of an explicit tableau's tall trees are zero,
    and about a third of the products of any tableau have the factor τ."""

    exact = False

    @classmethod
    def create(cls, A: Sequence[Sequence[Interval]], b: Sequence[Interval], bits: int,
               vertices: int) -> LimbBallContext | None:
        """The context, or None when the digits cannot hold the weights of trees with up
        to ``vertices`` vertices (module docstring) or ``bits`` is out of its range."""
        s = len(b)
        layout = _layout(bits, s)
        if layout is None or bits > 1000:
            return None

        def up(x: Interval) -> float:
            return float(max(abs(x.lo), abs(x.hi))) * (1 + 2.0**-50)

        alpha = max((sum(up(x) for x in row) for row in A), default=0.0) * (1 + s * 2.0**-52)
        beta_b = sum(up(x) for x in b) * (1 + s * 2.0**-52)
        M = max(1.0, alpha) * max(1.0, beta_b)
        log2_bound = vertices * math.log2(M) + 1  # + 1: the rounding of the mid-points
        if log2_bound >= layout[0] - 4:
            return None
        return cls(A, b, bits, layout)

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval], bits: int,
                 layout: tuple[int, int]):
        self.s = s = len(b)
        self.digit_bits, self.F = beta, F = layout
        self.L = L = F + 1
        self.mask = (1 << beta) - 1
        self.bits = F * beta  # P >= the requested bits
        self.K0 = F - 1  # the lowest digit position a product computes
        self.K = 2 * L - 1 - self.K0  # positions K0 … 2L − 2
        self.unit = 2.0**-self.bits
        self.limit = 2.0 ** (beta - 4)  # magnitudes above this would not fit the integer digit
        # the dropped positions p < K0 hold at most min(p+1, L) products of digits below
        # 2^β (all nonnegative: the signed top digit is not among them), worth 2^(β(p−F))
        # units 2^−P; the carry out of position F − 1 is floored (< 1 unit)
        drop = math.fsum(min(p + 1, L) * 2.0 ** (2 * beta + beta * (p - F)) for p in range(self.K0))
        self.e_mul = (1.0 + drop) * (1 + 2.0**-40)
        self.e_dot = (1.0 + s * drop) * (1 + 2.0**-40)
        balls_A = [[_ball_at(x, self.bits, 0) for x in row] for row in A]
        balls_b = [_ball_at(x, self.bits, 0) for x in b]
        self.Ad = np.array([[self._digits(m) for m, _, _ in row] for row in balls_A], dtype=np.int64)  # (s, s, L)
        self.bd = np.array([[self._digits(m) for m, _, _ in balls_b]], dtype=np.int64)  # (1, s, L)
        # the entries that are not zero (mid-point): (x Mᵀ)_i may be nonzero only where some
        # x_j that may be is met by one of them
        self.A_nz, self.b_nz = reach_pattern(self.Ad.any(axis=2)), reach_pattern(self.bd.any(axis=2))
        self._A_plan, self._b_plan = _product_plan(self.Ad), _product_plan(self.bd)
        self.Ar_t = np.ascontiguousarray(np.array([[r for _, r, _ in row] for row in balls_A]).T)
        self.Ag_t = np.ascontiguousarray(np.array([[g for _, _, g in row] for row in balls_A]).T)
        self.br = np.array([r for _, r, _ in balls_b])
        self.bg = np.array([g for _, _, g in balls_b])
        self._dot_up = 1.0 + (2 * s + 8) * 2.0**-52

    def _digits(self, m: int) -> list[int]:
        """The digits of ``m`` (floor digits, the last one signed)."""
        beta = self.digit_bits
        return [(m >> (beta * j)) & self.mask for j in range(self.L - 1)] + [m >> (beta * (self.L - 1))]

    def to_ints(self, digits: np.ndarray) -> np.ndarray:
        """The integers ``Σ_j d_j 2^(β·j)`` of int64 digits ``(n, K)`` (any K, each digit
        below 2^(62−β) in magnitude), as Python ints."""
        return digits_to_ints(digits, self.digit_bits)

    # ------------------------------------------------------------- digits

    def _carry(self, z: np.ndarray) -> np.ndarray:
        """Positions ``K0 …`` of exact digit sums (axis 0 of ``z``, values on the last
        axis) to the digits of positions ``F …`` (in place): the carry out of position
        ``F − 1`` floored, every digit but the last in [0, 2^β), the last signed."""
        beta, mask = self.digit_bits, self.mask
        c = z[0] >> beta  # arithmetic shift: the floor
        for p in range(1, z.shape[0] - 1):
            v = z[p]
            v += c
            c = v >> beta
            v &= mask
        z[-1] += c
        return z[1:]

    def _check(self, g: np.ndarray) -> None:
        if g.size and not g.max() < self.limit:  # also NaN
            raise ArithmeticError("certified digits: a weight outgrew the integer digit (this is a bug: "
                                  "LimbBallContext.create bounds every weight)")

    # ------------------------------------------------------------- kernel

    def vectors(self, n: int, s: int) -> LimbStore:
        return LimbStore((n, s), self.L)

    def scalars(self, n: int) -> LimbStore:
        return LimbStore((n,), self.L)

    def ones(self, k: int, s: int) -> Any:
        mid = np.zeros((k, s, self.L), dtype=STORE)
        mid[..., self.F] = 1
        return (mid, np.zeros((k, s)), np.ones((k, s)), np.full((k, s), _ONE, dtype=np.uint8))

    def one(self, k: int) -> Any:
        mid = np.zeros((k, self.L), dtype=STORE)
        mid[:, self.F] = 1
        return (mid, np.zeros(k), np.ones(k), np.full(k, _ONE, dtype=np.uint8))

    def take(self, x: Any, idx: np.ndarray) -> Any:
        """The rows ``idx`` of a value or a store.  A store keeps the digits of the rows
        whose code is not :data:`_ZERO` only, and places the others at its row 0, which is
        zeros: one gather reads them all (zeros and a scatter of the others' digits cost
        up to three times as much, at every share of zeros)."""
        if not isinstance(x, LimbStore):
            return tuple(take_rows(part, idx) for part in x)
        digits = np.take(x.digits, x.places(idx), axis=0)
        return digits, np.take(x.rad, idx, axis=0), np.take(x.g, idx, axis=0), np.take(x.codes, idx, axis=0)

    def put(self, store: LimbStore, lo: int, x: Any) -> None:
        """Store the rows of ``x`` from row ``lo`` on: the digits of those whose code
        is not :data:`_ZERO` at the store's next free places."""
        n = len(x[1])
        codes = self._codes(x)
        store.rad[lo:lo + n] = x[1]
        store.g[lo:lo + n] = x[2]
        store.codes[lo:lo + n] = codes
        rows = self._nonzero_rows(x, 1.0 if _COMPACT else -1.0)
        if rows is not None and len(rows) == n:
            rows = None
        k = n if rows is None else len(rows)
        if store.count + k > len(store.digits):
            raise AssertionError("certified digits: a store was written twice")
        if rows is None:
            copy_digits(store.digits[store.count:store.count + n], x[0])
            if store.place is not None or lo != store.count - 1:  # not the rows in order
                store.placed()[lo:lo + n] = np.arange(store.count, store.count + n)
        else:
            place = store.placed()
            place[lo:lo + n] = 0  # row 0 of the digits: zeros
            if k:
                copy_digits(store.digits[store.count:store.count + k], take_rows(x[0], rows))
                place[lo + rows] = np.arange(store.count, store.count + k)
        store.count += k

    def _nonzero_rows(self, x: Any, share: float) -> np.ndarray | None:
        """The rows of ``x`` with a code that is not :data:`_ZERO` (some stage's, for
        vectors), or None when they are more than ``share`` of all."""
        codes = self._codes(x)
        return _sparse_rows(codes != _ZERO if codes.ndim == 1 else _any_in_row(codes), share)

    def _codes(self, x: Any) -> np.ndarray:
        """The value's codes, or, for a bare (mid-point, radius, magnitude) triple,
        :data:`_ZERO` or :data:`_ANY` as its digits are."""
        if len(x) > 3:
            result: np.ndarray = x[3]
            return result
        return _any_in_row(x[0].reshape(-1, self.L)).reshape(x[1].shape).astype(np.uint8)

    def _may_be_nonzero(self, x: Any) -> np.ndarray:
        result: np.ndarray = self._codes(x) != _ZERO
        return result

    def mul(self, x: Any, y: Any) -> Any:
        xm, xr, xg = x[:3]
        ym, yr, yg = y[:3]
        cx, cy = self._codes(x), self._codes(y)
        code = np.minimum(cx, cy)  # zero if either is, one if both are, else any
        cx, cy = cx.reshape(-1), cy.reshape(-1)
        rows = _sparse_rows((cx == _ANY) & (cy == _ANY))
        if rows is None:
            out = self._mul_digits(xm.reshape(-1, self.L), ym.reshape(-1, self.L))
        else:
            # a zero mid-point times anything is zero, exactly, and 1 times y is y: the
            # digits of 1 are those of 2^P, so the digit products are y's digits in the
            # kept positions (none dropped, no carry) — the same digits, bit for bit
            out = np.zeros((self.L, len(cx)), dtype=STORE)  # mostly zeros: the smaller type
            if len(rows):
                out[:, rows] = self._mul_digits(_flat_rows(xm, rows), _flat_rows(ym, rows))
            for rows, other in ((np.flatnonzero((cx == _ONE) & (cy != _ZERO)), ym),
                                (np.flatnonzero((cy == _ONE) & (cx == _ANY)), xm)):
                if len(rows):
                    out[:, rows] = _flat_rows(other, rows).T
        rad, g = self._mul_bounds(xr, xg, yr, yg)
        return out.T.reshape(xm.shape), rad, g, code

    def _mul_bounds(self, xr: np.ndarray, xg: np.ndarray, yr: np.ndarray,
                    yg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The radius ``(|x|r_y + |y|r_x + r_x·r_y)·(1 + 12·2^−52) + e`` and the magnitude
        ``|x||y|·(1 + 12·2^−52) + e`` of products (``e = e_mul`` units), in place in two
        arrays: the same operations in the same order as the expressions, without their
        temporaries."""
        err = self.e_mul * self.unit
        if not (xr.shape == xg.shape == yr.shape == yg.shape):
            rad, g = (xg * yr + yg * xr + xr * yr) * _UP4 + err, xg * yg * _UP4 + err
        else:
            rad, g = np.multiply(xg, yr), np.multiply(yg, xr)
            rad += g
            np.multiply(xr, yr, out=g)
            rad += g
            rad *= _UP4
            rad += err
            np.multiply(xg, yg, out=g)
            g *= _UP4
            g += err
        self._check(g)
        return rad, g

    def _mul_digits(self, xf: np.ndarray, yf: np.ndarray) -> np.ndarray:
        """The digits of the products of the mid-points ``xf``, ``yf`` (rows of L digits),
        digit-major: ``(L, n)`` int64 (what the next operation reads: no transposition
        back; a value's digits are a transposed view of it)."""
        L, K0 = self.L, self.K0
        out = np.empty((L, len(xf)), dtype=np.int64)
        for a0 in range(0, len(xf), _BLOCK):
            # digits first within the block: every numpy call runs over contiguous rows
            xb = np.ascontiguousarray(xf[a0:a0 + _BLOCK].T, dtype=np.int64)
            yb = np.ascontiguousarray(yf[a0:a0 + _BLOCK].T, dtype=np.int64)
            z = np.zeros((self.K, xb.shape[1]), dtype=np.int64)
            for i in range(L):
                jlo = max(0, K0 - i)
                z[i + jlo - K0:i + L - K0] += xb[i] * yb[jlo:]
            out[:, a0:a0 + _BLOCK] = self._carry(z)
        return out

    def _product(self, xm: np.ndarray, row_nz: np.ndarray, Md: np.ndarray, plan: list[_Pass]) -> np.ndarray:
        """Digits of ``x Mᵀ`` for the digit matrix ``Md`` (outputs, s, L) of A or b: digit
        ``l`` of ``x_j`` times digit ``q`` of column ``j`` lands at position ``l + q``
        (positions from ``K0`` on), one pass per nonzero digit ``q`` of a column
        (:func:`_product_plan`: the zeros of a sparse tableau, and of entries such as 1/2
        with one nonzero digit, cost nothing).  Integer sums: exact in any order.  The rows
        where ``row_nz`` is False are zero (every nonzero entry meets a zero ``x_j``)."""
        rows = _sparse_rows(row_nz)
        if rows is None:
            return self._product_digits(xm, Md, plan).transpose(2, 1, 0)
        # rows of zero mid-points give zero, exactly: only the others are multiplied
        out = np.zeros((self.L, Md.shape[0], len(xm)), dtype=STORE)  # mostly zeros: the smaller type
        if len(rows):
            out[:, :, rows] = self._product_digits(take_rows(xm, rows), Md, plan)
        return out.transpose(2, 1, 0)

    def _product_digits(self, xm: np.ndarray, Md: np.ndarray, plan: list[_Pass]) -> np.ndarray:
        """The digits of ``x Mᵀ``, digit-major: ``(L, outputs, n)`` int64."""
        n, L, K0 = xm.shape[0], self.L, self.K0
        outputs = Md.shape[0]
        out = np.empty((L, outputs, n), dtype=np.int64)
        for a0 in range(0, n, _BLOCK):
            xb = np.ascontiguousarray(xm[a0:a0 + _BLOCK].transpose(1, 2, 0), dtype=np.int64)  # (s, L, m)
            z = np.zeros((self.K, outputs, xb.shape[2]), dtype=np.int64)
            for j, q, rows, coef in plan:
                lo = max(0, K0 - q)  # the digits l of x_j with l + q >= K0
                if rows is None:
                    z[q + lo - K0:q + L - K0] += coef[None, :, None] * xb[j, lo:L][:, None, :]
                else:
                    for i, c in zip(rows, coef):
                        z[q + lo - K0:q + L - K0, i] += c * xb[j, lo:L]
            out[:, :, a0:a0 + _BLOCK] = self._carry(z)
        return out

    def _rad(self, x: Any, Mr: np.ndarray, Mg: np.ndarray) -> Any:
        _, xr, xg = x[:3]
        err = self.e_dot * self.unit
        # products of s terms (numpy's matmul: any order of summation, with or without
        # fused multiply-adds, is within γ_s of the exact sums, which _dot_up covers)
        rad = (xg @ Mr + xr @ Mg + xr @ Mr) * self._dot_up + err
        g = (xg @ Mg) * self._dot_up + err
        self._check(g)
        return rad, g

    def matvec(self, x: Any) -> Any:
        rad, g = self._rad(x, self.Ar_t, self.Ag_t)
        nz = may_be_nonzero(self._may_be_nonzero(x), self.A_nz)
        return self._product(x[0], _any_in_row(nz), self.Ad, self._A_plan), rad, g, nz.astype(np.uint8)

    def dot(self, x: Any) -> Any:
        rad, g = self._rad(x, self.br, self.bg)
        nz = may_be_nonzero(self._may_be_nonzero(x), self.b_nz)[:, 0]
        return self._product(x[0], nz, self.bd, self._b_plan)[:, 0, :], rad, g, nz.astype(np.uint8)

    def enclosures(self, x: Any) -> list[Enclosure]:
        """Scalars of this context as enclosures (exact rational end points)."""
        one = 1 << self.bits
        return [Enclosure(Fraction(int(m), one), Fraction(r), False)
                for m, r in zip(self.to_ints(x[0]).tolist(), x[1].tolist())]

    # ------------------------------------------------------------- condition sums

    def sums(self, k: int, n: int) -> DigitSums:
        return DigitSums(self.L, k)

    def add_terms(self, acc: DigitSums, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        """Σ c·w with c = ±(n−1)!/σ exact, as ``g_k · Σ m·w``: the coefficients of a
        condition k share a divisor ``g_k`` (:func:`~rkcheck.evaluation.digit_sums.multipliers`),
        so each term's digits are multiplied by a small integer ``m = c/g_k`` and summed
        per condition and digit in float64, uncarried — exact (``multipliers`` checks the
        bound).  Radii ``|c|·r`` as in :class:`~rkcheck.evaluation.balls.BallContext`."""
        order = getattr(terms, "all_terms", terms)  # some rows of an order: its own terms
        mult, cabs, _ = multipliers(order, self.digit_bits)
        acc.terms = order
        cond, idx = terms.block(i0, i1)
        self._bin(acc, w_terms, mult[terms.positions(i0, i1)] if order is not terms else mult[i0:i1], cabs[idx], cond)

    def _bin(self, acc: DigitSums, w_terms: Any, mult: np.ndarray, cabs: np.ndarray, cond: np.ndarray) -> None:
        """The terms ``w_terms`` with the multipliers ``mult`` and coefficients ``|c|`` =
        ``cabs`` into the bins ``cond`` of ``acc``."""
        wm = w_terms[0]
        # a term whose mid-point is zero adds zero to every digit sum: only the others count
        rows = _sparse_rows(self._may_be_nonzero(w_terms))
        if rows is None:
            acc.add_digits(wm.T, mult, cond)
        elif len(rows):
            acc.add_digits(take_rows(wm, rows).T, mult[rows], cond[rows])
        # |c| rounded to float (relative 2^−53) times r rounded once more: _UP1 covers both
        rad = acc.radius_room(cond)
        np.multiply(w_terms[1], cabs, out=rad)
        rad *= _UP1

    def finish_sums(self, acc: DigitSums, k: int, n: int) -> DigitBallSums:
        """R = Σ/(n−1)!: the exact mid-point sums (each condition's digit sums carried;
        times its divisor) over (n−1)!·2^P, the radius bounds rounded up (the float
        additions into each bin, at most a few hundred, covered by γ_256)."""
        divisors = np.ones(k, dtype=np.int64) if acc.terms is None else multipliers(acc.terms, self.digit_bits)[2][:k]
        return self._finish(acc, divisors, n)

    def _finish(self, acc: DigitSums, divisors: np.ndarray, n: int) -> DigitBallSums:
        """The ball sums of ``acc``'s conditions, whose divisors are ``divisors``."""
        k = len(divisors)
        digits, radii = acc.totals()
        rads = summed_radii(radii, k, self.bits)
        carried = np.empty((self.L, k), dtype=np.int64)
        for c0 in range(0, k, _BLOCK):  # by blocks of conditions: small temporaries
            c1 = min(k, c0 + _BLOCK)
            d = np.zeros((self.L + 1, c1 - c0), dtype=np.int64)  # position 0: nothing to floor below
            d[1:] = digits[:, c0:c1]  # exact: each sum is an integer below 2^53
            carried[:, c0:c1] = self._carry(d)
        return DigitBallSums(carried, divisors, rads, self.bits, self.digit_bits, math.factorial(n - 1))

    def selected_sums(self, part: Any) -> DigitSums:
        """Bins for the selected conditions of ``part`` (a
        :class:`~rkcheck.evaluation.subset.Subset`'s order): the sums of
        :meth:`add_terms`, the terms' conditions renumbered among the selected."""
        return DigitSums(self.L, part.conditions)

    def add_selected(self, acc: DigitSums, w_terms: Any, part: Any, t0: int, t1: int) -> None:
        """The selected terms ``t0 … t1−1`` of ``part`` into their bins, as :meth:`add_terms`."""
        own = part.own_terms
        mult, cabs, _ = multipliers(own, self.digit_bits)
        self._bin(acc, w_terms, mult[t0:t1], cabs[part.coefficient[t0:t1]], own.conditions(t0, t1))

    def finish_selected(self, acc: DigitSums, part: Any) -> DigitBallSums:
        """The balls of the selected conditions."""
        divisors = multipliers(part.own_terms, self.digit_bits)[2][:part.conditions]
        return self._finish(acc, divisors, part.terms.vertices)


#: stores keep the digits of the rows with a nonzero code only (False: of every row)
_COMPACT = True


#: one pass of a matrix product: (column j, digit q, the outputs where it is nonzero or None: all, their digits)
_Pass = tuple[int, int, list[int] | None, np.ndarray]


def _product_plan(Md: np.ndarray) -> list[_Pass]:
    """The passes of :meth:`LimbBallContext._product` for the digit matrix ``Md``
    (outputs, s, L): ``(j, q, rows, coefficients)`` for every column ``j`` and digit
    ``q`` that is nonzero in some output — the outputs where it is nonzero one by one
    when they are at most half of them (``rows``), else all outputs at once (``rows``
    None, ``coefficients`` the whole digit column)."""
    plan: list[_Pass] = []
    outputs, s, L = Md.shape
    for j in range(s):
        for q in range(L):
            col = Md[:, j, q]
            rows = np.flatnonzero(col)
            if not len(rows):
                continue
            if 2 * len(rows) <= outputs:
                plan.append((j, q, rows.tolist(), col[rows].copy()))
            else:
                plan.append((j, q, None, col.copy()))
    return plan


#: the codes of a value's mid-points: zero, exactly one, anything (:class:`LimbBallContext`)
_ZERO, _ANY, _ONE = 0, 1, 2

#: the share of rows with nonzero mid-points below which only those rows are multiplied
#: (gathering them and scattering the products back costs less than the digits of the rest)
_SPARSE = 0.75


def _flat_rows(x: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``x.reshape(-1, L)[rows]`` for the digits ``(n, L)`` or ``(n, s, L)`` of a value,
    reading only those rows: the digits of a matrix product's vectors are digit-major
    with the stages before the trees, which no reshape can view without copying every
    row (2 % of RK4's ball check at order 18)."""
    if x.ndim == 2:
        return take_rows(x, rows)
    n, s, L = x.shape
    if x.flags.c_contiguous:
        return np.take(x.reshape(n * s, L), rows, axis=0)
    by_trees, by_stages = x.transpose(2, 0, 1), x.transpose(2, 1, 0)  # (L, n, s), (L, s, n)
    if by_trees.flags.c_contiguous:
        return np.take(by_trees.reshape(L, n * s), rows, axis=1).T
    if by_stages.flags.c_contiguous:  # row i·s + j is column j·n + i
        columns: np.ndarray = (rows % s) * n + rows // s
        return np.take(by_stages.reshape(L, s * n), columns, axis=1).T
    return np.take(x.reshape(n * s, L), rows, axis=0)


def _sparse_rows(nonzero: np.ndarray, share: float = _SPARSE) -> np.ndarray | None:
    """The rows where ``nonzero`` holds, or None when they are more than ``share`` of
    all: the work then runs over every row."""
    rows = np.flatnonzero(nonzero)
    return None if len(rows) > share * len(nonzero) else rows


def _any_in_row(x: np.ndarray) -> np.ndarray:
    """Whether each row of ``x`` (digits, or flags) has a nonzero entry: the columns
    or-ed together (numpy's ``any(axis=1)`` over a few entries per row took four times
    as long)."""
    acc = x[:, 0].copy()
    for j in range(1, x.shape[1]):
        acc |= x[:, j]
    result: np.ndarray = acc != 0
    return result
