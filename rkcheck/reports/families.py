"""Reports of families: their conditions as polynomials, and the solution sets of
``rkcheck solve`` (text for people, JSON for machines)."""

from __future__ import annotations

import re
from typing import Any

from rich.console import Console
from rich.text import Text

from rkcheck.numbers.parametric import THETA
from rkcheck.version import __version__

#: The JSON documents' schema version (``rkcheck.solve`` and family conditions).
FAMILY_SCHEMA = 1


def polynomial_text(p: Any, field: Any) -> str:
    """A polynomial as text, the field generator shown as its closed form (``sqrt(3)``)
    or as θ."""
    text = str(p)
    if THETA in text:
        name = field.name if field is not None and field.sqrt_of else "θ"
        text = text.replace(THETA, name)
    return text


def shown_basis(result: Any) -> list[Any]:
    """The Gröbner basis without the field generator's own minimal polynomial (it defines
    the numbers, not the solutions)."""
    out = []
    for g in result.groebner:
        names = g.context().names()
        used = {names[i] for m in g.monoms() for i, e in enumerate(m) if e}
        if used != {THETA}:
            out.append(g)
    return out


def _field_note(field: Any) -> str | None:
    if field is None or field.sqrt_of:
        return None
    return f"θ = {field.name}"


# ------------------------------------------------------------------ conditions


def conditions_doc(fc: Any, lazy: bool = False) -> dict[str, Any]:
    """``rkcheck conditions FAMILY --format json`` (``lazy``: the conditions a generator,
    each polynomial written out only as the report reaches it)."""
    fam = fc.family
    field = fam.ring.field

    def cond(c: Any) -> dict[str, Any]:
        return {"kind": c.kind, "id": c.id, "bracket": c.bracket, "order": c.order,
                "polynomial": polynomial_text(c.polynomial, field), "degree": c.degree, "vanishes": c.vanishes}

    rows = (cond(c) for c in fc.energy + (fc.classical or []))
    return {
        "rkcheck": __version__,
        "schema": FAMILY_SCHEMA,
        # a family of kernels has no stages: its kernel instead (its surrogate's nodes are a means)
        "family": {"name": fam.name, "source": fam.info.source, "parameters": list(fam.parameters),
                   "stages": None if fam.kernel else fam.stages, "field": None if field is None else field.name,
                   "kernel": {"A": fam.kernel[0], "b": fam.kernel[1]} if fam.kernel else None,
                   "surrogate": {"nodes": fam.stages, "exact_to_vertices": fam.reach} if fam.kernel else None},
        "degree": fc.degree,
        "order_checked": fc.order,
        "energy_order_generic": fc.energy_order,
        "energy_order_everywhere": fc.energy_order_everywhere,
        "energy_order_all": fc.energy_order_all,
        "fails_everywhere": None if fc.fails_everywhere is None else fc.fails_everywhere.id,
        "exceptional": [c.id for c in fc.exceptional],
        "classical_order_generic": fc.classical_order,
        "quadrature_order_generic": fc.quadrature_order,
        "quadrature_order_checked": fc.quadrature_checked,
        "conditions": rows if lazy else list(rows),
        "warnings": _verify_warnings(fam),
    }


def render_conditions(fc: Any, console: Console, show_all: bool = False, quiet: bool = False) -> None:
    """The family's conditions (``quiet``: its last line only)."""
    if not quiet:
        _conditions_text(fc, console, show_all)
    console.print(family_verdict_line(fc), soft_wrap=True)


def family_verdict_line(fc: Any) -> Text:
    """FAIL when a condition is a nonzero constant (no member reaches its order), else
    what the conditions leave to ``solve``."""
    first = fc.fails_everywhere
    if first is not None:
        return Text(f"FAIL: condition {first.id} of order {first.order} is a nonzero constant: no parameter value "
                    f"gives energy order {first.order}", style="bold red")
    if not fc.exceptional or fc.energy_order_all:
        return Text(f"OK: every condition up to order {fc.order} vanishes for every parameter value",
                    style="bold green")
    return Text(f"OK: energy order {fc.energy_order} for every parameter value, more where the first conditions "
                f"of order {fc.exceptional[0].order} vanish (rkcheck solve finds where)", style="bold green")


def _conditions_text(fc: Any, console: Console, show_all: bool) -> None:
    fam = fc.family
    field = fam.ring.field
    deg = "none" if fc.degree is None else fc.degree
    console.print(Text(f"{fam.name}: a family in {', '.join(fam.parameters)}", style="bold"))
    note = _field_note(field)
    if note:
        console.print(note)
    if fam.kernel:
        console.print(f"a continuous-stage kernel, through its exact surrogate on {fam.stages} rational nodes "
                      f"(elementary weights exact for trees up to {fam.reach} vertices)")
    for w in _verify_warnings(fam):
        console.print(Text(f"warning: {w}", style="yellow"))
    total = len(fc.energy)
    zero = sum(c.vanishes for c in fc.energy)
    console.print(f"energy conditions, degree m = {deg}, up to order {fc.order}: {total}, "
                  f"{zero} vanish identically")
    generic = fc.energy_order
    label = f"≥ {generic}" if generic == fc.order and not fc.exceptional else str(generic)
    if fc.energy_order_all:
        label = "all (no condition for degree 1: every method preserves linear energy)"
    everywhere = fc.energy_order_everywhere
    console.print(f"energy order for {'every parameter value' if everywhere else 'generic parameter values'}: {label}")
    if fc.classical is not None:
        classical = fc.classical_order
        at_least = classical == fc.classical_order_checked  # every classical condition checked vanished
        console.print(f"classical order for generic parameter values: {'≥ ' if at_least else ''}{classical}")
    quadrature = fc.quadrature_order
    if fam.kernel and quadrature == fc.quadrature_checked:  # a kernel's rule has no largest order
        quadrature = f"≥ {quadrature} (checked up to {quadrature})"
    console.print(f"quadrature order of (b, A·1) for generic parameter values: {quadrature}")
    if show_all:
        shown = fc.energy + (fc.classical or [])
    else:
        shown = fc.exceptional
        if shown and everywhere:
            console.print("the first conditions that do not vanish identically (a nonzero constant among them: no "
                          "parameter value satisfies them all; --all lists every condition):")
        elif shown:
            console.print("the first conditions that do not vanish identically (their zeros are the exceptional "
                          "values; --all lists every condition):")
    for c in shown:
        mark = "0" if c.vanishes else polynomial_text(c.polynomial, field)
        degree = "" if c.vanishes else f"  [degree {c.degree}]"
        console.print(Text(f"  {c.kind} order {c.order}  {c.id}  {c.bracket}:  {mark}{degree}"))
    if fc.exceptional and not show_all and not everywhere:
        console.print(f"where they vanish: rkcheck solve {fam.info.source} --degree {deg} --order {fc.order}")


# ------------------------------------------------------------------ solutions


def solve_doc(family: Any, result: Any, options: dict[str, Any]) -> dict[str, Any]:
    field = family.ring.field

    points = None if result.solutions is None else [
        {"values": {k: value_text(v, result.variables) for k, v in s.values.items()}, "real": s.real}
        for s in result.solutions]
    finite = result.dimension <= 0
    return {
        "rkcheck": __version__,
        "schema": FAMILY_SCHEMA,
        "family": {"name": family.name, "source": family.info.source, "field": None if field is None else field.name},
        "options": options,
        "warnings": list(family.warnings),
        "parameters": list(result.variables),
        "equations": result.equations,
        "eliminated": {k: polynomial_text(v, field) for k, v in result.eliminated.items()},
        "groebner": _basis_doc(result, field),
        "dimension": result.dimension,
        "route": result.route,
        "rule_dimension": result.rule_dimension if result.route == "structured" else None,
        "components": None if result.components is None else [component_doc(c, field) for c in result.components],
        "avf_on_every_component": avf_everywhere(result),
        # every solution, when there are finitely many; the structured route also finds
        # the points of the finite pieces of a positive-dimensional set
        "solutions": points if finite else None,
        "points_of_finite_components": None if finite else points,
        "seconds": round(result.seconds, 3),
    }


def _basis_doc(result: Any, field: Any) -> list[str] | None:
    """The reduced basis as texts: ``["1"]`` for no solution (the unit ideal, on either
    route); the structured route has the basis of finitely many solutions, none for a
    positive-dimensional set (its components instead)."""
    if result.dimension == -1:
        return ["1"]
    if result.route == "structured" and (result.dimension > 0 or not result.groebner):
        return None
    return [polynomial_text(g, field) for g in shown_basis(result)]


def component_doc(c: Any, field: Any = None) -> dict[str, Any]:
    return {"dimension": c.dimension, "points": c.points, "real": c.real, "avf": c.avf,
            "equations": [e if isinstance(e, str) else polynomial_text(e, field) for e in c.equations]}


def avf_everywhere(result: Any) -> bool | None:
    """Whether A = (A·1) bᵀ on every component (None: not decided, or no components)."""
    if not result.components:
        return None
    flags = [c.avf for c in result.components]
    return None if any(f is None for f in flags) else all(flags)


def _verify_warnings(family: Any) -> list[str]:
    """The family's warnings, and what its Σb says of the members' consistency."""
    note = family.consistency_note
    return [*family.warnings, *([note] if note else [])]


def render_solution_set(family: Any, result: Any, console: Console, scope: str | None = None) -> None:
    """The solution set; ``scope``: a line saying which conditions were solved, when the
    command line did not say it."""
    field = family.ring.field
    equations = f"{result.equations} equation{'' if result.equations == 1 else 's'}"
    console.print(Text(f"{family.name}: {equations} in {', '.join(result.variables)}", style="bold"))
    for w in family.warnings:
        console.print(Text(f"warning: {w}", style="yellow"))
    if scope:
        console.print(Text(scope))
    note = _field_note(field)
    if note:
        console.print(note)
    if result.route == "structured":
        _render_components(result, console)
    else:
        console.print("reduced Gröbner basis (eliminated variables first, then degree reverse lexicographic):")
        for g in shown_basis(result):
            console.print(f"  {polynomial_text(g, field)} = 0")
        if not shown_basis(result):
            console.print("  (empty: no equation is left)")
    if result.dimension < 0:
        console.print(Text("no solution: the conditions are inconsistent", style="bold red"))
        return
    if result.dimension > 0 and result.route == "structured":
        console.print(Text(f"dimension {result.dimension}: infinitely many solutions, the components above",
                           style="bold"))
        if result.solutions:
            console.print(f"the points of the finite components ({len(result.solutions)}):")
            _render_points(result.solutions, console)
        return
    if result.dimension > 0 and not shown_basis(result):
        console.print(Text(f"dimension {result.dimension}: every value of {', '.join(result.variables)} is a solution "
                           "(every condition vanishes identically)", style="bold"))
        return
    if result.dimension > 0:
        console.print(Text(f"dimension {result.dimension}: infinitely many solutions, the set above", style="bold"))
        if result.components and len(result.components) > 1:
            console.print(f"split along factors into {len(result.components)} pieces (each solution lies in one; "
                          "a piece is not proven irreducible):")
            if any(p.whole for p in result.pieces or []):
                from rkcheck.numbers.decompose import MAX_PIECES

                console.print(f"  splitting stopped at MAX_PIECES = {MAX_PIECES}: a piece marked whole may be a "
                              "union of several")
            _render_pieces(result, console, field, _avf_form(family))
        elif result.components:
            form = _avf_form(family)
            avf = {True: f"{form} on all of it (AVF)", False: f"not {form}", None: ""}[result.components[0].avf]
            console.print(f"no basis element factors: one piece{', ' + avf if avf else ''}")
        return
    sols = result.solutions or []
    real = sum(s.real for s in sols)
    console.print(Text(f"{len(sols)} solution{'s' if len(sols) != 1 else ''} ({real} real)", style="bold green"))
    _render_points(sols, console)


def value_text(v: Any, parameters: Any) -> str:
    """A solution's value as text; the imaginary unit ``i`` is written ``sqrt(-1)`` when a
    parameter is called i, which would read as that parameter."""
    if "i" not in parameters:
        return str(v.text)
    return re.sub(r"(?<![\w.])i(?![\w(])", "sqrt(-1)", v.text)


def _render_points(sols: list[Any], console: Console) -> None:
    for k, s in enumerate(sols, start=1):
        values = ", ".join(f"{name} = {value_text(v, s.values)}" for name, v in s.values.items())
        console.print(f"  {k}. {values}{'' if s.real else '  (not real)'}")


def _render_components(result: Any, console: Console) -> None:
    """The structured route: quadrature conditions first, then the conditions linear in A
    per solution orbit of the nodes, then the rest (docs/families.md)."""
    comps = result.components or []
    basis = shown_basis(result)
    if basis:
        console.print(f"reduced Gröbner basis of the solutions (degree reverse lexicographic): {len(basis)} "
                      "polynomials (--format json lists them)")
    count = f"{len(comps)} component{'s' if len(comps) != 1 else ''}"
    if result.rule_dimension:
        console.print(f"structured route over the rules: the quadrature conditions leave a set of dimension "
                      f"{result.rule_dimension}; the conditions linear in A and the rest solved on all of it at "
                      f"once, then each exceptional orbit of nodes; {count}")
    else:
        console.print(f"structured route: quadrature conditions, then the conditions linear in A, per orbit of "
                      f"nodes; {count}")
    for k, c in enumerate(comps, start=1):
        what = f"{c.points} point{'s' if c.points != 1 else ''}" if c.dimension == 0 else f"dimension {c.dimension}"
        avf = {True: "A = (A·1) bᵀ (AVF)", False: "not A = (A·1) bᵀ", None: "AVF not decided"}[c.avf]
        console.print(f"  component {k}: {what}, {avf}")
        if c.node:
            console.print(f"    ({c.node}: a node of the component, a root of the first equation)")
        for e in c.equations:
            console.print(f"    {e} = 0")


def _avf_form(family: Any) -> str:
    """What makes a solution AVF: a tableau's A = (A·1) bᵀ, a kernel's A = τ and B = 1."""
    return "A = τ, B = 1" if family.kernel else "A = (A·1) bᵀ"


def _render_pieces(result: Any, console: Console, field: Any, form: str) -> None:
    for k, c in enumerate(result.components, start=1):
        avf = {True: f", {form} (AVF)", False: f", not {form}", None: ""}[c.avf]
        whole = " (whole: not split further)" if result.pieces and result.pieces[k - 1].whole else ""
        console.print(f"  piece {k}: dimension {c.dimension}{avf}{whole}")
        for e in c.equations:
            console.print(f"    {e if isinstance(e, str) else polynomial_text(e, field)} = 0")
