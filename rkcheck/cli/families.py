"""``rkcheck solve``, and the reports of ``verify``/``conditions`` on a family file."""

from __future__ import annotations

from typing import Any

import click

from rkcheck.cli.common import (
    DEGREE,
    busy,
    echo_json_rows,
    exit_codes,
    flag_values,
    output_options,
    settings,
    stdout_console,
)
from rkcheck.cli.output import check_output_target, write_text
from rkcheck.errors import OptionError, UserError, not_applying


def at_option(f: Any) -> Any:
    return click.option("--at", "at", metavar="NAME=VALUE", multiple=True,
                        help="With a family file (free [parameters]): the member at these values, one per "
                        "parameter, exact: 'k=1/3', 'k=sqrt(3)/6', 'k=root(x^3 - x - 1, 1)' (repeatable).")(f)


def family_member(file: str, at: tuple[str, ...]) -> Any:
    """The method in the family FILE at the values of ``--at`` (``NAME=VALUE`` each),
    with the file's ``[check]`` and claims: one method, checked as any other."""
    from rkcheck.api.families import is_family_file, load_family

    if not is_family_file(file):
        raise OptionError(f"{file} has no free [parameters]: it is one method already", "--at")
    values: dict[str, str] = {}
    for text in at:
        name, equals, value = (part.strip() for part in text.partition("="))
        if not equals or not name or not value:
            raise OptionError(f"expected NAME=VALUE, got {text!r}", "--at")
        if name in values:
            raise OptionError(f"{name} is given twice", "--at")
        values[name] = value
    family = load_family(file)
    try:
        return family.at(values, name=f"{family.name} at {', '.join(f'{k} = {v}' for k, v in values.items())}")
    except UserError as err:  # a value's error, named by the option and its parameter
        raise OptionError(err.message, f"--at {err.place}" if err.place else "--at") from None


def family_report(file: str, flags: dict, classical_order: int | str | None, fmt: str, show_all: bool,
                  emit: str | None = None, output: str | None = None, ignored: list[str] | None = None) -> Any:
    """The conditions of a family as polynomials (``verify`` and ``conditions`` on a file
    with ``[parameters]``): ``flags`` holds the degree and order given on the command
    line; the file's ``[check]`` supplies the others; ``classical_order`` ``"order"``:
    the classical conditions up to the energy order; ``ignored``: options given that do
    not apply to a family (a warning names them)."""
    import dataclasses

    from rkcheck.api.families import check_options, family_conditions, load_family
    from rkcheck.api.verification import UNSET

    check_output_target(output, [file])
    family = load_family(file)
    if ignored:
        note = (f"{not_applying(ignored)} to a family (its conditions are exact polynomials, its decimals read at "
                "face value): ignored")
        family = dataclasses.replace(family, notes=(*family.notes, note))
    degree, order = check_options(family, flags.get("degree", UNSET), flags.get("order", UNSET), ("--degree", "--order"))
    # "order": the classical conditions up to the same order as the energy conditions
    classical = order if classical_order == "order" else classical_order
    assert classical is None or isinstance(classical, int)
    with busy("the conditions as polynomials in the parameters"):
        result = family_conditions(family, degree=degree, order=order, classical_order=classical)
    if emit is not None:  # the polynomials as code (rkcheck.reports.family_code)
        from rkcheck.reports.family_code import FAMILY_LANGUAGES, emit_family

        if emit not in FAMILY_LANGUAGES:
            raise UserError(f"--emit {emit}: a family's conditions are written in {', '.join(FAMILY_LANGUAGES)}")
        write_text(emit_family(result, emit), output)
        return result
    if fmt == "json":
        from rkcheck.reports.families import conditions_doc

        echo_json_rows(conditions_doc(result, lazy=True))
        return result
    from rkcheck.reports.families import render_conditions

    render_conditions(result, stdout_console(), show_all=show_all or settings().verbose, quiet=settings().quiet)
    return result


@click.command(epilog=exit_codes(usage="a bad file, option, equation, or a limit reached (one line on stderr)"))
@click.argument("file", metavar="FILE")
@click.option("--degree", "-m", type=DEGREE, default=None,
              help="Polynomial degree m of the Hamiltonians ('none' = no bound).  [default: the file's [check], "
                   "else none]")
@click.option("--order", "-N", type=click.IntRange(1, 12), default=None,
              help="Energy order: every condition up to it.  [default: the file's [check], else 6]")
@click.option("--classical-order", type=click.IntRange(1, 12), default=None,
              help="Also the classical order conditions up to this order.")
@click.option("--where", "where", multiple=True, metavar="EQUATION",
              help="An extra equation in the parameters, e.g. \"a11 = a22\" or \"b1 + b2 + b3 = 1\"; an expression "
                   "without '=' means it is 0 (repeatable).")
@click.option("--max-seconds", type=click.FloatRange(1, 86_400), default=60, show_default=True,
              help="Time limit of the Gröbner bases; beyond it, a one-line error.")
@click.option("--route", type=click.Choice(["auto", "structured", "plain"]), default="auto", show_default=True,
              help="structured: quadrature conditions, then the conditions linear in A (A free); plain: one "
                   "Gröbner basis of every condition; auto: structured where it applies.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write the report to this file.")
@output_options
def solve(file, degree, order, classical_order, where, max_seconds, route, fmt, output) -> None:
    """The exact solution set of a family's conditions: every energy condition up to
    --order for Hamiltonians of degree <= --degree (plus --classical-order and --where
    equations), as a reduced Gröbner basis, its dimension, and every solution exactly
    when there are finitely many.

    FILE is a tableau file with a [parameters] table (name = "free"); its entries are
    polynomials in the parameters.

    \b
    Examples:
      rkcheck solve tableaux/families/theorem1-s2-m3.toml --degree 3 --order 6
      rkcheck solve tableaux/families/theorem1-s4-m8.toml --degree 8 --order 9
      rkcheck solve family.toml -m 5 -N 6 --where "b1 + b2 + b3 = 1" --format json
    """
    from rkcheck.api.families import check_options, load_family
    from rkcheck.api.families import solve as run
    from rkcheck.api.verification import UNSET

    check_output_target(output, [file])
    family = load_family(file)
    flags = flag_values("degree", "order")  # given on the command line, else the file's [check]
    degree, order = check_options(family, flags.get("degree", UNSET), flags.get("order", UNSET), ("--degree", "--order"))
    try:
        with busy("solving the family's conditions"):
            result = run(family, degree=degree, order=order, classical_order=classical_order, where=list(where),
                         max_seconds=max_seconds, route=route)
    except UserError as err:  # an option's error names the option as typed (the API's argument is "route")
        if err.source or err.place != "route":
            raise
        raise type(err)(err.message, "--route") from None
    if fmt == "json":
        from rkcheck.reports.families import solve_doc
        from rkcheck.reports.jsondoc import dumps

        options = {"degree": degree, "order": order, "classical_order": classical_order, "where": list(where),
                   "route": route}
        text = dumps(solve_doc(family, result, options))
        if output:
            write_text(text + "\n", output)
        else:
            click.echo(text)
        return
    from rkcheck.reports.families import render_solution_set

    scope = _scope(family, flags, degree, order)
    if output and output != "-":
        import io

        from rich.console import Console

        buffer = io.StringIO()
        render_solution_set(family, result, Console(file=buffer, no_color=True, width=120), scope)
        write_text(buffer.getvalue(), output)
        return
    render_solution_set(family, result, stdout_console(), scope)


def _scope(family: Any, flags: dict[str, Any], degree: int | None, order: int) -> str | None:
    """What was solved, when the command line did not say it all: each value and where it
    came from (typed, the file's [check], or the default)."""
    if "degree" in flags and "order" in flags:
        return None

    def source(name: str) -> str:
        return "" if name in flags else (" (the file's [check])" if name in family.info.check else " (the default)")

    bound = "no degree bound" if degree is None else f"degree ≤ {degree}"
    return f"energy conditions to order {order}{source('order')}, {bound}{source('degree')}"


@click.command(epilog=exit_codes(usage="a bad file, grid or option, or matplotlib missing for --plot (one line on stderr)"))
@click.argument("file", metavar="FILE")
@click.option("--grid", "grids", multiple=True, required=True, metavar="NAME=LO:HI:N",
              help="N equally spaced rational values of a parameter from LO to HI (or NAME=VALUE: one value); "
                   "every parameter needs one.")
@click.option("--degree", "-m", type=DEGREE, default=None, help="Polynomial degree m (default: the file's [check]).")
@click.option("--order", "-N", type=click.IntRange(1, 12), default=None,
              help="Energy order checked at each point (default: the file's [check], else 6).")
@click.option("--plot", metavar="OUT.png|.svg|.pdf", default=None, help="Chart the energy order over the grid "
              "(needs matplotlib: rkcheck[plot]).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--json", "as_json", is_flag=True, help="Same as --format json.")
@output_options
def sweep(file, grids, degree, order, plot, fmt, as_json) -> None:
    """The energy order of a family at every point of a grid of parameter values, each
    evaluated exactly (rational grid points, the conditions as exact polynomials).

    \b
    Examples:
      rkcheck sweep tableaux/families/sweep-s2-lobatto.toml --grid "beta=-1:1:21" --grid "gamma=0:1:21"
      rkcheck sweep FAMILY --grid "beta=-1:1:41" --grid "gamma=0:2:41" --plot order.png --json
    """
    from rkcheck.api.families import check_options, load_family
    from rkcheck.api.families import sweep as run
    from rkcheck.api.verification import UNSET

    family = load_family(file)
    # given on the command line (degree None: 'none'), else the file's [check]
    flags = flag_values("degree", "order")
    deg, N = check_options(family, flags.get("degree", UNSET), flags.get("order", UNSET), ("--degree", "--order"))
    if plot is not None:
        from rkcheck.reports.charts import pyplot

        pyplot("--plot")  # matplotlib present: fail before the work, not after
    with busy("the family's conditions over the grid"):
        result = run(family, list(grids), degree=deg, order=N)
    if plot is not None:
        from rkcheck.reports.sweep import sweep_chart

        sweep_chart(result, plot)
    if fmt == "json" or as_json:
        from rkcheck.reports.sweep import sweep_doc

        echo_json_rows(sweep_doc(result, lazy=True), rows="points")  # a Ctrl-C ends the points, the document closes
        return
    from rkcheck.reports.sweep import render_sweep

    render_sweep(result, stdout_console())
