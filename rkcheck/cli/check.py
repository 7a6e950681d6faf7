"""``verify``, ``show``, ``conditions``, ``explain``: one tableau, one tree, the conditions."""

from __future__ import annotations

import sys

import click

from rkcheck.cli.common import (
    DEGREE,
    EXIT_FAIL,
    EXIT_INTERRUPTED,
    EXIT_OK,
    announce_estimate,
    budget,
    cache_option,
    check_options,
    decimals_option,
    dps_option,
    echo_json,
    echo_json_rows,
    exit_codes,
    fail_on_option,
    flag_values,
    load_tableau,
    max_conditions_option,
    max_stages_option,
    order_option,
    output_options,
    progress_steps,
    project_config,
    settings,
    stdout_console,
)
from rkcheck.cli.families import at_option, family_member
from rkcheck.cli.output import printed_for, write_text
from rkcheck.errors import CheckInterrupted, OptionError, UserError
from rkcheck.options import DEFAULT_DPS, INPUT_FORMATS, JOBS_RANGE


def input_format_option(f):
    """--input-format: read FILE as this format instead of guessing by suffix and content."""
    return click.option("--input-format", type=click.Choice(INPUT_FORMATS), default=None,
                        help="Read FILE as this format [default: by suffix, then content].")(f)


def load_input(file: str, max_stages: int, input_format: str | None):
    """The tableau of FILE (or @name), in the format asked for, if any."""
    return load_tableau(file, max_stages, input_format)


@click.command(epilog=exit_codes(
    "a claim is broken or a condition fails, as --fail-on says: by default a file\nwith claims is judged "
    "by its claims, one without by its conditions (an AVF\ncertificate counts as holding)",
    "interrupted (Ctrl-C, SIGTERM); the report holds the orders that finished"))
@click.argument("file", metavar="FILE")
@check_options
@input_format_option
@click.option("--all", "show_all", is_flag=True, help="List every condition, not only the failing ones.")
@click.option("--draw", is_flag=True, help="Draw the free tree of each failing condition listed (text output).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--fail-fast", is_flag=True, help="Stop after the first order with a failing condition.")
@click.option("--jobs", "-j", type=click.IntRange(*JOBS_RANGE), default=1, show_default=True,
              help="Split an exact check's passes (groups of primes) over this many local processes.")
@click.option("--scheduler", metavar="ADDRESS", default=None,
              help="Split an exact check's passes over the workers of this Dask cluster (tcp://host:8786; "
              "needs rkcheck[cluster]).")
@fail_on_option
@at_option
@output_options
def verify(file, degree, order, dps, decimals, max_stages, max_conditions, arithmetic, require, input_format, show_all,
           draw, fmt, fail_fast, jobs, scheduler, fail_on, at) -> None:
    """Check every energy condition of the tableau in FILE ('-' = stdin), and the
    claims of its [expect] table."""
    from rkcheck.api.families import is_family_file
    from rkcheck.api.verification import run_check

    config = project_config()
    if not at and is_family_file(file):  # free [parameters]: the conditions as polynomials
        from rkcheck.cli.families import family_report

        # a family's polynomials are exact, its decimals at face value: the other check
        # options do not apply, and saying nothing would let them seem to
        unused = [f"--{name.replace('_', '-')}" for name in flag_values() if name not in ("degree", "order")]
        conditions = family_report(file, flag_values("degree", "order"), "order", fmt, show_all, ignored=unused)
        # a condition that is a nonzero constant fails for every member: the family fails
        gate = (fail_on or config.fail_on or "auto") != "never"
        sys.exit(EXIT_FAIL if gate and conditions.fails_everywhere is not None else EXIT_OK)
    if draw and fmt != "text":
        raise UserError(f"--draw draws in the text report, not in --format {fmt}")
    tab = family_member(file, at) if at else load_input(file, max_stages, input_format)
    fail_on = fail_on or config.fail_on or "auto"
    interrupted = False
    try:
        with progress_steps("checking", "orders") as update:  # the API's check: same options, same result
            result = run_check(tab, flag_values(), config.check, fail_on, budget(max_conditions), update,
                               scheduler=scheduler, jobs=jobs)
        failed = result.failed
    except CheckInterrupted as stop:  # report what was finished, then exit 130
        result, failed, interrupted = stop.result, True, True
    with printed_for(tab.info.source or file):
        _write_report(result, fmt, show_all, fail_on, draw)
    if interrupted:
        done = [p.order for p in result.per_order if p.checked]
        click.echo(f"rkcheck: interrupted; the report holds the orders that finished"
                   f"{f' (up to {max(done)})' if done else ' (none)'}", err=True)
        sys.exit(EXIT_INTERRUPTED)
    sys.exit(EXIT_FAIL if failed else EXIT_OK)


def _write_report(result, fmt: str, show_all: bool, fail_on: str, draw: bool) -> None:
    """The check's report on standard output, as JSON (streamed: a Ctrl-C while it is
    written closes the document) or as text."""
    if fmt == "json":
        from rkcheck.reports.jsondoc import check_doc
        echo_json_rows(check_doc(result, lazy=True))  # the rows go out as made: a Ctrl-C ends them, the document closes
    else:
        from rkcheck.reports.text import render_check

        out = settings()
        render_check(result, stdout_console(), show_all=show_all, quiet=out.quiet, verbose=out.verbose,
                     fail_on=fail_on, draw=draw)


@click.command(epilog=exit_codes())
@click.argument("file", metavar="FILE")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "toml", "tableau-json", "latex", "julia", "python"]),
              default="text", show_default=True,
              help="text/json: the report; toml/tableau-json: the tableau as a file rkcheck reads back; "
              "latex/julia/python: the tableau as code with exact entries.")
@decimals_option("auto")
@max_stages_option
@input_format_option
@at_option
@output_options
def show(file, fmt, decimals, max_stages, input_format, at) -> None:
    """Print the tableau in FILE as a Butcher table, with its kind and any warnings
    (FILE may be @name, a shipped tableau; .csv/.tsv and nodepy .txt files are read too)."""
    from rkcheck.api.tableaux import tableau_warnings, write  # the public rkcheck.write

    tab = family_member(file, at) if at else load_input(file, max_stages, input_format)
    if getattr(tab, "is_continuous", False):
        from rkcheck.reports.continuous import show_continuous

        show_continuous(tab, fmt, file, decimals)
        return
    if fmt not in ("text", "json"):
        click.echo(write(tab, "json" if fmt == "tableau-json" else fmt), nl=False)
        return
    warnings = tableau_warnings(tab, decimals)
    if fmt == "json":
        from rkcheck.reports.jsondoc import show_doc

        echo_json(show_doc(tab, file, decimals, warnings))
        return
    from rkcheck.reports.text import render_tableau

    render_tableau(tab, stdout_console(), decimals, warnings)


@click.command(epilog=exit_codes())
@click.argument("file", metavar="[FAMILY]", required=False)
@order_option(help="Energy order (free trees with <= N+1 vertices) [required; with a FAMILY file: default its "
                   "[check], else 6].")
@click.option("--degree", "-m", type=DEGREE, default="none", show_default=True, help="Maximum vertex degree m ('none' = no bound).")
@click.option("--count", is_flag=True, help="Only count the conditions per order (from generating functions: "
              "instant at any order).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--emit", type=click.Choice(["python", "sympy", "julia", "matlab", "latex"]), default=None,
              help="Write the conditions as code: functions of A and b returning the residuals.")
@click.option("--classical", is_flag=True, help="--emit: also the classical order conditions up to the same order.")
@click.option("--stages", "-s", "stages", type=click.IntRange(1, 64), default=None,
              help="--emit: the number of stages (adds unpack/pack of the free entries; sympy: the symbols).")
@click.option("--explicit", is_flag=True, help="--emit with --stages: A strictly lower triangular.")
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="--emit: write to this file instead of stdout.")
@max_conditions_option
@cache_option
@output_options
def conditions(file, order, degree, count, fmt, emit, classical, stages, explicit, output, max_conditions) -> None:
    """List the energy conditions (non-superfluous free trees) up to an order, or write
    them as code (--emit) for optimisers and computer algebra.  With a FAMILY file (a
    tableau with free [parameters]): each condition as an exact polynomial in the
    parameters (--classical: also the classical order conditions).

    \b
    Examples:
      rkcheck conditions --order 6 --degree 3
      rkcheck conditions --order 30 --count
      rkcheck conditions --emit python --degree 4 --order 6 --stages 3 --explicit -o conditions.py
    """
    from rkcheck.api.trees import conditions as list_conditions

    if file is None and order is None:
        raise click.MissingParameter(ctx=click.get_current_context(), param_hint="'--order' / '-N'",
                                     param_type="option")
    if emit is not None and fmt != "text":  # for a family and for the trees alike
        raise UserError(f"--format {fmt} and --emit do not go together (--emit writes {emit} code)")
    if file is not None:
        if count or stages or explicit or (output and emit is None):
            raise UserError("with a FAMILY file: --order, --degree, --classical, --format and --emit only "
                            "(--output goes with --emit)")
        from rkcheck.api.families import is_family_file
        from rkcheck.api.tableaux import load as load_file

        if not is_family_file(file) and getattr(load_file(file), "is_continuous", False):
            raise UserError("a continuous-stage method has no free parameters: `rkcheck verify FILE --all` lists "
                            "every condition with its exact residual", source=file)
        from rkcheck.cli.families import family_report

        # --degree left at its default: the family file's [check] degree, as verify reads it
        # --order too: given, else the file's [check] (order 6 without one), as verify reads it
        family_report(file, flag_values("degree", "order"), "order" if classical else None, fmt, True,
                      emit=emit, output=output)
        return
    if emit is None and (classical or stages or explicit or output):
        raise UserError("--classical, --stages, --explicit and --output go with --emit")
    if explicit and stages is None:
        raise UserError("--explicit needs --stages")
    if emit is not None and count:
        raise UserError("--count and --emit do not go together")
    listing = list_conditions(order, degree, count=count, max_conditions=max_conditions,
                              announce=announce_estimate()).listing
    if emit is not None:  # conditions as code (rkcheck.reports.code)
        from rkcheck.reports.code import emit as emit_code

        write_text(emit_code(listing, emit, classical, stages, explicit), output)
        return
    if fmt == "json":
        from rkcheck.reports.jsondoc import conditions_list_doc

        echo_json_rows(conditions_list_doc(listing, with_conditions=not count, lazy=True))
        return
    from rkcheck.reports.trees import render_condition_list

    render_condition_list(listing, stdout_console(), count)


@click.command(epilog=exit_codes())
@click.argument("tree_id", metavar="ID")
@click.option("--tableau", "tableau_file", metavar="FILE", default=None, help="Evaluate every term on this tableau.")
@click.option("--draw", "picture", metavar="FILE", default=None,
              help="Also draw the free tree to FILE (.svg, .png or .pdf; needs rkcheck[plot]).")
@dps_option(DEFAULT_DPS)
@decimals_option("auto")
@max_stages_option
@output_options
def explain(tree_id, tableau_file, picture, dps, decimals, max_stages) -> None:
    """Show one energy condition: the free tree of ID (drawn, its centre and the root
    of ID marked), its rootings, signs, σ and weights.

    ID is a level sequence of any rooting of the tree, e.g. 1,2,3,3,2 (as printed in
    the id column of verify and conditions).
    """
    from rkcheck.api.trees import energy_condition
    from rkcheck.reports.trees import render_explanation

    try:
        cond = energy_condition(tree_id, tableau_file or None, dps=dps, decimals=decimals, max_stages=max_stages)
    except OptionError as err:
        if err.place != "tree":
            raise
        raise UserError(err.message, "ID") from None  # the API's argument is this command's ID
    if picture:
        from rkcheck.reports.charts import tree_picture
        from rkcheck.reports.trees import tree_drawing

        given = ",".join(map(str, cond.given))
        title = (f"{given}: superfluous, no energy condition" if cond.tree is None
                 else f"{cond.id}  {cond.bracket}" + (f"  (given as {given})" if cond.id != given else ""))
        tree_picture(tree_drawing(cond.given), title, picture)
    with printed_for(tableau_file):
        render_explanation(cond, stdout_console())
