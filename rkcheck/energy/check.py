"""``check(tableau, options)``: every energy condition, the orders, and the AVF verdict.

This is the pure core behind ``rkcheck verify``: it takes a loaded
:class:`~rkcheck.methods.tableau.Tableau` and returns a :class:`CheckResult` (plain data
that the reports render).  It does no I/O and knows nothing of the CLI.

The verdicts of all conditions are kept per number of vertices as compact arrays (3.5
million conditions at order 20); a condition's record (canonical id, bracket) and its
residual are built only when someone looks at it.  Within an order, conditions are
presented by canonical id (level sequence) ascending.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Callable, Iterator, NamedTuple, Sequence

import numpy as np

from rkcheck.energy.avf import AvfVerdict, theorem1_remark
from rkcheck.energy.budget import Budget, check_budget, estimate
from rkcheck.energy.lineintegral import Certificate
from rkcheck.energy.orders import OrderResult, classical_order, quadrature_order
from rkcheck.energy import scalars as sc
from rkcheck.energy.properties import properties_of_values
from rkcheck.energy.verdicts import (
    FAILS,
    HOLDS,
    HOLDS_TO_DIGITS,
    Verdict,
    classify_bounds,
    classify_many,
)
from rkcheck.errors import CheckInterrupted  # noqa: F401 (re-exported: it lives with the errors)
from rkcheck.evaluation.algorithm import EvaluationInterrupted
from rkcheck.evaluation.backends import (
    Evaluation,
    channels_for,
    choose_backend,
    evaluate,
)
from rkcheck.methods.tableau import Tableau, consistency_warnings
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.grammar import ROUNDED_MIN_DIGITS
from rkcheck.numbers.precision import entry_bits
from rkcheck.options import DEFAULT_DPS, DEFAULT_ORDER, CheckOptions  # noqa: F401 (re-exported)
from rkcheck.trees.listing import ConditionListing, ConditionRecord, condition_listing

_STATE = (HOLDS, HOLDS_TO_DIGITS, FAILS)
_CODE = {HOLDS: 0, HOLDS_TO_DIGITS: 1, FAILS: 2}


class ConditionResult(NamedTuple):
    """One condition: its record, a certified enclosure of its residual R (for the
    designated rooting), the verdict, and the exact value of R when it is exact."""

    condition: ConditionRecord
    enclosure: Enclosure
    verdict: Verdict
    value: Any = None  # Fraction (or field element) when exact, else None


@dataclass
class OrderVerdicts:
    """The verdicts of the conditions with ``vertices`` vertices, in listing order."""

    vertices: int
    state: np.ndarray  # int8: 0 holds, 1 holds_to_digits, 2 fails
    digits: np.ndarray  # int32 (meaningful where state == 1)
    values: Any  # ExactOrderSums or list[Enclosure] (representative sign)
    _rank: np.ndarray | None = field(default=None, repr=False)  # presentation order
    _records: list | None = field(default=None, repr=False)
    _exact: list | None = field(default=None, repr=False)  # all exact values, rebuilt at once

    @property
    def order(self) -> int:
        return self.vertices - 1

    def __len__(self) -> int:
        return len(self.state)


class ConditionResults(Sequence[ConditionResult]):
    """Every checked condition, by vertices and then canonical id, built on demand."""

    def __init__(self, listing: ConditionListing, orders: dict[int, OrderVerdicts]):
        self.listing = listing
        self.orders = dict(sorted(orders.items()))
        self._offsets = np.cumsum([0] + [len(o) for o in self.orders.values()])

    def __len__(self) -> int:
        return int(self._offsets[-1])

    def _presentation(self, o: OrderVerdicts) -> np.ndarray:
        if o._rank is None:
            o._records = self.listing.records(o.vertices)
            seqs = [r.level_sequence for r in o._records]
            o._rank = np.array(sorted(range(len(o)), key=seqs.__getitem__), dtype=np.int64)
        return o._rank

    def _record(self, o: OrderVerdicts, k: int) -> ConditionRecord:
        return o._records[k] if o._records is not None else self.listing.record(o.vertices, k)

    def result(self, n: int, k: int) -> ConditionResult:
        """Condition ``k`` (listing order) of the order with ``n`` vertices."""
        o = self.orders[n]
        record = self._record(o, k)
        verdict = Verdict(_STATE[o.state[k]], int(o.digits[k]) if o.state[k] == 1 else None)
        if isinstance(o.values, list) or hasattr(o.values, "excludes_zero"):
            e = o.values[k] if isinstance(o.values, list) else o.values.enclosure(k)
            return ConditionResult(record, Enclosure(e.mid * record.flip, e.rad, e.exact), verdict)
        if o._exact is None and o._records is not None:  # a whole order is being read
            o._exact = o.values.values()
        value = (o._exact[k] if o._exact is not None else o.values.value(k)) * record.flip
        return ConditionResult(record, _enclosure_of(value), verdict, value)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        if i < 0:
            i += len(self)
        idx = int(np.searchsorted(self._offsets, i, side="right")) - 1
        o = list(self.orders.values())[idx]
        return self.result(o.vertices, int(self._presentation(o)[i - self._offsets[idx]]))

    def __iter__(self) -> Iterator[ConditionResult]:
        for o in self.orders.values():
            for k in self._presentation(o):
                yield self.result(o.vertices, int(k))

    def _positions(self, state: str) -> Iterator[tuple[int, int]]:
        """``(vertices, k)`` of the conditions in a state, in presentation order."""
        code = _CODE[state]
        for o in self.orders.values():
            hits = np.flatnonzero(o.state == code)
            if len(hits) == 0:
                continue
            seqs = {int(k): self.listing.record(o.vertices, int(k)).level_sequence for k in hits}
            for k in sorted(seqs, key=seqs.__getitem__):
                yield o.vertices, k

    def with_state(self, state: str) -> Iterator[ConditionResult]:
        """The conditions in a state, in presentation order, without building the others."""
        for n, k in self._positions(state):
            yield self.result(n, k)

    def first_record(self, state: str) -> ConditionRecord | None:
        """The record of the first condition in a state, without its value: an exact
        value in a field of high degree needs the coefficients' prime budget for the
        whole order (7 s for HBVM(6, 3) at 14 vertices), where the id needs nothing."""
        for n, k in self._positions(state):
            return self._record(self.orders[n], k)
        return None

    def count(self, state: str) -> int:
        code = _CODE[state]
        return int(sum(int(np.count_nonzero(o.state == code)) for o in self.orders.values()))


def _enclosure_of(value: Any) -> Enclosure:
    """The enclosure of an exact residual: itself for a rational, a tight certified one
    (exact flag off: it is a numerical view) for an algebraic number."""
    if isinstance(value, Fraction):
        return Enclosure.of(value)
    iv = value.enclosure(256)
    return Enclosure(iv.mid, iv.rad, False)


class Failures(Sequence[ConditionResult]):
    """The failing conditions of a result: counted at once, built only as far as read."""

    def __init__(self, results: ConditionResults):
        self._results = results
        self._count = results.count(FAILS)
        self._built: list[ConditionResult] = []
        self._source = results.with_state(FAILS)

    def __len__(self) -> int:
        return self._count

    def _build(self, upto: int) -> None:
        while len(self._built) < min(upto, self._count):
            self._built.append(next(self._source))

    def __getitem__(self, i):
        if isinstance(i, slice):
            start, stop, step = i.indices(self._count)
            self._build(stop)
            return self._built[start:stop:step]
        if i < 0:
            i += self._count
        self._build(i + 1)
        return self._built[i]

    def __iter__(self) -> Iterator[ConditionResult]:
        for i in range(self._count):
            yield self[i]

    def __eq__(self, other: object) -> bool:
        if isinstance(other, (list, tuple, Failures)):
            return len(self) == len(other) and list(self) == list(other)
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True)
class OrderCounts:
    """One row of the per-order table: conditions, checked, held, failed, weakest digits."""

    order: int
    conditions: int  # how many conditions this order has
    checked: int
    held: int
    failed: int
    min_digits: int | None  # weakest certified digits among numerically held ones


@dataclass
class CheckResult:
    """Everything ``verify`` reports about one tableau: conditions, orders, certificates."""

    tableau: Tableau
    options: CheckOptions
    backend: str  # "exact" or "ball"
    results: ConditionResults
    per_order: list[OrderCounts]
    energy_order: int
    energy_order_all: bool  # certified for every order (AVF or line-integral certificate)
    quadrature: OrderResult
    classical: OrderResult
    avf: AvfVerdict | None
    # proves every order for degree m: the line-integral certificate (AVF is σ = 1) or,
    # for degree 2, the stability-function certificate
    certificate: Certificate | None
    theorem1: str | None
    warnings: list[str]
    timings: dict[str, float] = field(default_factory=dict)
    _failures: Failures | None = field(default=None, repr=False)
    interrupted: bool = False  # Ctrl-C: only the orders in ``results`` were finished
    properties: Any = None  # rkcheck.energy.properties.TableauProperties: reduction, R(z), symplectic, symmetric

    @property
    def failures(self) -> Failures:
        if self._failures is None:
            self._failures = Failures(self.results)
        return self._failures

    @property
    def all_hold(self) -> bool:
        return len(self.failures) == 0

    @property
    def first_failure(self) -> ConditionResult | None:
        return self.failures[0] if len(self.failures) else None

    @property
    def min_digits(self) -> int | None:
        digits = [p.min_digits for p in self.per_order if p.min_digits is not None]
        return min(digits) if digits else None

    @property
    def energy_order_label(self) -> str:
        """``all`` (proven for every order by a certificate), ``≥ N`` (every condition up
        to the checked order N holds, not proven beyond) or the exact energy order ``n``."""
        if self.energy_order_all:
            return "all"
        if not len(self.failures):
            return f"≥ {self.options.order}"
        return str(self.energy_order)

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state["_failures"] = None  # a generator does not pickle; it is rebuilt on demand
        return state


# ---------------------------------------------------------------------- verdicts


def order_verdicts(n: int, values: Any) -> OrderVerdicts:
    """The verdicts of one order's residuals (definitions §5): exact residues (zero or
    not), certified balls (excludes 0, magnitude bound), or a list of enclosures."""
    if hasattr(values, "excludes_zero"):
        state, digits = classify_bounds(values.excludes_zero(), values.magnitude_bound())
        return OrderVerdicts(n, state, digits, values)
    if isinstance(values, list):
        verdicts = classify_many(values)
        state = np.array([_CODE[v.state] for v in verdicts], dtype=np.int8)
        digits = np.array([v.digits if v.digits is not None else -1 for v in verdicts], dtype=np.int32)
        return OrderVerdicts(n, state, digits, values)
    zero = values.is_zero()
    state = np.where(zero, 0, 2).astype(np.int8)
    return OrderVerdicts(n, state, np.full(len(state), -1, dtype=np.int32), values)


def per_order_counts(listing: ConditionListing, orders: dict[int, OrderVerdicts]) -> list[OrderCounts]:
    out = []
    for k, total in listing.counts_by_order().items():
        o = orders.get(k + 1)
        if o is None:
            out.append(OrderCounts(k, total, 0, 0, 0, None))
            continue
        failed = int(np.count_nonzero(o.state == 2))
        digits = o.digits[o.state == 1]
        out.append(OrderCounts(k, total, len(o), len(o) - failed, failed, int(digits.min()) if len(digits) else None))
    return out


def energy_order_of(per_order: list[OrderCounts], order: int) -> int:
    """Largest n <= order such that every condition with <= n+1 vertices holds (definitions §3)."""
    failing = [p.order for p in per_order if p.failed]
    return min(failing) - 1 if failing else order


# ---------------------------------------------------------------------- check


def evaluate_orders(listing: ConditionListing, tableau: Tableau, options: CheckOptions, enclosures=None,
                    arithmetic: str = "auto", progress=None) -> tuple[str, dict[int, OrderVerdicts]]:
    """Every condition of the listing, judged; with ``fail_fast`` only the orders up to
    the first one that has a certainly failing condition."""
    wanted = sorted(listing.orders)
    if options.fail_fast and wanted:
        # orders are cheap at the bottom and costly at the top: look one order at a time
        # until a failure, doubling the batch, so that a low failure never pays for the top
        orders: dict[int, OrderVerdicts] = {}
        backend = "exact"
        i, step = 0, 1
        while i < len(wanted):
            batch = wanted[i:i + step]
            try:
                ev: Evaluation = evaluate(listing, tableau, options.dps, options.decimals, arithmetic, batch, enclosures)
            except EvaluationInterrupted as stop:
                stop.finished = {**{n: o.values for n, o in orders.items()}, **stop.finished}
                raise
            backend = ev.backend
            for n in batch:
                orders[n] = order_verdicts(n, ev.orders[n])
            if progress is not None:
                progress(wanted.index(batch[-1]) + 1, len(wanted))
            failing = [n for n in batch if np.any(orders[n].state == 2)]
            if failing:  # keep the orders up to the first failing one: what fail-fast promises
                return backend, {n: v for n, v in orders.items() if n <= failing[0]}
            i += step
            step *= 2
        return backend, orders
    ev = evaluate(listing, tableau, options.dps, options.decimals, arithmetic, None, enclosures, progress)
    return ev.backend, {n: order_verdicts(n, v) for n, v in ev.orders.items()}


def judge_box(listing: ConditionListing, tableau: Tableau, options: CheckOptions, A, b,
              orders: dict[int, OrderVerdicts]) -> tuple[dict[int, OrderVerdicts], str | None]:
    """Decimal entries are one box of inputs (definitions §5.2): the conditions the balls
    left undecided are judged again by the mean value form around the face values
    (:mod:`rkcheck.evaluation.box`), which proves a failure on the whole box where the
    balls' dependency problem hid it.  Returns the orders and a warning when the
    refinement did not fit."""
    from rkcheck.evaluation.box import RefinedSums, box_refinement_fits, refine_box

    undecided = [n for n, o in orders.items() if np.any(o.state == 1)]
    if not undecided:
        return orders, None
    if not box_refinement_fits(listing, A, b):
        return orders, ("the box of decimal inputs is too large to bound its variation at this order: "
                        "a condition reported as holding to D digits may still fail on the whole box")
    refined = refine_box(listing, A, b, tableau.exact_A(), tableau.exact_b(), undecided)
    out = dict(orders)
    for n, ref in refined.items():
        out[n] = order_verdicts(n, RefinedSums(orders[n].values, ref))
    if options.fail_fast:
        failing = [n for n in sorted(out) if np.any(out[n].state == 2)]
        if failing:
            out = {n: v for n, v in out.items() if n <= failing[0]}
    return out, None


def sharpen_weak_holds(listing: ConditionListing, tableau: Tableau, options: CheckOptions,
                       orders: dict[int, OrderVerdicts]) -> tuple[dict[int, OrderVerdicts], str | None]:
    """On point data (no decimal box) a ball that contains 0 but is wider than 1 says
    nothing: "holds to D digits" with D ≤ 0 is not a holds (definitions §5).  Such orders
    are evaluated again at doubled precision, up to 8× ``--dps``, until every condition
    fails or holds to at least one digit.  Returns the orders and a note of the precision
    used (or of what stayed undecided)."""
    from rkcheck.options import DPS_RANGE

    def weak(out: dict[int, OrderVerdicts]) -> list[int]:
        return [n for n, o in out.items() if np.any((o.state == 1) & (o.digits <= 0))]

    todo = weak(orders)
    if not todo:
        return orders, None
    out = dict(orders)
    dps, cap = options.dps, min(8 * options.dps, DPS_RANGE[1])
    while todo and dps < cap:
        dps = min(2 * dps, cap)
        ev = evaluate(listing, tableau, dps, options.decimals, "ball", todo)
        for n in todo:
            out[n] = order_verdicts(n, ev.orders[n])
        todo = weak(out)
    if todo:
        return out, (f"some conditions of order {', '.join(str(n - 1) for n in todo)} are still undecided at "
                     f"{dps} digits (their enclosures contain 0 but are wider than 1): raise --dps")
    return out, f"the balls needed {dps} digits to decide every condition (--dps {options.dps} was not enough)"


def check(tableau: Tableau, options: CheckOptions, arithmetic: str = "auto", budget: Budget | None = None,
          progress: Callable[[int, int], None] | None = None) -> CheckResult:
    """Run the whole check of definitions §3–§5 on ``tableau``.

    ``budget``: refuse (:class:`~rkcheck.energy.budget.ResourceError`) a check that would
    not fit, and announce a long one, before any work.  ``progress(done, total)`` as the
    evaluation advances.  Ctrl-C raises :class:`CheckInterrupted` with the orders that
    were finished."""
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    kind = choose_backend(tableau, options.decimals, arithmetic)
    channels = channels_for(tableau, options.order, options.decimals, arithmetic) if kind == "exact" else 0
    check_budget(estimate(options.order, options.degree, kind, channels, tableau.stages, options.dps),
                 budget, options.order)
    listing = condition_listing(options.order, options.degree)
    t1 = time.perf_counter()
    timings["trees"] = t1 - t0  # the listing of the conditions (JSON key kept)

    bits = entry_bits(options.dps)
    A, b = tableau.enclosures(bits, options.decimals)  # once: backend, orders, certificates
    interrupted = False
    try:
        backend, orders = evaluate_orders(listing, tableau, options, (A, b), arithmetic, progress)
    except EvaluationInterrupted as stop:
        backend, interrupted = kind, True
        orders = {n: order_verdicts(n, v) for n, v in stop.finished.items()}
    box_warning = None
    if backend == "ball" and tableau.is_rational and tableau.is_box(options.decimals) and not interrupted:
        try:
            orders, box_warning = judge_box(listing, tableau, options, A, b, orders)
        except EvaluationInterrupted:
            interrupted = True
    elif backend == "ball" and not tableau.is_box(options.decimals) and not interrupted:
        try:
            orders, box_warning = sharpen_weak_holds(listing, tableau, options, orders)
        except EvaluationInterrupted:
            interrupted = True
    exact = backend == "exact"
    t2 = time.perf_counter()
    timings["evaluation"] = t2 - t1

    warnings = list(tableau.warnings) + consistency_warnings(tableau, bits, options.decimals)
    if box_warning:
        warnings.append(box_warning)
    # the tableau's own scalars, once: exact (rational or in its field) or the enclosures
    values = sc.tableau_values(tableau, A, b, exact, options.decimals)
    quad = quadrature_order(*values)
    classical = classical_order(tableau, options.order, options.dps, options.decimals, arithmetic)
    avf = cert = None
    # Tableau-level algebra (rkcheck.energy.properties): the irreducible form, R(z),
    # symplecticity, symmetry; the AVF verdict and the certificate of every order (AVF,
    # line integral, and for m = 2 the stability function). Exact for exact tableaux.
    props = properties_of_values(*values)
    if options.degree is not None:
        avf, cert = props.certificates(options.degree)
    t3 = time.perf_counter()
    timings["orders_and_avf"] = t3 - t2

    results = ConditionResults(listing, orders)
    per_order = per_order_counts(listing, orders)
    energy_order = energy_order_of(per_order, options.order)
    failures = Failures(results)
    first = results.first_record(FAILS)
    if first is not None:
        # A certificate "to D digits" is refuted by a condition that certainly fails; an
        # exact certificate cannot be, so that would be a bug.
        if avf is not None and avf.equals_avf:
            if avf.verdict.state != HOLDS_TO_DIGITS:
                raise AssertionError(f"internal inconsistency: exact AVF but {first.id} fails")
            avf = AvfVerdict(
                avf.degree, Verdict(FAILS),
                f"A = (A·1)bᵀ only to {avf.verdict.digits} digits, and condition {first.id} certainly fails",
                avf.reduced_stages, avf.stages, avf.kept, avf.s_min, avf.notes,
            )
        if cert is not None and cert.certified:
            if cert.verdict.state != HOLDS_TO_DIGITS:
                raise AssertionError(f"internal inconsistency: exact certificate but {first.id} fails")
            cert = cert.refuted(first.id)
    energy_all = bool(cert and cert.certified)
    first_label = f"condition {first.id} ({first.bracket})" if first else None
    # Theorem 1 concludes "beyond order N" only from exact holds (per-order counts, so
    # that millions of conditions are not visited one by one)
    min_digits = min((p.min_digits for p in per_order if p.min_digits is not None), default=None)
    exact_holds = min_digits is None and all(p.checked == p.conditions for p in per_order)
    remark = theorem1_remark(avf, first_label, options.order, exact_holds, min_digits) if avf else None
    if tableau.rounded_digits is not None and options.decimals in ("rounded", "auto"):
        warnings.append(
            f"decimals with >= {ROUNDED_MIN_DIGITS} significant digits (here as few as {tableau.rounded_digits}) "
            "are read as rounded to their last digit (definitions §5); --decimals exact takes them at face value"
        )
    timings["total"] = time.perf_counter() - t0
    result = CheckResult(
        tableau=tableau,
        options=options,
        backend=backend,
        results=results,
        per_order=per_order,
        energy_order=energy_order,
        energy_order_all=energy_all,
        quadrature=quad,
        classical=classical,
        avf=avf,
        certificate=cert,
        theorem1=remark,
        warnings=warnings,
        timings=timings,
        _failures=failures,
        interrupted=interrupted,
        properties=props,
    )
    if interrupted:
        raise CheckInterrupted(result)
    return result


def inconsistent(result: CheckResult) -> bool:
    """``Σb ≠ 1`` certainly: the method is not even of order 1, and fails whatever its
    energy conditions say (definitions §5.3)."""
    q = result.quadrature
    return q.order == 0 and q.first_failure is not None


@dataclass(frozen=True)
class Shortfall:
    """Why the holds of a check do not meet ``--require`` (definitions §5.3)."""

    require: str
    count: int  # conditions that hold only to too few digits (0: the certificate alone)
    examples: list[str]  # their ids, first ones in presentation order
    certificate: bool  # the certificate of every order holds only numerically

    def text(self) -> str:
        what = "a proof" if self.require == "proof" else f"{self.require.split(':')[1]} digits"
        parts = []
        if self.count:
            ids = "; ".join(self.examples) + ("; …" if self.count > len(self.examples) else "")
            parts.append(f"{self.count} condition{'s' if self.count != 1 else ''} hold only to digits ({ids})")
        if self.certificate:
            parts.append("the certificate of every order holds only to digits")
        return f"--require {self.require}: " + "; ".join(parts) + f", which is not {what}"


def requirement_shortfall(result: CheckResult) -> Shortfall | None:
    """What keeps the holds of ``result`` from meeting its ``options.require``: conditions
    that hold only to digits (``proof``) or to fewer than D (``digits:D``), or a
    certificate that is only numerical.  None when the requirement is met."""
    require = result.options.require
    if require == "any":
        return None
    need = result.options.required_digits

    def short(digits: np.ndarray) -> np.ndarray:
        return np.ones(len(digits), dtype=bool) if need is None else digits < need

    count = sum(int(np.count_nonzero((o.state == 1) & short(o.digits))) for o in result.results.orders.values())
    examples = []
    if count:
        for r in result.results.with_state(HOLDS_TO_DIGITS):
            if need is None or (r.verdict.digits or 0) < need:
                examples.append(r.condition.id)
                if len(examples) == 3:
                    break
    cert = result.certificate
    cert_short = bool(result.energy_order_all and cert is not None and cert.verdict.state == HOLDS_TO_DIGITS
                      and (need is None or (cert.verdict.digits or 0) < need))
    if not count and not cert_short:
        return None
    return Shortfall(require, count, examples, cert_short)


def overall(result: CheckResult) -> Verdict:
    """All checked conditions at once: fails if any fails (or ``Σb ≠ 1`` certainly),
    else the weakest digits."""
    if len(result.failures) or inconsistent(result):
        return Verdict(FAILS)
    digits = result.min_digits
    return Verdict(HOLDS_TO_DIGITS, digits) if digits is not None else Verdict(HOLDS)


def conditions_ok(result: CheckResult) -> bool:
    """Every checked condition holds, or a certificate proves them all; the method is
    consistent (``Σb = 1`` not certainly false); and the holds meet ``--require``."""
    if inconsistent(result):
        return False
    if not (result.all_hold or result.energy_order_all):
        return False
    return requirement_shortfall(result) is None


class CheckRunner:
    """``check`` with a memo per options, so that a verify run and the claim runs it
    implies share their work (same tableau, same options => same result)."""

    def __init__(self, budget: Budget | None = None, progress=None, arithmetic: str = "auto") -> None:
        self._memo: dict[CheckOptions, CheckResult] = {}
        self.budget, self.progress, self.arithmetic = budget, progress, arithmetic

    def __call__(self, tableau: Tableau, options: CheckOptions) -> CheckResult:
        if options not in self._memo:
            self._memo[options] = check(tableau, options, self.arithmetic, self.budget, self.progress)
        return self._memo[options]
