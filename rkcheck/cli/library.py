"""``new`` and ``catalog``: writing tableau files for method families, and cataloguing them."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

from rkcheck.cli.common import (
    DEGREE,
    guard,
    order_option,
    output_options,
    busy,
    progress,
    write_text,
)
from rkcheck.errors import UserError
from rkcheck.methods.classics import NAMES as CLASSIC_NAMES
from rkcheck.methods.families import FAMILIES
from rkcheck.options import MAX_FAMILY_STAGES


def _command_line(spec, mode: str, digits: int | None) -> str:
    """The ``rkcheck new`` command that writes ``spec`` (recorded in the file's description)."""
    parts = ["rkcheck new", spec.name]
    params = spec.params()
    if spec.name == "kernel":
        parts += [f"--zeta {params['zeta']}", f"--beta {params['beta']}"]
    else:
        parts.append(f"-s {spec.s}")
        if spec.name == "hbvm":
            parts.append(f"-k {spec.k}")
        if spec.name == "avf" and spec.rule != "gauss":
            parts.append(f"--rule {spec.rule}")
    if mode == "exact":
        parts.append("--exact")
    elif digits is not None:
        parts.append(f"--digits {digits}")
    return " ".join(parts)


@click.command()
@click.argument("family", metavar="FAMILY|METHOD", type=click.Choice(FAMILIES + tuple(CLASSIC_NAMES)))
@click.option("--stages", "-s", "s", type=click.IntRange(1, MAX_FAMILY_STAGES), default=None, help="Number of stages s.")
@click.option("-k", "k", type=click.IntRange(1, MAX_FAMILY_STAGES), default=None,
              help="HBVM: number of Gauss nodes k (>= s).")
@click.option("--rule", default="gauss", show_default=True,
              help="AVF: quadrature rule gauss | radau-i | radau-ii | lobatto | zeta:<value>.")
@click.option("--zeta", default="0", show_default=True, help="kernel: the rule parameter ζ (nodes = zeros of P_2 − ζP_1).")
@click.option("--beta", default="1/10", show_default=True, help="kernel: the perturbation size β.")
@click.option("--digits", type=click.IntRange(1, 5000), default=None,
              help="Write D-digit decimals (default: exact expressions when the nodes have a closed form "
              "in square roots, else 60-digit decimals).")
@click.option("--exact", is_flag=True, help="Require exact entries (fails if the nodes have no closed form).")
@click.option("--name", default=None, help="The [method] name (default: from the family).")
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write to this file instead of stdout.")
@output_options
def new(family, s, k, rule, zeta, beta, digits, exact, name, output) -> None:
    """Write a complete tableau file (TOML) for a method FAMILY, or for a classical
    METHOD (exact entries from the literature, with claims: rk4, rk38, heun, ralston,
    midpoint, rk3, ssprk3, euler, backward-euler, implicit-midpoint, trapezoid, sdirk2,
    sdirk3).

    \b
    Examples:
      rkcheck new rk4                             # a classical method
      rkcheck new gauss -s 3                      # exact: sqrt(15) closed forms
      rkcheck new hbvm -k 6 -s 2 -o hbvm-6-2.toml # 60-digit decimals (no closed form)
      rkcheck new avf -s 2 --rule radau-ii        # rational: plain fractions
      rkcheck new kernel --zeta 1/3 --beta 1e-12  # the seed's counterexample family
      rkcheck new gauss -s 2 | rkcheck verify - --degree 4
    """
    from rkcheck.io.writers import render_toml
    from rkcheck.methods.families import parse_spec

    if family in CLASSIC_NAMES:
        from rkcheck.io.formats import document_toml
        from rkcheck.methods.classics import CLASSICS

        doc = CLASSICS[CLASSIC_NAMES[family]].document()
        if name:
            doc["method"]["name"] = name
        write_text(document_toml(doc), output)
        return

    if exact and digits is not None:
        raise UserError("give either --exact or --digits, not both")
    table: dict[str, Any] = {"name": family}
    if family == "kernel":
        table.update(zeta=zeta, beta=beta)
    else:
        if s is None:
            raise UserError(f"{family} needs --stages/-s")
        table["s"] = s
        if family == "hbvm":
            if k is None:
                raise UserError("hbvm needs -k (the number of Gauss nodes, k >= s)")
            table["k"] = k
        if family == "avf":
            table["rule"] = rule
    spec = parse_spec(table)
    mode = "exact" if exact else ("digits" if digits is not None else "auto")
    with busy(f"computing the {family} coefficients"):
        text = render_toml(spec, mode, digits or 60, name, _command_line(spec, mode, digits))
    write_text(text, output)


@click.command()
@click.argument("paths", nargs=-1, required=False, metavar="[PATH...]")
@click.option("--degrees", default="2,3,4,6,none", show_default=True,
              help="Comma-separated degrees m for the energy-order columns ('none' = all Hamiltonians).")
@order_option(default=8)
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write to this file ('-' = stdout, the default).")
@output_options
def catalog(paths, degrees, order, output) -> None:
    """Write a Markdown catalogue of tableau files (how tableaux/README.md is made);
    without PATH, of the tableaux shipped with rkcheck (the names @name accepts).

    \b
    Example:
      rkcheck catalog tableaux/ -o tableaux/README.md
      rkcheck catalog --order 4            # the shipped library
    """
    from rkcheck.batch.catalog import catalog_row
    from rkcheck.io.discovery import find_tableau_files
    from rkcheck.io.library import library_root
    from rkcheck.reports.markdown import catalog_markdown

    shown = paths  # the command line the header records: no path stays no path
    if not paths:
        root_dir = library_root()
        if root_dir is None:
            raise UserError("no tableaux are installed with rkcheck; give a PATH")
        paths = (str(root_dir),)

    degs = [DEGREE.convert(part, None, None) for part in degrees.split(",")]
    guard(order, None if None in degs else max(degs), runs=0)  # the resource guard (issue 16)
    files = find_tableau_files(list(paths), exclude=["README*", "*/README*"])
    root = Path(paths[0]) if len(paths) == 1 and Path(paths[0]).is_dir() else None
    rows = []
    with progress("catalog", len(files)) as advance:
        for f in files:
            row = catalog_row(f, degs, order)
            if root is not None:
                row.path = str(Path(f).relative_to(root))
            rows.append(row)
            advance()
    labels = ["all H" if d is None else f"m={d}" for d in degs]
    command = " ".join(["rkcheck catalog", *shown] + ([f"--degrees {degrees}"] if degrees != "2,3,4,6,none" else [])
                       + ([f"--order {order}"] if order != 8 else []) + ([f"-o {output}"] if output else []))
    write_text(catalog_markdown(rows, labels, order, command), output)
