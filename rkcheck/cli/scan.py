"""``scan``: every tableau file under some folders, in parallel, in one report."""

from __future__ import annotations

import sys
import time

import click

from rkcheck.cli.common import (
    EXIT_INTERRUPTED,
    EXIT_OK,
    check_options,
    check_output_target,
    fail_on_option,
    flag_values,
    output_options,
    progress,
    project_config,
    settings,
    stdout_console,
    write_text,
)
from rkcheck.errors import UserError
from rkcheck.io.printable import printable
from rkcheck.options import DEFAULT_ORDER, SCAN_FORMATS


@click.command()
@click.argument("paths", nargs=-1, metavar="[PATH...]")
@check_options
@click.option("--jobs", "-j", type=click.IntRange(1, 256), default=None, help="Worker processes [default: all cores].")
@click.option("--exclude", multiple=True, metavar="GLOB", help="Skip files matching GLOB (path or name); repeatable.")
@click.option("--format", "fmt", type=click.Choice(SCAN_FORMATS), default=None,
              help="Output format [default: [tool.rkcheck] format, else text].")
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write the report to this file (written even when interrupted).")
@click.option("--sort", "sort", type=click.Choice(["path", "energy"]), default="path", show_default=True,
              help="Row order: by path, or by energy order (best first) and then by the energy error constant C "
              "(a column C in the text report).")
@fail_on_option
@output_options
def scan(paths, degree, order, dps, decimals, max_stages, max_conditions, arithmetic, require, jobs, exclude, fmt,
         output, fail_on, sort) -> None:
    """Check every *.toml / *.json tableau under PATH... (recursively, in parallel).

    One row per file in a fixed order; a file that cannot be read is a row with its error,
    never a crash; other TOML/JSON files (pyproject.toml) are skipped. Defaults come from
    [tool.rkcheck] in the nearest pyproject.toml (paths, exclude, degree, order, dps,
    format, fail_on, jobs); flags override it.

    \b
    Exit code: 1 when a file fails under --fail-on (default: claims) or cannot be
    checked, 0 otherwise, 2 for a bad option, 130 when interrupted (the rows that
    finished are still written).
    """
    from rkcheck.batch.scan import default_jobs, exit_status, run_scan
    from rkcheck.io.discovery import find_tableau_files
    from rkcheck.reports import scan as scan_report

    config = project_config()
    roots = list(paths) or config.paths
    if not roots:
        raise UserError("give PATH... or set paths in [tool.rkcheck]", "scan")
    check_output_target(output)
    flags = flag_values()
    fmt = fmt or config.format or "text"
    fail_on = fail_on or config.fail_on or "claims"
    jobs = jobs or config.jobs or default_jobs()
    from rkcheck.energy.budget import Budget, check_budget, estimate
    from rkcheck.io.machine import available_memory

    # the resource guard (issue 16): the scan's default options must fit before the tables
    # are built; each file's own [check] is judged against the same budget (an error row)
    files_budget = Budget(available_memory(), max_conditions, None)
    default_order = flags.get("order", config.check.get("order", DEFAULT_ORDER))
    default_degree = flags.get("degree", config.check.get("degree"))
    check_budget(estimate(default_order, default_degree, "exact"), files_budget, default_order)
    t0 = time.perf_counter()
    outcomes, interrupted, files = [], False, []
    try:
        files = find_tableau_files(roots, list(exclude) + config.exclude)
        with progress("checking", len(files)) as advance:
            announce = _announcer(len(files))

            def on_result(r) -> None:
                advance()
                announce(r)

            outcomes, interrupted = run_scan(files, flags, config.check, fail_on, jobs, max_stages, on_result,
                                             files_budget)
    except KeyboardInterrupt:  # before or between files: the report still says what finished
        interrupted = True
    elapsed = time.perf_counter() - t0
    if sort == "energy":  # methods of equal energy order compared by their error constant
        from rkcheck.batch.ranking import rank_outcomes

        outcomes = rank_outcomes(outcomes)
    options = dict(flags, fail_on=fail_on, jobs=jobs, paths=roots)
    if fmt == "text" and output and output != "-":
        write_text(scan_report.scan_text(outcomes, elapsed, interrupted, constants=sort == "energy"), output)
    elif fmt == "text":
        scan_report.render_scan_text(outcomes, stdout_console(), elapsed, interrupted, verbose=settings().verbose,
                                     constants=sort == "energy")
    else:
        write_text(scan_report.scan_document(fmt, outcomes, interrupted, options, elapsed), output)
    if interrupted:
        click.echo("rkcheck: interrupted; the report holds the files that finished", err=True)
        sys.exit(EXIT_INTERRUPTED)
    sys.exit(EXIT_OK if fail_on == "never" else exit_status(outcomes))


def _announcer(total: int):
    """With --verbose and stderr not a terminal (CI logs, a calling program), one line per
    finished file on stderr: ``rkcheck: [3/40] ok path`` (on a terminal the progress bar
    says the same)."""
    import os

    if not settings().verbose or settings().quiet or os.isatty(2):
        return lambda r: None
    count = [0]

    def announce(r) -> None:
        count[0] += 1
        click.echo(f"rkcheck: [{count[0]}/{total}] {r.status} {printable(r.path)}", err=True)

    return announce
