"""The partial derivatives of every condition along the interval entries of a box of
decimal inputs, enclosed over the whole box (definitions §5.2), on the float64 screen.

A value carries, beside its float ball over the box, its gradient: one float ball per
*direction* (an entry that is an interval).  Forward-mode differentiation through the
kernel of :mod:`~rkcheck.evaluation.algorithm` — ``∂(xy) = x∂y + y∂x``, ``∂(Ax) = A∂x +
(∂A)x``, ``∂(bᵀx) = bᵀ∂x + (∂b)ᵀx`` — with every operation's rounding bounded as on the
screen (:class:`~rkcheck.evaluation.balls.FloatContext`), so each partial derivative of a
condition is enclosed over the box: only a few of its digits are needed
(:mod:`~rkcheck.evaluation.box` multiplies it by an entry's radius).

Its cost is ``E`` (the number of directions) times the screen's; the directions are
split into passes whose arrays fit in :data:`MAX_GRADIENT_BYTES`, one direction per pass
at worst, so a box is never too large to judge.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from rkcheck.evaluation.balls import (
    ETA,
    INFLATE,
    FloatContext,
    FloatSums,
    U,
    _float_coefficients,
    round_up,
)
from rkcheck.numbers.intervals import Interval, float_above

if TYPE_CHECKING:
    from rkcheck.trees.listing import ConditionListing

#: which entries of A and of b are directions (stand for intervals of inputs); by default
#: every entry that is not a point
Varies = tuple[Sequence[Sequence[bool]], Sequence[bool]]

def direction_cells(A: Sequence[Sequence[Interval]], b: Sequence[Interval],
                    varies: Varies | None = None) -> list[tuple[Interval, bool]]:
    """Every entry of A (row by row), then of b, with whether it is a direction of the
    box: as ``varies`` says, by default when it is not a point."""
    if varies is None:
        return [(x, not x.is_point) for row in (*A, b) for x in row]
    return [(x, v) for row, vs in zip(A, varies[0]) for x, v in zip(row, vs)] + list(zip(b, varies[1]))


#: Bytes one tree's derivative arrays may take, summed over the weights kept (φ, ψ, a, w:
#: mid and radius each); above, the directions are split into several passes.
MAX_GRADIENT_BYTES = 1 << 30


def _add(p: Any, q: Any) -> Any:
    m = p[0] + q[0]
    return m, (p[1] + q[1] + U * np.abs(m)) * INFLATE + ETA


def _expand(x: Any) -> Any:
    return x[0][..., None], x[1][..., None]


def _product_rule(x: Any, dy: Any, y: Any, dx: Any) -> Any:
    """``x·∂y + y·∂x`` as ``_add(mul(x, ∂y), mul(y, ∂x))`` on the screen — the same
    float operations in the same order, so the same bits — with the values ``x``, ``y``
    broadcast along the directions and the temporaries reused in place."""
    (xm, xr), (ym, yr) = _expand(x), _expand(y)
    (dym, dyr), (dxm, dxr) = dy, dx
    out = []
    for am, ar, dm, dr in ((xm, xr, dym, dyr), (ym, yr, dxm, dxr)):
        # FloatContext.mul: ((|a|·r_d + |d|·r_a) + r_a·r_d + u·|p|)·INFLATE + ETA
        pm = am * dm
        pr = np.abs(am) * dr
        tmp = np.abs(dm)
        tmp *= ar
        pr += tmp
        np.multiply(ar, dr, out=tmp)
        pr += tmp
        round_up(pr, pm, tmp)
        out.append((pm, pr, tmp))
    (m, r, tmp), (pm, pr, _) = out
    m += pm  # _add: (p_r + q_r + u·|m|)·INFLATE + ETA
    r += pr
    round_up(r, m, tmp)
    return m, r


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
    signed = False

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval], directions: slice | None = None,
                 signed: bool = False, varies: Varies | None = None):
        self.f = FloatContext(A, b)
        self.signed = signed
        s = len(b)
        flags = [v for _, v in direction_cells(A, b, varies)]
        a_vars = [(i, j) for i in range(s) for j in range(s) if flags[i * s + j]]
        b_vars = [i for i in range(s) if flags[s * s + i]]
        if directions is not None:  # only these of the interval entries (A's, then b's)
            keep = set(range(len(a_vars) + len(b_vars))[directions])
            a_vars, b_vars = ([v for e, v in enumerate(a_vars) if e in keep],
                              [v for e, v in enumerate(b_vars, len(a_vars)) if e in keep])
        self.a_vars = a_vars
        self.b_vars = b_vars
        self.EA = len(self.a_vars)
        self.E = self.EA + len(self.b_vars)

    def _zeros(self, shape: tuple[int, ...], width: int) -> Any:
        return np.zeros(shape + (width,)), np.zeros(shape + (width,))

    def vectors(self, n: int, s: int) -> Any:
        return self.f.vectors(n, s), self._zeros((n, s), self.EA)

    def scalars(self, n: int) -> Any:
        return self.f.scalars(n), self._zeros((n,), self.E)

    def ones(self, k: int, s: int) -> Any:
        return self.f.ones(k, s), self._zeros((k, s), self.EA)

    def one(self, k: int) -> Any:
        return self.f.one(k), self._zeros((k,), self.E)

    def take(self, x: Any, idx: np.ndarray) -> Any:
        return self.f.take(x[0], idx), self.f.take(x[1], idx)

    def put(self, store: Any, lo: int, x: Any) -> None:
        self.f.put(store[0], lo, x[0])
        self.f.put(store[1], lo, x[1])

    def mul(self, x: Any, y: Any) -> Any:
        value = self.f.mul(x[0], y[0])
        if x[1][0].shape[-1] == 0:  # vectors along no direction of A: nothing to differentiate
            return value, self._zeros(value[0].shape, 0)
        return value, _product_rule(x[0], y[1], y[0], x[1])

    def matvec(self, x: Any) -> Any:
        value = self.f.matvec(x[0])
        if not self.EA:
            return value, self._zeros(value[0].shape, 0)
        gm, gr = x[1]
        dm, dr = self.f.matvec((np.swapaxes(gm, -1, -2), np.swapaxes(gr, -1, -2)))
        grad = (np.swapaxes(dm, -1, -2), np.swapaxes(dr, -1, -2))
        # ∂(Ax)_i/∂a_ij = x_j
        em, er = self._zeros(x[0][0].shape, self.EA)
        for e, (i, j) in enumerate(self.a_vars):
            em[..., i, e] = x[0][0][..., j]
            er[..., i, e] = x[0][1][..., j]
        return value, _add(grad, (em, er))

    def dot(self, x: Any) -> Any:
        value = self.f.dot(x[0])
        gm, gr = x[1]
        # along A's entries: bᵀ∂x (b holds no A entry)
        grad_a = self._zeros(x[0][0].shape[:-1], 0)
        if self.EA:
            grad_a = _add(self.f.dot((np.swapaxes(gm, -1, -2), np.swapaxes(gr, -1, -2))),
                          self._zeros(x[0][0].shape[:-1], self.EA))
        if not self.b_vars:
            return value, grad_a
        # along b_i: ∂(bᵀx)/∂b_i = x_i (x does not depend on b)
        # (np.take along the last axis: fancy indexing there runs numpy's slow general path)
        zero = self._zeros(x[0][0].shape[:-1], len(self.b_vars))
        grad_b = _add(zero, (np.take(x[0][0], self.b_vars, axis=-1), np.take(x[0][1], self.b_vars, axis=-1)))
        if not self.EA:
            return value, grad_b
        return value, (np.concatenate([grad_a[0], grad_b[0]], axis=-1),
                       np.concatenate([grad_a[1], grad_b[1]], axis=-1))

    def sums(self, k: int, n: int) -> Any:
        # the screen's four accumulators (mid, rad, Σ|term|, count) for the values, and
        # the same with one column per direction for the derivatives
        return self.f.sums(k, n), [np.zeros((k, self.E)), np.zeros((k, self.E)), np.zeros((k, self.E)), np.zeros(k)]

    def add_terms(self, acc: Any, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        """:meth:`FloatContext.add_terms` for the values and for every direction at once,
        over one set of bins: the same elementwise operations, and one bincount over
        (condition, direction) pairs, which adds each bin's terms in the same order as a
        bincount per direction (the sums are the same, bit for bit)."""
        cond, idx = terms.block(i0, i1)
        self._add_block(acc, w_terms, cond, _float_coefficients(terms, n)[idx])

    def _add_block(self, acc: Any, w_terms: Any, cond: np.ndarray, c: np.ndarray) -> None:
        """The terms ``c·w`` of one block into the bins of their conditions ``cond``."""
        uniq, inv = acc[0][4](cond)
        u = len(uniq)
        _bin_terms(acc[0], c, w_terms[0], uniq, inv, None)
        count = np.bincount(inv, minlength=u)
        if self.E:
            E = self.E
            bins = (inv.astype(np.int64)[:, None] * E + np.arange(E)).ravel()
            _bin_terms(acc[1], c[:, None], w_terms[1], uniq, bins, (u, E))
            acc[1][3][uniq] += count
        acc[0][3][uniq] += count

    def finish_sums(self, acc: Any, k: int, n: int) -> tuple[FloatSums, np.ndarray]:
        """The conditions on the screen over the box, and ``G[k, e]``: an upper bound of
        ``sup_X |∂R_k/∂x_e|`` — or, ``signed``, the enclosure itself, ``G[k, e] = (mid,
        rad)``, for derivatives combined along literals that feed several entries
        (:class:`~rkcheck.evaluation.box.Chain`)."""
        values, acc = self.f.finish_sums(acc[0], k, n), acc[1]
        cols = [self.f.finish_sums([acc[0][:, e], acc[1][:, e], acc[2][:, e], acc[3]], k, n) for e in range(self.E)]
        if self.signed:
            return values, (np.stack([np.stack([c.mid, c.rad], axis=1) for c in cols], axis=1) if cols
                            else np.zeros((k, 0, 2)))
        return values, (np.stack([c.magnitude_bound() for c in cols], axis=1) if cols else np.zeros((k, 0)))

    def selected_sums(self, part: Any) -> Any:
        """Bins for the selected conditions of ``part`` (a
        :class:`~rkcheck.evaluation.subset.Subset`'s order)."""
        return self.sums(part.conditions, part.terms.vertices)

    def add_selected(self, acc: Any, w_terms: Any, part: Any, t0: int, t1: int) -> None:
        """The selected terms ``t0 … t1−1`` of ``part`` into their bins, as :meth:`add_terms`."""
        c = _float_coefficients(part.terms, part.terms.vertices)[part.coefficient[t0:t1]]
        self._add_block(acc, w_terms, part.condition[t0:t1].astype(np.intp), c)

    def finish_selected(self, acc: Any, part: Any) -> tuple[FloatSums, np.ndarray]:
        return self.finish_sums(acc, part.conditions, part.terms.vertices)


def _bin_terms(acc: Any, c: Any, w: Any, uniq: np.ndarray, bins: np.ndarray, shape: tuple[int, int] | None) -> None:
    """Add the terms ``c·w`` (mid, radius — the coefficient rounded once, the product
    once more —, magnitude) of one block into the accumulators' bins (``shape``: the
    conditions × directions of a gradient, or None for values)."""
    tm = c * w[0]
    tr = np.abs(c) * w[1]
    mag = np.abs(tm)
    tr += 2 * U * mag
    tr *= INFLATE
    tr += ETA
    if shape is None:
        size, places = len(uniq), uniq
    else:  # the bins' entries in the flattened accumulators (made by sums: contiguous, so
        # reshape gives a view): numpy adds into rows of a 2-D array entry by entry, slowly
        size = shape[0] * shape[1]
        places = (uniq[:, None] * shape[1] + np.arange(shape[1])).ravel()
    for a, x in zip(acc, (tm, tr, mag)):
        a.reshape(-1)[places] += np.bincount(bins, weights=x.ravel(), minlength=size)


class LiteralChain:
    """The entries' derivatives along the decimal literals they are written with
    (:class:`~rkcheck.numbers.literals.LiteralBox`) as float balls, and the literals'
    radii: the chain rule that turns the derivatives along the entries into the
    variation along the literals, ``V = Σ_l r_l · sup |Σ_e ∂R/∂x_e · ∂x_e/∂λ_l|``."""

    def __init__(self, mid: np.ndarray, rad: np.ndarray, radii: np.ndarray):
        self.mid, self.rad, self.radii = mid, rad, radii

    @staticmethod
    def of(box: Any) -> "LiteralChain | None":
        """The chain of a :class:`~rkcheck.numbers.literals.LiteralBox`; None where a
        derivative or a radius lies past float64's range (no claim along it)."""
        shape = (len(box.rows), len(box.radii))
        mid, rad = np.zeros(shape), np.zeros(shape)
        for e, row in enumerate(box.rows):  # sparse: an entry uses few of the literals
            for lit, x in row.items():
                m = float(x.mid) if abs(x.mid) < 2**1000 else math.inf
                mid[e, lit] = m
                rad[e, lit] = float_above(max(x.hi - Fraction(m), Fraction(m) - x.lo)) if math.isfinite(m) else math.inf
        radii = np.array([float_above(r) for r in box.radii], dtype=float)
        chain = LiteralChain(mid, rad, radii)
        finite = np.all(np.isfinite(mid)) and np.all(np.isfinite(rad)) and np.all(np.isfinite(radii))
        return chain if finite else None

    def variation(self, G: np.ndarray) -> np.ndarray:
        """``V`` from the signed enclosures ``G[k, e] = (mid, rad)`` of the derivatives
        along the entries, rounded up: ``|Σ_e D·J| ≤ |Σ Dm·Jm| + Σ (|Dm|·Jr + Dr·(|Jm| +
        Jr))``, each float sum of E products within ``γ`` of its terms' magnitudes."""
        Dm, Dr = G[..., 0], G[..., 1]
        E, L = self.mid.shape
        centre = Dm @ self.mid
        spread = np.abs(Dm) @ self.rad + Dr @ (np.abs(self.mid) + self.rad)
        magnitude = np.abs(Dm) @ np.abs(self.mid)
        gamma = 2 * (E + 2) * U
        along = (np.abs(centre) + spread + gamma * (magnitude + spread)) * INFLATE + ETA
        result: np.ndarray = (along @ self.radii) * (1 + (L + 2) * U) * INFLATE + ETA
        return np.where(np.isnan(result), np.inf, result)


def balls_per_tree(s: int, E: int, EA: int) -> int:
    """The float balls of derivatives one tree keeps along ``E`` directions, ``EA`` of them
    A's entries: a direction of A's is carried by Φ, ψ, a and w, one of b's by a and w
    only."""
    return 2 * s * EA + 2 * E


def gradient_bytes(listing: ConditionListing, s: int, E: int, EA: int | None = None) -> int:
    """Memory of the derivative arrays for ``listing`` (what :class:`GradientContext`
    keeps) along ``E`` directions, ``EA`` of them A's entries (None: all)."""
    top = max(listing.orders, default=1)
    kept = listing.first[min(top, len(listing.first) - 1)]
    return int(kept) * balls_per_tree(s, E, E if EA is None else EA) * 16


def gradient_groups(listing: ConditionListing, s: int, E: int, EA: int | None = None) -> list[slice]:
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
