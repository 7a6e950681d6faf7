"""Certified balls behind the float screen: most conditions of a method fail, and a float
decides that as surely as a ball (definitions §5).

:func:`screened_sums` evaluates every condition on the a-priori float screen
(:class:`~rkcheck.evaluation.screen.ScreenContext`), then only the conditions it leaves
open — those whose float enclosure contains 0: the ones the method satisfies, and any
too small for a float to tell — in the certified balls, on the trees their terms need
(:class:`~rkcheck.evaluation.subset.Subset`, the same recurrences as a pass over the
listing).  A condition the screen decides fails; its ball (the value a report shows)
is computed when asked for, in one pass for its order and every order below that has
not been computed, so that a report that shows a few failing conditions of the low
orders pays for those orders alone.

The screen gives way to one pass of the balls over everything when it would not save
time: as soon as an order of many conditions has more than one open condition in
:data:`OPEN_SHARE` (a method that satisfies many conditions — every energy-preserving
one: the screen then stops at a low order), or when the open conditions' terms or
trees are not few (:meth:`~rkcheck.evaluation.subset.Subset.build`).
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np

from rkcheck.evaluation.algorithm import EvaluationInterrupted, condition_sums
from rkcheck.evaluation.protocols import BoundedSums, SubsetContext
from rkcheck.evaluation.screen import ScreenContext
from rkcheck.evaluation.subset import Subset
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.trees.listing import ConditionListing

#: the screen goes on while at most one condition in this many is left open per order
#: (the low orders of a method that fails at its top ones leave a few percent open)
OPEN_SHARE = 8
#: orders with fewer conditions than this are not counted against the share
_SMALL_ORDER = 1024


class _ManyOpen(Exception):
    """The screen leaves too many conditions open to pay."""


class _Balls:
    """The balls of the screened conditions, order by order as they are asked for."""

    def __init__(self, listing: ConditionListing, ctx: SubsetContext, s: int, wanted: list[int]):
        self.listing, self.ctx, self.s, self.wanted = listing, ctx, s, wanted
        self.orders: dict[int, BoundedSums] = {}

    def of(self, n: int) -> BoundedSums:
        if n not in self.orders:
            missing = [m for m in self.wanted if m <= n and m not in self.orders]
            self.orders.update(condition_sums(self.listing, self.ctx, self.s, missing))
        return self.orders[n]


class ScreenedSums:
    """The conditions of one order: decided by the screen, or by their balls where it
    left them open (``open``: their indices, sorted).  What
    :func:`~rkcheck.energy.results.order_verdicts` reads: ``excludes_zero``,
    ``magnitude_bound``, ``enclosure`` — the enclosure of a condition the screen decided
    is its ball, computed on first use (module docstring)."""

    def __init__(self, n: int, screen: Any, open_: np.ndarray, balls: Any, whole: _Balls):
        self.n, self.screen, self.open, self.balls, self.whole = n, screen, open_, balls, whole

    def __len__(self) -> int:
        return len(self.screen)

    def excludes_zero(self) -> np.ndarray:
        out: np.ndarray = self.screen.excludes_zero()
        if len(self.open):
            out[self.open] = self.balls.excludes_zero()
        return out

    def magnitude_bound(self) -> np.ndarray:
        """The balls' bounds where they decide; the screen's elsewhere (conditions that
        fail: their bound gives no digits)."""
        out: np.ndarray = self.screen.magnitude_bound()
        if len(self.open):
            out[self.open] = self.balls.magnitude_bound()
        return out

    def enclosure(self, k: int) -> Enclosure:
        i = int(np.searchsorted(self.open, k))
        if i < len(self.open) and self.open[i] == k:
            enclosure: Enclosure = self.balls.enclosure(i)
            return enclosure
        return self.whole.of(self.n).enclosure(k)


def screened_sums(listing: ConditionListing, ctx: SubsetContext, screen: ScreenContext, s: int,
                  wanted: list[int], on_order: Callable[[int, Any], None] | None = None) -> dict[int, Any]:
    """``{vertices: sums}`` of ``wanted`` as :func:`~rkcheck.evaluation.algorithm.condition_sums`
    gives them in the balls ``ctx`` — the same verdicts, digits and enclosures — through
    the float ``screen`` where it pays (module docstring).  ``on_order(n, sums)`` as the
    screen finishes each order."""
    screens: dict[int, Any] = {}

    def screened(n: int, sums: Any) -> None:
        left = len(sums) - int(np.count_nonzero(sums.excludes_zero()))
        if len(sums) >= _SMALL_ORDER and left * OPEN_SHARE > len(sums):
            raise _ManyOpen
        screens[n] = sums
        if on_order is not None:
            on_order(n, sums)

    try:
        condition_sums(listing, screen, s, wanted, screened)
    except _ManyOpen:  # the orders already reported are not reported twice
        return condition_sums(listing, ctx, s, wanted, None if on_order is None else
                              (lambda n, sums: None if n in screens else on_order(n, sums)))
    except EvaluationInterrupted:
        # the screen's enclosures are certified: the finished orders stand as they are
        raise EvaluationInterrupted(dict(screens)) from None
    opened = {n: np.flatnonzero(~screens[n].excludes_zero()) for n in wanted}
    subset = Subset.build(listing, {n: k for n, k in opened.items() if len(k)}, s)
    if subset is None:
        return condition_sums(listing, ctx, s, wanted)
    try:
        balls = subset.residues(ctx)
    except KeyboardInterrupt:
        raise EvaluationInterrupted(dict(screens)) from None
    whole = _Balls(listing, ctx, s, wanted)
    return {n: ScreenedSums(n, screens[n], opened[n], balls.get(n), whole) for n in wanted}
