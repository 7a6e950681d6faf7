"""Checked conditions: one :class:`Condition` per free tree, kept compactly per order.

The verdicts of all conditions are kept per number of vertices as arrays (3.5 million
conditions at order 20, :class:`OrderVerdicts`); a :class:`Condition` — its free tree,
verdict, enclosure and exact residual — is built only when someone looks at it.  Within
an order, conditions are presented by canonical id (level sequence) ascending.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Iterator, NamedTuple, Sequence, overload

import numpy as np

from rkcheck.errors import is_digits_limit
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.trees.centroid import Listing
from rkcheck.trees.free import FreeTree
from rkcheck.verdicts import (
    FAILS,
    HOLDS_TO_DIGITS,
    State,
    Verdict,
    classify_bounds,
    classify_many,
)


def _shown(value: Any) -> str:
    try:
        return repr(value)
    except ValueError as err:
        if not is_digits_limit(err):
            raise
        return f"<{type(value).__name__} with more digits than sys.get_int_max_str_digits()>"


class Condition(NamedTuple):
    """One checked energy condition (definitions §3, §5): its free tree, its verdict, a
    certified enclosure of its residual R for the designated rooting, and R exactly
    when the check was exact (a ``Fraction`` or a field element; None otherwise)."""

    tree: FreeTree
    verdict: Verdict
    enclosure: Enclosure
    residual: Any = None

    def __repr__(self) -> str:
        # field by field as a named tuple shows itself, except a number of more digits
        # than Python writes (an echo in the REPL must not raise)
        return "Condition(" + ", ".join(f"{name}={_shown(getattr(self, name))}" for name in self._fields) + ")"

    @property
    def id(self) -> str:
        return self.tree.id

    @property
    def level_sequence(self) -> tuple[int, ...]:
        return self.tree.level_sequence

    @property
    def bracket(self) -> str:
        return self.tree.bracket

    @property
    def vertices(self) -> int:
        return self.tree.vertices

    @property
    def order(self) -> int:
        """The energy order this condition belongs to: vertices − 1."""
        return self.tree.order

    @property
    def max_degree(self) -> int:
        return self.tree.max_degree

    @property
    def state(self) -> State:
        return self.verdict.state

    @property
    def digits(self) -> int | None:
        return self.verdict.digits

    @property
    def holds(self) -> bool:
        """``holds`` or ``holds to D digits``."""
        return self.verdict.holds


@dataclass
class OrderVerdicts:
    """The verdicts of the conditions with ``vertices`` vertices, in listing order."""

    vertices: int
    state: np.ndarray  # int8 State codes
    digits: np.ndarray  # int32 (meaningful where the state is holds_to_digits)
    values: Any  # ExactOrderSums, ball order sums, or list[Enclosure] (representative sign)
    _rank: np.ndarray | None = field(default=None, repr=False)  # presentation order
    _records: list[FreeTree] | None = field(default=None, repr=False)
    _flips: list[int] | None = field(default=None, repr=False)  # the records' flips (a whole order read)
    _exact: list[Any] | None = field(default=None, repr=False)  # all exact values, rebuilt at once

    @property
    def order(self) -> int:
        return self.vertices - 1

    def __len__(self) -> int:
        return len(self.state)

    def count(self, state: State) -> int:
        return int(np.count_nonzero(self.state == state.code))

    def any(self, state: State) -> bool:
        return bool(np.any(self.state == state.code))


def classify_sums(sums: Any) -> tuple[Any, Any]:
    """(state codes, digits) of certified order sums: their magnitude bounds in the
    sums' own units where they have them (balls past float64's range: digits past 320)."""
    if hasattr(sums, "magnitude_bound_scaled"):
        bound, z = sums.magnitude_bound_scaled()
        return classify_bounds(sums.excludes_zero(), bound, z)
    return classify_bounds(sums.excludes_zero(), sums.magnitude_bound())


def order_verdicts(n: int, values: Any) -> OrderVerdicts:
    """The verdicts of one order's residuals (definitions §5): exact residues (zero or
    not), certified balls (excludes 0, magnitude bound), or a list of enclosures."""
    if hasattr(values, "excludes_zero"):
        state, digits = classify_sums(values)
        return OrderVerdicts(n, state, digits, values)
    if isinstance(values, list):
        verdicts = classify_many(values)
        state = np.array([v.state.code for v in verdicts], dtype=np.int8)
        digits = np.array([v.digits if v.digits is not None else -1 for v in verdicts], dtype=np.int32)
        return OrderVerdicts(n, state, digits, values)
    zero = values.is_zero()
    state = np.where(zero, State.HOLDS.code, State.FAILS.code).astype(np.int8)
    return OrderVerdicts(n, state, np.full(len(state), -1, dtype=np.int32), values)


def _enclosure_of(value: Any) -> Enclosure:
    """The enclosure of an exact residual: itself for a rational, a tight certified one
    (exact flag off: it is a numerical view) for an algebraic number."""
    if isinstance(value, Fraction):
        return Enclosure.of(value)
    mid, rad = value.ball(256)
    return Enclosure(mid, rad, False)


class ConditionResults(Sequence[Condition]):
    """Every checked condition, by vertices and then canonical id, built on demand."""

    def __init__(self, listing: Listing, orders: dict[int, OrderVerdicts]):
        self.listing = listing
        self.orders = dict(sorted(orders.items()))
        self._offsets = np.cumsum([0] + [len(o) for o in self.orders.values()])

    def __len__(self) -> int:
        return int(self._offsets[-1])

    def _presentation(self, o: OrderVerdicts) -> np.ndarray:
        if o._rank is None:
            named = self.listing.named(o.vertices)
            o._records, o._flips = [tree for tree, _ in named], [flip for _, flip in named]
            o._rank = self.listing.presentation(o.vertices, o._records)
        return o._rank

    def _record(self, o: OrderVerdicts, k: int) -> FreeTree:
        return o._records[k] if o._records is not None else self.listing.record(o.vertices, k)

    def result(self, n: int, k: int) -> Condition:
        """Condition ``k`` (listing order) of the order with ``n`` vertices."""
        o = self.orders[n]
        tree = self._record(o, k)
        flip = o._flips[k] if o._flips is not None else self.listing.flip(n, k)
        state = State.of_code(int(o.state[k]))
        verdict = Verdict(state, int(o.digits[k]) if state is HOLDS_TO_DIGITS else None)
        if isinstance(o.values, list) or hasattr(o.values, "excludes_zero"):
            e = o.values[k] if isinstance(o.values, list) else o.values.enclosure(k)
            return Condition(tree, verdict, Enclosure(e.mid * flip, e.rad, e.exact))
        if o._exact is None and o._records is not None:  # a whole order is being read
            o._exact = o.values.values()
        value = o._exact[k] if o._exact is not None else o.values.value(k)
        if flip < 0:  # a negation, not a product: a field element's product reduces modulo g
            value = -value
        if hasattr(value, "rational") and (q := value.rational()) is not None:
            value = q  # a rational residual of an algebraic tableau is that rational, exactly
        return Condition(tree, verdict, _enclosure_of(value), value)

    @overload
    def __getitem__(self, i: int) -> Condition: ...
    @overload
    def __getitem__(self, i: slice) -> list[Condition]: ...

    def __getitem__(self, i: int | slice) -> Condition | list[Condition]:
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        if i < 0:
            i += len(self)
        idx = int(np.searchsorted(self._offsets, i, side="right")) - 1
        o = list(self.orders.values())[idx]
        return self.result(o.vertices, int(self._presentation(o)[i - self._offsets[idx]]))

    def __iter__(self) -> Iterator[Condition]:
        for o in self.orders.values():
            for k in self._presentation(o):
                yield self.result(o.vertices, int(k))

    def _positions(self, state: State) -> Iterator[tuple[int, int]]:
        """``(vertices, k)`` of the conditions in a state, in presentation order."""
        for o in self.orders.values():
            hits = np.flatnonzero(o.state == state.code)
            if len(hits) == 0:
                continue
            seqs = {int(k): self.listing.record(o.vertices, int(k)).level_sequence for k in hits}
            for k in sorted(seqs, key=seqs.__getitem__):
                yield o.vertices, k

    def with_state(self, state: State) -> Iterator[Condition]:
        """The conditions in a state, in presentation order, without building the others."""
        for n, k in self._positions(state):
            yield self.result(n, k)

    def first_record(self, state: State) -> FreeTree | None:
        """The free tree of the first condition in a state, without its value: an exact
        value in a field of high degree needs the coefficients' prime budget for the
        whole order (7 s for HBVM(6, 3) at 14 vertices), where the id needs nothing."""
        for n, k in self._positions(state):
            return self._record(self.orders[n], k)
        return None

    def count(self, state: State) -> int:
        return sum(o.count(state) for o in self.orders.values())


class Failures(Sequence[Condition]):
    """The failing conditions of a result: counted at once, built only as far as read."""

    def __init__(self, results: ConditionResults):
        self._results = results
        self._count = results.count(FAILS)
        self._built: list[Condition] = []
        self._source = results.with_state(FAILS)

    def __len__(self) -> int:
        return self._count

    def _build(self, upto: int) -> None:
        while len(self._built) < min(upto, self._count):
            self._built.append(next(self._source))

    @overload
    def __getitem__(self, i: int) -> Condition: ...
    @overload
    def __getitem__(self, i: slice) -> list[Condition]: ...

    def __getitem__(self, i: int | slice) -> Condition | list[Condition]:
        if isinstance(i, slice):
            start, stop, step = i.indices(self._count)
            self._build(stop)
            return self._built[start:stop:step]
        if i < 0:
            i += self._count
        self._build(i + 1)
        return self._built[i]

    def __iter__(self) -> Iterator[Condition]:
        for i in range(self._count):
            yield self[i]

    def __eq__(self, other: object) -> bool:
        if isinstance(other, (list, tuple, Failures)):
            return len(self) == len(other) and list(self) == list(other)
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]

    def __getstate__(self) -> dict[str, Any]:
        # a generator does not pickle: what was built travels, the rest is rebuilt
        return {"_results": self._results, "_count": self._count, "_built": list(self._built)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._source = self._results.with_state(FAILS)
        for _ in self._built:
            next(self._source)


@dataclass(frozen=True)
class OrderCounts:
    """One row of the per-order table: conditions, checked, held, failed, weakest digits."""

    order: int
    conditions: int  # how many conditions this order has
    checked: int
    held: int
    failed: int
    min_digits: int | None  # weakest certified digits among numerically held ones


def per_order_counts(listing: Listing, orders: dict[int, OrderVerdicts]) -> list[OrderCounts]:
    out = []
    for k, total in listing.counts_by_order().items():
        o = orders.get(k + 1)
        if o is None:
            out.append(OrderCounts(k, total, 0, 0, 0, None))
            continue
        failed = o.count(FAILS)
        digits = o.digits[o.state == HOLDS_TO_DIGITS.code]
        out.append(OrderCounts(k, total, len(o), len(o) - failed, failed, int(digits.min()) if len(digits) else None))
    return out


def checked_through(per_order: list[OrderCounts], order: int) -> int:
    """The largest n <= order such that every condition of order <= n was checked: the
    order asked for, unless Ctrl-C or ``--fail-fast`` left an order out (order 1 has no
    condition, so 1 when order 2 is not finished)."""
    short = [p.order for p in per_order if p.checked < p.conditions]
    return min(short) - 1 if short else order


def energy_orders_of(per_order: list[OrderCounts], order: int) -> tuple[int, int]:
    """(proven, to digits): the largest n <= order such that every condition with <= n+1
    vertices holds exactly (definitions §3, §5: the energy order), and the largest such
    that every one holds, exactly or to digits — both within the orders every condition
    of which was checked (an order left unfinished holds nothing)."""
    reach = checked_through(per_order, order)
    failing = [p.order for p in per_order if p.failed]
    to_digits = min(failing) - 1 if failing else order
    unproven = [p.order for p in per_order if p.failed or p.min_digits is not None]
    return min(min(unproven) - 1 if unproven else order, reach), min(to_digits, reach)
