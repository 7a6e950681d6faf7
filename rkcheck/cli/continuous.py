"""``discretize``: a continuous-stage method turned into a tableau by a quadrature rule."""

from __future__ import annotations

import click

from rkcheck.cli.common import (
    exit_codes,
    output_options,
)
from rkcheck.cli.output import check_output_target, write_text


@click.command(epilog=exit_codes())
@click.argument("file", metavar="FILE")
@click.option("--rule", required=True,
              help="gauss-K | radau-i-K | radau-ii-K | lobatto-K | newton-cotes-K (K nodes), or a tableau FILE "
              "whose b and c are the rule.")
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write to this file instead of stdout.")
@output_options
def discretize(file, rule, output) -> None:
    """Write the tableau a_ij = b_j A(c_i, c_j), b_i = b_i B(c_i) of the continuous-stage
    method in FILE on a quadrature rule (TOML, exact; 60-digit decimals past 8
    irrational nodes), and say up to which degree of Hamiltonian it keeps every energy
    condition.

    \b
    Examples:
      rkcheck discretize tableaux/continuous/epcm-2.toml --rule gauss-4   # HBVM(4, 2)
      rkcheck discretize tableaux/continuous/avf.toml --rule lobatto-3 -o avf-lobatto-3.toml
    """
    from rkcheck.api.tableaux import discretize as discretize_method

    check_output_target(output, [file, rule])  # a rule may be a tableau file too
    text, note = discretize_method(file, rule, command=" ".join(["rkcheck", "discretize", file, "--rule", rule]))
    write_text(text, output)
    click.echo(note, err=True)  # the tableau alone on stdout: it can be piped into verify
