"""Decimal tableaux judged over their whole box of inputs, jointly (definitions §5.2).

A tableau written in rounded decimals stands for every tableau in a box ``X`` (one
interval per entry).  Evaluating the conditions in interval arithmetic over ``X`` treats
two occurrences of one entry as independent, so the enclosure of ``R`` can contain 0
although ``R`` is nonzero on the whole box (``b(b − 1)/2`` with ``b ≈ 0.9999999999``).
The *mean value form* removes that dependency to first order: for the face value
``x̃ ∈ X``,

    R(x) = R(x̃) + ∇R(ξ)·(x − x̃)   for some ξ on the segment, so
    |R(x) − R(x̃)| ≤ V = Σ_e  sup_X |∂R/∂x_e| · r_e,   r_e = max |x_e − x̃_e|.

One pass over the conditions computes, for each of them:

* ``R(x̃)`` in certified balls at the face values, at a precision far beyond the box
  (:data:`CENTRE_BITS_BEYOND_BOX` bits below the narrowest entry's radius), so that the
  ball's radius ``ε`` is negligible beside ``V`` — where it is not (a condition that
  hardly varies on the box), that order's ``R(x̃)`` is computed exactly instead;
* the partial derivatives, enclosed over ``X`` by forward-mode differentiation on the
  float64 screen (:mod:`~rkcheck.evaluation.slopes`; they only need a few correct
  digits), which also gives the conditions on the screen over ``X`` (interval
  arithmetic, dependency and all).

Then

* ``|R(x̃)| > V + ε``: R has the sign of ``R(x̃)`` on all of X: the condition **fails**,
  as it does where the screen's own enclosure excludes 0;
* otherwise it holds to the digits of the smaller bound, ``|R(x̃)| + ε + V`` or the
  screen's.

Weights that are zero for every tableau with the tableau's zero entries are skipped
(:mod:`~rkcheck.evaluation.support`): exactly zero on the box, they add nothing.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Callable, Iterable, Sequence

import numpy as np

from rkcheck.evaluation.balls import ETA, INFLATE, BallSums, FloatSums, U
from rkcheck.evaluation.slopes import GradientContext, gradient_groups
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.intervals import Interval, float_above

if TYPE_CHECKING:
    from rkcheck.trees.listing import ConditionListing

#: bits of the centre's balls below the narrowest entry radius: the ball's radius ε then
#: lies near 2^−128 of the variation V (V is at least the radius times the rounding of
#: the float derivatives, 2^−53 of their size)
CENTRE_BITS_BEYOND_BOX = 128

#: an order whose centre ball is wider than this share of some condition's variation is
#: computed exactly (residues modulo primes): the ball would cost that condition digits
CENTRE_SPREAD = 2.0**-20


def centre_bits(A: Sequence[Sequence[Interval]], b: Sequence[Interval]) -> int:
    """The working bits of the centre's balls: :data:`CENTRE_BITS_BEYOND_BOX` below the
    narrowest radius of an interval entry."""
    radii = [x.rad for row in (*A, b) for x in row if x.rad > 0]
    if not radii:
        return CENTRE_BITS_BEYOND_BOX
    r = Fraction(min(radii))
    below = r.denominator.bit_length() - r.numerator.bit_length()
    return max(below, 0) + CENTRE_BITS_BEYOND_BOX


class BallCentre:
    """``R(x̃)`` of one order's conditions in balls: ``M/(f·2^P) ± ρ/(f·2^S)``
    (:class:`~rkcheck.evaluation.balls.BallSums`), decided without a Fraction per
    condition."""

    def __init__(self, sums: BallSums):
        self.sums = sums

    def spread(self) -> np.ndarray:
        """The balls' radii (floats, about: only for choosing the exact route)."""
        s = self.sums
        result: np.ndarray = np.ldexp(np.asarray(s.rads, dtype=float), -s.shift) / float(s.factorial)
        return result

    def beyond(self, variation: np.ndarray) -> np.ndarray:
        """``|R(x̃)| > V`` for every value in the ball: ``|M| > 2^P·(f·V + ρ·2^−S)``, the
        right side rounded up (a float compared with a Python integer exactly; an
        overflow to inf claims nothing)."""
        s = self.sums
        f = float(s.factorial)
        if f < s.factorial:
            f = math.nextafter(f, math.inf)
        with np.errstate(over="ignore", invalid="ignore"):
            t = (f * variation + np.ldexp(np.asarray(s.rads, dtype=float), -s.shift)) * (1 + 8 * U) + ETA
        return s.exceeds(t)

    def bound(self, variation: np.ndarray) -> np.ndarray:
        """An upper bound of ``|R(x̃)| + ε + V`` (floats, rounded up)."""
        with np.errstate(over="ignore"):
            result: np.ndarray = (self.sums.magnitude_bound() + variation) * INFLATE + ETA
            return result

    def enclosure(self, k: int, variation: float) -> Enclosure:
        e = self.sums.enclosure(k)
        return Enclosure(e.mid, e.rad + Fraction(variation), False)


class ExactCentre:
    """``R(x̃) = integers[k] / scale`` exactly (residues modulo primes), decided with
    integer comparisons: a Fraction per condition (a gcd each) costs more than the
    evaluation."""

    def __init__(self, integers: list[int], scale: int):
        self.integers, self.scale = integers, scale
        self._c: np.ndarray | None = None

    def beyond(self, variation: np.ndarray) -> np.ndarray:
        """``|R(x̃)| > V``, exactly.  Rounding to nearest is monotone and V is a float, so
        the correctly rounded ``c = |N|/scale`` above V proves ``|R(x̃)| > V`` and below V
        disproves it; only ``c = V`` is decided in integers: ``|N|·2^k > m·scale`` for
        ``V = m/2^k``."""
        c = self._magnitudes()
        if c is None:
            return self._beyond_exactly(variation, range(len(self.integers)))
        out = c > variation
        tie = np.flatnonzero(c == variation)
        if len(tie):
            out[tie] = self._beyond_exactly(variation, tie.tolist())[tie]
        return out

    def _beyond_exactly(self, variation: np.ndarray, indices: Iterable[int]) -> np.ndarray:
        out = np.zeros(len(self.integers), dtype=bool)
        for i in indices:
            x = self.integers[i]
            if x and math.isfinite(variation[i]):
                m, k = float(variation[i]).as_integer_ratio()
                out[i] = abs(x) * k > m * self.scale
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

    def bound(self, variation: np.ndarray) -> np.ndarray:
        """An upper bound of ``|R(x̃)| + V``: floats, rounded up."""
        c = self._magnitudes()
        if c is None:  # the integer division raises past float64's range, as float(Fraction) does
            c = np.array([_float_or_inf(abs(x), self.scale) for x in self.integers], dtype=float)
        result: np.ndarray = (c * (1 + 4 * U) + variation) * INFLATE + ETA
        return result

    def enclosure(self, k: int, variation: float) -> Enclosure:
        return Enclosure(Fraction(self.integers[k], self.scale), Fraction(variation), False)


def _float_or_inf(x: int, q: int) -> float:
    try:
        return x / q
    except OverflowError:
        return math.inf


class BoxSums:
    """The conditions of one order judged over the box (the representative's sign):
    the mean value form ``R(x̃) ± V`` and the screen's enclosure over the box, each
    decisive where it is sharper.  What :func:`~rkcheck.energy.results.order_verdicts`
    reads: ``excludes_zero``, ``magnitude_bound``, ``enclosure``."""

    def __init__(self, centre: BallCentre | ExactCentre, screen: FloatSums, variation: np.ndarray):
        self.centre, self.screen, self.variation = centre, screen, variation
        self._fails = centre.beyond(variation)
        self._screen_fails = np.asarray(screen.excludes_zero(), dtype=bool)
        self._bound = centre.bound(variation)
        self._screen_bound = np.asarray(screen.magnitude_bound(), dtype=float)

    def __len__(self) -> int:
        return len(self.variation)

    def excludes_zero(self) -> np.ndarray:
        result: np.ndarray = self._fails | self._screen_fails
        return result

    def magnitude_bound(self) -> np.ndarray:
        result: np.ndarray = np.minimum(self._bound, self._screen_bound)
        return result

    def enclosure(self, k: int) -> Enclosure:
        """The enclosure that decides: the mean value form's where it fails or bounds
        ``|R|`` at least as tightly, else the screen's."""
        if self._fails[k] or not (self._screen_fails[k] or self._screen_bound[k] < self._bound[k]):
            return self.centre.enclosure(k, float(self.variation[k]))
        return self.screen.enclosure(k)


class _Pair:
    """Two contexts run side by side over the same weights: a value is a pair of theirs."""

    exact = False

    def __init__(self, first: Any, second: Any) -> None:
        self.parts = (first, second)

    @property
    def width(self) -> int:
        return max(getattr(c, "width", 1) for c in self.parts)

    def vectors(self, n: int, s: int) -> Any:
        return tuple(c.vectors(n, s) for c in self.parts)

    def scalars(self, n: int) -> Any:
        return tuple(c.scalars(n) for c in self.parts)

    def ones(self, k: int, s: int) -> Any:
        return tuple(c.ones(k, s) for c in self.parts)

    def one(self, k: int) -> Any:
        return tuple(c.one(k) for c in self.parts)

    def take(self, x: Any, idx: np.ndarray) -> Any:
        return tuple(c.take(v, idx) for c, v in zip(self.parts, x))

    def put(self, store: Any, lo: int, x: Any) -> None:
        for c, part, v in zip(self.parts, store, x):
            c.put(part, lo, v)

    def mul(self, x: Any, y: Any) -> Any:
        return tuple(c.mul(u, v) for c, u, v in zip(self.parts, x, y))

    def matvec(self, x: Any) -> Any:
        return tuple(c.matvec(v) for c, v in zip(self.parts, x))

    def dot(self, x: Any) -> Any:
        return tuple(c.dot(v) for c, v in zip(self.parts, x))

    def sums(self, k: int, n: int) -> Any:
        return tuple(c.sums(k, n) for c in self.parts)

    def add_terms(self, acc: Any, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        for c, a, v in zip(self.parts, acc, w_terms):
            c.add_terms(a, v, terms, n, i0, i1)

    def finish_sums(self, acc: Any, k: int, n: int) -> Any:
        return tuple(c.finish_sums(a, k, n) for c, a in zip(self.parts, acc))


def box_radii(A: Sequence[Sequence[Interval]], b: Sequence[Interval], centre_A: Sequence[Sequence[Any]],
              centre_b: Sequence[Any], ctx: GradientContext) -> np.ndarray:
    """``r_e = max |x_e − x̃_e|`` over the box, as floats rounded up (inf past float64's
    range: no claim)."""
    out = []
    for i, j in ctx.a_vars:
        x, c = A[i][j], Fraction(centre_A[i][j])
        out.append(max(c - x.lo, x.hi - c))
    for i in ctx.b_vars:
        x, c = b[i], Fraction(centre_b[i])
        out.append(max(c - x.lo, x.hi - c))
    return np.array([float_above(r) for r in out], dtype=float)


def judge_box(listing: ConditionListing, A: Sequence[Sequence[Interval]], b: Sequence[Interval],
              centre_A: Sequence[Sequence[Any]], centre_b: Sequence[Any],
              orders: Sequence[int], on_order: Callable[[int, BoxSums], None] | None = None) -> dict[int, BoxSums]:
    """The conditions of ``orders`` judged over the box ``(A, b)`` of intervals by the
    mean value form around ``(centre_A, centre_b)``, the face values (exact rationals):
    ``{n: BoxSums}``.  ``on_order`` as each order is judged (when the derivatives take
    more than one pass: after the last)."""
    from rkcheck.evaluation.algorithm import EvaluationInterrupted, condition_sums
    from rkcheck.evaluation.backends import certified_context
    from rkcheck.evaluation.support import SupportContext, zero_pattern

    wanted = sorted(orders)
    if not wanted:
        return {}
    s = len(b)
    whole = GradientContext(A, b)
    groups = gradient_groups(listing, s, whole.E, whole.EA)
    radii = box_radii(A, b, centre_A, centre_b, whole)
    zeros = zero_pattern(A, b)

    def supported(ctx: Any) -> Any:
        return SupportContext(ctx, *zeros) if zeros[0].any() or zeros[1].any() else ctx

    points_A = [[Interval(x, x) for x in row] for row in centre_A]
    points_b = [Interval(x, x) for x in centre_b]
    centre = certified_context(points_A, points_b, centre_bits(A, b), wanted[-1])
    first = supported(_Pair(centre, GradientContext(A, b, groups[0])))
    out: dict[int, BoxSums] = {}

    def judged(n: int, sums: Any, more: Sequence[Any] = ()) -> BoxSums:
        ball, (screen, G) = sums
        if more:  # each direction's column computed alone: the passes' columns side by side
            G = np.concatenate([G] + [m[n][1] for m in more], axis=1)
        V = (G @ radii) * (1 + (whole.E + 2) * U) * INFLATE + ETA
        return BoxSums(BallCentre(ball), screen, V)

    def done(n: int, sums: Any) -> None:
        out[n] = judged(n, sums)
        if on_order is not None:
            on_order(n, out[n])

    try:
        raw = condition_sums(listing, first, s, wanted, done if len(groups) == 1 else None)
    except EvaluationInterrupted as stop:
        # the orders judged so far, around the balls' centre (sound; no exact pass after
        # a Ctrl-C), or none while later passes of derivatives were still to come
        stop.finished = dict(out) if len(groups) == 1 else {}
        raise
    if len(groups) > 1:
        try:
            more = [condition_sums(listing, supported(GradientContext(A, b, g)), s, wanted) for g in groups[1:]]
        except EvaluationInterrupted as stop:
            stop.finished = {}
            raise
        for n in wanted:
            out[n] = judged(n, raw[n], more)
            if on_order is not None:
                on_order(n, out[n])
    return _exact_where_needed(listing, centre_A, centre_b, out)


def _exact_where_needed(listing: ConditionListing, centre_A: Sequence[Sequence[Any]], centre_b: Sequence[Any],
                        judged: dict[int, BoxSums]) -> dict[int, BoxSums]:
    """The orders where the centre's ball is not far narrower than the variation of some
    condition (:data:`CENTRE_SPREAD`: one that hardly varies on the box, or a box far
    narrower than the balls' precision), judged again around the exact ``R(x̃)``."""
    from rkcheck.evaluation.algorithm import EvaluationInterrupted
    from rkcheck.evaluation.modular import exact_condition_sums
    from rkcheck.evaluation.scaled import scaled_rational

    loose = [n for n, j in judged.items()
             if isinstance(j.centre, BallCentre) and np.any(~(j.centre.spread() <= CENTRE_SPREAD * j.variation))]
    if not loose:
        return judged
    try:
        exact = exact_condition_sums(scaled_rational(centre_A, centre_b), listing, loose)
    except EvaluationInterrupted as stop:  # every order is judged already, around the balls
        stop.finished = dict(judged)
        raise
    out = dict(judged)
    for n in loose:
        out[n] = BoxSums(ExactCentre(exact[n].integers(), exact[n].scale), judged[n].screen, judged[n].variation)
    return out


__all__ = ["BallCentre", "BoxSums", "ExactCentre", "judge_box", "centre_bits", "box_radii"]
