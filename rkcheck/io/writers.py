"""``rkcheck new``: a complete tableau file with explicit entries for a family.

Exact mode writes the nodes as closed forms in square roots (``[constants] c1 = ...``)
and every weight and coefficient as an exact expression over them (Lagrange integrals
written out with elementary symmetric sums), so the file loses nothing and rkcheck checks
it at any precision.  Rational families get plain fractions.  When the nodes have no
closed form in square roots, entries are D-digit decimals (correctly rounded from
certified enclosures), which rkcheck reads as rounded to their last digit.
"""

from __future__ import annotations

from rkcheck.errors import UserError
from rkcheck.methods.closed_forms import (
    MAX_EXACT_NODES,
    expression_texts,
    simplified_texts,
)
from rkcheck.methods.families import coefficients
from rkcheck.methods.family_spec import FamilySpec
from rkcheck.numbers.formatting import decimal_string
from rkcheck.numbers.precision import bits_for_digits

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


# ------------------------------------------------------------------ writing


def _toml_str(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _toml_list(items: list[str]) -> str:
    return "[" + ", ".join(_toml_str(x) for x in items) + "]"


def render_toml(
    spec: FamilySpec, mode: str = "auto", digits: int = 60, name: str | None = None, command: str = ""
) -> str:
    """The TOML text of a family; ``mode``: 'auto' (exact if possible), 'exact' or 'digits'."""
    if digits < 1 or digits > 5000:
        raise UserError(f"--digits must be between 1 and 5000, got {digits}")
    r = spec.base_rule()
    lines = ["[method]", f"name = {_toml_str(name or spec.title())}"]
    order = r.order()
    desc = f"{spec.title()}; its quadrature rule has order {order}."
    if command:
        desc += f" Written by `{command}`."
    lines.append(f"description = {_toml_str(desc)}")
    lines.append(f"references = {_toml_list(REFERENCES[spec.name])}")
    lines.append("")
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
        c = [sum((x for x in row[1:]), row[0]) for row in A]
        lines += ["[tableau]", "A = ["]
        lines += [f"  {_toml_list([str(x.lo) for x in row])}," for row in A]
        lines += ["]", f"b = {_toml_list([str(x.lo) for x in b])}", f"c = {_toml_list([str(x.lo) for x in c])}"]
    elif texts is not None:
        consts, A_t, b_t, c_t = simplified_texts(*texts)
        if consts:
            lines.append("[constants]")
            lines += [f"{k} = {_toml_str(v)}" for k, v in consts.items()]
            lines.append("")
        lines += ["[tableau]", "A = ["]
        lines += [f"  {_toml_list(row)}," for row in A_t]
        lines += ["]", f"b = {_toml_list(b_t)}", f"c = {_toml_list(c_t)}"]
    else:
        bits = bits_for_digits(digits, 64)
        A, b = coefficients(spec, bits)
        c = [sum((x for x in row[1:]), row[0]) for row in A]

        def dec(x) -> str:
            return str(x.lo) if x.is_point else decimal_string(x.mid, digits, keep_zeros=True)

        lines += ["[tableau]", "A = ["]
        lines += [f"  {_toml_list([dec(x) for x in row])}," for row in A]
        lines += ["]", f"b = {_toml_list([dec(x) for x in b])}", f"c = {_toml_list([dec(x) for x in c])}"]
    return "\n".join(lines) + "\n"
