"""Certified balls: the number contexts for data that is not exact (definitions §5).

Two contexts behind the kernel of :mod:`rkcheck.evaluation.algorithm`:

:class:`BallContext` — arbitrary precision.  A value is a ball ``m·2^−P ± r``: the
    mid-point ``m`` is an exact integer at scale ``2^−P`` (numpy object arrays of Python
    ints, so loops run in C), the radius ``r`` a float64 upper bound kept in units of
    ``2^−S`` with ``S = max(0, P − 1000)``: the rounding unit ``2^−P`` is then a normal
    float (``2^−1000`` at most) and radii up to ``2^(2024−P)`` fit — absolute units would
    cap certified digits near 10^−320, units of ``2^−P`` overflow for rounded input
    beyond about 170 digits.  A radius that still overflows is refused with a message.
    A product is ``(m₁m₂) >> P`` (floored: less than one unit lost) with radius
    ``|x₁|r₂ + |x₂|r₁ + r₁r₂`` plus one unit; sums of mid-points are exact.  Every float
    operation rounds to nearest, so each computed radius is multiplied by
    ``1 + (2k+4)·2^−52`` for a k-term expression (Higham's γ_k) and magnitudes ``|x|`` by
    ``1 + 2^−51``: radii stay upper bounds.
:class:`FloatContext` — the float64 screen: mid-point and radius both float64, with the
    rounding of every product and sum bounded by ``γ_n = n·u/(1 − n·u)`` (``u = 2^−53``)
    and every radius inflated by ``1 + 16u`` plus the smallest subnormal.  It may say
    ``fails`` only when its own bound excludes 0.

Both give :class:`~rkcheck.numbers.enclosure.Enclosure` values per condition.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Sequence

import numpy as np

from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.intervals import Interval

_UP1 = 1.0 + 2.0**-51
_UP4 = 1.0 + 12 * 2.0**-52
U = 2.0**-53
ETA = 2.0**-1074  # smallest subnormal: covers underflow in the bounds
INFLATE = 1.0 + 16 * U


def _fraction_float_up(x: Fraction) -> float:
    """A float ≥ x >= 0 (correctly rounded, then one ulp up); inf (no claim) past
    float64's range."""
    try:
        f = float(x)
    except OverflowError:
        return math.inf
    return math.nextafter(f, math.inf) if Fraction(f) < x else f


def _float_or_inf(x: Fraction) -> float:
    """x as a float, ±inf past float64's range (the float screen then claims nothing)."""
    try:
        return float(x)
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def _ball_at(x: Interval, bits: int, shift: int) -> tuple[int, float, float]:
    """(mid-point at scale 2^−bits, radius in units of 2^−shift, magnitude bound) of a
    ball enclosing ``x``."""
    one = 1 << bits
    lo, hi = x.lo * one, x.hi * one
    m = math.floor((lo + hi) / 2)
    r = max(hi - m, m - lo) / one * (1 << shift)  # in units of 2^−shift
    return m, _fraction_float_up(r) * _UP1, _fraction_float_up(abs(Fraction(m, one))) * _UP1


#: Up to this many working bits the int64 digits are faster than Python integers, from
#: this many vertices on (below, numpy's cost per call dominates: at 11 to 13 vertices
#: the digits took 1.2–3× the time of Python integers, at 15 and 17 about 0.7×; measured
#: with benchmarks/bench_engine.py's tableau at 15, 50, 80 and 110 digits).
LIMB_MAX_BITS = 400
LIMB_MIN_VERTICES = 15


class BallContext:
    """Certified fixed-point balls at ``bits`` bits (see the module docstring).

    A value is a triple (mid-points: object array of ints at scale 2^−P, radii: floats in
    units of 2^−S, magnitudes: floats bounding |mid·2^−P| from above).  Carrying the
    magnitudes avoids converting big integers to floats in every product."""

    exact = False

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval], bits: int):
        self.s = len(b)
        self.bits = bits
        self.fixed_one = 1 << bits
        self.shift = max(0, bits - 1000)  # S: radii are floats in units of 2^−S
        self.unit = 2.0 ** (self.shift - bits)  # 2^−P in those units: a normal float
        self.unit_abs = 2.0**-bits if bits <= 1074 else ETA  # 2^−P (or more) in absolute terms
        self._r_down = 2.0**-self.shift  # r·2^−S for a product of two radii
        balls_A = [[self._ball(x) for x in row] for row in A]
        balls_b = [self._ball(x) for x in b]
        self.Am_t = np.array([[m for m, _, _ in row] for row in balls_A], dtype=object).T
        self.Ar_t = np.array([[r for _, r, _ in row] for row in balls_A]).T
        self.Ag_t = np.array([[g for _, _, g in row] for row in balls_A]).T
        self.bm = np.array([m for m, _, _ in balls_b], dtype=object)
        self.br = np.array([r for _, r, _ in balls_b])
        self.bg = np.array([g for _, _, g in balls_b])
        self._dot_up = 1.0 + (2 * self.s + 8) * 2.0**-52

    def _ball(self, x: Interval) -> tuple[int, float, float]:
        return _ball_at(x, self.bits, self.shift)

    # ------------------------------------------------------------- kernel

    def vectors(self, n: int, s: int) -> Any:
        return (np.zeros((n, s), dtype=object), np.zeros((n, s)), np.zeros((n, s)))

    def scalars(self, n: int) -> Any:
        return (np.zeros(n, dtype=object), np.zeros(n), np.zeros(n))

    def ones(self, k: int, s: int) -> Any:
        return (np.full((k, s), self.fixed_one, dtype=object), np.zeros((k, s)), np.ones((k, s)))

    def one(self, k: int) -> Any:
        return (np.full(k, self.fixed_one, dtype=object), np.zeros(k), np.ones(k))

    def take(self, x: Any, idx: np.ndarray) -> Any:
        return (x[0][idx], x[1][idx], x[2][idx])

    def put(self, store: Any, lo: int, x: Any) -> None:
        for part, value in zip(store, x):
            part[lo:lo + len(value)] = value

    def mul(self, x: Any, y: Any) -> Any:
        xm, xr, xg = x
        ym, yr, yg = y
        rad = (xg * yr + yg * xr + xr * yr * self._r_down) * _UP4 + self.unit
        return ((xm * ym) >> self.bits, rad, xg * yg * _UP4 + self.unit_abs)

    def _dot(self, x: Any, Mm: np.ndarray, Mr: np.ndarray, Mg: np.ndarray) -> Any:
        xm, xr, xg = x
        mid = xm.dot(Mm) >> self.bits
        rad = (xg.dot(Mr) + xr.dot(Mg) + xr.dot(Mr) * self._r_down) * self._dot_up + self.unit
        return mid, rad, xg.dot(Mg) * self._dot_up + self.unit_abs

    def matvec(self, x: Any) -> Any:
        return self._dot(x, self.Am_t, self.Ar_t, self.Ag_t)

    def dot(self, x: Any) -> Any:
        return self._dot(x, self.bm, self.br, self.bg)

    def enclosures(self, x: Any) -> list[Enclosure]:
        """Scalars of this context as enclosures (exact rational end points)."""
        r_scale = 1 << self.shift
        return [Enclosure(Fraction(int(m), self.fixed_one), Fraction(r) / r_scale, False)
                for m, r in zip(x[0].tolist(), x[1].tolist())]

    def sums(self, k: int, n: int) -> Any:
        return [np.zeros(k, dtype=object), np.zeros(k)]

    def add_terms(self, acc: Any, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        """Σ c·w with c = ±(n−1)!/σ exact: mid-points summed exactly, radii |c|·r."""
        cond, idx = terms.block(i0, i1)
        self._bin(acc, w_terms, _coefficients(terms)[idx], cond)

    def _bin(self, acc: Any, w_terms: Any, coef: np.ndarray, cond: np.ndarray) -> None:
        np.add.at(acc[0], cond, w_terms[0] * coef)
        # |c| rounded to float (relative 2^−53) times r rounded once more: _UP1 covers both;
        # one term after another into its bin, so that a subset's radii are the pass's
        np.add.at(acc[1], cond, w_terms[1] * np.abs(coef.astype(float)) * _UP1)

    def finish_sums(self, acc: Any, k: int, n: int) -> "BallSums":
        """R = Σ/(n−1)!: the exact mid-point sums over (n−1)!·2^P, the radius bounds
        rounded up (the float additions into each bin, at most a few hundred, covered by
        γ_256)."""
        return BallSums(acc[0][:k], summed_radii(acc[1], k, self.bits), self.bits, self.shift, math.factorial(n - 1))

    def selected_sums(self, part: Any) -> Any:
        """Bins for the selected conditions of ``part`` (a
        :class:`~rkcheck.evaluation.subset.Subset`'s order)."""
        return self.sums(part.conditions, part.terms.vertices)

    def add_selected(self, acc: Any, w_terms: Any, part: Any, t0: int, t1: int) -> None:
        """The selected terms ``t0 … t1−1`` of ``part`` into their bins, as :meth:`add_terms`."""
        self._bin(acc, w_terms, _coefficients(part.terms)[part.coefficient[t0:t1]],
                  part.condition[t0:t1].astype(np.intp))

    def finish_selected(self, acc: Any, part: Any) -> "BallSums":
        return self.finish_sums(acc, part.conditions, part.terms.vertices)


def take_rows(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """``x[idx]`` for integer indices ``idx`` along the first axis: ``np.take`` where the
    rows have several entries (numpy's fancy indexing copies a 2-D array entry by entry,
    4–10 times slower for rows of a few entries), indexing elsewhere (as fast for one
    entry per row, faster for rows of none).  But ``np.take`` copies an array that is not
    C-contiguous whole before it gathers (the digit-major digits of a product of
    :mod:`~rkcheck.evaluation.limbs`: those copies were 14 % of the instructions of RK4's
    ball check at order 16): a transposed array is gathered along its own last axis, any
    other by indexing, which reads only the rows asked for."""
    if x.ndim > 1 and x.size and idx.dtype.kind in "iu":
        if x.flags.c_contiguous:
            return np.take(x, idx, axis=0)
        major = np.moveaxis(x, 0, -1)
        if major.flags.c_contiguous:
            return np.moveaxis(np.take(major, idx, axis=-1), -1, 0)
    result: np.ndarray = x[idx]
    return result


def round_up(r: np.ndarray, m: np.ndarray, tmp: np.ndarray) -> None:
    """``r ← (r + u·|m|)·INFLATE + ETA`` in place, the last steps of every radius of the
    float screen (``tmp``: scratch of ``m``'s shape)."""
    np.abs(m, out=tmp)
    tmp *= U
    r += tmp
    r *= INFLATE
    r += ETA


class BlockBins:
    """The bins of blocks of terms over one order's ``k`` conditions: called on a block's
    conditions, (the distinct conditions of the block, each term's index among them).

    A block of terms touches a few thousand of an order's conditions, spread over all of
    them: a bincount of the block over every condition (and the addition of that array
    into the sums) cost far more than the block's arithmetic once an order has a few
    hundred thousand conditions.  Binned by these indices, each bin still adds its terms
    in their order starting from 0, and is then added to its condition's sum once: the
    sums are the same, bit for bit, in whatever order the distinct conditions come.
    They are found through a table over the conditions, kept for the order's blocks
    (only the entries of a block's conditions are read, each after it is written): a few
    passes over the block, where sorting it (``np.unique``) took twice as long."""

    __slots__ = ("_slot",)

    def __init__(self, k: int):
        self._slot = np.empty(k, dtype=np.intp)

    def __call__(self, cond: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        slot, at = self._slot, np.arange(len(cond))
        slot[cond] = at  # for each condition, the position of one of its terms
        uniq = cond[slot[cond] == at]  # that term's condition: each condition once
        slot[uniq] = np.arange(len(uniq))
        inv: np.ndarray = slot[cond]
        return uniq, inv


def summed_radii(radii: np.ndarray, k: int, bits: int) -> np.ndarray:
    """The first k summed radii rounded up (the float additions into each bin, at most a
    few hundred, covered by γ_256); refused when they overflowed the float range."""
    rads = radii[:k] * (1.0 + 256 * U)
    if not np.all(np.isfinite(rads)):
        from rkcheck.errors import UserError

        raise UserError(f"the certified error bounds overflow float64 (about 1.8e308) at {bits} bits: the "
                        "entries are too large in magnitude for balls at this precision (a lower --dps lowers it, "
                        "down to 10 digits); exact arithmetic has no such limit: --arithmetic exact, with "
                        "--decimals exact where decimals are read as intervals")
    return rads


class BallSums:
    """The condition sums of one order as balls: ``R_k = mids[k]/(f·2^P) ± rads[k]/(f·2^S)``
    (f = (n−1)!).  Decided without building a Fraction per condition."""

    def __init__(self, mids: np.ndarray, rads: np.ndarray, bits: int, shift: int, factorial: int):
        self.mids, self.rads, self.bits, self.shift, self.factorial = mids, rads, bits, shift, factorial

    def __len__(self) -> int:
        return len(self.mids)

    def enclosure(self, k: int) -> Enclosure:
        f = self.factorial
        return Enclosure(Fraction(int(self.mids[k]), f << self.bits), Fraction(float(self.rads[k])) / (f << self.shift), False)

    def excludes_zero(self) -> np.ndarray:
        """|mid| > rad, exactly (a Python int against a float compares exactly; numpy's
        comparison of an object array with floats is that comparison, element by element)."""
        limit = self.rads * 2.0 ** (self.bits - self.shift)  # rad in units of 2^−P (inf: no claim)
        return np.asarray(np.abs(self._ints()) > limit, dtype=bool)

    def exceeds(self, t: np.ndarray) -> np.ndarray:
        """``|mid| > t·2^P`` exactly, for floats ``t`` (an infinite or NaN ``t`` claims
        nothing): what the mean value form of a box compares its centre's balls with."""
        return exceeds_scaled(np.abs(np.asarray(self.mids, dtype=object)), t, self.bits)

    def magnitude_bound(self) -> np.ndarray:
        """Floats bounding |mid| + rad from above: ``|m|·2^−P`` rounded up through its 60
        leading bits (``((|m| >> e) + 1)·2^(e−P)``), the radius added, over ``f``, the
        whole inflated by ``1 + 2^−50`` (the three roundings)."""
        return self._magnitude_in_units(0)

    def magnitude_bound_scaled(self) -> tuple[np.ndarray, int]:
        """(b, Z): floats b with |mid| + rad ≤ b·2^−Z, in the radii's units (Z = S): below
        float64's range an absolute bound would floor at 2^−1074 and cap the digits of
        every verdict near 320, whatever the precision."""
        return self._magnitude_in_units(self.shift), self.shift

    def _magnitude_in_units(self, z: int) -> np.ndarray:
        m = np.abs(self._ints())
        if not len(m):
            return np.zeros(0)
        e = np.maximum(_bit_length(m).astype(np.int64) - 60, 0)
        top = ((m >> e.astype(object)) + 1).astype(float)  # below 2^61: a float within 2^−52
        with np.errstate(over="ignore"):  # past float64: an infinite bound is still a bound
            mid_up = np.ldexp(top, e - self.bits + z)  # >= |m|·2^(z−P)
            bound: np.ndarray = (mid_up + np.ldexp(np.asarray(self.rads, dtype=float), z - self.shift)) \
                / float(self.factorial) * (1 + 2.0**-50) + ETA
        return bound

    def _ints(self) -> np.ndarray:
        """The mid-points as an object array of Python integers (what the contexts give:
        a numpy integer would compare with a float inexactly)."""
        mids = np.asarray(self.mids, dtype=object)
        if len(mids) and type(mids[0]) is not int:
            raise TypeError("ball sums: mid-points must be Python integers")
        return mids


_bit_length = np.frompyfunc(int.bit_length, 1, 1)


def exceeds_scaled(ints: np.ndarray, t: np.ndarray, bits: int) -> np.ndarray:
    """``ints > t·2^bits`` exactly, for nonnegative Python integers and floats ``t`` (an
    infinite or NaN ``t`` claims nothing): ``t = m·2^e`` with an integer ``m`` of 53
    bits, compared by shifts — ``t·2^bits`` itself overflows a float past 1024 bits."""
    ok = np.isfinite(t)
    mant, exp = np.frexp(np.where(ok, t, 0.0))
    m = (mant * 2.0**53).astype(np.int64).astype(object)
    shift = exp.astype(np.int64) - 53 + bits
    out = np.zeros(len(t), dtype=bool)
    up = ok & (shift >= 0)
    down = ok & (shift < 0)
    if up.any():
        out[up] = ints[up] > np.left_shift(m[up], shift[up].astype(object))
    if down.any():  # ints·2^(−shift) > m
        out[down] = np.left_shift(ints[down], (-shift[down]).astype(object)) > m[down]
    return out


def _coefficients(terms: Any) -> np.ndarray:
    cached = getattr(terms, "_coef_object", None)
    if cached is None:
        cached = np.array(terms.coefficients, dtype=object)
        terms._coef_object = cached
    return cached


def _float_coefficients(terms: Any, n: int) -> np.ndarray:
    """``c/(n−1)!`` as floats (correctly rounded: Python's true division of integers is,
    as ``float(Fraction)``), once per order's terms: the gradient of a decimal box asks
    for them once per direction and block."""
    cached = getattr(terms, "_coef_float", None)
    if cached is None:
        f = math.factorial(n - 1)
        cached = np.array([c / f for c in terms.coefficients], dtype=float)
        terms._coef_float = cached
    return cached


class FloatContext:
    """The float64 screen (module docstring): fast, certified, about 15 digits at best."""

    exact = False

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval]):
        self.s = len(b)
        Am = np.array([[_float_or_inf(x.mid) for x in row] for row in A])
        Ar = np.array([[_fraction_float_up(x.rad) + abs(_float_or_inf(x.mid)) * U for x in row] for row in A]) * INFLATE + ETA
        bm = np.array([_float_or_inf(x.mid) for x in b])
        br = np.array([_fraction_float_up(x.rad) + abs(_float_or_inf(x.mid)) * U for x in b]) * INFLATE + ETA
        self.Am_t, self.Ar_t, self.Aabs_t = Am.T.copy(), Ar.T.copy(), np.abs(Am).T.copy()
        self.bm, self.br, self.babs = bm, br, np.abs(bm)
        self._gamma = (self.s + 1) * U / (1 - (self.s + 1) * U)

    def vectors(self, n: int, s: int) -> Any:
        return (np.zeros((n, s)), np.zeros((n, s)))

    def scalars(self, n: int) -> Any:
        return (np.zeros(n), np.zeros(n))

    def ones(self, k: int, s: int) -> Any:
        return (np.ones((k, s)), np.zeros((k, s)))

    def one(self, k: int) -> Any:
        return (np.ones(k), np.zeros(k))

    def take(self, x: Any, idx: np.ndarray) -> Any:
        return (take_rows(x[0], idx), take_rows(x[1], idx))

    def put(self, store: Any, lo: int, x: Any) -> None:
        store[0][lo:lo + len(x[0])] = x[0]
        store[1][lo:lo + len(x[1])] = x[1]

    def mul(self, x: Any, y: Any) -> Any:
        xm, xr = x
        ym, yr = y
        pm = xm * ym
        # ((|x|·r_y + |y|·r_x) + r_x·r_y + u·|p|)·INFLATE + ETA, evaluated in that order
        # with two temporaries: the same roundings as the one expression, less traffic
        pr = np.abs(xm) * yr
        tmp = np.abs(ym) * xr
        if tmp.shape != pr.shape or pr.shape != pm.shape:
            pr = (pr + tmp + xr * yr + U * np.abs(pm)) * INFLATE + ETA
            return (pm, pr)
        pr += tmp
        np.multiply(xr, yr, out=tmp)
        pr += tmp
        round_up(pr, pm, tmp)
        return (pm, pr)

    def _dot(self, x: Any, Mm: np.ndarray, Mr: np.ndarray, Mabs: np.ndarray) -> Any:
        xm, xr = x
        mid = xm @ Mm
        absx = np.abs(xm)
        rad = absx @ Mr + xr @ Mabs + xr @ Mr + self._gamma * (absx @ Mabs)
        return mid, rad * INFLATE + ETA

    def matvec(self, x: Any) -> Any:
        return self._dot(x, self.Am_t, self.Ar_t, self.Aabs_t)

    def dot(self, x: Any) -> Any:
        return self._dot(x, self.bm, self.br, self.babs)

    def sums(self, k: int, n: int) -> Any:
        # mid, rad, Σ|term|, count, and the bins of the order's blocks
        return [np.zeros(k), np.zeros(k), np.zeros(k), np.zeros(k), BlockBins(k)]

    def add_terms(self, acc: Any, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        cond, idx = terms.block(i0, i1)
        c = _float_coefficients(terms, n)[idx]
        tm = c * w_terms[0]
        # the coefficient is c(1 ± u) (a rounded quotient), the product rounds once more
        tr = (np.abs(c) * w_terms[1] + 2 * U * np.abs(tm)) * INFLATE + ETA
        uniq, inv = acc[4](cond)
        u = len(uniq)
        acc[0][uniq] += np.bincount(inv, weights=tm, minlength=u)
        acc[1][uniq] += np.bincount(inv, weights=tr, minlength=u)
        acc[2][uniq] += np.bincount(inv, weights=np.abs(tm), minlength=u)
        acc[3][uniq] += np.bincount(inv, minlength=u)

    def finish_sums(self, acc: Any, k: int, n: int) -> "FloatSums":
        mid, rad, absum, count = (a[:k] for a in acc[:4])
        g = (count + 64) * U / (1 - (count + 64) * U)  # the summation (and the chunked adds)
        return FloatSums(mid, (rad + g * absum) * INFLATE + ETA)

    def enclosures(self, x: Any) -> list[Enclosure]:
        return [Enclosure(m, r, False) for m, r in zip(x[0].tolist(), x[1].tolist())]


class FloatSums:
    """The condition sums of one order on the float screen: mid ± rad, floats."""

    def __init__(self, mid: np.ndarray, rad: np.ndarray):
        self.mid, self.rad = mid, rad

    def __len__(self) -> int:
        return len(self.mid)

    def enclosure(self, k: int) -> Enclosure:
        return Enclosure(float(self.mid[k]), float(self.rad[k]), False)

    def excludes_zero(self) -> np.ndarray:
        result: np.ndarray = np.abs(self.mid) > self.rad
        return result

    def magnitude_bound(self) -> np.ndarray:
        result: np.ndarray = (np.abs(self.mid) + self.rad) * (1 + 2.0**-51) + ETA
        return result
