"""``rkcheck show`` of a continuous-stage method: the kernel, its degrees and what the
kernel says by itself (certificate, AVF, symmetry, symplecticity)."""

from __future__ import annotations

from typing import Any

import click

from rkcheck.errors import UserError


def show_doc(method: Any, file: str) -> dict[str, Any]:
    from rkcheck.energy.continuous import kernel_facts
    from rkcheck.io.printable import printable
    from rkcheck.reports.jsondoc import SCHEMA
    from rkcheck.version import __version__

    k = method.kernel
    facts = kernel_facts(method, None)
    return {
        "schema": SCHEMA, "rkcheck": __version__, "file": printable(file),
        "method": {"name": method.name, "description": method.info.description,
                   "references": list(method.info.references)},
        "tableau": {
            "stages": None, "structure": "continuous",
            "numbers": "rational" if k.ring.field is None else f"algebraic (degree {k.ring.field.degree})",
            "kernel": {"A": method.A, "b": method.b, "M": None if method.M is None else [list(r) for r in method.M],
                       "degree_tau": k.deg_tau, "degree_sigma": k.deg_sigma, "degree_b": k.deg_b},
        },
        "certificate": {"state": facts.certificate.verdict.state, "reason": facts.certificate.reason},
        "equals_avf": facts.avf.equals_avf,
        "symmetric": {"state": facts.properties.symmetric.verdict.state, "reason": facts.properties.symmetric.reason},
        "symplectic": {"state": facts.properties.symplectic.verdict.state,
                       "reason": facts.properties.symplectic.reason},
        "warnings": list(method.info.warnings),
    }


def show_continuous(method: Any, fmt: str, file: str) -> None:
    """Print the method (text or json); the tableau formats have no kernel."""
    if fmt not in ("text", "json"):
        raise UserError(f"--format {fmt}: a continuous-stage method has no Butcher table; "
                        "`rkcheck discretize FILE --rule gauss-3` writes a tableau of it", source=file)
    doc = show_doc(method, file)
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
              f"certificate  {'yes' if doc['certificate']['state'] != 'fails' else 'no'} — {doc['certificate']['reason']}",
              f"AVF          {'yes' if doc['equals_avf'] else 'no'}",
              f"symmetric    {'yes' if doc['symmetric']['state'] != 'fails' else 'no'} — {doc['symmetric']['reason']}",
              f"symplectic   {'yes' if doc['symplectic']['state'] != 'fails' else 'no'} — {doc['symplectic']['reason']}"]
    lines += [f"warning: {w}" for w in doc["warnings"]]
    click.echo("\n".join(lines))
