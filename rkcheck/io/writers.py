"""``rkcheck new``: a complete tableau file with explicit entries for a family.

Exact mode writes the nodes as closed forms in square roots (``[constants] c1 = ...``)
and every weight and coefficient as an exact expression over them (Lagrange integrals
written out with elementary symmetric sums), so the file loses nothing and rkcheck checks
it at any precision.  Rational families get plain fractions.  When the nodes have no
closed form in square roots, entries are D-digit decimals (correctly rounded from
certified enclosures), which rkcheck reads as rounded to their last digit.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

from rkcheck.errors import UserError
from rkcheck.methods.families import FamilySpec, coefficients
from rkcheck.methods.quadrature import poly_integral, shifted_legendre
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


# ------------------------------------------------------------- text algebra


def _par(text: str) -> str:
    return text if _atomic(text) else f"({text})"


def _atomic(text: str) -> bool:
    depth = 0
    for i, ch in enumerate(text):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif depth == 0 and ch in "+-" and i > 0:
            return False
        elif depth == 0 and ch in "*/" :
            return False
    return not text.startswith("-")


def _esym(names: list[str], k: int) -> str:
    """Elementary symmetric polynomial e_k of the names, as text."""
    if k == 0:
        return "1"
    return " + ".join("*".join(c) for c in combinations(names, k))


def _power(x: str, k: int) -> str:
    if x == "1" or k == 1:
        return x
    return f"{_par(x)}^{k}"


def lagrange_integral_text(names: list[str], i: int, lo: str, hi: str) -> str:
    """``∫_lo^hi ℓ_i(x) dx`` over the nodes ``names`` as an exact expression."""
    others = names[:i] + names[i + 1:]
    n = len(others)
    num = ""
    for k in range(n + 1):  # coefficient of x^k in Π (x − c_j) is (−1)^(n−k) e_(n−k)
        e = _esym(others, n - k)
        if hi == "1" and lo == "0":
            upper = "1"
        elif lo == "0":
            upper = _power(hi, k + 1)
        else:
            upper = f"({_power(hi, k + 1)} - {_power(lo, k + 1)})"
        if e == "1":
            factor = upper
        elif upper == "1":
            factor = _par(e)
        else:
            factor = f"{_par(e)}*{upper}"
        term = factor if k == 0 else f"{factor}/{k + 1}"
        negative = (n - k) % 2 == 1
        if not num:
            num = f"-{term}" if negative else term
        else:
            num = f"{num} {'-' if negative else '+'} {term}"
    factors = [f"({names[i]} - {o})" for o in others]
    if not factors:
        return num
    den = factors[0] if len(factors) == 1 else "(" + "*".join(factors) + ")"
    return f"({num})/{den}"


def _poly_text(p: list[Fraction], x: str) -> str:
    out = ""
    for k, coeff in enumerate(p):
        if coeff == 0:
            continue
        mag = abs(coeff)
        body = _power(x, k) if k else ""
        if not body:
            t = str(mag)
        elif mag == 1:
            t = body
        else:
            t = f"{mag}*{body}"
        if not out:
            out = t if coeff > 0 else f"-{t}"
        else:
            out += f" {'+' if coeff > 0 else '-'} {t}"
    return out or "0"


def expression_texts(spec: FamilySpec) -> tuple[dict[str, str], list[list[str]], list[str], list[str]] | None:
    """(constants, A, b, c) as exact entry texts, or None without closed-form nodes."""
    r = spec.base_rule()
    forms = r.node_closed_forms()
    if forms is None:
        return None
    n = len(forms)
    c = [f"c{i + 1}" for i in range(n)]
    bn = [f"b{i + 1}" for i in range(n)]
    consts = {c[i]: forms[i] for i in range(n)}
    for j in range(n):
        consts[bn[j]] = lagrange_integral_text(c, j, "0", "1")
    name = spec.name
    if name == "avf":
        A = [[f"{c[i]}*{bn[j]}" for j in range(n)] for i in range(n)]
    elif name in ("gauss", "lobatto-iiia", "radau-iia"):
        A = [[lagrange_integral_text(c, j, "0", c[i]) for j in range(n)] for i in range(n)]
    elif name in ("lobatto-iiib", "radau-ia"):
        A = [
            [
                (f"{bn[j]}/{bn[i]}*" if i != j else "") + lagrange_integral_text(c, i, c[j], "1")
                for j in range(n)
            ]
            for i in range(n)
        ]
    elif name == "hbvm":
        A = []
        for i in range(n):
            row = []
            for l in range(n):
                parts = []
                for j in range(spec.s):
                    P = shifted_legendre(j)
                    g = _poly_text(poly_integral(P), c[i])
                    p = _poly_text(P, c[l])
                    parts.append(f"{2 * j + 1}*({g})*({p})")
                row.append(f"{bn[l]}*({' + '.join(parts)})")
            A.append(row)
    else:
        z, beta = spec.zeta, spec.beta
        A = [
            [f"{c[i]}*{bn[j]} + ({beta})*(({z - 1}) - 2*({z})*{c[i]})*{bn[j]}*(1 - 2*{c[j]})" for j in range(n)]
            for i in range(n)
        ]
    return consts, A, bn, c


def simplified_texts(consts: dict[str, str], A: list[list[str]], b: list[str], c: list[str]):
    """The same entries as exact values in their number field
    (:mod:`rkcheck.numbers.algebraic`): ``5/36 - sqrt(15)/30`` when the entries are
    rational or one square root suffices; otherwise (nested roots, ``root(p, k)``) the
    node constants and Lagrange forms, which are exact too."""
    from rkcheck.numbers import grammar as ex
    from rkcheck.numbers.algebraic import NotAlgebraic, field_of

    s = len(b)
    flat = [x for row in A for x in row] + list(b) + list(c)
    try:
        found = field_of([ex.parse(x) for x in flat], {k: ex.parse(v) for k, v in consts.items()})
    except NotAlgebraic:
        return consts, A, b, c
    if found.field is None:
        texts = [str(v) for v in found.values]
    elif found.field.sqrt_of:
        texts = [v.text() for v in found.values]
    else:
        # in a field of higher degree the coefficients in a primitive element are long
        # and opaque; the node constants and Lagrange forms say more (and are exact)
        return consts, A, b, c
    A_t = [texts[i * s:(i + 1) * s] for i in range(s)]
    return {}, A_t, texts[s * s:s * s + s], texts[s * s + s:]


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
                f"the nodes of {spec.title()} have no closed form in square roots; use --digits D for decimals"
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
