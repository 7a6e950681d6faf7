"""``check(tableau, options)``: every energy condition, the orders, and the AVF verdict.

This is the pure core behind ``rkcheck verify``: it takes a loaded
:class:`~rkcheck.methods.tableau.Tableau` and returns a :class:`CheckResult` (plain data that the
reports render).  It does no I/O and knows nothing of the CLI.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from rkcheck.energy.avf import AvfVerdict, theorem1_remark
from rkcheck.energy.lineintegral import LineIntegralCertificate
from rkcheck.energy.orders import OrderResult, classical_order, quadrature_order
from rkcheck.energy.properties import tableau_properties
from rkcheck.energy.verdicts import (
    FAILS,
    HOLDS,
    HOLDS_TO_DIGITS,
    Verdict,
    classify,
    classify_many,
    combine,
)
from rkcheck.evaluation.backends import make_backend
from rkcheck.methods.tableau import Tableau, consistency_warnings
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.grammar import ROUNDED_MIN_DIGITS
from rkcheck.numbers.precision import entry_bits
from rkcheck.options import DEFAULT_DPS, DEFAULT_ORDER, CheckOptions  # noqa: F401 (re-exported)
from rkcheck.trees.conditions import ConditionTable, EnergyCondition, condition_table


class ConditionResult(NamedTuple):
    condition: EnergyCondition
    enclosure: Enclosure
    verdict: Verdict


@dataclass(frozen=True)
class OrderCounts:
    order: int
    conditions: int  # how many conditions this order has
    checked: int
    held: int
    failed: int
    min_digits: int | None  # weakest certified digits among numerically held ones


@dataclass
class CheckResult:
    tableau: Tableau
    options: CheckOptions
    backend: str  # "exact" or "ball"
    results: list[ConditionResult]
    per_order: list[OrderCounts]
    energy_order: int
    energy_order_all: bool  # certified for every order (AVF or line-integral certificate)
    quadrature: OrderResult
    classical: OrderResult
    avf: AvfVerdict | None
    certificate: LineIntegralCertificate | None  # proves every order for degree m (AVF, line integral, stability)
    theorem1: str | None
    warnings: list[str]
    timings: dict[str, float] = field(default_factory=dict)
    properties: Any = None  # rkcheck.energy.properties.TableauProperties: reduction, R(z), symplectic, symmetric

    @property
    def failures(self) -> list[ConditionResult]:
        return [r for r in self.results if r.verdict.state == FAILS]

    @property
    def all_hold(self) -> bool:
        return not self.failures

    @property
    def first_failure(self) -> ConditionResult | None:
        fails = self.failures
        return fails[0] if fails else None

    @property
    def energy_order_label(self) -> str:
        """``all`` (proven for every order by a certificate), ``≥ N`` (every condition up
        to the checked order N holds, not proven beyond) or the exact energy order ``n``."""
        if self.energy_order_all:
            return "all"
        if self.first_failure is None:
            return f"≥ {self.options.order}"
        return str(self.energy_order)

    @property
    def min_digits(self) -> int | None:
        digits = [r.verdict.digits for r in self.results if r.verdict.state == HOLDS_TO_DIGITS]
        return min(digits) if digits else None  # type: ignore[type-var]


def evaluate_conditions(
    table: ConditionTable, backend, fail_fast: bool = False
) -> list[ConditionResult]:
    """Every condition of ``table`` on ``backend`` (weights computed once, shared)."""
    backend.tree_weights(table.trees)
    out: list[ConditionResult] = []
    if not fail_fast:
        batch = getattr(backend, "enclose_table", None)
        if batch is not None:
            encs = batch(table)
            return [ConditionResult(c, e, v) for c, e, v in zip(table.conditions, encs, classify_many(encs))]
    stop_after_order = None
    for cond in table.conditions:
        if stop_after_order is not None and cond.order > stop_after_order:
            break
        enc = backend.enclose_terms(table.trees, cond.terms, cond.denominator)
        verdict = classify(enc)
        out.append(ConditionResult(cond, enc, verdict))
        if fail_fast and verdict.state == FAILS and stop_after_order is None:
            stop_after_order = cond.order  # finish this order, so its counts are complete
    return out


def energy_order_of(results: list[ConditionResult], order: int) -> int:
    """Largest n <= order such that every condition with <= n+1 vertices holds (definitions §3)."""
    failing = [r.condition.order for r in results if r.verdict.state == FAILS]
    return min(failing) - 1 if failing else order


def per_order_counts(table: ConditionTable, results: list[ConditionResult]) -> list[OrderCounts]:
    totals = table.counts_by_order()
    out = []
    for k in sorted(totals):
        rs = [r for r in results if r.condition.order == k]
        failed = sum(1 for r in rs if r.verdict.state == FAILS)
        digits = [r.verdict.digits for r in rs if r.verdict.state == HOLDS_TO_DIGITS]
        out.append(
            OrderCounts(k, totals[k], len(rs), len(rs) - failed, failed, min(digits) if digits else None)  # type: ignore[type-var]
        )
    return out


def check(tableau: Tableau, options: CheckOptions) -> CheckResult:
    """Run the whole check of definitions §3–§5 on ``tableau``."""
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    table = condition_table(options.order, options.degree)
    t1 = time.perf_counter()
    timings["trees"] = t1 - t0

    bits = entry_bits(options.dps)
    A, b = tableau.enclosures(bits, options.decimals)  # once: backend, orders, certificates
    backend = make_backend(tableau, options.dps, options.decimals, (A, b))
    exact = backend.exact
    results = evaluate_conditions(table, backend, options.fail_fast)
    t2 = time.perf_counter()
    timings["evaluation"] = t2 - t1

    warnings = list(tableau.warnings) + consistency_warnings(tableau, bits, options.decimals)
    quad = quadrature_order(A, b, exact)
    classical = classical_order(backend, options.order)
    avf = cert = None
    # Tableau-level algebra (rkcheck.energy.properties): the irreducible form, R(z),
    # symplecticity, symmetry; the AVF verdict and the certificate of every order (AVF,
    # line integral, and for m = 2 the stability function). Exact for exact tableaux.
    props = tableau_properties(tableau, A, b, exact, options.decimals)
    if options.degree is not None:
        avf, cert = props.certificates(options.degree)
    t3 = time.perf_counter()
    timings["orders_and_avf"] = t3 - t2

    energy_order = energy_order_of(results, options.order)
    first = next((r for r in results if r.verdict.state == FAILS), None)
    if first is not None:
        # A certificate "to D digits" is refuted by a condition that certainly fails; an
        # exact certificate cannot be, so that would be a bug.
        if avf is not None and avf.equals_avf:
            if avf.verdict.state != HOLDS_TO_DIGITS:
                raise AssertionError(f"internal inconsistency: exact AVF but {first.condition.id} fails")
            avf = AvfVerdict(
                avf.degree, Verdict(FAILS),
                f"A = (A·1)bᵀ only to {avf.verdict.digits} digits, and condition {first.condition.id} certainly fails",
                avf.reduced_stages, avf.stages, avf.kept, avf.s_min, avf.notes,
            )
        if cert is not None and cert.certified:
            if cert.verdict.state != HOLDS_TO_DIGITS:
                raise AssertionError(f"internal inconsistency: exact certificate but {first.condition.id} fails")
            cert = cert.refuted(first.condition.id)
    energy_all = bool(cert and cert.certified)
    first_label = f"condition {first.condition.id} ({first.condition.bracket})" if first else None
    exact_holds = all(r.verdict.state == HOLDS for r in results)  # Theorem 1 concludes only from exact holds
    min_digits = min((r.verdict.digits for r in results if r.verdict.state == HOLDS_TO_DIGITS), default=None)
    remark = theorem1_remark(avf, first_label, options.order, exact_holds, min_digits) if avf else None
    if tableau.rounded_digits is not None and options.decimals == "rounded":
        warnings.append(
            f"decimals with >= {ROUNDED_MIN_DIGITS} significant digits (here as few as {tableau.rounded_digits}) "
            "are read as rounded to their last digit (definitions §5); --decimals exact takes them at face value"
        )
    timings["total"] = time.perf_counter() - t0
    return CheckResult(
        tableau=tableau,
        options=options,
        backend=backend.name,
        results=results,
        per_order=per_order_counts(table, results),
        energy_order=energy_order,
        energy_order_all=energy_all,
        quadrature=quad,
        classical=classical,
        avf=avf,
        certificate=cert,
        theorem1=remark,
        warnings=warnings,
        timings=timings,
        properties=props,
    )


def overall(result: CheckResult) -> Verdict:
    return combine([r.verdict for r in result.results])


def conditions_ok(result: CheckResult) -> bool:
    """Every checked condition holds, or the AVF certificate proves them all."""
    return result.all_hold or result.energy_order_all


class CheckRunner:
    """``check`` with a memo per options, so that a verify run and the claim runs it
    implies share their work (same tableau, same options => same result)."""

    def __init__(self) -> None:
        self._memo: dict[CheckOptions, CheckResult] = {}

    def __call__(self, tableau: Tableau, options: CheckOptions) -> CheckResult:
        if options not in self._memo:
            self._memo[options] = check(tableau, options)
        return self._memo[options]
