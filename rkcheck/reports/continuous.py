"""``rkcheck show`` of a continuous-stage method: the kernel, its degrees and what the
kernel says by itself (certificate, AVF, symmetry, symplecticity)."""

from __future__ import annotations

from typing import Any

import click

from rkcheck.errors import UserError


def show_doc(method: Any, file: str, decimals: Any = None) -> dict[str, Any]:
    """The document of ``show`` (``decimals``: the mode under which the kernel's decimals
    stand for intervals, judged over their box as ``verify`` judges them; None: at face
    value)."""
    from rkcheck.energy.continuous import kernel_facts
    from rkcheck.io.printable import printable
    from rkcheck.numbers.reading import DecimalsMode
    from rkcheck.reports.jsondoc import SCHEMA
    from rkcheck.version import __version__

    k = method.kernel
    mode = DecimalsMode(decimals) if decimals is not None else None
    box = mode if mode is not None and method.is_box(mode) else None
    facts = kernel_facts(method, None, box)
    numbers = "rational" if k.ring.field is None else f"algebraic (degree {k.ring.field.degree})"
    return {
        "schema": SCHEMA, "rkcheck": __version__, "file": printable(file),
        "method": {"name": method.name, "description": method.info.description,
                   "references": list(method.info.references)},
        "tableau": {
            "stages": None, "structure": "continuous",
            "numbers": "decimal (a box of kernels)" if box is not None else numbers,
            "kernel": {"A": method.A, "b": method.b, "M": None if method.M is None else [list(r) for r in method.M],
                       "degree_tau": k.deg_tau, "degree_sigma": k.deg_sigma, "degree_b": k.deg_b},
        },
        "certificate": _state(facts.certificate.verdict, facts.certificate.reason),
        "equals_avf": None if not facts.avf.verdict.decided else facts.avf.equals_avf,
        "avf": _state(facts.avf.verdict, facts.avf.reason),
        "symmetric": _state(facts.properties.symmetric.verdict, facts.properties.symmetric.reason),
        "symplectic": _state(facts.properties.symplectic.verdict, facts.properties.symplectic.reason),
        "warnings": list(method.info.warnings),
    }


def _state(verdict: Any, reason: str) -> dict[str, Any]:
    doc = {"state": verdict.state, "reason": reason}
    if verdict.digits is not None:
        doc["digits"] = verdict.digits
    return doc


def _answer(doc: dict[str, Any]) -> str:
    """A property's entry of the document as ``yes``, ``yes, to D digits`` or ``no``."""
    from rkcheck.verdicts import State, Verdict

    return Verdict(State(doc["state"]), doc.get("digits")).answer()


def show_continuous(method: Any, fmt: str, file: str, decimals: Any = None) -> None:
    """Print the method (text or json); the tableau formats have no kernel."""
    if fmt not in ("text", "json"):
        raise UserError(f"--format {fmt}: a continuous-stage method has no Butcher table; "
                        "`rkcheck discretize FILE --rule gauss-3` writes a tableau of it", source=file)
    doc = show_doc(method, file, decimals)
    if fmt == "json":
        from rkcheck.reports.jsondoc import dumps

        click.echo(dumps(doc))
        return
    kern = doc["tableau"]["kernel"]
    lines = [method.name, f"continuous-stage method, {doc['tableau']['numbers']}"]
    if method.M is not None:
        lines.append("M = [" + ", ".join("[" + ", ".join(r) + "]" for r in method.M) + "]  (Miyatake–Butcher)")
    lines += [f"A(τ, σ) = {method.A}", f"B(τ) = {method.b}",
              f"degrees: {kern['degree_tau']} in τ, {kern['degree_sigma']} in σ; B: {kern['degree_b']}",
              f"certificate  {_answer(doc['certificate'])} — {doc['certificate']['reason']}",
              # the kernel's own verdict, for every Hamiltonian (verify judges a degree)
              f"AVF          {_answer(doc['avf'])}, for every Hamiltonian — {doc['avf']['reason']}",
              f"symmetric    {_answer(doc['symmetric'])} — {doc['symmetric']['reason']}",
              f"symplectic   {_answer(doc['symplectic'])} — {doc['symplectic']['reason']}"]
    lines += [f"warning: {w}" for w in doc["warnings"]]
    click.echo("\n".join(lines))
