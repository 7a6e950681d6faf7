"""``new`` and ``catalog``: writing tableau files for method families, and cataloguing them."""

from __future__ import annotations

import sys
from contextlib import nullcontext

import click

from rkcheck.api.methods import (
    CLASSICAL_METHODS,
    FAMILIES,
    unused_refusal,
)
from rkcheck.cli.common import (
    DEGREE,
    EXIT_FAIL,
    busy,
    exit_codes,
    flag_values,
    order_option,
    output_options,
    progress_steps,
)
from rkcheck.cli.output import check_output_target, write_text
from rkcheck.errors import UserError
from rkcheck.options import DIGITS_RANGE, MAX_FAMILY_STAGES


@click.command(epilog=exit_codes())
@click.argument("family", metavar="FAMILY|METHOD", type=click.Choice(FAMILIES + CLASSICAL_METHODS))
@click.option("--stages", "-s", "s", type=click.IntRange(1, MAX_FAMILY_STAGES), default=None, help="Number of stages s.")
@click.option("-k", "k", type=click.IntRange(1, MAX_FAMILY_STAGES), default=None,
              help="HBVM: number of Gauss nodes k (>= s).")
@click.option("--rule", default="gauss", show_default=True,
              help="AVF: quadrature rule gauss | radau-i | radau-ii | lobatto | zeta:<value>.")
@click.option("--zeta", default="0", show_default=True, help="kernel: the rule parameter ζ (nodes = zeros of P_2 − ζP_1).")
@click.option("--beta", default="1/10", show_default=True, help="kernel: the perturbation size β.")
@click.option("--digits", type=click.IntRange(*DIGITS_RANGE), default=None,
              help="Write D-digit decimals (default: exact expressions when the nodes have a closed form — "
              "square roots, or root(p, k) of their polynomial up to 8 nodes — else 60-digit decimals).")
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
      rkcheck new hbvm -k 6 -s 2 -o hbvm-6-2.toml # exact: root(p, k) of the nodes' polynomial
      rkcheck new gauss -s 10                     # 60-digit decimals (more than 8 nodes)
      rkcheck new avf -s 2 --rule radau-ii        # rational: plain fractions
      rkcheck new kernel --zeta 1/3 --beta 1e-12  # the seed's counterexample family
      rkcheck new gauss -s 2 | rkcheck verify - --degree 4
    """
    from rkcheck.api.methods import new_toml

    # a family's coefficients can take a moment (Gauss s = 20 at 1000 digits: about a
    # second); a classical method is written at once
    # typed, even at its default value: refused, never ignored
    given = ["stages" if name == "s" else name for name in flag_values("s", "k", "rule", "zeta", "beta", "digits",
                                                                        "exact")]
    refusal = unused_refusal(family, given, lambda name: _FLAGS["s" if name == "stages" else name])
    if refusal is not None:
        raise UserError(refusal)
    with busy(f"computing the {family} coefficients") if family in FAMILIES else nullcontext():
        try:
            text = new_toml(family, stages=s, k=k, rule=rule, zeta=zeta, beta=beta, digits=digits, exact=exact,
                            name=name)
        except UserError as err:  # the family table's keys are these options here
            if err.place and err.place.startswith("family."):
                raise type(err)(err.message, _FLAGS.get(err.place[len("family."):], err.place), err.source) from None
            raise
    write_text(text, output)


#: each of new's family options by the name its [family] table and parameters use
_FLAGS = {"s": "-s", "k": "-k", "rule": "--rule", "zeta": "--zeta", "beta": "--beta", "digits": "--digits",
          "exact": "--exact"}


@click.command(epilog=exit_codes(fail="a file could not be read (its row says why); the catalogue is still written",
                                   usage="a bad option, a PATH with no tableau file, or a limit (one line on stderr)"))
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
    from rkcheck.api.batch import catalog as make_catalog
    from rkcheck.reports.markdown import catalog_markdown

    try:
        degs = [DEGREE.convert(part.strip(), None, None) for part in degrees.split(",")]
    except click.BadParameter as err:
        raise UserError(err.message, "--degrees") from None
    if len(set(degs)) != len(degs):
        raise UserError(f"a degree is given twice in {degrees!r}", "--degrees")
    check_output_target(output, paths)
    with progress_steps("catalog", "files") as update:
        result = make_catalog(paths, degrees=degs, order=order, progress=update)
    # the command line the header records: no path stays no path
    command = " ".join(["rkcheck catalog", *paths] + ([f"--degrees {degrees}"] if degrees != "2,3,4,6,none" else [])
                       + ([f"--order {order}"] if order != 8 else []) + ([f"-o {output}"] if output else []))
    write_text(catalog_markdown(result.rows, result.labels, result.order, command, result.families), output)
    if any(r.error for r in result.rows):  # as a scan: a file that cannot be read fails the run
        sys.exit(EXIT_FAIL)
