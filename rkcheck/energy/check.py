"""``check(tableau, options)``: every energy condition, the orders, and the AVF verdict.

This is the pure core behind ``rkcheck verify``: it takes a loaded
:class:`~rkcheck.methods.tableau.Tableau` and returns a :class:`CheckResult` (plain data
that the reports render).  It does no I/O and knows nothing of the CLI.  The tableau's
numbers are read once per check (:class:`~rkcheck.evaluation.values.TableauValues`),
evaluated over the conditions (:mod:`rkcheck.evaluation`), judged (:mod:`.judging`) and
assembled here with the tableau's own properties and certificates.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, fields
from fractions import Fraction
from typing import Any, Callable, Self, cast

from rkcheck.energy.budget import Budget, Estimate, check_budget, entries_size, estimate
from rkcheck.energy.judging import (
    Progress,
    box_directions,
    evaluate_orders,
    refine_undecided,
)
from rkcheck.energy.results import (
    Condition,
    ConditionResults,
    Failures,
    OrderCounts,
    OrderVerdicts,
    checked_through,
    energy_orders_of,
    order_verdicts,
    per_order_counts,
)
from rkcheck.errors import CheckInterrupted
from rkcheck.evaluation.algorithm import EvaluationInterrupted
from rkcheck.evaluation.backends import channels_for
from rkcheck.evaluation.values import Backend, TableauValues
from rkcheck.methods.continuous import Surrogate
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.formatting import digits_text
from rkcheck.numbers.grammar import ROUNDED_MIN_DIGITS
from rkcheck.options import CheckOptions
from rkcheck.properties import scalars as sc
from rkcheck.properties.avf import AvfVerdict, theorem1_remark
from rkcheck.properties.from_nodes import node_properties, node_quadrature_order
from rkcheck.properties.linear import LinearCertificate
from rkcheck.properties.lineintegral import Certificate
from rkcheck.properties.orders import OrderResult, classical_order, quadrature_order
from rkcheck.properties.tableau import TableauProperties, properties_of_values
from rkcheck.trees.centroid import CENTROID_FROM_ORDER, Listing, centroid_listing
from rkcheck.trees.free import FreeTree
from rkcheck.trees.listing import condition_listing
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS, UNDECIDED, State, Verdict


@dataclass
class CheckResult:
    """Everything ``verify`` reports about one tableau: conditions, orders, certificates,
    and — when the tableau's claims were judged — the claims and the file's verdict."""

    tableau: Tableau
    options: CheckOptions
    backend: Backend
    conditions: ConditionResults
    per_order: list[OrderCounts]
    energy_order: int  # proven: every condition up to it holds exactly (definitions §3, §5)
    # the largest n such that every condition up to n+1 vertices holds, exactly or to digits
    energy_order_to_digits: int
    energy_order_all: bool  # proven for every order by an exact certificate (AVF, line integral, R(z))
    quadrature: OrderResult
    classical: OrderResult
    avf: AvfVerdict | None
    # proves every order for degree m: the line-integral certificate (AVF is σ = 1) or,
    # for degree 2, the stability-function certificate
    certificate: Certificate | None
    theorem1: str | None
    warnings: list[str]
    values: TableauValues
    properties: TableauProperties
    timings: dict[str, float] = field(default_factory=dict)
    interrupted: bool = False  # Ctrl-C: only the orders in ``conditions`` were finished
    claims: list[Any] | None = None  # ClaimResult per [expect] claim, when judged
    failed: bool = False  # what the CLI's exit code 1 means under its ``--fail-on``
    _failures: Failures | None = field(default=None, repr=False)

    @property
    def failures(self) -> Failures:
        """The conditions that certainly fail, by vertices and then canonical id."""
        if self._failures is None:
            self._failures = Failures(self.conditions)
        return self._failures

    @property
    def all_hold(self) -> bool:
        return len(self.failures) == 0

    @property
    def first_failure(self) -> Condition | None:
        return self.failures[0] if len(self.failures) else None

    @property
    def min_digits(self) -> int | None:
        digits = [p.min_digits for p in self.per_order if p.min_digits is not None]
        return min(digits) if digits else None

    @property
    def energy_order_digits(self) -> int | None:
        """The digits to which the conditions beyond the proven :attr:`energy_order` (up
        to :attr:`energy_order_to_digits`) hold; None when every hold is exact."""
        top = self.energy_order_to_digits
        digits = [p.min_digits for p in self.per_order
                  if self.energy_order < p.order <= top and p.min_digits is not None]
        return min(digits) if digits else None

    @property
    def checked_through(self) -> int:
        """The largest order every condition up to which was checked: the order asked
        for, less after Ctrl-C (or past the first failure with ``--fail-fast``)."""
        return checked_through(self.per_order, self.options.order)

    @property
    def energy_order_all_digits(self) -> int | None:
        """D when a certificate of every order holds only to D digits (then
        :attr:`energy_order_all` is False: a numerical certificate proves nothing)."""
        cert = self.certificate
        if cert is None or not cert.certified or cert.verdict.state != HOLDS_TO_DIGITS:
            return None
        return cert.verdict.digits

    @property
    def certified_all(self) -> bool:
        """A certificate of every order holds: exactly, or to digits."""
        return self.energy_order_all or self.energy_order_all_digits is not None

    @property
    def energy_order_label(self) -> str:
        """``all`` (proven for every order by a certificate), ``≥ N`` (every condition up
        to the checked order N holds, not proven beyond) or the exact energy order ``n``;
        holds to digits qualify it: ``all to 15 digits``, ``1; ≥ 4 to 15 digits``,
        ``1; 4 to 15 digits`` (proven to order 1, to 15 digits up to 4)."""
        if self.energy_order_all:
            return "all"
        if self.energy_order_all_digits is not None:
            return f"all to {digits_text(self.energy_order_all_digits)}"
        reach = f"≥ {self.checked_through}" if not len(self.failures) else str(self.energy_order_to_digits)
        digits = self.energy_order_digits
        if digits is None:
            return reach
        return f"{self.energy_order}; {reach} to {digits_text(digits)}"

    @property
    def verdict(self) -> State:
        """All checked conditions at once: ``fails`` if any fails (or ``Σb ≠ 1``
        certainly), else ``holds_to_digits`` if any holds only to digits, else ``holds``."""
        return overall(self).state

    @property
    def ok(self) -> bool:
        """True when the CLI would exit 0 (``fail_on='auto'``: claims if the tableau has
        any, else every condition holds or a certificate proves them)."""
        return not self.failed

    @property
    def classical_order(self) -> int:
        return self.classical.order

    @property
    def quadrature_order(self) -> int:
        return self.quadrature.order

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state["_failures"] = None  # rebuilt on demand
        return state

    @classmethod
    def of(cls, result: "CheckResult", **changes: Any) -> Self:
        """``result`` as this class (a subclass that adds methods), with ``changes``."""
        values = {f.name: getattr(result, f.name) for f in fields(result)} | changes
        return cls(**values)


# ---------------------------------------------------------------------- check


def check(tableau: Tableau, options: CheckOptions, budget: Budget | None = None,
          progress: Callable[[int, int], None] | None = None, values: TableauValues | None = None) -> CheckResult:
    """Run the whole check of definitions §3–§5 on ``tableau``.

    ``budget``: refuse (:class:`~rkcheck.errors.ResourceError`) a check that would
    not fit, and announce a long one, before any work.  ``progress(done, total)`` as the
    evaluation advances.  ``values``: the tableau read under ``options.reading``, when
    the caller already has it (several checks of one tableau share it).  Ctrl-C raises
    :class:`CheckInterrupted` with the orders that were finished."""
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    values = values or TableauValues.of(tableau, options.reading)
    listing = _listing(values, options, budget)
    t1 = time.perf_counter()
    timings["trees"] = t1 - t0  # the listing of the conditions (JSON key kept)

    orders, interrupted, note = _judged_orders(listing, values, options, progress)
    t2 = time.perf_counter()
    timings["evaluation"] = t2 - t1

    warnings = (list(tableau.info.warnings) + values.consistency_warnings() + ([note] if note else [])
                + list(listing.store_notes))
    facts = _facts(values)
    quad = facts["quadrature"]
    classical = _memo(facts, ("classical", options.order), lambda: classical_order(values, options.order))
    # tableau-level algebra: the irreducible form, R(z), symplecticity, symmetry; the AVF
    # verdict and the certificate of every order (AVF, line integral, and for m = 2 the
    # stability function)
    surrogate = tableau.info.continuous
    # a tableau's AvfVerdict and Certificate, or a kernel's, read like them
    avf: Any
    cert: Any
    if surrogate is not None:  # a continuous method: its kernel speaks for itself, not the surrogate
        quad, props, avf, cert = _continuous_facts(surrogate, quad, options, values)
    else:
        props = _memo(facts, "properties", lambda: _properties(values, facts))
        avf, cert = props.certificates(options.degree) if options.degree is not None else (None, None)
    timings["orders_and_avf"] = time.perf_counter() - t2
    conditions = ConditionResults(listing, orders)
    per_order = per_order_counts(listing, orders)
    avf, cert = _refuted(avf, cert, conditions.first_record(FAILS))
    if tableau.rounded_digits is not None and options.decimals.rounds:
        warnings.append(
            f"decimals with >= {ROUNDED_MIN_DIGITS} significant digits (here as few as {tableau.rounded_digits}) "
            "are read as rounded to their last digit (definitions §5); --decimals exact takes them at face value"
        )
    timings["total"] = time.perf_counter() - t0
    proven, to_digits = energy_orders_of(per_order, options.order)
    result = CheckResult(
        tableau=tableau, options=options, backend=values.backend, conditions=conditions, per_order=per_order,
        energy_order=proven, energy_order_to_digits=to_digits,
        energy_order_all=bool(cert and cert.certified and cert.verdict.state == HOLDS),
        quadrature=quad, classical=classical, avf=avf, certificate=cert,
        theorem1=None if surrogate is not None else _theorem1(avf, quad, conditions, per_order, options.order),
        warnings=warnings, values=values,
        properties=props, timings=timings, interrupted=interrupted,
    )
    if interrupted:
        raise CheckInterrupted(result)
    return result


def _exact_series(values: TableauValues) -> list[Fraction] | None:
    """R(z)'s series over Q from a family's node form (None without one): the
    properties then take no product in the nodes' field for it."""
    exact = values.exact
    if exact is None or exact.nodes is None:
        return None
    series: list[Fraction] = exact.nodes.stability_series(2 * values.stages)
    return series


def _algebra(values: TableauValues) -> Any:
    """The family's node algebra, when its properties are decided there (no field)."""
    exact = values.tableau.exact_values()
    return exact.algebra if exact is not None else None


def _facts(values: TableauValues) -> dict[Any, Any]:
    """What a check computes from the tableau alone, kept on its values: the runs a file's
    claims add (other degrees and orders) share the scalars, quadrature order, classical
    order to each order and the properties — in a field of degree 48 the stability
    function and symplecticity alone take over a second."""
    facts: dict[Any, Any] = values.__dict__.setdefault("_check_facts", {})  # a frozen dataclass: its own dict
    if "quadrature" not in facts:
        algebra = _algebra(values)
        if algebra is not None:
            facts["quadrature"] = node_quadrature_order(algebra)
        else:
            facts["scalars"] = sc.tableau_values(values)  # the tableau's own scalars, once
            facts["quadrature"] = quadrature_order(*facts["scalars"])
    return facts


def _properties(values: TableauValues, facts: dict[Any, Any]) -> TableauProperties:
    algebra = _algebra(values)
    if algebra is not None:
        return node_properties(algebra)
    A, b = facts["scalars"]
    return properties_of_values(A, b, _exact_series(values))


def _memo(facts: dict[Any, Any], key: Any, compute: Callable[[], Any]) -> Any:
    if key not in facts:
        facts[key] = compute()
    return facts[key]


def check_estimate(values: TableauValues, options: CheckOptions) -> Estimate:
    """What checking ``values`` as ``options`` say costs, estimated before it starts (its
    channels, stages, precision, box directions and entries)."""
    channels = channels_for(values, options.order) if values.backend is Backend.EXACT else 0
    texts = [getattr(e, "text", "") for e in values.tableau.entries()]
    directions = box_directions(values)
    box = (len(texts), sum(map(len, texts))) if directions else None
    return estimate(options.order, options.degree, values.backend, channels, values.stages, options.dps,
                    directions, entry_bytes=entries_size(texts), box_entries=box)


def _listing(values: TableauValues, options: CheckOptions,
             budget: Budget | None) -> Listing:
    """The conditions to check, after the budget allowed them: from
    :data:`~rkcheck.trees.centroid.CENTROID_FROM_ORDER` on, an exact check enumerates
    them by centroid (the rooted trees of its top orders would take gigabytes)."""
    check_budget(check_estimate(values, options), budget, options.order)
    if values.backend is Backend.EXACT and options.order >= CENTROID_FROM_ORDER:
        return centroid_listing(options.order, options.degree)
    # built order by order as the evaluation asks: --fail-fast stops before the high orders
    return condition_listing(options.order, options.degree, lazy=True)


def _judged_orders(listing: Listing, values: TableauValues, options: CheckOptions,
                   progress: Progress | None) -> tuple[dict[int, OrderVerdicts], bool, str | None]:
    """Every condition judged — with what the balls left undecided judged again
    (:func:`~rkcheck.energy.judging.refine_undecided`) —, whether Ctrl-C cut the work
    short, and a note on that refinement."""
    try:
        orders = evaluate_orders(listing, values, options.fail_fast, progress)
    except EvaluationInterrupted as stop:
        return {n: order_verdicts(n, v) for n, v in stop.finished.items()}, True, None
    try:
        orders, note = refine_undecided(listing, values, options.fail_fast, orders)
    except KeyboardInterrupt:  # the refinement's own, or while its listing is read
        return orders, True, None
    return orders, False, note


def _continuous_facts(surrogate: Surrogate, quad: OrderResult, options: CheckOptions,
                      values: TableauValues) -> tuple[OrderResult, Any, Any, Any]:
    """A continuous method's quadrature order (the surrogate's, where its rule is exact),
    kernel properties, equals-AVF and certificate (:mod:`rkcheck.energy.continuous`)."""
    from rkcheck.energy.continuous import kernel_facts

    n = surrogate.vertices
    if quad.checked > n:  # beyond n vertices the surrogate's rule, not the method, answers
        # the failing power k = to_digits + 1 is the method's only when k <= n
        exact_failure = quad.first_failure if quad.first_failure and (quad.to_digits or 0) + 1 <= n else None
        quad = OrderResult(min(quad.order, n), n, quad.verdict, exact_failure, min(quad.to_digits or 0, n))
    box = options.decimals if surrogate.method.is_box(options.decimals) else None
    facts = kernel_facts(surrogate.method, options.degree, box, options.order + 1)
    # degree 1 has no condition and every method preserves linear energy, as a tableau's
    cert = LinearCertificate() if options.degree == 1 else facts.certificate
    return quad, facts.properties, facts.avf, cert


def _refuted(avf: AvfVerdict | None, cert: Certificate | None,
             first: FreeTree | None) -> tuple[AvfVerdict | None, Certificate | None]:
    """A certificate "to D digits" is refuted by a condition that certainly fails; an
    exact certificate cannot be, so that would be a bug."""
    if first is None:
        return avf, cert
    if avf is not None and avf.verdict.state == UNDECIDED:  # a continuous kernel's: the failure decides it
        avf = cast(Any, avf).refuted(first.id)
    if avf is not None and avf.equals_avf:
        if avf.verdict.state != HOLDS_TO_DIGITS:
            raise AssertionError(f"internal inconsistency: exact AVF but {first.id} fails")
        avf = AvfVerdict(
            avf.degree, Verdict(FAILS),
            f"A = (A·1)bᵀ only to {digits_text(avf.verdict.digits)}, and condition {first.id} certainly fails",
            avf.reduced_stages, avf.stages, avf.kept, avf.s_min, avf.notes,
        )
    if cert is not None and cert.certified:
        if cert.verdict.state != HOLDS_TO_DIGITS:
            raise AssertionError(f"internal inconsistency: exact certificate but {first.id} fails")
        cert = cert.refuted(first.id)
    return avf, cert


def _theorem1(avf: AvfVerdict | None, quad: OrderResult, conditions: ConditionResults, per_order: list[OrderCounts],
              order: int) -> str | None:
    """The Theorem 1 sentence; it concludes "beyond order N" only from exact holds
    (per-order counts, so that millions of conditions are not visited one by one).  None
    for an inconsistent method: the theorem is about consistent ones (Σb = 1)."""
    if avf is None or _sum_b_fails(quad):
        return None
    first = conditions.first_record(FAILS)
    first_label = f"condition {first.id} ({first.bracket})" if first else None
    min_digits = min((p.min_digits for p in per_order if p.min_digits is not None), default=None)
    exact_holds = min_digits is None and all(p.checked == p.conditions for p in per_order)
    return theorem1_remark(avf, first_label, order, exact_holds, min_digits)


# ---------------------------------------------------------------------- verdicts


def inconsistent(result: CheckResult) -> bool:
    """``Σb ≠ 1`` certainly: the method is not even of order 1, and fails whatever its
    energy conditions say (definitions §5.3)."""
    return _sum_b_fails(result.quadrature)


def _sum_b_fails(q: OrderResult) -> bool:
    # Σb = 1 itself failed: not merely unproven (held to digits) with a later power failing
    return q.to_digits == 0 and q.first_failure is not None


def overall(result: CheckResult) -> Verdict:
    """All checked conditions at once: fails if any fails (or ``Σb ≠ 1`` certainly),
    else the weakest digits."""
    if len(result.failures) or inconsistent(result):
        return Verdict(FAILS)
    digits = result.min_digits
    return Verdict(HOLDS_TO_DIGITS, digits) if digits is not None else Verdict(State.HOLDS)


def progress_unit(values: TableauValues, options: CheckOptions) -> str:
    """What one step of a check's ``progress(done, total)`` is: a pass over one prime
    (exact arithmetic, all orders at once), or one order (balls, and fail-fast)."""
    return "primes" if values.backend is Backend.EXACT and not options.fail_fast else "orders"


class CheckRunner:
    """``check`` with a memo per options, so that a verify run and the claim runs it
    implies share their work (same tableau, same options => same result), and one
    reading of the tableau per number reading.

    A ``progress`` that has a ``begin(label, unit)`` method hears of each check run before
    its steps (a claim on another degree is a run of its own): a progress bar then shows
    one bar per run, named, with its unit, instead of one bar that starts over."""

    def __init__(self, budget: Budget | None = None, progress: Any = None) -> None:
        self._memo: dict[tuple[int, CheckOptions], CheckResult] = {}
        self._values: dict[Any, TableauValues] = {}
        self.budget, self.progress = budget, progress

    def __call__(self, tableau: Tableau, options: CheckOptions) -> CheckResult:
        key = (id(tableau), options)  # the memo holds the tableau: its id is not reused
        if key not in self._memo:
            read = (id(tableau), options.reading)
            if read not in self._values:
                self._values[read] = TableauValues.of(tableau, options.reading)
            begin = getattr(self.progress, "begin", None)
            if callable(begin):
                degree = "all H" if options.degree is None else f"degree ≤ {options.degree}"
                begin(f"{degree}, order ≤ {options.order}", progress_unit(self._values[read], options))
            self._memo[key] = check(tableau, options, self.budget, self.progress, self._values[read])
        return self._memo[key]
