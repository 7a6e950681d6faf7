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

The derivatives cost one float ball per interval entry beside every weight.  On a large
listing (:data:`MAJORANT_MIN_VERTICES`) whose box has many entries, the conditions are
first judged with a bound of ``V`` along one direction
(:mod:`~rkcheck.evaluation.majorant`, ``V ≤ V̄``): where ``|R(x̃)| > V̄ + ε`` the condition
fails, as it would with ``V``; the others — the conditions the method nearly satisfies
— get every direction, on the trees their terms need
(:class:`~rkcheck.evaluation.subset.Subset`), and a decided condition gets its ``V``
when a report shows its enclosure (:class:`Refiner`, its order and the ones below in
one pass).  So the verdicts, mid-points and the decided conditions' enclosures are
those of every direction over the whole listing.  An open condition's derivatives are
the same float sums of the same terms computed in other blocks (weights in batches of
other sizes, terms binned in other chunks); where they cancel heavily their bound is
mostly rounding error, and its ``V`` can move by parts per million (1.5·10⁻⁶ relative
found): a sound bound either way, whose digits change only if it lies that close to a
power of ten.  An order whose open
conditions are not few takes every direction over the listing; a method whose small
orders leave most conditions open (checked at a degree it preserves) takes them over
the whole listing at once, as without the majorant.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cached_property
from typing import TYPE_CHECKING, Any, Callable, Sequence

import numpy as np

from rkcheck.evaluation.algorithm import EvaluationInterrupted, condition_sums
from rkcheck.evaluation.backends import certified_context
from rkcheck.evaluation.balls import ETA, INFLATE, FloatSums, U
from rkcheck.evaluation.box_sums import BallCentre, BoxSums, ExactCentre, OpenScreen
from rkcheck.evaluation.majorant import MajorantContext
from rkcheck.evaluation.protocols import EnclosingContext
from rkcheck.evaluation.slopes import (
    MAX_GRADIENT_BYTES,
    GradientContext,
    LiteralChain,
    Varies,
    balls_per_tree,
    direction_cells,
    gradient_groups,
)
from rkcheck.evaluation.subset import Subset
from rkcheck.evaluation.support import SupportContext, zero_pattern
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


def centre_bits(A: Sequence[Sequence[Interval]], b: Sequence[Interval], varies: Varies | None = None) -> int:
    """The working bits of the centre's balls: :data:`CENTRE_BITS_BEYOND_BOX` below the
    narrowest radius of an entry that is a direction (``varies``; by default any entry
    that is not a point)."""
    radii = [x.rad for x, v in direction_cells(A, b, varies) if v and x.rad > 0]
    if not radii:
        return CENTRE_BITS_BEYOND_BOX
    r = Fraction(min(radii))
    below = r.denominator.bit_length() - r.numerator.bit_length()
    return max(below, 0) + CENTRE_BITS_BEYOND_BOX


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


def as_interval(x: Any) -> Interval:
    """A face value as an interval: an exact rational as its point, a narrow enclosure of
    an irrational one as itself."""
    return x if isinstance(x, Interval) else Interval.point(Fraction(x))


def box_radii(A: Sequence[Sequence[Interval]], b: Sequence[Interval], centre_A: Sequence[Sequence[Any]],
              centre_b: Sequence[Any], ctx: GradientContext) -> np.ndarray:
    """``r_e = max |x_e − x̃_e|`` over the box (and over the enclosure of an irrational
    face value ``x̃_e``), as floats rounded up (inf past float64's range: no claim)."""
    out = []
    for i, j in ctx.a_vars:
        x, c = A[i][j], as_interval(centre_A[i][j])
        out.append(max(c.hi - x.lo, x.hi - c.lo))
    for i in ctx.b_vars:
        x, c = b[i], as_interval(centre_b[i])
        out.append(max(c.hi - x.lo, x.hi - c.lo))
    return np.array([float_above(r) for r in out], dtype=float)


def judge_box(listing: ConditionListing, A: Sequence[Sequence[Interval]], b: Sequence[Interval],
              centre_A: Sequence[Sequence[Any]], centre_b: Sequence[Any],
              orders: Sequence[int], on_order: Callable[[int, BoxSums], None] | None = None,
              chain: LiteralChain | None = None, varies: Varies | None = None) -> dict[int, BoxSums]:
    """The conditions of ``orders`` judged over the box ``(A, b)`` of intervals by the
    mean value form around ``(centre_A, centre_b)``, the face values (exact rationals, or
    narrow enclosures of irrational ones: the centre's balls then enclose them, and
    every radius covers them): ``{n: BoxSums}``.  ``on_order`` as each order is judged (when the derivatives take
    more than one pass: after the last).  With a ``chain`` (decimal literals that feed
    several entries) the variation runs along the literals: over the tableaux the
    literals allow, not over every tableau in the entries' box.  ``varies``: which entries
    are directions (by default those that are not points; an exact irrational entry,
    enclosed, is one number, not a direction).

    From :data:`MAJORANT_MIN_VERTICES` vertices, a box whose derivatives cost several
    times its values is first bounded along one direction
    (:mod:`~rkcheck.evaluation.majorant`): the conditions that bound decides fail, and
    the directions are evaluated for the others only, on the trees their terms need —
    unless they are not few (a method that satisfies many conditions)."""
    wanted = sorted(orders)
    if not wanted:
        return {}
    box = _Box(listing, A, b, centre_A, centre_b, wanted, chain, varies)
    out = _by_majorant(box, on_order)
    if out is None:
        out = _by_directions(box, on_order)
    return _exact_where_needed(listing, centre_A, centre_b, out)


class _Box:
    """What both routes of :func:`judge_box` share: the box, its radii along every
    direction, the centre's ball context and the pattern of zeros."""

    def __init__(self, listing: ConditionListing, A: Sequence[Sequence[Interval]], b: Sequence[Interval],
                 centre_A: Sequence[Sequence[Any]], centre_b: Sequence[Any], wanted: list[int],
                 chain: LiteralChain | None = None, varies: Varies | None = None):
        self.listing, self.A, self.b, self.centre_A, self.centre_b = listing, A, b, centre_A, centre_b
        self.wanted, self.s, self.chain, self.varies = wanted, len(b), chain, varies
        self.whole = GradientContext(A, b, varies=varies)
        self.groups = gradient_groups(listing, self.s, self.whole.E, self.whole.EA)
        self.radii = box_radii(A, b, centre_A, centre_b, self.whole)
        self.zeros = zero_pattern(A, b)

    @cached_property
    def centre(self) -> EnclosingContext:
        """The centre's ball context, made when a route first evaluates it (a
        :class:`Refiner` asks for derivatives only)."""
        points_A = [[as_interval(x) for x in row] for row in self.centre_A]
        return certified_context(points_A, [as_interval(x) for x in self.centre_b],
                                 centre_bits(self.A, self.b, self.varies), self.wanted[-1])

    def supported(self, ctx: Any) -> Any:
        return SupportContext(ctx, *self.zeros) if self.zeros[0].any() or self.zeros[1].any() else ctx

    def gradients(self, directions: slice | None = None) -> GradientContext:
        """The derivatives along ``directions`` (None: all), signed where a chain takes
        them along the literals."""
        return GradientContext(self.A, self.b, directions, signed=self.chain is not None, varies=self.varies)

    def variation(self, G: np.ndarray) -> np.ndarray:
        """``V = Σ_e G[:, e]·r_e`` rounded up (the products and the sum of E terms), or
        along the literals when the box has a chain."""
        if self.chain is not None:
            return self.chain.variation(G)
        result: np.ndarray = (G @ self.radii) * (1 + (self.whole.E + 2) * U) * INFLATE + ETA
        return result


def _by_directions(box: _Box, on_order: Callable[[int, BoxSums], None] | None) -> dict[int, BoxSums]:
    """Every condition with every direction: the centre and the first group of directions
    in one pass, the other groups (when their arrays would not fit at once) in more."""
    listing, s, wanted, groups = box.listing, box.s, box.wanted, box.groups
    first = box.supported(_Pair(box.centre, box.gradients(groups[0])))
    out: dict[int, BoxSums] = {}

    def judged(n: int, sums: Any, more: Sequence[Any] = ()) -> BoxSums:
        ball, (screen, G) = sums
        if more:  # each direction's column computed alone: the passes' columns side by side
            G = np.concatenate([G] + [m[n][1] for m in more], axis=1)
        return BoxSums(BallCentre(ball), screen, box.variation(G))

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
            more = [condition_sums(listing, box.supported(box.gradients(g)), s, wanted) for g in groups[1:]]
        except EvaluationInterrupted as stop:
            stop.finished = {}
            raise
        for n in wanted:
            out[n] = judged(n, raw[n], more)
            if on_order is not None:
                on_order(n, out[n])
    return out


#: the majorant decides first only for listings of at least this many vertices, where
#: the directions cost (below, a pass of them takes milliseconds)
MAJORANT_MIN_VERTICES = 15

#: ... and only when the derivatives carry at least this many times the majorant's
#: values per tree (``2·s·E_A + 2·E`` against ``2·s + 2``): decimal RK4's derivatives
#: run along b alone, and cost little more than the majorant would
MAJORANT_MIN_WORK = 4

#: the conditions the majorant leaves open in an order are evaluated with every
#: direction on the trees their terms need when they are at most one in OPEN_SHARE
#: (their trees as few, :class:`~rkcheck.evaluation.subset.Subset`), else that order
#: over the listing; the orders up to _PROBE_VERTICES vertices, evaluated first, must
#: leave at most one in _PROBE_SHARE open (a method checked at a degree it preserves
#: satisfies most conditions: every direction is needed, and the probe is all the
#: majorant costs)
OPEN_SHARE = 8
_PROBE_VERTICES = 13
_PROBE_SHARE = 4


def _by_majorant(box: _Box, on_order: Callable[[int, BoxSums], None] | None) -> dict[int, BoxSums] | None:
    """The conditions the majorant ``V̄`` decides (they fail), the others with every
    direction on the trees they need, order by order as the majorant's pass finishes
    them (``on_order`` told of each); None where that would not pay (then every
    direction goes over the whole listing)."""
    listing, s, wanted = box.listing, box.s, box.wanted
    majorant = _majorant(box)
    if majorant is None:
        return None
    pair = box.supported(_Pair(box.centre, majorant))
    probe = [n for n in wanted if n <= _PROBE_VERTICES]
    if probe:
        try:
            raw = condition_sums(listing, pair, s, probe)
        except EvaluationInterrupted as stop:  # nothing judged yet: the probe's sums are not verdicts
            stop.finished = {}
            raise
        opened = sum(int(np.count_nonzero(~BallCentre(ball).beyond(_coarse(G)))) for ball, (_, G) in raw.values())
        if opened * _PROBE_SHARE > sum(len(G) for _, (_, G) in raw.values()):
            return None
    refiner = Refiner(listing, box.A, box.b, box.centre_A, box.centre_b, box.chain, box.varies)
    out: dict[int, BoxSums] = {}

    def judged(n: int, sums: Any) -> None:
        ball, (_, G) = sums
        centre, coarse = BallCentre(ball), _coarse(G)
        decided = centre.beyond(coarse)
        variation, screen = coarse.copy(), OpenScreen(len(coarse))
        opened = np.flatnonzero(~decided)
        if len(opened):
            scr, G_open, whole = _every_direction(box, n, opened)
            variation[opened] = box.variation(G_open) if whole is None else whole[opened]
            screen = OpenScreen(len(coarse), opened, scr)
            if whole is not None:  # the order went over the listing: every V is known
                refiner.know(n, whole)
        out[n] = BoxSums(centre, screen, variation, (refiner, n, decided))
        if on_order is not None:
            on_order(n, out[n])

    try:
        condition_sums(listing, pair, s, wanted, judged)
    except EvaluationInterrupted as stop:  # the orders judged so far, around the balls' centre
        stop.finished = dict(out)
        raise
    return out


def _majorant(box: _Box) -> MajorantContext | None:
    """The majorant of the box, where it may pay: a large listing, derivatives that cost
    several times the majorant's values, and radii and corners within float64's range."""
    s, E = box.s, box.whole
    if box.wanted[-1] < MAJORANT_MIN_VERTICES or balls_per_tree(s, E.E, E.EA) < MAJORANT_MIN_WORK * (2 * s + 2):
        return None
    if not np.all(np.isfinite(box.radii)):  # a radius past float64's range: V̄ would claim nothing
        return None
    radii_A = [[0.0] * s for _ in range(s)]
    radii_b = [0.0] * s
    for r, (i, j) in zip(box.radii, E.a_vars):
        radii_A[i][j] = float(r)
    for r, i in zip(box.radii[len(E.a_vars):], E.b_vars):
        radii_b[i] = float(r)
    try:
        return MajorantContext(radii_A, radii_b, box.centre_A, box.centre_b)
    except OverflowError:  # a corner |x̃| + r past float64's range
        return None


def _coarse(G: np.ndarray) -> np.ndarray:
    """``V̄`` from the majorant's one column (already an upper bound, rounded up)."""
    result: np.ndarray = G[:, 0] * INFLATE + ETA
    return result


def _every_direction(box: _Box, n: int, opened: np.ndarray) -> tuple[FloatSums, np.ndarray, np.ndarray | None]:
    """The screen's sums and the derivatives ``G`` of the conditions ``opened`` of the
    order with ``n`` vertices along every direction: on the trees their terms need when
    they are few, else over the listing up to that order — then also the variation of
    every condition of the order (the third value; None otherwise)."""
    s, E = box.s, box.whole
    subset = Subset.build(box.listing, {n: opened}, s, OPEN_SHARE)
    if subset is not None and len(subset.trees) * balls_per_tree(s, E.E, E.EA) * 16 <= MAX_GRADIENT_BYTES:
        screen, G = subset.residues(box.supported(box.gradients()))[n]
        return screen, G, None
    passes = [condition_sums(box.listing, box.supported(box.gradients(g)), s, [n])[n] for g in box.groups]
    screen, G = passes[0][0], np.concatenate([p[1] for p in passes], axis=1)
    return FloatSums(screen.mid[opened], screen.rad[opened]), G[opened], box.variation(G)


class Refiner:
    """The variation ``V`` of every condition of an order along every direction, computed
    when a report asks for the enclosure of a condition the majorant decided (it fails
    with ``V̄``; its enclosure is ``R(x̃) ± V``, as without the majorant): the orders up to
    the one asked, not yet computed, in one pass.  Kept with the results (it pickles:
    the listing travels as its key)."""

    def __init__(self, listing: ConditionListing, A: Sequence[Sequence[Interval]], b: Sequence[Interval],
                 centre_A: Sequence[Sequence[Any]], centre_b: Sequence[Any], chain: LiteralChain | None = None,
                 varies: Varies | None = None):
        self.listing, self.A, self.b, self.centre_A, self.centre_b = listing, A, b, centre_A, centre_b
        self.chain, self.varies = chain, varies
        self._done: dict[int, np.ndarray] = {}

    def know(self, n: int, variation: np.ndarray) -> None:
        """``V`` of the order with ``n`` vertices, computed already."""
        self._done[n] = variation

    def variation(self, n: int) -> np.ndarray:
        if n not in self._done:
            box = _Box(self.listing, self.A, self.b, self.centre_A, self.centre_b, [n], self.chain, self.varies)
            todo = [k for k in self.listing.orders if k <= n and k not in self._done]
            passes = [condition_sums(self.listing, box.supported(box.gradients(g)), box.s, todo)
                      for g in box.groups]
            for k in todo:
                self._done[k] = box.variation(np.concatenate([p[k][1] for p in passes], axis=1))
        return self._done[n]


def _exact_where_needed(listing: ConditionListing, centre_A: Sequence[Sequence[Any]], centre_b: Sequence[Any],
                        judged: dict[int, BoxSums]) -> dict[int, BoxSums]:
    """The orders where the centre's ball is not far narrower than the variation of some
    condition (:data:`CENTRE_SPREAD`: one that hardly varies on the box, or a box far
    narrower than the balls' precision), judged again around the exact ``R(x̃)``."""
    from rkcheck.evaluation.modular import exact_condition_sums
    from rkcheck.evaluation.scaled import scaled_rational

    loose = [n for n, j in judged.items()
             if isinstance(j.centre, BallCentre) and np.any(~(j.centre.spread() <= CENTRE_SPREAD * j.variation))]
    if not loose or any(isinstance(x, Interval) for x in (*(x for row in centre_A for x in row), *centre_b)):
        return judged  # (an irrational centre keeps its balls: sound, if fewer digits)
    try:
        exact = exact_condition_sums(scaled_rational(centre_A, centre_b), listing, loose)
    except EvaluationInterrupted as stop:  # every order is judged already, around the balls
        stop.finished = dict(judged)
        raise
    out = dict(judged)
    for n in loose:
        out[n] = judged[n].around(ExactCentre(exact[n].integers(), exact[n].scale))
    return out


__all__ = ["BallCentre", "BoxSums", "ExactCentre", "OpenScreen", "Refiner", "judge_box", "centre_bits", "box_radii"]
