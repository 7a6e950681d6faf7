"""The ``rkcheck`` group, its commands, and the entry point that turns every error into
one line on stderr and an exit code (0 ok, 1 fail, 2 user error, 3 bug, 130 interrupted)."""

from __future__ import annotations

import sys

import click

from rkcheck import __version__
from rkcheck.cli.check import conditions, explain, show, verify
from rkcheck.cli.common import (
    EXIT_INTERNAL,
    EXIT_INTERRUPTED,
    EXIT_OK,
    EXIT_USAGE,
    output_options,
)
from rkcheck.cli.dynamics import simulate, workprec
from rkcheck.cli.library import catalog, new
from rkcheck.cli.scan import scan
from rkcheck.cli.studies import bench, kernel, perturb
from rkcheck.errors import UserError


@click.group(context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(__version__, prog_name="rkcheck")
@output_options
def cli() -> None:
    """Check the energy-preservation conditions of a Runge–Kutta method.

    Give it a Butcher tableau (TOML or JSON) and it evaluates every B-series energy
    condition (one per free tree, Chartier–Faou–Murua) for polynomial Hamiltonians of
    degree <= m, in exact or certified arbitrary-precision arithmetic, and says whether
    the tableau is the Averaged Vector Field method.

    \b
    Start with:
      rkcheck show tableaux/collocation/gauss-2.toml
      rkcheck verify tableaux/collocation/gauss-2.toml --degree 4
    """


for command in (verify, show, conditions, explain, new, scan, catalog, bench, perturb, kernel, simulate, workprec):
    cli.add_command(command)


def main(argv: list[str] | None = None) -> None:
    """Entry point: one-line errors with exit code 2, never a traceback for user errors."""
    try:
        cli.main(args=argv, prog_name="rkcheck", standalone_mode=False)
    except UserError as err:
        click.echo(f"rkcheck: error: {err}", err=True)
        sys.exit(EXIT_USAGE)
    except click.UsageError as err:
        if type(err).__name__ == "NoArgsIsHelpError":  # click >= 8.2: bare `rkcheck`
            click.echo(err.ctx.get_help() if err.ctx else err.format_message())
            sys.exit(EXIT_USAGE)
        where = f"{err.ctx.command_path}: " if err.ctx is not None else ""
        click.echo(f"rkcheck: error: {where}{err.format_message()} (see --help)", err=True)
        sys.exit(EXIT_USAGE)
    except click.Abort:
        click.echo("rkcheck: aborted", err=True)
        sys.exit(EXIT_INTERRUPTED)
    except click.exceptions.Exit as err:
        sys.exit(err.exit_code)
    except click.ClickException as err:
        click.echo(f"rkcheck: error: {err.format_message()}", err=True)
        sys.exit(EXIT_USAGE)
    except BrokenPipeError:  # `rkcheck ... | head`
        sys.exit(EXIT_OK)
    except KeyboardInterrupt:
        click.echo("rkcheck: interrupted", err=True)
        sys.exit(EXIT_INTERRUPTED)
    except MemoryError:  # the estimate let it through, the machine did not: a limit, not a bug
        click.echo("rkcheck: error: out of memory; lower --order or --dps, or set --max-conditions to refuse "
                   "such checks before they start", err=True)
        sys.exit(EXIT_USAGE)
    except Exception as err:  # a bug in rkcheck, not a user error
        import os

        if os.environ.get("RKCHECK_DEBUG"):
            raise
        click.echo(
            f"rkcheck: internal error: {type(err).__name__}: {err} — this is a bug in rkcheck; please report "
            "it with the command and the file (RKCHECK_DEBUG=1 shows the traceback)",
            err=True,
        )
        sys.exit(EXIT_INTERNAL)
