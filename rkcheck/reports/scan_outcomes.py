"""What a scan's reports say of one file's outcome document
(:func:`~rkcheck.reports.scan.outcome_docs`): its summary, broken claims and failing
conditions, and why it failed — shared by the text, CSV, JUnit and GitHub formats.
"""

from __future__ import annotations

from typing import Any


def _summary(o: dict[str, Any]) -> dict[str, Any]:
    return (o.get("result") or {}).get("summary", {})


def broken_claims(o: dict[str, Any]) -> list[dict[str, Any]]:
    return [c for c in ((o.get("result") or {}).get("claims") or []) if not c["met"]]


def failing_conditions(o: dict[str, Any], limit: int | None = 5) -> list[dict[str, Any]]:
    conds = (o.get("result") or {}).get("conditions") or []
    return [c for c in conds if c["state"] == "fails"][:limit]


def residual_text(c: dict[str, Any]) -> str:
    """A condition's residual as the JSON document gives it: the exact value when it is
    known (``-1/2880``, ``sqrt(3)/144``), else the certified ball ``mid ± radius``."""
    if c.get("residual_exact") is not None:
        return c["residual_exact"]
    return f"{c['residual']} ± {c['radius']}"


def judged_by_claims(o: dict[str, Any], fail_on: str) -> bool:
    """Whether a file's failure is about its claims (``--fail-on`` claims, or auto with
    claims) rather than its conditions."""
    return bool(broken_claims(o)) and fail_on != "conditions"


def _condition_line(c: dict[str, Any]) -> str:
    return f"condition {c['id']} {c['bracket']} (order {c['order']}) fails: R = {residual_text(c)}"


def claim_evidence(o: dict[str, Any], claim: dict[str, Any]) -> list[str]:
    """What contradicts a broken claim, from what the file's check found: the first
    failing classical or quadrature condition, or the failing energy conditions the
    claim covers (orders up to the claimed one, when the claim's degree is the one the
    conditions were checked for); never the conditions beyond what the claim says."""
    s = _summary(o)
    kind = claim["claim"]
    if kind == "classical_order" and s.get("classical_first_failure"):
        return [f"first failing classical condition: {s['classical_first_failure']}"]
    if kind == "quadrature_order" and s.get("quadrature_first_failure"):
        return [f"first failing quadrature condition: {s['quadrature_first_failure']}"]
    if kind != "energy_order" or claim["degree"] != s.get("degree"):
        return []
    limit = int(claim["claimed"]) if claim["claimed"].isdigit() else None  # "all": every order
    conds = (o.get("result") or {}).get("conditions") or []
    return [_condition_line(c) for c in conds if c["state"] == "fails" and (limit is None or c["order"] <= limit)]


def _claim_line(c: dict[str, Any]) -> str:
    return f"{c['place']}: claimed {c['claimed']}, found {c['found']}" + (f" ({c['note']})" if c.get("note") else "")


def failure_message(o: dict[str, Any], fail_on: str = "claims") -> str:
    """One line: the broken claims when the file is judged by them, else why the
    conditions fail (the first failing ones, with exact residuals when known)."""
    s = _summary(o)
    if judged_by_claims(o, fail_on):
        broken = broken_claims(o)
        if broken:
            return "; ".join(f"{c['place']}: claimed {c['claimed']}, found {c['found']}" for c in broken)
        return (s.get("require") or {}).get("reason") or "check failed"  # every claim met: the gate failed it
    fails = failing_conditions(o, 3)
    if fails:
        n = s.get("conditions_failed", len(fails))
        return (f"{n} failing condition{'s' if n != 1 else ''} (energy order {s.get('energy_order')}), first: "
                + ", ".join(f"{c['id']} {c['bracket']} (R = {residual_text(c)})" for c in fails))
    if s.get("inconsistent"):
        return "Σb ≠ 1 (certain): the method is inconsistent"
    return (s.get("require") or {}).get("reason") or "check failed"
