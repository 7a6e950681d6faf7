"""Which number context a tableau is evaluated in, and the evaluation of every condition
of a :class:`~rkcheck.trees.listing.ConditionListing` in it (definitions §5).

* **exact** — the tableau's entries are exact (rationals; number fields): residues
  modulo primes (:mod:`rkcheck.evaluation.modular`), verdicts ``holds``/``fails``;
* **ball** — anything else (rounded decimals, computed family coefficients), or on
  request: certified fixed-point balls at the working precision
  (:class:`~rkcheck.evaluation.balls.BallContext`);
* **float64** — the screen (:class:`~rkcheck.evaluation.balls.FloatContext`), for
  comparisons; never the source of a ``holds``.

This stage returns numbers (residues or enclosures); judging them is the verdict stage's
job (:mod:`rkcheck.energy`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Callable, Iterable, Mapping, Sequence

from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.balls import (
    LIMB_MAX_BITS,
    LIMB_MIN_VERTICES,
    BallContext,
    FloatContext,
)
from rkcheck.evaluation.limbs import LimbBallContext
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.protocols import BoundedSums, EnclosingContext, ExactSums
from rkcheck.evaluation.scaled import ScaledTableau
from rkcheck.evaluation.screen import ScreenContext
from rkcheck.evaluation.screened import screened_sums
from rkcheck.evaluation.values import Backend, TableauValues
from rkcheck.numbers.intervals import Interval
from rkcheck.trees.centroid import Listing
from rkcheck.trees.listing import ConditionListing


@dataclass
class Evaluation:
    """Per number of vertices: :class:`~rkcheck.evaluation.modular.ExactOrderSums` (exact)
    or the balls' order sums, each for the class representative's rooting (the listing's
    records give the designated sign)."""

    backend: Backend
    orders: Mapping[int, ExactSums | BoundedSums] = field(default_factory=dict)
    scaled: ScaledTableau | None = None


#: how far below the widest entry radius the ball arithmetic works (bits)
BALL_BITS_BELOW_RADIUS = 1000


def certified_context(A: Sequence[Sequence[Interval]], b: Sequence[Interval], bits: int,
                      vertices: int | None = None) -> EnclosingContext:
    """The ball context for trees with up to ``vertices`` vertices: int64 digit
    mid-points (:class:`~rkcheck.evaluation.limbs.LimbBallContext`, faster on large
    listings) when the listing is large and the precision and the size of the weights
    allow it, else :class:`BallContext` (``vertices=None``: always).

    Entries that are intervals (decimals read as rounded) cap the working precision at
    about 1000 bits below their widest radius: the float radii span about 2000 binary
    orders of magnitude, and precision beyond the entries' own accuracy buys nothing
    (without the cap ``--dps 700`` on a 50-digit decimal overflowed the radii)."""
    widest = max((x.rad for row in (*A, b) for x in row), default=0)
    if widest > 0:
        below = Fraction(widest).denominator.bit_length() - Fraction(widest).numerator.bit_length()
        bits = min(bits, max(below, 0) + BALL_BITS_BELOW_RADIUS)
    if vertices is not None and vertices >= LIMB_MIN_VERTICES and bits <= LIMB_MAX_BITS:
        ctx = LimbBallContext.create(A, b, bits, vertices)
        if ctx is not None:
            return ctx
    return BallContext(A, b, bits)


def ball_context(values: TableauValues, vertices: int | None = None) -> EnclosingContext:
    """The certified ball context (:func:`certified_context`:
    Python-integer or int64-digit mid-points) for trees with up to ``vertices`` vertices,
    at the reading's precision."""
    return certified_context(values.A, values.b, values.reading.ball_bits, vertices)


def float_context(values: TableauValues) -> FloatContext:
    A, b = values.tableau.enclosures(128, values.reading.decimals)
    return FloatContext(A, b)


def evaluate(listing: Listing, values: TableauValues, orders: Iterable[int] | None = None,
             progress: Callable[[int, int], None] | None = None) -> Evaluation:
    """Every condition of ``listing`` (or of the given numbers of vertices), in the
    values' backend; ``progress(done, total)`` as the work advances (passes over primes,
    or orders)."""
    if values.backend is Backend.EXACT:
        scaled = values.scaled
        return Evaluation(Backend.EXACT, exact_condition_sums(scaled, listing, orders, progress), scaled)
    assert isinstance(listing, ConditionListing), "a centroid listing is for exact checks"
    wanted = sorted(listing.orders if orders is None else orders)
    ctx = ball_context(values, vertices=wanted[-1] if wanted else None)
    on_order = None if progress is None else (lambda n, _: progress(wanted.index(n) + 1, len(wanted)))
    if isinstance(ctx, (LimbBallContext, BallContext)):
        screen = screen_for(values, wanted, ctx.bits)
        if screen is not None:
            return Evaluation(Backend.BALL, screened_sums(listing, ctx, screen, values.stages, wanted, on_order))
    return Evaluation(Backend.BALL, condition_sums(listing, ctx, values.stages, wanted, on_order))


def screen_for(values: TableauValues, wanted: list[int], bits: int) -> ScreenContext | None:
    """The float screen in front of balls of ``bits`` fixed-point bits on large listings
    (where a pass of the balls costs: from
    :data:`~rkcheck.evaluation.balls.LIMB_MIN_VERTICES` vertices), or None where it
    cannot bound these entries (:meth:`~rkcheck.evaluation.screen.ScreenContext.create`)."""
    if not wanted or wanted[-1] < LIMB_MIN_VERTICES:
        return None
    return ScreenContext.create(values.A, values.b, wanted[-1], bits)


def channels_for(values: TableauValues, order: int) -> int:
    """How many channels (prime × root) an exact check to ``order`` needs (for estimates)."""
    if values.backend is not Backend.EXACT:
        return 0
    scaled = values.scaled
    bits = scaled.decision_bits(order + 1, order + 1)
    return len(scaled.primes_for(bits)) * scaled.degree
