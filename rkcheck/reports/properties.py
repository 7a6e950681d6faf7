"""The tableau's own properties in reports: the stage reduction, symplecticity, symmetry,
the stability function R(z) and the energy error constant (text rows and JSON keys).

JSON (added to ``summary``; keys are a public interface, see docs/json-schema.md):

* ``reduction``: ``stages``, ``reduced_stages``, ``classes`` (1-based original stages of
  each reduced stage), ``dropped`` (stages dropped), ``cancelled`` (the merged stages
  among them: stages merged into one that nothing uses and whose weights cancel), ``exact``;
* ``symplectic`` / ``symmetric``: ``state``, ``digits``, ``reason``; symplectic adds
  ``defect`` (largest |entry| of BA + AᵀB − bbᵀ, exact text or decimal) and
  ``defect_entry``; symmetric adds ``permutation``;
* ``stability``: ``R`` (text), ``numerator``/``denominator`` (coefficient texts, ascending
  powers, or null), ``identity`` (``state``, ``digits`` of R(z)R(−z) ≡ 1), ``defect``
  (text of R(z)R(−z) − 1), ``leading_power``, ``leading_coefficient``,
  ``quadratic_energy_order`` (proven: null = every order, exactly),
  ``quadratic_energy_order_to_digits`` and ``quadratic_energy_order_digits`` (the order
  reached counting coefficients that vanish only to digits, and those digits);
* ``error_constant``: null, or ``norm`` ("euclidean"), ``degree``, ``energy_order``,
  ``order``, ``conditions``, ``failing``, ``value`` (decimal), ``squared`` (exact p/q or
  null), ``lower``, ``upper``.
"""

from __future__ import annotations

from typing import Any

from rich.text import Text

from rkcheck.energy.error_constants import ErrorConstant, error_constant
from rkcheck.evaluation.values import TableauValues
from rkcheck.numbers.formatting import decimal_string
from rkcheck.properties import scalars as sc
from rkcheck.properties.stability import (
    StabilityFunction,
    stability_function,
    stability_of_series,
)
from rkcheck.verdicts import FAILS, HOLDS

_SUP = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")
STYLE = {HOLDS: "green", "holds_to_digits": "yellow", FAILS: "red"}


def _coefficient_text(x) -> str:
    q = sc.rational(x)
    if q is not None:
        return str(q)
    if sc.is_interval(x):
        return sc.text(x, 20)
    return sc.exact_text(x)


def stability_doc(stab: StabilityFunction) -> dict[str, Any]:
    return {
        "R": stab.text(),
        "numerator": None if stab.numerator is None else [_coefficient_text(a) for a in stab.numerator],
        "denominator": None if stab.denominator is None else [_coefficient_text(a) for a in stab.denominator],
        "identity": {"state": stab.identity.state, "digits": stab.identity.digits},
        "defect": stab.defect_text(),
        "leading_power": stab.leading_power,
        "leading_coefficient": None if stab.leading_coefficient is None else _coefficient_text(stab.leading_coefficient),
        **_quadratic_orders(stab),
    }


def _quadratic_orders(stab: StabilityFunction) -> dict[str, Any]:
    """The m = 2 energy order from ``R(z)R(−z) − 1 = Σ e_2k z^2k``: proven (every e_2k
    before it exactly 0), and reached when the e_2k that vanish only to digits count."""
    reach = stab.quadratic_energy_order
    top = stab.leading_power if stab.leading_power is not None else len(stab.defect)
    proven, digits = reach, []
    for k in range(2, top, 2):
        v = sc.verdict(stab.defect[k])
        if v.state != HOLDS:
            proven = k - 1 if proven is None else min(proven, k - 1)
            if v.digits is not None:
                digits.append(v.digits)
    return {"quadratic_energy_order": proven, "quadratic_energy_order_to_digits": reach,
            "quadratic_energy_order_digits": min(digits) if digits else None}


def error_constant_doc(ec: ErrorConstant | None) -> dict[str, Any] | None:
    if ec is None:
        return None
    lo, hi = ec.bounds
    return {
        "norm": "euclidean",
        "degree": ec.degree,
        "energy_order": ec.energy_order,
        "order": ec.order,
        "conditions": ec.conditions,
        "failing": ec.failing,
        "value": ec.short(12),
        "squared": str(ec.squared) if ec.exact else None,
        # 17 significant digits, rounded outwards (a bound stays a bound)
        "lower": decimal_string(lo - lo / 10**16, 17),
        "upper": decimal_string(hi, 17, up=True),
    }


def properties_doc(res) -> dict[str, Any]:
    """The keys this module adds to ``summary`` (empty when the check has no properties)."""
    props = res.properties
    if props is None:
        return {}
    if getattr(props, "continuous", False):  # a kernel: no stage reduction, no R(z)
        return {
            "symplectic": {"state": props.symplectic.verdict.state, "digits": props.symplectic.verdict.digits,
                           "reason": props.symplectic.reason},
            "symmetric": {"state": props.symmetric.verdict.state, "digits": props.symmetric.verdict.digits,
                          "reason": props.symmetric.reason},
            "error_constant": error_constant_doc(error_constant(res)),
        }
    red = props.reduction
    sym, symm = props.symplectic, props.symmetric
    defect = None
    if sym.defect is not None:
        q = sc.rational(sym.defect)
        defect = str(abs(q)) if q is not None else _coefficient_text(sym.defect)
    return {
        "reduction": {
            "stages": red.stages,
            "reduced_stages": red.reduced_stages,
            "classes": [[i + 1 for i in c] for c in red.classes],
            "dropped": sorted(i + 1 for i in red.dropped),
            "cancelled": [[i + 1 for i in c] for c in red.cancelled],
            "exact": not red.decisions,
        },
        "symplectic": {
            "state": sym.verdict.state, "digits": sym.verdict.digits, "reason": sym.reason,
            "defect": defect, "defect_entry": None if sym.defect_entry is None else list(sym.defect_entry),
        },
        "symmetric": {
            "state": symm.verdict.state, "digits": symm.verdict.digits, "reason": symm.reason,
            "permutation": None if symm.permutation is None else list(symm.permutation),
        },
        "stability": stability_doc(props.stability),
        "error_constant": error_constant_doc(error_constant(res)),
    }


def _verdict_text(pv) -> Text:
    label = pv.label()
    t = Text(label, style=STYLE.get(pv.verdict.state, ""))
    t.append(f" — {pv.reason}", style="")
    return t


def property_rows(res) -> list[tuple[str, Text | str]]:
    """Rows for the ``verify`` report (label, value)."""
    rows: list[tuple[str, Text | str]] = []
    ec = error_constant(res)
    if ec is not None:
        n = ec.conditions
        o = str(ec.order).translate(_SUP)
        o1 = str(ec.order + 1).translate(_SUP)
        rows.append((
            "error constant",
            f"C = {ec.text()}, the Euclidean norm of the {n} residual{'s' if n != 1 else ''} of order {ec.order} "
            f"(ΔH = h{o} Σ R(t̄)F_t̄(H) + O(h{o1}))",
        ))
    props = res.properties
    if props is None:
        return rows
    rows.append(("symplectic", _verdict_text(props.symplectic)))
    rows.append(("symmetric", _verdict_text(props.symmetric)))
    stab = props.stability
    if stab is not None:  # None for a continuous method's kernel
        rows.append(("stability", f"{stab.text()};  {stab.defect_text()}"))
    return rows


def stability_line(stab: StabilityFunction) -> str:
    """``R(z) = …`` and ``R(z)R(−z) − 1`` on one line (for ``show``)."""
    return f"{stab.text()};  {stab.defect_text()}"


def tableau_stability(values: TableauValues) -> StabilityFunction:
    """R(z) of a tableau without running a check (for ``show``): exact when its values
    are, else from their enclosures."""
    exact = values.exact
    if exact is not None and exact.algebra is not None:  # over Q from the node form, no field
        return stability_of_series(exact.nodes.stability_series(2 * values.stages), values.stages)
    return stability_function(*sc.tableau_values(values))