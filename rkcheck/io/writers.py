"""Tableau files as TOML text: the one TOML writer (``show --format toml``, ``rkcheck new``
and :func:`rkcheck.new_toml`), and the document ``rkcheck new`` writes for a family.

Exact mode writes the nodes as closed forms in square roots (``[constants] c1 = ...``)
and every weight and coefficient as an exact expression over them (Lagrange integrals
written out with elementary symmetric sums), so the file loses nothing and rkcheck checks
it at any precision.  Rational families get plain fractions.  When the nodes have no
closed form in square roots, entries are D-digit decimals (correctly rounded from
certified enclosures), which rkcheck reads as rounded to their last digit.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any, Callable

from rkcheck.errors import UserError
from rkcheck.numbers.intervals import Interval

if TYPE_CHECKING:
    from rkcheck.methods.family_spec import FamilySpec

REFERENCES = {
    "avf": ["G. R. W. Quispel, D. I. McLaren, J. Phys. A 41 (2008) 045206",
            "E. Celledoni, B. Owren, Y. Sun, the minimal stage energy preserving RK method is AVF (seed paper)"],
    "gauss": ["J. C. Butcher, Math. Comp. 18 (1964) 50-64"],
    "lobatto-iiia": ["E. Hairer, G. Wanner, Solving ODEs II, Springer 1996, Section IV.5"],
    "lobatto-iiib": ["E. Hairer, G. Wanner, Solving ODEs II, Springer 1996, Section IV.5"],
    "radau-iia": ["E. Hairer, G. Wanner, Solving ODEs II, Springer 1996, Section IV.5"],
    "radau-ia": ["E. Hairer, G. Wanner, Solving ODEs II, Springer 1996, Section IV.5"],
    "hbvm": ["L. Brugnano, F. Iavernaro, D. Trigiante, JNAIAM 5 (2010) 17-37"],
    "kernel": ["E. Celledoni, B. Owren, Y. Sun, the minimal stage energy preserving RK method is AVF (seed paper), Section 2.4"],
}


# ------------------------------------------------------------------ TOML text


def toml_value(value: Any) -> str:
    """A TOML value: a basic string, integer, boolean, array or inline table."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        # a JSON string is a TOML basic string, except that TOML wants DEL escaped too
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{toml_key(k)} = {toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"cannot write {type(value).__name__} as TOML")


def toml_key(key: str) -> str:
    return key if key.replace("_", "").replace("-", "").isalnum() and key.isascii() else json.dumps(key)


def document_toml(doc: dict[str, dict[str, Any]], block_matrix: bool = False) -> str:
    """A tableau document as TOML text: one table per top-level key, each followed by a
    blank line, and the tableau's ``A`` one row per line — aligned under the first row,
    or with ``block_matrix`` (as ``rkcheck new`` writes) indented between ``A = [`` and
    ``]``, every row ending in a comma."""
    out: list[str] = []
    for table, content in doc.items():
        out.append(f"[{table}]")
        for key, value in content.items():
            if key == "A" and table == "tableau":
                rows = [toml_value(r) for r in value]
                if block_matrix:
                    out.append("A = [\n" + "".join(f"  {r},\n" for r in rows) + "]")
                else:
                    out.append("A = [" + ",\n     ".join(rows) + "]")
            else:
                out.append(f"{toml_key(key)} = {toml_value(value)}")
        out.append("")
    return "\n".join(out)


# ------------------------------------------------------------------ rkcheck new


def render_toml(
    spec: FamilySpec, mode: str = "auto", digits: int = 60, name: str | None = None, command: str = ""
) -> str:
    """The TOML text of a family; ``mode``: 'auto' (exact if possible), 'exact' or 'digits'."""
    # the family machinery is loaded here, not with the module: writing any other tableau
    # as TOML (show --format toml) needs none of it
    from rkcheck.methods.closed_forms import (
        MAX_EXACT_NODES,
        expression_texts,
        simplified_texts,
    )
    from rkcheck.methods.families import coefficients
    from rkcheck.numbers.formatting import decimal_string
    from rkcheck.numbers.precision import bits_for_digits

    if digits < 1 or digits > 5000:
        raise UserError(f"--digits must be between 1 and 5000, got {digits}")
    r = spec.base_rule()
    desc = f"{spec.title()}; its quadrature rule has order {r.order()}."
    if command:
        desc += f" Written by `{command}`."
    doc: dict[str, dict[str, Any]] = {
        "method": {"name": name or spec.title(), "description": desc, "references": REFERENCES[spec.name]},
    }
    texts = None
    if mode in ("auto", "exact") and not r.is_rational:
        texts = expression_texts(spec)
        if texts is None and mode == "exact":
            raise UserError(
                f"the nodes of {spec.title()} have no closed form in roots (or more than {MAX_EXACT_NODES} nodes); "
                "use --digits D for decimals"
            )
    if r.is_rational and mode != "digits":
        A, b = coefficients(spec, 64)
        doc["tableau"] = _tableau_table(A, b, lambda x: str(x.lo))
    elif texts is not None:
        consts, A_t, b_t, c_t = simplified_texts(*texts)
        if consts:
            doc["constants"] = consts
        doc["tableau"] = {"A": A_t, "b": b_t, "c": c_t}
    else:
        A, b = coefficients(spec, bits_for_digits(digits, 64))
        # an enclosure of 0 (Radau IA's c₁) has no digit to print: its mid-point is noise
        doc["tableau"] = _tableau_table(
            A, b, lambda x: str(x.lo) if x.is_point else "0" if x.contains_zero() else decimal_string(
                x.mid, digits, keep_zeros=True))
    return document_toml(doc, block_matrix=True)


def _tableau_table(A: list[list[Interval]], b: list[Interval], text: Callable[[Interval], str]) -> dict[str, Any]:
    """The ``[tableau]`` table of computed coefficients: A, b and the row sums c."""
    c = [sum((x for x in row[1:]), row[0]) for row in A]
    return {"A": [[text(x) for x in row] for row in A], "b": [text(x) for x in b], "c": [text(x) for x in c]}
