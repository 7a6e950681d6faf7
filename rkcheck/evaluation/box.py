"""Decimal tableaux judged over their whole box of inputs, jointly (definitions §5.2).

A tableau written in rounded decimals stands for every tableau in a box ``X`` (one
interval per entry).  Evaluating the conditions in interval arithmetic over ``X`` treats
two occurrences of one entry as independent, so the enclosure of ``R`` can contain 0
although ``R`` is nonzero on the whole box (``b(b − 1)/2`` with ``b ≈ 0.9999999999``).
The *mean value form* removes that dependency to first order: for the face value
``x̃ ∈ X``,

    R(x) = R(x̃) + ∇R(ξ)·(x − x̃)   for some ξ on the segment, so
    |R(x) − R(x̃)| ≤ V = Σ_e  sup_X |∂R/∂x_e| · r_e,   r_e = max |x_e − x̃_e|.

``R(x̃)`` is computed exactly (residues modulo primes on the face values), the partial
derivatives are enclosed over ``X`` by forward-mode differentiation on the float64 screen
(certified: every operation carries its rounding bound; the derivatives only need a
few correct digits).  Then

* ``|R(x̃)| > V``: R has the sign of ``R(x̃)`` on all of X: the condition **fails**;
* otherwise it holds to the digits of ``min(ball bound, |R(x̃)| + V)``.

The gradient costs ``E`` (the number of entries that are intervals) times the float
screen; it is computed in passes that fit in :data:`MAX_GRADIENT_BYTES`, so the box is
always judged, at any order.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Sequence

import numpy as np

from rkcheck.evaluation.balls import ETA, INFLATE, FloatContext, U, _float_coefficients, block_bins
from rkcheck.numbers.intervals import Interval

#: Bytes one tree's derivative arrays may take, summed over the weights kept (φ, ψ, a, w:
#: mid and radius each); the refinement is skipped above :data:`MAX_GRADIENT_BYTES`.
MAX_GRADIENT_BYTES = 1 << 30


def _add(p, q):
    m = p[0] + q[0]
    return m, (p[1] + q[1] + U * np.abs(m)) * INFLATE + ETA


def _expand(x):
    return x[0][..., None], x[1][..., None]


class GradientContext:
    """Values and their partial derivatives with respect to the interval entries, over
    the whole box, on the float screen: a value is ``(value, gradient)``, each a
    ``(mid, rad)`` pair of arrays; the gradient has a trailing axis of one entry per
    direction.

    Φ and ψ = AΦ do not depend on b: their derivatives along b's entries are zero, exactly,
    so a vector (Φ, ψ) carries only the ``EA`` directions of A's entries, and a scalar
    (a = bᵀΦ, w) all ``E`` — A's, then b's.  Where the decimals are mostly in b (RK4 in
    decimals: its 0.5 and 1 are exact, b's four entries are the box) Φ and ψ carry no
    derivatives at all."""

    exact = False

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval], directions: slice | None = None):
        self.f = FloatContext(A, b)
        s = len(b)
        a_vars = [(i, j) for i in range(s) for j in range(s) if not A[i][j].is_point]
        b_vars = [i for i in range(s) if not b[i].is_point]
        if directions is not None:  # only these of the interval entries (A's, then b's)
            keep = set(range(len(a_vars) + len(b_vars))[directions])
            a_vars, b_vars = ([v for e, v in enumerate(a_vars) if e in keep],
                              [v for e, v in enumerate(b_vars, len(a_vars)) if e in keep])
        self.a_vars = a_vars
        self.b_vars = b_vars
        self.EA = len(self.a_vars)
        self.E = self.EA + len(self.b_vars)

    def _zeros(self, shape, width: int):
        return np.zeros(shape + (width,)), np.zeros(shape + (width,))

    def vectors(self, n: int, s: int):
        return self.f.vectors(n, s), self._zeros((n, s), self.EA)

    def scalars(self, n: int):
        return self.f.scalars(n), self._zeros((n,), self.E)

    def ones(self, k: int, s: int):
        return self.f.ones(k, s), self._zeros((k, s), self.EA)

    def one(self, k: int):
        return self.f.one(k), self._zeros((k,), self.E)

    def take(self, x, idx):
        return self.f.take(x[0], idx), self.f.take(x[1], idx)

    def put(self, store, lo: int, x) -> None:
        self.f.put(store[0], lo, x[0])
        self.f.put(store[1], lo, x[1])

    def mul(self, x, y):
        value = self.f.mul(x[0], y[0])
        grad = _add(self.f.mul(_expand(x[0]), y[1]), self.f.mul(_expand(y[0]), x[1]))
        return value, grad

    def matvec(self, x):
        value = self.f.matvec(x[0])
        gm, gr = x[1]
        dm, dr = self.f.matvec((np.swapaxes(gm, -1, -2), np.swapaxes(gr, -1, -2)))
        grad = (np.swapaxes(dm, -1, -2), np.swapaxes(dr, -1, -2))
        # ∂(Ax)_i/∂a_ij = x_j
        em, er = self._zeros(x[0][0].shape, self.EA)
        for e, (i, j) in enumerate(self.a_vars):
            em[..., i, e] = x[0][0][..., j]
            er[..., i, e] = x[0][1][..., j]
        return value, _add(grad, (em, er))

    def dot(self, x):
        value = self.f.dot(x[0])
        gm, gr = x[1]
        # along A's entries: bᵀ∂x (b holds no A entry)
        grad_a = _add(self.f.dot((np.swapaxes(gm, -1, -2), np.swapaxes(gr, -1, -2))),
                      self._zeros(x[0][0].shape[:-1], self.EA))
        if not self.b_vars:
            return value, grad_a
        # along b_i: ∂(bᵀx)/∂b_i = x_i (x does not depend on b)
        zero = self._zeros(x[0][0].shape[:-1], len(self.b_vars))
        grad_b = _add(zero, (x[0][0][..., self.b_vars], x[0][1][..., self.b_vars]))
        return value, (np.concatenate([grad_a[0], grad_b[0]], axis=-1),
                       np.concatenate([grad_a[1], grad_b[1]], axis=-1))

    def sums(self, k: int, n: int):
        # FloatContext's four accumulators (mid, rad, Σ|term|, count), one column per direction
        return [np.zeros((k, self.E)), np.zeros((k, self.E)), np.zeros((k, self.E)), np.zeros(k)]

    def add_terms(self, acc, w_terms, terms, n: int, i0: int, i1: int) -> None:
        """:meth:`FloatContext.add_terms` for every direction at once: the same
        elementwise operations, and one bincount over (condition, direction) pairs, which
        adds each bin's terms in the same order as a bincount per direction (the sums
        are the same, bit for bit)."""
        gm, gr = w_terms[1]
        E = self.E
        if not E:
            return
        cond, idx = terms.block(i0, i1)
        c = _float_coefficients(terms, n)[idx][:, None]
        tm = c * gm
        tr = (np.abs(c) * gr + 2 * U * np.abs(tm)) * INFLATE + ETA
        uniq, inv = block_bins(cond)
        u = len(uniq)
        bins = (inv.astype(np.int64)[:, None] * E + np.arange(E)).ravel()
        for a, x in zip(acc, (tm, tr, np.abs(tm))):
            a[uniq] += np.bincount(bins, weights=x.ravel(), minlength=u * E).reshape(u, E)
        acc[3][uniq] += np.bincount(inv, minlength=u)

    def finish_sums(self, acc, k: int, n: int) -> np.ndarray:
        """``G[k, e]``: an upper bound of ``sup_X |∂R_k/∂x_e|``."""
        cols = [self.f.finish_sums([acc[0][:, e], acc[1][:, e], acc[2][:, e], acc[3]], k, n).magnitude_bound()
                for e in range(self.E)]
        return np.stack(cols, axis=1) if cols else np.zeros((k, 0))


def gradient_bytes(listing, s: int, E: int, EA: int | None = None) -> int:
    """Memory of the derivative arrays for ``listing`` (what :class:`GradientContext`
    keeps) along ``E`` directions, ``EA`` of them A's entries (None: all): a direction of
    A's is carried by Φ, ψ, a and w, one of b's by a and w only."""
    top = max(listing.orders, default=1)
    kept = listing.first[min(top, len(listing.first) - 1)]
    EA = E if EA is None else EA
    return int(kept) * (2 * s * EA + 2 * E) * 16


class BoxRefinement:
    """The mean value form of every condition of one order (representative sign):
    ``R(x̃) = integers[k] / scale`` exactly, ``variation[k] = V`` (a float, rounded up).

    The centre is kept as integers over one common denominator and decided with integer
    comparisons: a Fraction per condition (a gcd each) cost more than evaluating them."""

    def __init__(self, integers: list[int], scale: int, variation: np.ndarray):
        self.integers, self.scale, self.variation = integers, scale, variation
        self._c: np.ndarray | None = None

    @property
    def centre(self) -> list[Fraction]:
        return [Fraction(x, self.scale) for x in self.integers]

    def centre_at(self, k: int) -> Fraction:
        return Fraction(self.integers[k], self.scale)

    def fails(self) -> np.ndarray:
        """``|R(x̃)| > V``, exactly.  Rounding to nearest is monotone and V is a float, so
        the correctly rounded ``c = |N|/scale`` above V proves ``|R(x̃)| > V`` and below V
        disproves it; only ``c = V`` is decided in integers: ``|N|·2^k > m·scale`` for
        ``V = m/2^k``."""
        c = self._magnitudes()
        if c is None:
            return self._fails_exactly(range(len(self.integers)))
        out = c > self.variation
        tie = np.flatnonzero(c == self.variation)
        if len(tie):
            out[tie] = self._fails_exactly(tie.tolist())[tie]
        return out

    def _fails_exactly(self, indices) -> np.ndarray:
        out = np.zeros(len(self.integers), dtype=bool)
        q, v = self.scale, self.variation
        for i in indices:
            x = self.integers[i]
            if x:
                m, k = float(v[i]).as_integer_ratio()
                out[i] = abs(x) * k > m * q
        return out

    def _magnitudes(self) -> np.ndarray | None:
        """``|N|/scale`` correctly rounded (integer true division, as ``float(Fraction)``),
        element by element in numpy's loop; None past float64's range."""
        if self._c is None:
            try:
                self._c = (np.abs(np.array(self.integers, dtype=object)) / self.scale).astype(float) \
                    if len(self.integers) else np.zeros(0)
            except OverflowError:
                return None
        return self._c

    def bound(self) -> np.ndarray:
        """An upper bound of ``|R|`` over the box: ``|R(x̃)| + V`` (floats, rounded up);
        ``|N|/scale`` is correctly rounded (integer true division), as ``float(Fraction)``."""
        c = self._magnitudes()
        if c is None:  # the integer division raises past float64's range, as float(Fraction) does
            q = self.scale
            c = np.array([abs(x) / q for x in self.integers], dtype=float)
        return (c * (1 + 4 * U) + self.variation) * INFLATE + ETA


def box_radii(A: Sequence[Sequence[Interval]], b: Sequence[Interval], centre_A, centre_b, ctx: GradientContext) -> np.ndarray:
    """``r_e = max |x_e − x̃_e|`` over the box, as floats rounded up."""
    out = []
    for i, j in ctx.a_vars:
        x, c = A[i][j], Fraction(centre_A[i][j])
        out.append(max(c - x.lo, x.hi - c))
    for i in ctx.b_vars:
        x, c = b[i], Fraction(centre_b[i])
        out.append(max(c - x.lo, x.hi - c))
    return np.array([math.nextafter(float(r), math.inf) for r in out], dtype=float)


#: bits of working precision beyond the bound of the centre's integer ``N`` (below): the
#: balls' rounding grows with the number of operations, far below 2^40 of them
CENTRE_GUARD_BITS = 40


def centre_integers(listing, centre_A, centre_b, orders: Sequence[int]) -> dict[int, tuple[list[int], int]]:
    """``R(x̃)`` exactly for every condition of ``orders``: ``{n: (N, scale)}`` with
    ``R = N_k / scale``, ``scale = (n−1)!·d^(n−1)`` (:mod:`~rkcheck.evaluation.modular`).

    One pass of balls at a working precision ``P`` a few dozen bits above the bound of
    ``|N|`` replaces the residues modulo as many primes (a decimal with 16 digits makes
    ``d ≈ 10^16``: about 30 primes at 16 vertices) and their Chinese remaindering.  The
    ball encloses ``R`` certifiably, so ``N`` lies in ``scale·(mid ± rad)``; once that
    interval is shorter than 1 it holds one integer only, the nearest to its centre.  An
    order where a ball is not that narrow, a listing whose balls would not fit in
    :data:`MAX_CENTRE_BALL_BYTES`, or a tableau whose weights are mostly nonzero
    (:data:`CENTRE_BALL_MAX_NONZERO`: then the residues are faster) is computed by
    residues instead: the answer is exact either way."""
    from rkcheck.errors import UserError
    from rkcheck.evaluation.algorithm import condition_sums
    from rkcheck.evaluation.balls import BallContext
    from rkcheck.evaluation.modular import exact_condition_sums
    from rkcheck.evaluation.scaled import scaled_rational

    scaled = scaled_rational(centre_A, centre_b)
    bits = max(scaled.coefficient_bits(n, listing.orders[n].max_terms) for n in orders) + CENTRE_GUARD_BITS
    out: dict[int, tuple[list[int], int]] = {}
    sums = {}
    if _centre_by_balls(listing, centre_A, centre_b, max(orders), bits):
        points_A = [[Interval(x, x) for x in row] for row in centre_A]
        points_b = [Interval(x, x) for x in centre_b]
        try:  # radii past float64 (huge entries) end as inf or NaN, or refused: residues
            with np.errstate(over="ignore", invalid="ignore"):
                sums = condition_sums(listing, BallContext(points_A, points_b, bits), len(centre_b), orders)
        except (UserError, ArithmeticError):
            sums = {}
    missing = []
    for n in orders:
        ints = _round_to_integers(sums[n], scaled.d ** (n - 1)) if n in sums else None
        if ints is None:
            missing.append(n)
        else:
            out[n] = (ints, math.factorial(n - 1) * scaled.d ** (n - 1))
    if missing:
        for n, e in exact_condition_sums(scaled, listing, missing).items():
            out[n] = (e.integers(), e.scale)
    return out


#: Bytes the centre's balls may take (Python integers of the working precision, one per
#: stored weight, counted as if none were zero); above, the residues (int32 per prime,
#: one prime at a time) compute the centre instead
MAX_CENTRE_BALL_BYTES = 512 << 20


def centre_ball_bytes(listing, s: int, top: int, bits: int, nonzero: int | None = None) -> int:
    """An upper bound of the memory of the centre's balls (weights up to ``top``
    vertices): a pointer and two floats per stored weight, and an integer object of
    ``bits`` bits per weight that may be nonzero (``nonzero``; all when None — a zero is
    Python's one shared 0)."""
    first = listing.first
    values = 2 * s * first[max(top - 1, 2)] + 2 * first[top]
    return values * 3 * 8 + (values if nonzero is None else nonzero) * (bits // 8 + 32)


#: the centre is computed by balls only when at most this share of the stored weights
#: may be nonzero by the tableau's pattern of zeros: a ball whose mid-point is the shared
#: Python 0 costs next to nothing, a nonzero one of ~900 bits more than its residues
#: modulo every prime.  Measured at order 16 with 16-digit decimals (about 30 primes):
#: RK4 (4 % of its weights nonzero) 1.2 s by balls against 1.6 s by residues, Gauss-3
#: (every weight nonzero) 10.4 s against 2.1 s: about even near 9 %.
CENTRE_BALL_MAX_NONZERO = 0.1


def _centre_by_balls(listing, centre_A, centre_b, top: int, bits: int) -> bool:
    """Whether balls compute the centre (else residues): when few of the weights stored
    may be nonzero (:data:`CENTRE_BALL_MAX_NONZERO`, counted by the tableau's pattern of
    zeros: :class:`_SupportCounter`) and their memory fits in
    :data:`MAX_CENTRE_BALL_BYTES` (an explicit RK4 at order 18 stores 0.3 million nonzero
    weights of 13 million)."""
    from rkcheck.evaluation.algorithm import store_weights

    if all(x != 0 for row in (*centre_A, centre_b) for x in row):
        return CENTRE_BALL_MAX_NONZERO >= 1 and _centre_balls_fit(listing, len(centre_b), top, bits, None)
    s = len(centre_b)
    counter = _SupportCounter(centre_A, centre_b)
    store_weights(listing, counter, s, top)
    if counter.nonzero > CENTRE_BALL_MAX_NONZERO * counter.stored:
        return False
    return _centre_balls_fit(listing, s, top, bits, counter.nonzero)


def _centre_balls_fit(listing, s: int, top: int, bits: int, nonzero: int | None) -> bool:
    return centre_ball_bytes(listing, s, top, bits, nonzero) <= MAX_CENTRE_BALL_BYTES


class _SupportCounter:
    """The elementary weights' pattern of zeros: True where a weight may be nonzero
    (products and sums of entries, none of which is zero), False where it is zero for
    every tableau with the same zero entries.  Counts the weights stored that may be
    nonzero (every stored block passes :meth:`put` once)."""

    exact = False

    def __init__(self, A, b):
        kind = np.uint8 if len(b) < 256 else np.int32  # sums of s zeros and ones
        self.A_t = np.array([[x != 0 for x in row] for row in A], dtype=kind).T.copy()
        self.b = np.array([x != 0 for x in b], dtype=kind)
        self.kind = kind
        self.nonzero = 0
        self.stored = 0

    def vectors(self, n: int, s: int):
        return np.zeros((n, s), dtype=bool)

    def scalars(self, n: int):
        return np.zeros(n, dtype=bool)

    def ones(self, k: int, s: int):
        return np.ones((k, s), dtype=bool)

    def one(self, k: int):
        return np.ones(k, dtype=bool)

    def take(self, x, idx):
        return x[idx]

    def put(self, store, lo: int, x) -> None:
        store[lo:lo + len(x)] = x
        self.nonzero += int(np.count_nonzero(x))
        self.stored += x.size

    def mul(self, x, y):
        return x & y

    def matvec(self, x):
        return (x.astype(self.kind) @ self.A_t) > 0

    def dot(self, x):
        return (x.astype(self.kind) @ self.b) > 0

    def sums(self, k: int, n: int):
        return None

    def add_terms(self, acc, w_terms, terms, n: int, i0: int, i1: int) -> None:
        return None

    def finish_sums(self, acc, k: int, n: int):
        return None


def _round_to_integers(sums, dpow: int) -> list[int] | None:
    """The integers ``N_k = scale·R_k`` from ball sums ``R_k = mid_k/(f·2^P) ±
    rad_k/(f·2^S)`` with ``scale = f·dpow``: ``N_k ∈ X/2^P ± Y_k`` with ``X = dpow·mid``,
    ``Y_k = dpow·rad_k/2^S``; when every ``Y_k < 1/2`` the one integer there is the
    nearest to ``X/2^P`` (None when some ball is wider).  Vectorised over the conditions
    (numpy object arrays of Python integers)."""
    P, S = sums.bits, sums.shift
    if len(sums.mids) == 0:
        return []
    rmax = float(np.max(sums.rads))
    if not math.isfinite(rmax):
        return None
    a, k = rmax.as_integer_ratio()
    if 2 * dpow * a >= k << S:  # some Y_k >= 1/2
        return None
    X = np.asarray(sums.mids, dtype=object) * dpow
    N = (X + (1 << (P - 1))) >> P  # the nearest integers to X/2^P
    # the balls certify an integer within Y_k <= Y_max of X/2^P: it can only be N
    # (a check of the arithmetic, never failing unless a ball is wrong)
    if np.max(np.abs((N << P) - X)) * k << S > (dpow * a) << P:
        return None
    return N.tolist()  # Python integers (an object array's elements)


def gradient_groups(listing, s: int, E: int, EA: int | None = None) -> list[slice]:
    """The directions (interval entries: ``EA`` of A's — None: all —, then b's) split
    into passes whose derivative arrays fit in :data:`MAX_GRADIENT_BYTES` — one direction
    per pass at worst: the refinement is never skipped, a large box only takes more
    passes."""
    EA = E if EA is None else EA
    groups, lo = [], 0
    for e in range(1, E + 1):
        if e - lo > 1 and gradient_bytes(listing, s, e - lo, max(0, min(e, EA) - lo)) > MAX_GRADIENT_BYTES:
            groups.append(slice(lo, e - 1))
            lo = e - 1
    return groups + [slice(lo, E)] if E else [slice(0, 0)]


def refine_box(listing, A, b, centre_A, centre_b, orders: Sequence[int]) -> dict[int, BoxRefinement]:
    """The mean value form (module docstring) of the conditions of ``orders``, for the box
    ``(A, b)`` of intervals and its point ``(centre_A, centre_b)`` (exact rationals)."""
    from rkcheck.evaluation.algorithm import condition_sums

    wanted = sorted(orders)
    if not wanted:
        return {}
    centre = centre_integers(listing, centre_A, centre_b, wanted)
    ctx = GradientContext(A, b)
    parts = [condition_sums(listing, GradientContext(A, b, group), len(b), wanted)
             for group in gradient_groups(listing, len(b), ctx.E, ctx.EA)]
    r = box_radii(A, b, centre_A, centre_b, ctx)
    out = {}
    for n in wanted:
        # each direction's column is computed alone (GradientContext: no mixing between
        # directions), so the passes' columns side by side are the one pass's matrix
        G = np.concatenate([part[n] for part in parts], axis=1) if len(parts) > 1 else parts[0][n]
        V = (G @ r) * (1 + (ctx.E + 2) * U) * INFLATE + ETA if ctx.E else np.zeros(len(G))
        out[n] = BoxRefinement(*centre[n], V)
    return out


__all__ = ["GradientContext", "BoxRefinement", "refine_box", "centre_integers", "MAX_GRADIENT_BYTES"]


class RefinedSums:
    """Ball sums of one order with the mean value form folded in: where it proves a
    failure, the enclosure shown is ``R(x̃) ± V`` (it excludes 0); elsewhere the tighter of
    the two magnitude bounds counts.  Everything else is the ball sums'."""

    def __init__(self, balls, refinement: BoxRefinement):
        self.balls = balls
        self.refinement = refinement
        self._fails = refinement.fails()
        self._ball_excludes = np.asarray(balls.excludes_zero(), dtype=bool)

    def __len__(self) -> int:
        return len(self.balls)

    def excludes_zero(self) -> np.ndarray:
        return self._ball_excludes | self._fails

    def magnitude_bound(self) -> np.ndarray:
        return np.minimum(np.asarray(self.balls.magnitude_bound(), dtype=float), self.refinement.bound())

    def enclosure(self, k: int):
        from rkcheck.numbers.enclosure import Enclosure

        if self._fails[k] and not self._ball_excludes[k]:
            return Enclosure(self.refinement.centre_at(k), Fraction(float(self.refinement.variation[k])), False)
        return self.balls.enclosure(k)
