"""Conditions evaluated and judged, order by order (definitions §5).

:func:`evaluate_orders` evaluates the conditions in the backend of the tableau's values
and turns each order's residuals into verdicts; :func:`refine_undecided` judges again
what the balls left open: a box of decimal inputs by the mean value form over the whole
box, point data at a higher precision.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Callable, Mapping

import numpy as np

from rkcheck.energy.results import OrderVerdicts, order_verdicts
from rkcheck.evaluation.algorithm import EvaluationInterrupted
from rkcheck.evaluation.backends import evaluate
from rkcheck.evaluation.box import centre_bits, judge_box
from rkcheck.evaluation.slopes import direction_cells
from rkcheck.evaluation.values import Backend, NumberKind, TableauValues
from rkcheck.numbers.reading import Arithmetic, DecimalsMode
from rkcheck.options import DPS_RANGE
from rkcheck.trees.centroid import Listing
from rkcheck.trees.listing import ConditionListing
from rkcheck.verdicts import FAILS, HOLDS_TO_DIGITS

#: ``progress(done, total)``: told as orders (or passes) finish
Progress = Callable[[int, int], None]


def evaluate_orders(listing: Listing, values: TableauValues, fail_fast: bool = False,
                    progress: Progress | None = None) -> dict[int, OrderVerdicts]:
    """Every condition of the listing, judged; with ``fail_fast`` only the orders up to
    the first one that has a certainly failing condition."""
    wanted = sorted(listing.orders)
    values = _as_sharp_as_the_box(values)  # once, not at every batch of orders
    if not (fail_fast and wanted):
        whole = _order_sums(listing, values, None, progress)
        return {n: order_verdicts(n, v) for n, v in whole.items()}
    # orders are cheap at the bottom and costly at the top: look one order at a time
    # until a failure, doubling the batch, so that a low failure never pays for the top
    orders: dict[int, OrderVerdicts] = {}
    i, step = 0, 1
    while i < len(wanted):
        batch = wanted[i:i + step]
        try:
            sums = _order_sums(listing, values, batch)
        except EvaluationInterrupted as stop:
            stop.finished = {**{n: o.values for n, o in orders.items()}, **stop.finished}
            raise
        for n in batch:
            orders[n] = order_verdicts(n, sums[n])
        if progress is not None:
            progress(wanted.index(batch[-1]) + 1, len(wanted))
        if any(orders[n].any(FAILS) for n in batch):
            return _up_to_first_failure(orders)
        i += step
        step *= 2
    return orders


def _order_sums(listing: Listing, values: TableauValues, orders: list[int] | None,
                progress: Progress | None = None) -> Mapping[int, Any]:
    """The residuals of ``orders`` (None: all of the listing's): a box of decimal inputs judged over the whole box
    (definitions §5.2; :func:`~rkcheck.evaluation.box.judge_box`), anything else
    evaluated in its backend.  ``progress(done, total)`` as orders (or passes) finish.
    Ctrl-C is an :class:`EvaluationInterrupted` wherever it comes — also while the
    listing of the orders is still being built, before any of them is evaluated."""
    try:
        return _sums_of(listing, values, orders, progress)
    except EvaluationInterrupted:
        raise
    except KeyboardInterrupt:
        raise EvaluationInterrupted({}) from None


def _sums_of(listing: Listing, values: TableauValues, orders: list[int] | None,
             progress: Progress | None) -> Mapping[int, Any]:
    if not judged_over_box(values):
        return evaluate(listing, values, orders, progress).orders
    assert isinstance(listing, ConditionListing), "a centroid listing is for exact checks"
    wanted = sorted(listing.orders if orders is None else orders)
    on_order = None if progress is None else (lambda n, _: progress(wanted.index(n) + 1, len(wanted)))
    centre_A, centre_b = _centre(values)
    return judge_box(listing, values.A, values.b, centre_A, centre_b, wanted, on_order, values.literal_chain,
                     values.varies)


def _centre(values: TableauValues) -> tuple[list[list[Any]], list[Any]]:
    """The centre of the box: the entries with each literal at the middle of the numbers
    it stands for (the face value of a rounded decimal; the middle of a double's rounding
    interval, which is not centred on the decimal naming the double — about the face
    value the box would be wider than it is, and a condition nonzero on all of it could
    hold "to digits").  Exact rationals, or, with a square root of a decimal or an exact
    root beside the decimals, enclosures far narrower than the box (the centre's own
    precision, :func:`centre_bits`, and more)."""
    tab = values.tableau
    mode = values.reading.decimals
    if tab.is_rational:  # the centre too: literals' middles are rationals
        return ([[_entry_centre(e, 64, mode).lo for e in row] for row in tab.A],
                [_entry_centre(e, 64, mode).lo for e in tab.b])
    bits = centre_bits(values.A, values.b, values.varies) + 64
    return [[_entry_centre(e, bits, mode) for e in row] for row in tab.A], [_entry_centre(e, bits, mode) for e in tab.b]


def _entry_centre(entry: Any, bits: int, mode: DecimalsMode) -> Any:
    return entry.centre(bits, mode) if entry.is_box(mode) else entry.enclosure(bits, DecimalsMode.EXACT)


def box_order(listing: ConditionListing, values: TableauValues, n: int) -> dict[int, OrderVerdicts]:
    """The conditions with ``n`` vertices of a decimal box judged over the whole box
    (:func:`judged_over_box`), as the check judges them."""
    return {n: order_verdicts(n, _order_sums(listing, values, [n])[n])}


def box_directions(values: TableauValues) -> int:
    """The interval entries of a decimal box judged over the whole box (the directions
    of its derivatives), 0 for anything else."""
    if not judged_over_box(values):
        return 0
    return sum(v for _, v in direction_cells(values.A, values.b, values.varies))


def judged_over_box(values: TableauValues) -> bool:
    """Decimal entries that stand for intervals: one box of inputs judged jointly, around
    its face values (rational, or enclosed where a root makes them irrational; a rounded
    decimal is never promoted to a number field)."""
    return _box_of_inputs(values) and _radii_within_floats(values)


def _box_of_inputs(values: TableauValues) -> bool:
    return values.backend is Backend.BALL and values.kind is NumberKind.BOX


#: the narrowest entry radius the joint box takes: its variation V is a float64 sum of
#: derivatives times radii, so a radius near float64's smallest numbers (decimals of more
#: than about 290 digits) would floor V at 2^−1074 and cap every verdict near 320
#: digits; such boxes are judged by the certified balls, whose radii are scaled
BOX_MIN_RADIUS = Fraction(1, 1 << 960)


def _radii_within_floats(values: TableauValues) -> bool:
    """Every direction's radius within float64's range (an exact irrational entry,
    enclosed as narrowly as ``--dps`` asks, is no direction)."""
    return all(x.rad >= BOX_MIN_RADIUS for x, varies in direction_cells(values.A, values.b, values.varies)
               if varies and x.rad)


def _as_sharp_as_the_box(values: TableauValues) -> TableauValues:
    """A box left to the balls (radii below float64's range) at the precision the box's
    own centre would have had — past its narrowest radius (:func:`centre_bits`), not the
    default 50 digits, which would cap a 300-digit input's verdicts near 64 digits."""
    if not _box_of_inputs(values) or _radii_within_floats(values):
        return values
    dps = min(max(values.reading.dps, math.ceil(centre_bits(values.A, values.b, values.varies) * math.log10(2)) + 1), DPS_RANGE[1])
    return values if dps == values.reading.dps else TableauValues.of(values.tableau, values.reading.at(dps))


def _up_to_first_failure(orders: dict[int, OrderVerdicts]) -> dict[int, OrderVerdicts]:
    """The orders up to the first one with a failing condition: what fail-fast promises."""
    failing = [n for n in sorted(orders) if orders[n].any(FAILS)]
    return {n: o for n, o in orders.items() if n <= failing[0]} if failing else orders


def refine_undecided(listing: Listing, values: TableauValues, fail_fast: bool,
                     orders: dict[int, OrderVerdicts]) -> tuple[dict[int, OrderVerdicts], str | None]:
    """What the balls left undecided on point data, judged again at a higher precision
    (:func:`sharpen_weak_holds`).  A box of decimal inputs was judged over the whole box
    already.  Returns the orders and a note for the report."""
    if values.backend is not Backend.BALL or values.kind is NumberKind.BOX:
        return orders, None
    return sharpen_weak_holds(listing, values, orders)


def sharpen_weak_holds(listing: Listing, values: TableauValues,
                       orders: dict[int, OrderVerdicts]) -> tuple[dict[int, OrderVerdicts], str | None]:
    """On point data (no decimal box) a ball that contains 0 but is wider than 1 says
    nothing: "holds to D digits" with D ≤ 0 is not a holds (definitions §5).  Such orders
    are evaluated again at doubled precision, up to 8× the working precision, until every
    condition fails or holds to at least one digit.  Returns the orders and a note of the
    precision used (or of what stayed undecided)."""

    def weak(out: dict[int, OrderVerdicts]) -> list[int]:
        return [n for n, o in out.items() if np.any((o.state == HOLDS_TO_DIGITS.code) & (o.digits <= 0))]

    todo = weak(orders)
    if not todo:
        return orders, None
    out = dict(orders)
    base = values.reading.dps
    dps, cap = base, min(8 * base, DPS_RANGE[1])
    while todo and dps < cap:
        dps = min(2 * dps, cap)
        sharper = TableauValues.of(values.tableau, values.reading.at(dps).using(Arithmetic.BALL))
        ev = evaluate(listing, sharper, todo)
        for n in todo:
            out[n] = order_verdicts(n, ev.orders[n])
        todo = weak(out)
    if todo:
        return out, (f"some conditions of order {', '.join(str(n - 1) for n in todo)} are still undecided at "
                     f"{dps} digits (their enclosures contain 0 but are wider than 1): raise --dps")
    return out, f"the balls needed {dps} digits to decide every condition (--dps {base} was not enough)"
