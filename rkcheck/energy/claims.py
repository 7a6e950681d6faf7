"""Claims judged: each ``[expect]`` claim (:mod:`rkcheck.methods.claims`) against the
check runs it needs, reported as *claimed* against *found*.

Meanings (definitions §3–§4):

* ``energy_order = n`` — exactly n: every condition with ≤ n+1 vertices holds and one
  with n+2 vertices fails (checked to order ``max(order, n+1)``).
* ``energy_order = "all"`` — energy is preserved to every order: met by the AVF
  certificate, or, without it, by every condition up to ``order`` holding, with the note
  "verified to order N, not proven beyond".
* ``avf = true|false`` — the AVF verdict for that degree.
* ``classical_order = p`` / ``quadrature_order = q`` — exactly p / q.

An order claim met only because conditions hold to D digits is met "to D digits", like a
property claim: the found column says so and the note gives the proven order.
* ``symplectic`` / ``symmetric = true|false`` — the verdicts of
  :mod:`rkcheck.properties.symplectic` on the irreducible form (``holds to D digits`` counts
  as true, with the digits in the note).
* ``stability_defect = 0`` — ``R(z)R(−z) ≡ 1``; ``{power = 2k, coefficient = "c"}`` — the
  leading term of ``R(z)R(−z) − 1`` is ``c z^2k`` (:mod:`rkcheck.properties.stability`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from typing import Any, Callable

from rkcheck.energy.budget import (
    Budget,
    check_budget,
    entries_bytes,
    estimate,
)
from rkcheck.energy.check import CheckResult, CheckRunner
from rkcheck.energy.gate import conditions_ok, requirement_shortfall
from rkcheck.errors import ResourceError, UserError
from rkcheck.methods.claims import Claim
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.formatting import digits_text
from rkcheck.numbers.reading import DecimalsMode
from rkcheck.options import CheckOptions
from rkcheck.verdicts import HOLDS_TO_DIGITS, Verdict


@dataclass(frozen=True)
class ClaimResult:
    """One claim judged: met or not, what was found, and a note."""

    claim: Claim
    met: bool
    found: str
    note: str | None = None
    digits: int | None = None  # the evidence holds only to this many digits (None: exactly)
    proven: bool = True  # False: met by the orders checked, not proven beyond them

    @property
    def name(self) -> str:
        """``energy_order = all``: the claim as its file writes it."""
        return f"{self.claim.kind} = {self.claimed}"

    @property
    def claimed(self) -> str:
        v = self.claim.value
        return str(v).lower() if isinstance(v, bool) else str(v)


# ------------------------------------------------------------------ checking


def needed_options(claims: list[Claim], base: CheckOptions) -> dict[int | None, CheckOptions]:
    """The distinct check runs the claims need: one per degree, each to the highest order
    any claim on that degree needs.  ``base`` is the run the user asked for.  A classical
    order claim needs no energy run of its own (:func:`judge` checks the rooted trees
    it needs on the base run's values)."""
    runs: dict[int | None, int] = {base.degree: base.order}
    for c in claims:
        if c.kind in ("energy_order", "avf"):
            need = c.order or base.order
            if c.kind == "energy_order" and isinstance(c.value, int):
                need = max(need, c.value + 1)
            runs[c.degree] = max(runs.get(c.degree, 0), need)
    return {deg: replace(base, degree=deg, order=order, fail_fast=False) for deg, order in runs.items()}


def judge(claim: Claim, result: CheckResult) -> ClaimResult:
    """One claim against the check run made for it (see :func:`needed_options`)."""
    if claim.kind in ("symplectic", "symmetric", "stability_defect"):
        return judge_property(claim, result)
    if claim.kind == "quadrature_order" or claim.kind == "classical_order":
        r = result.quadrature if claim.kind == "quadrature_order" else result.classical
        if claim.kind == "classical_order" and r.first_failure is None and r.checked < int(claim.value) + 1:
            from rkcheck.properties.orders import (
                classical_order,  # one order beyond the claim decides it
            )

            r = classical_order(result.values, int(claim.value) + 1)
        found = r.to_digits
        # nothing failed: at least this order, maybe more — a classical order checked no
        # further, or a kernel's rule, whose order has no bound (a tableau's s nodes stop at 2s)
        unbounded = claim.kind == "classical_order" or result.tableau.info.continuous is not None
        if unbounded and r.first_failure is None:
            return ClaimResult(claim, False, f"≥ {_reach(found, r.digits)}", f"checked to order {r.checked} only")
        return _to_digits(claim, found == claim.value, str(found), r.order, r.digits)
    if claim.kind == "avf":
        if result.avf is None:
            return ClaimResult(claim, claim.value is False, "false")
        return _yes_no(claim, result.avf.verdict, result.avf.reason)
    return _judge_energy_order(claim, result)


def _yes_no(claim: Claim, verdict: Verdict, note: str | None) -> ClaimResult:
    """A true/false claim on a property whose verdict is ``verdict``: met when it agrees,
    to the verdict's digits; a property neither shown nor refuted (``undecided``, or held
    to 0 digits) meets neither claim."""
    if not verdict.decided:
        return ClaimResult(claim, False, "undecided", note)
    digits = verdict.digits if verdict.state == HOLDS_TO_DIGITS else None
    return ClaimResult(claim, verdict.holds == claim.value, str(verdict.holds).lower(), note, digits)


def _judge_energy_order(claim: Claim, result: CheckResult) -> ClaimResult:
    n_checked = result.checked_through  # an interrupted check: the orders it finished
    found = result.energy_order_label
    cert = result.certificate
    if claim.value == "all":
        if result.energy_order_all:
            return ClaimResult(claim, True, "all", cert.claim_note if cert is not None else "certificate: every order")
        digits = result.energy_order_all_digits
        if digits is not None:
            name = cert.name.replace("certificate", "criterion") if cert is not None else None
            return _to_digits(claim, True, "all", None, digits, name)
        if not len(result.failures):
            note = f"verified to order {n_checked}, not proven beyond"
            if result.energy_order_digits is None:
                return ClaimResult(claim, True, found, note, proven=False)
            return replace(_to_digits(claim, True, f"≥ {n_checked}", result.energy_order, result.energy_order_digits,
                                      note), proven=False)
        return ClaimResult(claim, False, found)
    # len(), not first_failure: the verdict needs no exact value (check.first_record)
    if result.certified_all:
        return ClaimResult(claim, False, found)
    if not len(result.failures):
        return ClaimResult(claim, False, found, f"no condition fails up to order {n_checked}")
    reach = result.energy_order_to_digits
    return _to_digits(claim, reach == claim.value, str(reach), result.energy_order, result.energy_order_digits)


def _reach(found: int | str | None, digits: int | None) -> str:
    return str(found) if digits is None else f"{found} to {digits_text(digits)}"


def _to_digits(claim: Claim, met: bool, found: str, proven: int | None, digits: int | None,
               note: str | None = None) -> ClaimResult:
    """An order claim whose holds beyond the proven order ``proven`` are only to
    ``digits`` digits (None: all exact): found "to D digits", the proven order in the note."""
    if digits is None:
        return ClaimResult(claim, met, found, note)
    parts = [note] if note else []
    if proven is not None:
        parts.append(f"proven to order {proven} only; beyond it to {digits_text(digits)}, not a proof")
    else:
        parts.append(f"to {digits_text(digits)}, not a proof")
    return ClaimResult(claim, met, _reach(found, digits), "; ".join(parts), digits)


def judge_property(claim: Claim, result: CheckResult) -> ClaimResult:
    """A claim on the tableau's own algebra (symplectic, symmetric, stability_defect)."""
    from rkcheck.properties import scalars as sc

    props = result.properties
    if claim.kind in ("symplectic", "symmetric"):
        pv = getattr(props, claim.kind)
        return _yes_no(claim, pv.verdict, pv.reason)
    stab = props.stability
    if stab is None:  # a continuous method: its kernel has no stability function as a finite object
        raise UserError("does not apply to a continuous method (it has no stability function here); "
                        "claim it of a discretized tableau", claim.place, result.tableau.info.source)
    note = stab.defect_text()
    if stab.leading_power is None:
        return _shown(ClaimResult(claim, claim.power is None, "0", note), stab.identity)
    lead = stab.leading_coefficient
    q = sc.rational(lead)
    found = f"{q if q is not None else sc.text(lead, 12)} z^{stab.leading_power}"
    if claim.power is None or claim.power != stab.leading_power:
        return ClaimResult(claim, False, found, note)
    from rkcheck.numbers.entries import Entry

    entry = Entry.parse(claim.coefficient or "0")
    if entry.exact is not None:
        diff = lead - sc.const(entry.exact, lead)
    else:
        diff = sc.enclosure(lead, 256) - entry.enclosure(256, DecimalsMode.EXACT)
    return _shown(ClaimResult(claim, True, found, note), sc.verdict(diff))


def _shown(result: ClaimResult, verdict: Verdict) -> ClaimResult:
    """``result`` as far as ``verdict`` (that the value found is the value claimed) shows
    it: not met when it fails or decides nothing, met only to its digits when it holds
    to digits."""
    if not verdict.shown:
        return replace(result, met=False)
    return replace(result, digits=verdict.digits if verdict.state == HOLDS_TO_DIGITS else None)


def check_claims(tableau: Tableau, claims: list[Claim], base: CheckOptions,
                 run_check: Callable[[Tableau, CheckOptions], CheckResult]) -> list[ClaimResult]:
    """Judge every claim; ``run_check(tableau, options)`` is the check function (injected
    so that callers can share runs; normally :func:`rkcheck.energy.check.check`)."""
    runs = needed_options(claims, base)
    results = {deg: _claim_run(run_check, tableau, opts, base) for deg, opts in runs.items()}
    return [judge(c, results[c.degree if c.kind in ("energy_order", "avf") else base.degree]) for c in claims]


def _claim_run(run_check: Callable[[Tableau, CheckOptions], CheckResult], tableau: Tableau, opts: CheckOptions,
               base: CheckOptions) -> CheckResult:
    """A run the claims need; one too large for the machine says it is the claims' (the
    degree in the file's [expect]), not the options' the command line gave."""
    try:
        return run_check(tableau, opts)
    except ResourceError as err:
        if opts.degree == base.degree:
            raise
        bound = "every degree" if opts.degree is None else f"degree {opts.degree}"
        # lowering --degree cannot help: the claims name their own degree
        message = re.sub(r"lower --order or --degrees?\b", "lower --order", err.message)
        raise ResourceError(f"the file's [expect] claims for {bound} are checked to order {opts.order} too: "
                            f"{message}", err.place, err.source or tableau.info.source) from None


# ------------------------------------------------------------------ one file


def judge_tableau(tableau: Tableau, options: CheckOptions, fail_on: str = "auto", budget: Budget | None = None,
                  progress: Any = None, result_type: type[CheckResult] = CheckResult) -> CheckResult:
    """Check a tableau and its claims: the main run's result (as ``result_type``, a
    subclass that adds methods) with ``claims`` (None when the tableau has none) and
    ``failed`` (the file's verdict under ``fail_on``).

    The claim runs share the main run when their options coincide (one CheckRunner);
    ``budget`` and ``progress`` go to every run (:func:`rkcheck.energy.check.check`)."""
    if getattr(tableau, "is_continuous", False):  # its B-series through an exact surrogate tableau
        tableau = surrogate_within(tableau, options, list(tableau.info.claims), budget)
    runner = CheckRunner(budget, progress)
    result = runner(tableau, options)
    claims = check_claims(tableau, list(tableau.info.claims), options, runner) if tableau.info.claims else None
    require_ok = requirement_shortfall(result, claims) is None
    return result_type.of(result, claims=claims,
                          failed=file_fails(conditions_ok(result), claims, fail_on, require_ok))


def surrogate_within(method: Any, options: CheckOptions, claims: list[Claim], budget: Budget | None) -> Tableau:
    """The surrogate tableau a continuous method is checked through, built once the
    budget allows its entries: hundreds of nodes make n² entries of a thousand digits,
    which took the memory the check's own estimate then found missing (or GMP, failing
    to allocate, aborted the process)."""
    vertices, positive = vertices_needed(options, claims), in_intervals(method, options)
    if budget is not None:
        stages, characters = method.surrogate_size(vertices, positive)
        count_ = stages * (stages + 1)
        box = (count_, characters) if positive else None  # on the positive rule: a decimal box
        check_budget(estimate(options.order, options.degree, "ball" if positive else "exact", stages=stages,
                              entry_bytes=entries_bytes(count_, characters), box_entries=box),
                     replace(budget, announce=None), options.order)
    surrogate: Tableau = method.surrogate(vertices, positive)
    return surrogate


def surrogate_bytes(method: Any, vertices: int, positive: bool) -> tuple[int, int]:
    """The stages of a continuous method's surrogate exact for trees of up to
    ``vertices`` vertices, and about what its entries take, weighed before it is built."""
    stages, characters = method.surrogate_size(vertices, positive)
    return stages, entries_bytes(stages * (stages + 1), characters)


def in_intervals(method: Any, options: CheckOptions) -> bool:
    """Whether a continuous method's conditions are judged over the box of its decimals:
    then on the surrogate of positive weights.  Balls on exact data (``--arithmetic
    ball``) keep the equispaced rule: their radii start 50 digits down, where Σ|w_i| costs
    a few digits (and the check raises the precision if it must), while the positive
    rule's larger rationals cost the exact classical order 10× the time."""
    return bool(method.is_box(options.decimals))


def vertices_needed(options: CheckOptions, claims: list[Claim]) -> int:
    """The largest rooted tree whose elementary weight a check and its claims read.  An
    energy condition of a free tree with n + 1 vertices (order n) is
    ``Σ_u ±1/σ(u) Π_{t ∈ B₋(u)} a(t)`` (definitions §3): the trees of the forests
    ``B₋(u)`` have at most n vertices, as have the classical conditions to order n; an
    order claim is decided one order beyond it."""
    need = options.order
    for c in claims:
        if c.kind in ("energy_order", "avf"):
            need = max(need, c.order or options.order)
            if isinstance(c.value, int) and not isinstance(c.value, bool):
                need = max(need, c.value + 1)
        elif c.kind in ("classical_order", "quadrature_order"):
            need = max(need, int(c.value) + 1)
    return need


# ---------------------------------------------------------------- exit policy

def file_fails(conditions_ok: bool, claim_results: list[ClaimResult] | None, fail_on: str = "auto",
               require_ok: bool = True) -> bool:
    """Whether a checked file counts as failed (exit 1) under ``--fail-on``.

    ``auto`` (the default): a file with claims is judged by its claims, a file without
    claims by its conditions.  ``conditions``: any failing condition (an AVF certificate
    counts as success).  ``claims``: any broken claim.  ``never``: never fails.
    ``require_ok``: the holds and the claims met reach ``--require``
    (:func:`~rkcheck.energy.gate.requirement_shortfall`); a shortfall fails the file
    under every ``--fail-on`` but ``never``, as its name promises.
    """
    claims_ok = all(r.met for r in claim_results) if claim_results else True
    if fail_on == "never":
        return False
    if not require_ok:
        return True
    if fail_on == "claims":
        return not claims_ok
    if fail_on == "conditions":
        return not conditions_ok
    return not claims_ok if claim_results else not conditions_ok
