"""A tableau written out for other tools: TOML, JSON, LaTeX, Julia and Python.

Every writer keeps the entries exact.  TOML and JSON write the entries as rkcheck reads
them (strings in its grammar, the ``[constants]`` table kept), so
``load(write(t)) == t`` entry for entry.  The code writers translate the same
expressions: LaTeX an ``array`` with ``\\frac`` and ``\\sqrt`` (a Butcher array:
``c | A`` over ``| bᵀ``); Julia ``Rational{BigInt}``/``sqrt(big(…))`` expressions;
Python ``fractions.Fraction`` and, for square roots, ``sympy.sqrt`` (exact) — the code
is meant to be pasted, and is never read back by rkcheck.
"""

from __future__ import annotations

import json
from typing import Any, Callable

from rkcheck.errors import UserError
from rkcheck.io.code_forms import Code, Julia, Latex, NoExactForm, Python
from rkcheck.io.writers import document_toml, render_toml
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Entry, TableauEntry

WRITE_FORMATS = ("toml", "json", "latex", "julia", "python")


# ------------------------------------------------------------------ documents


def tableau_document(tab: Tableau) -> dict[str, Any]:
    """The tableau as a tableau-file document (method, constants, tableau, check, expect)."""
    doc: dict[str, Any] = {"method": {"name": tab.name}}
    if tab.info.description:
        doc["method"]["description"] = tab.info.description
    if tab.info.references:
        doc["method"]["references"] = list(tab.info.references)
    if tab.info.constants.definitions:
        doc["constants"] = {k: xp.to_text(v) for k, v in tab.info.constants.definitions.items()}
    doc["tableau"] = {"A": [[e.text for e in row] for row in tab.A], "b": [e.text for e in tab.b]}
    if tab.c is not None:
        doc["tableau"]["c"] = [e.text for e in tab.c]
    if tab.info.check:  # the options the file asks for: the written file checks the same
        # (no degree bound is read as None; TOML has no null: it is written "none")
        doc["check"] = {k: "none" if k == "degree" and v is None else v for k, v in tab.info.check.items()}
    if tab.info.expect:
        doc["expect"] = dict(tab.info.expect)
    return doc


def to_toml(tab: Tableau) -> str:
    """The tableau as a TOML tableau file (read back by :func:`rkcheck.io.loader.loads`)."""
    return document_toml(tableau_document(tab))


def to_json(tab: Tableau) -> str:
    """The tableau as a JSON tableau file (read back by :func:`rkcheck.io.loader.loads`)."""
    return json.dumps(tableau_document(tab), indent=2, ensure_ascii=False) + "\n"


def _node(e: TableauEntry) -> ex.Expr:
    """The expression of an entry.  :func:`write` has already turned a family's computed
    coefficients into written entries (:func:`_as_written`), so every entry has one."""
    assert isinstance(e, Entry), "write() passes written tableaux only"
    return e.node


#: At most this many square roots (in an entry and the constants it names) are combined
#: by :func:`simplified`: the number field of a few square roots of rationals is built
#: in milliseconds.
MAX_SIMPLIFIED_ROOTS = 8


def _simplifiable(node: ex.Expr, constants: dict[str, ex.Expr]) -> bool:
    """Whether an entry's exact value may replace it: no decimal literal (a decimal may
    stand for more than its face value), only square roots of root-free arguments, not
    too many of them, in the entry and in every constant it names."""
    seen: set[str] = set()
    todo, calls = [node], 0
    while todo:
        n = todo.pop()
        for sub in xp.walk(n):
            if isinstance(sub, ex.Num) and sub.digits is not None:
                return False
            if isinstance(sub, ex.Call):
                calls += 1
                if sub.func != "sqrt" or any(isinstance(x, ex.Call) for x in xp.walk(sub.args[0])):
                    return False
            if isinstance(sub, ex.Name) and sub.name not in seen:
                seen.add(sub.name)
                todo.append(constants[sub.name])
    return calls <= MAX_SIMPLIFIED_ROOTS


def _canonical(values) -> list[ex.Expr] | None:
    """Exact values as expressions when each has a short canonical form: rationals, or
    ``p + q·sqrt(n)`` in one quadratic field; else None."""
    if values.field is None:
        return [ex.Num(v, str(v), None, 0) for v in values.values]
    if not values.field.name.startswith("sqrt("):
        return None
    return [ex.parse(v.text()) for v in values.values]


def simplified(nodes: list[ex.Expr], constants: dict[str, ex.Expr] | None = None) -> list[ex.Expr]:
    """Entries for the code writers, each as its exact value in its shortest canonical
    form: ``1 - 1/3`` is ``2/3``, ``1 + (-1) + 1`` is ``1``, ``sqrt(12)/4 + 1 - 1/2`` is
    ``1/2 + sqrt(3)/2``, a Lagrange integral over nodes in Q(√15) is ``5/36 - sqrt(15)/30``
    (like terms combined, constants folded, exactly).  An entry stays as written when
    :func:`_simplifiable` says no, or when its value needs more than one square root."""
    from rkcheck.numbers.algebraic import NotAlgebraic
    from rkcheck.numbers.field_builder import field_of

    constants = constants or {}
    out = list(nodes)
    todo = [k for k, n in enumerate(nodes) if not isinstance(n, ex.Num) and _simplifiable(n, constants)]
    try:  # all at once: one field for the whole tableau (the usual case)
        joint = _canonical(field_of([nodes[k] for k in todo], constants))
    except (NotAlgebraic, UserError):
        joint = None
    if joint is not None:
        for k, node in zip(todo, joint):
            out[k] = node
        return out
    for k in todo:  # several fields: entry by entry
        try:
            one = _canonical(field_of([nodes[k]], constants))
        except (NotAlgebraic, UserError):
            one = None
        if one is not None:
            out[k] = one[0]
    return out


def _entries(tab: Tableau) -> tuple[list[list[ex.Expr]], list[ex.Expr], list[ex.Expr]]:
    """A, b and c as the code writers write them (:func:`simplified`); c = A·1 when the
    tableau gives none."""
    s = len(tab.b)
    A = [[_node(e) for e in row] for row in tab.A]
    c = _row_sums(A) if tab.c is None else [_node(e) for e in tab.c]
    flat = simplified([x for row in A for x in row] + [_node(e) for e in tab.b] + c, tab.info.constants.definitions)
    return [flat[i * s:(i + 1) * s] for i in range(s)], flat[s * s:s * s + s], flat[s * s + s:]


def _row_sums(A: list[list[ex.Expr]]) -> list[ex.Expr]:
    """``c = A·1`` as expressions (definitions §1), for writers that need a ``c``."""
    out: list[ex.Expr] = []
    for row in A:
        nonzero = [x for x in row if not (isinstance(x, ex.Num) and x.value == 0)]
        total: ex.Expr = nonzero[0] if nonzero else ex.parse("0")
        for x in nonzero[1:]:
            total = ex.Binary("+", total, x, 0)
        out.append(total)
    return out


def _used_constants(tab: Tableau, nodes: list[ex.Expr]) -> dict[str, ex.Expr]:
    """The constants the written entries still name (directly or through each other), in
    the table's order: a constant folded into every entry is not written."""
    definitions = tab.info.constants.definitions
    used: set[str] = set()
    todo = [n.name for node in nodes for n in xp.names(node)]
    while todo:
        name = todo.pop()
        if name not in used:
            used.add(name)
            todo += [n.name for n in xp.names(definitions[name])]
    return {k: v for k, v in definitions.items() if k in used}


def to_latex(tab: Tableau) -> str:
    """The Butcher array ``c | A`` over ``| bᵀ`` as a LaTeX ``array`` (exact entries,
    constants written out)."""
    code = Latex(tab.info.constants.definitions)
    A, b, c = _entries(tab)
    s = len(b)
    lines = [rf"% {tab.name}", r"\[", rf"\begin{{array}}{{c|{'c' * s}}}"]
    for ci, row in zip(c, A):
        lines.append("  " + " & ".join([code.render(ci)] + [code.render(x) for x in row]) + r" \\")
    lines.append(r"  \hline")
    lines.append("  " + " & ".join([""] + [code.render(x) for x in b]))
    lines += [r"\end{array}", r"\]", ""]
    return "\n".join(lines)


def _code_lines(tab: Tableau, code: Code, assign: str, vector: Callable[[list[str]], str],
                matrix: Callable[[list[list[str]]], str]) -> list[str]:
    A, b, c = _entries(tab)
    constants = _used_constants(tab, [x for row in A for x in row] + b + c)
    names = code.identifiers(constants)
    lines = [f"{names[name]}{assign}{code.render(value)}" for name, value in constants.items()]
    lines.append(f"A{assign}" + matrix([[code.render(x) for x in row] for row in A]))
    lines.append(f"b{assign}" + vector([code.render(x) for x in b]))
    lines.append(f"c{assign}" + vector([code.render(x) for x in c]))
    return lines


def _julia_cell(text: str) -> str:
    """A matrix cell: Julia separates cells by spaces, so a cell with spaces is wrapped."""
    return f"({text})" if " " in text else text


def to_julia(tab: Tableau) -> str:
    """Julia code defining ``A``, ``b``, ``c`` exactly (``Rational{BigInt}``; square roots
    as ``BigFloat``)."""
    lines = [f"# {tab.name} (written by rkcheck; exact rationals, sqrt in BigFloat{_face_value_note(tab)})"]
    lines += _code_lines(tab, Julia(), " = ", lambda v: "[" + ", ".join(v) + "]",
                         lambda m: "[" + ";\n     ".join(" ".join(_julia_cell(x) for x in r) for r in m) + "]")
    return "\n".join(lines) + "\n"


def _face_value_note(tab: Tableau) -> str:
    """What the code's header says of decimals: written as the rationals they write, so
    the rounding the decimals rule reads in them (definitions §5) is not carried."""
    entries = [*(x for row in tab.A for x in row), *tab.b]
    return "; decimals at face value" if any(isinstance(e, Entry) and e.has_decimal for e in entries) else ""


def to_python(tab: Tableau) -> str:
    """Python code defining ``A``, ``b``, ``c`` exactly (``Fraction``; ``sympy.sqrt`` when
    the tableau has square roots)."""
    body = _code_lines(tab, Python(), " = ", lambda v: "[" + ", ".join(v) + "]",
                       lambda m: "[\n    " + ",\n    ".join("[" + ", ".join(r) + "]" for r in m) + ",\n]")
    lines = [f"# {tab.name} (written by rkcheck; exact entries{_face_value_note(tab)})", "from fractions import Fraction"]
    if any("sympy." in line for line in body):
        lines.append("import sympy")
    return "\n".join(lines + [""] + body) + "\n"


WRITERS: dict[str, Callable[[Tableau], str]] = {
    "toml": to_toml, "json": to_json, "latex": to_latex, "julia": to_julia, "python": to_python,
}


def write(tab: Tableau, fmt: str) -> str:
    """The tableau in one of :data:`WRITE_FORMATS`.  A ``[family]`` tableau is first
    written out as ``rkcheck new`` writes it — closed forms where its nodes have them,
    else 60-digit decimals — so every format reads back (never the "≈" display texts)."""
    if fmt not in WRITERS:
        raise UserError(f"unknown output format {fmt!r} (known: {', '.join(WRITE_FORMATS)})")
    try:
        return WRITERS[fmt](_as_written(tab))
    except NoExactForm as err:
        raise err.located(_first_entry_calling(tab, err.func)) from None
    except RecursionError:  # a sum of thousands of terms is a tree too deep to render recursively
        raise UserError(f"nested too deeply to write as {fmt} (a chain of thousands of terms); "
                        "write the tableau as TOML or JSON", _deepest_entry(tab)) from None


def _first_entry_calling(tab: Tableau, func: str) -> str | None:
    """The place of the first entry that calls ``func``, itself or through a constant."""
    constants = tab.info.constants.definitions

    def calls(node: ex.Expr) -> bool:
        return bool(xp.fold(node, lambda n, kids: any(kids) or (isinstance(n, ex.Call) and n.func == func)
                            or (isinstance(n, ex.Name) and n.name in constants and calls(constants[n.name]))))

    nodes = ((place, getattr(e, "node", None)) for place, e in zip(tab.entry_places(), tab.entries()))
    return next((place for place, node in nodes if node is not None and calls(node)), None)


def _deepest_entry(tab: Tableau) -> str | None:
    """The place (``A[i][j]``, ``b[i]``) of the entry whose expression is deepest."""
    def depth(e: Any) -> int:
        node = getattr(e, "node", None)
        return 0 if node is None else int(xp.fold(node, lambda n, kids: 1 + max(kids, default=0)))

    best = max(zip(tab.entry_places(), tab.entries()), key=lambda pe: depth(pe[1]), default=None)
    return None if best is None else best[0]


def _as_written(tab: Tableau) -> Tableau:
    """A family's tableau as a written one (its own name, description, references and
    claims kept); any other tableau unchanged."""
    if tab.info.family is None:
        return tab

    from rkcheck.io.loader import loads
    from rkcheck.methods.family_spec import parse_spec

    written = loads(render_toml(parse_spec(dict(tab.info.family))), source=tab.info.source, fmt="toml")
    info = written.info.replace(description=tab.info.description, references=tab.info.references,
                                expect=tab.info.expect, claims=tab.info.claims, check=tab.info.check)
    return written.replace(name=tab.name, info=info)
