"""Stable JSON documents (schema 1).  The keys documented in docs/json-schema.md are a
public interface: keys may be added, never renamed or removed without a schema bump."""

from __future__ import annotations

from typing import Any

from rkcheck.energy.check import CheckResult, inconsistent
from rkcheck.energy.gate import conditions_ok, requirement_shortfall
from rkcheck.energy.results import Condition
from rkcheck.evaluation.values import TableauValues
from rkcheck.io.printable import printable
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.expressions import to_text
from rkcheck.numbers.formatting import ball_strings, decimal_string
from rkcheck.numbers.reading import DecimalsMode, Reading
from rkcheck.reports import jsontext
from rkcheck.reports.properties import properties_doc, stability_doc, tableau_stability
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS
from rkcheck.version import __version__

SCHEMA = 1


def dumps(doc: Any) -> str:
    return jsontext.dumps(doc)


def entry_doc(e) -> dict[str, Any]:
    return {
        "text": e.text,
        "exact": None if e.exact is None else str(e.exact),
        "algebraic": e.uses_sqrt,
        "rounded_digits": e.rounded_digits,
    }


def tableau_doc(values: TableauValues) -> dict[str, Any]:
    """The parsed tableau: every entry as written and, when rational, as an exact p/q."""
    tab = values.tableau
    return {
        "stages": tab.stages,
        "structure": tab.structure,
        "numbers": values.describe(),
        "rational": tab.is_rational,
        "constants": {k: to_text(v) for k, v in tab.info.constants.definitions.items()},
        "A": [[entry_doc(e) for e in row] for row in tab.A],
        "b": [entry_doc(e) for e in tab.b],
        "c": None if tab.c is None else [entry_doc(e) for e in tab.c],
        "family": None if tab.info.family is None else dict(tab.info.family),
    }


def method_doc(tab: Tableau) -> dict[str, Any]:
    return {"name": tab.name, "description": tab.info.description, "references": list(tab.info.references)}


def show_doc(tab: Tableau, file: str, decimals: DecimalsMode, warnings: list[str]) -> dict[str, Any]:
    """``rkcheck show --format json``."""
    values = TableauValues(tab, Reading(decimals))
    return {"schema": SCHEMA, "rkcheck": __version__, "file": printable(file), "method": method_doc(tab),
            "tableau": tableau_doc(values), "stability": stability_doc(tableau_stability(values)), "warnings": warnings}


def conditions_list_doc(listing, with_conditions: bool = True, lazy: bool = False) -> dict[str, Any]:
    """``rkcheck conditions --format json``: counts per order and (unless ``--count``) the
    condition trees, by vertices and then canonical id (``lazy``: a generator, made as
    they are written)."""
    doc: dict[str, Any] = {
        "schema": SCHEMA,
        "rkcheck": __version__,
        "order": listing.order,
        "degree": listing.degree,
        "total": len(listing),
        "counts": [{"order": k, "vertices": k + 1, "conditions": v} for k, v in listing.counts_by_order().items()],
    }
    if with_conditions:
        rows = ({"id": c.id, "level_sequence": list(c.level_sequence), "bracket": c.bracket,
                 "vertices": c.vertices, "order": c.order, "max_degree": c.max_degree, "rootings": c.rootings}
                for c in listing.sorted_records())
        doc["conditions"] = rows if lazy else list(rows)
    return doc


def residual_doc(r: Condition, dps: int) -> dict[str, Any]:
    enc = r.enclosure
    if r.residual is not None and hasattr(r.residual, "rational"):  # exact, in a number field
        q = r.residual.rational()
        if q is not None:
            return {"residual": decimal_string(q, dps), "residual_exact": str(q), "radius": "0", "digits": None}
        mid, radius = ball_strings(enc.mid, enc.rad, dps)
        return {"residual": mid, "residual_exact": r.residual.text(), "radius": radius, "digits": None}
    if enc.exact:
        residual = decimal_string(enc.mid, dps)
        return {"residual": residual, "residual_exact": str(enc.mid), "radius": "0", "digits": None}
    sig = dps
    if enc.rad > 0 and enc.mid != 0:
        # digits of the mid-point that the radius leaves meaningful, plus one
        ratio = enc.magnitude() / enc.rad
        sig = max(1, min(dps, len(str(int(ratio))) + 1))
    mid, radius = ball_strings(enc.mid, enc.rad, sig)
    return {
        "residual": mid,
        "residual_exact": None,
        "radius": radius,
        "digits": r.verdict.digits if r.verdict.state == HOLDS_TO_DIGITS else None,
    }


def condition_doc(r: Condition, dps: int) -> dict[str, Any]:
    c = r.tree
    doc = {
        "id": c.id,
        "level_sequence": list(c.level_sequence),
        "bracket": c.bracket,
        "vertices": c.vertices,
        "order": c.order,
        "max_degree": c.max_degree,
        "state": r.verdict.state,
    }
    doc.update(residual_doc(r, dps))
    return doc


def summary_doc(res: CheckResult) -> dict[str, Any]:
    o = res.options
    first = res.first_failure
    avf = res.avf
    # Ctrl-C before any failure: the orders that finished are no verdict on the method
    unfinished = res.interrupted and res.verdict != FAILS
    return {
        "verdict": "interrupted" if unfinished else res.verdict,
        "interrupted": res.interrupted,
        "energy_order": res.energy_order,
        "energy_order_to_digits": res.energy_order_to_digits,
        "energy_order_digits": res.energy_order_digits,
        "energy_order_all": res.energy_order_all,
        "energy_order_all_digits": res.energy_order_all_digits,
        "energy_order_label": res.energy_order_label,
        "order_checked": o.order,
        "degree": o.degree,
        "equals_avf": None if avf is None or not avf.verdict.decided else avf.equals_avf,
        "avf": _avf_doc(avf),
        "certificate": _certificate_doc(res.certificate),
        "theorem1": res.theorem1,
        "classical_order": res.classical.order,
        "classical_order_to_digits": res.classical.to_digits,
        "classical_order_digits": res.classical.digits,
        "classical_order_checked": res.classical.checked,
        "classical_first_failure": res.classical.first_failure,
        "quadrature_order": res.quadrature.order,
        "quadrature_order_to_digits": res.quadrature.to_digits,
        "quadrature_order_digits": res.quadrature.digits,
        "quadrature_first_failure": res.quadrature.first_failure,
        "conditions_total": sum(p.conditions for p in res.per_order),
        "conditions_checked": sum(p.checked for p in res.per_order),
        "conditions_held": sum(p.held for p in res.per_order),
        "conditions_failed": sum(p.failed for p in res.per_order),
        "min_digits": res.min_digits,
        # every condition exact, or an exact certificate of every order (and none failing)
        "proven": not unfinished and ((res.verdict == HOLDS and res.energy_order_all_digits is None)
                                      or (res.energy_order_all and res.verdict != FAILS)),
        "inconsistent": inconsistent(res),
        "require": _require_doc(res),
        "passed": conditions_ok(res) and not unfinished,
        "first_failure": None
        if first is None
        else {"id": first.id, "bracket": first.bracket, "order": first.order},
        "per_order": [_order_doc(p) for p in res.per_order],
    }


def _avf_doc(avf: Any) -> dict[str, Any] | None:
    if avf is None:
        return None
    return {
        "state": avf.verdict.state,
        "digits": avf.verdict.digits,
        "reason": avf.reason,
        "stages": avf.stages,
        "reduced_stages": avf.reduced_stages,
        "kept_stages": list(avf.kept),
        "s_min": avf.s_min,
        "notes": avf.notes,
    }


def _certificate_doc(certificate: Any) -> dict[str, Any] | None:
    if certificate is None:
        return None
    return {
        "kind": certificate.kind,  # avf / line_integral / stability / null
        "sigma": certificate.sigma,
        "state": certificate.verdict.state,
        "digits": certificate.verdict.digits,
        "reason": certificate.reason,
    }


def _order_doc(p: Any) -> dict[str, Any]:
    return {
        "order": p.order,
        "vertices": p.order + 1,
        "conditions": p.conditions,
        "checked": p.checked,
        "held": p.held,
        "failed": p.failed,
        "min_digits": p.min_digits,
    }


def _require_doc(res: CheckResult) -> dict[str, Any]:
    short = requirement_shortfall(res)
    return {
        "level": res.options.require,
        "met": short is None,
        "unproven": 0 if short is None else short.count,
        "examples": [] if short is None else short.examples,
        "certificate_unproven": False if short is None else short.certificate,
        "reason": None if short is None else short.text(),
    }


def claims_doc(claim_results) -> list[dict[str, Any]] | None:
    if claim_results is None:
        return None
    return [
        {
            "claim": r.claim.kind,
            "place": r.claim.place,
            "degree": r.claim.degree,
            "order": r.claim.order,
            "claimed": r.claimed,
            "found": r.found,
            "met": r.met,
            "note": r.note,
        }
        for r in claim_results
    ]


def check_doc(res: CheckResult, failing_only: bool = False, lazy: bool = False) -> dict[str, Any]:
    """The per-file object of ``verify --format json`` (also used by ``scan``);
    ``failing_only``: its ``conditions`` the failing ones only (what a scan's text
    report reads of them); ``lazy``: they are a generator, made as they are written
    (:func:`rkcheck.reports.jsontext.chunks`)."""
    o = res.options
    claim_results = res.claims
    summary = summary_doc(res)
    summary.update(properties_doc(res))  # reduction, symplectic, symmetric, stability, error_constant
    summary["claims_ok"] = None if claim_results is None else all(r.met for r in claim_results)
    conditions = (condition_doc(r, o.dps) for r in (res.failures if failing_only else res.conditions))
    return {
        "schema": SCHEMA,
        "rkcheck": __version__,
        "file": printable(res.tableau.info.source),
        "method": method_doc(res.tableau),
        "tableau": _tableau_summary(res),
        "options": {
            "degree": o.degree,
            "order": o.order,
            "dps": o.dps,
            "decimals": o.decimals,
            "require": o.require,
            "backend": res.backend,
            "fail_fast": o.fail_fast,
        },
        "summary": summary,
        "claims": claims_doc(claim_results),
        "conditions": conditions if lazy else list(conditions),
        "warnings": res.warnings,
        "timings": {k: round(v, 6) for k, v in res.timings.items()},
        "conditions_complete": True,  # false only where a writer was interrupted within the list
    }


def _tableau_summary(res: Any) -> dict[str, Any]:
    """``tableau`` of the verify document; a continuous-stage method adds its kernel (the
    stage count is None: its B-series comes from a surrogate, not from stages)."""
    surrogate = res.tableau.info.continuous
    if surrogate is None:
        return {"stages": res.tableau.stages, "structure": res.tableau.structure, "numbers": res.values.describe()}
    m = surrogate.method
    k = m.kernel
    return {
        "stages": None, "structure": "continuous", "numbers": res.values.describe(),
        "kernel": {"A": m.A, "b": m.b, "M": None if m.M is None else [list(r) for r in m.M],
                   "degree_tau": k.deg_tau, "degree_sigma": k.deg_sigma, "degree_b": k.deg_b},
        "surrogate": {"nodes": surrogate.nodes, "exact_to_vertices": surrogate.vertices,
                      "rule": "positive" if surrogate.positive else "equispaced"},
    }
