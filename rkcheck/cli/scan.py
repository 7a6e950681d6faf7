"""``scan``: every tableau file under some folders, in parallel, in one report."""

from __future__ import annotations

import sys
from typing import Any, Callable

import click

from rkcheck.cli.common import (
    EXIT_FAIL,
    EXIT_INTERRUPTED,
    EXIT_OK,
    check_options,
    exit_codes,
    fail_on_option,
    flag_values,
    output_options,
    progress_steps,
    project_config,
    settings,
    stdout_console,
)
from rkcheck.cli.output import check_output_target, write_text
from rkcheck.io.printable import printable
from rkcheck.options import JOBS_RANGE, SCAN_FORMATS, SCAN_SORTS


@click.command(epilog=exit_codes(
    "a file fails under --fail-on (default: a broken claim) or cannot be checked;\n"
    "never with --fail-on never, which always exits 0 after a complete scan",
    "interrupted (Ctrl-C, SIGTERM); the report holds the files that finished",
    "a bad option, [tool.rkcheck] or path, or no tableau file at all under the\npaths (unless --allow-empty); "
    "one line on stderr"))
@click.argument("paths", nargs=-1, metavar="[PATH...]")
@check_options
@click.option("--jobs", "-j", type=click.IntRange(*JOBS_RANGE), default=None, help="Worker processes [default: all cores].")
@click.option("--scheduler", metavar="ADDRESS", default=None,
              help="Check the files on this Dask cluster (tcp://host:8786) instead of local processes; "
              "'local': local processes whatever the environment says "
              "[default: RKCHECK_SCHEDULER, else [tool.rkcheck] scheduler; needs rkcheck[cluster]].")
@click.option("--exclude", multiple=True, metavar="GLOB", help="Skip files matching GLOB (path or name); repeatable.")
@click.option("--format", "fmt", type=click.Choice(SCAN_FORMATS), default=None,
              help="Output format [default: [tool.rkcheck] format, else text].")
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write the report to this file (written even when interrupted).")
@click.option("--sort", "sort", type=click.Choice(SCAN_SORTS), default="path", show_default=True,
              help="Row order: by path, or by energy order (best first) and then by the energy error constant C "
              "(a column C in the text report).")
@click.option("--allow-empty", is_flag=True, default=None,
              help="Pass (exit 0) when the paths hold no tableau file [default: exit 2; also [tool.rkcheck] allow_empty].")
@fail_on_option
@output_options
def scan(paths, degree, order, dps, decimals, max_stages, max_conditions, arithmetic, require, jobs, scheduler, exclude,
         fmt, output, fail_on, sort, allow_empty) -> None:
    """Check every *.toml / *.json tableau under PATH... (recursively, in parallel).

    One row per file in a fixed order; a file that cannot be read is a row with its error,
    never a crash; other TOML/JSON files (pyproject.toml) are skipped. Defaults come from
    [tool.rkcheck] in the nearest pyproject.toml (paths, exclude, degree, order, dps,
    format, fail_on, jobs, allow_empty, scheduler); flags override it.
    """
    from rkcheck.api.batch import scan as run_scan
    from rkcheck.api.batch import scan_roots
    from rkcheck.reports import scan as scan_report

    config = project_config()
    roots = scan_roots(paths, config)
    check_output_target(output, roots)
    fmt = fmt or config.format or "text"
    with progress_steps("checking", "files") as update:  # the API's scan: same options, same rows
        result = run_scan(roots, **flag_values(), exclude=exclude, fail_on=fail_on, jobs=jobs, sort=sort,
                          max_stages=max_stages, max_conditions=max_conditions, project=config,
                          allow_empty=allow_empty, progress=update, on_file=_announcer(), scheduler=scheduler,
                          json_in_workers=fmt == "json")
    outcomes, elapsed, interrupted = result.outcomes, result.elapsed, result.interrupted
    if fmt == "text" and output and output != "-":
        write_text(scan_report.scan_text(outcomes, elapsed, interrupted, constants=sort == "energy",
                                         fail_on=result.fail_on), output)
    elif fmt == "text":
        scan_report.render_scan_text(outcomes, stdout_console(), elapsed, interrupted, verbose=settings().verbose,
                                     constants=sort == "energy", fail_on=result.fail_on, quiet=settings().quiet)
    else:
        write_text(scan_report.scan_document(fmt, outcomes, interrupted, result.options, elapsed), output)
    if interrupted:
        click.echo("rkcheck: interrupted; the report holds the files that finished", err=True)
        sys.exit(EXIT_INTERRUPTED)
    sys.exit(EXIT_FAIL if result.failed else EXIT_OK)


def _announcer() -> Callable[[Any, int, int], None] | None:
    """With --verbose and stderr not a terminal (CI logs, a calling program), one line per
    finished file on stderr: ``rkcheck: [3/40] ok path`` (on a terminal the progress bar
    says the same)."""
    import os

    if not settings().verbose or settings().quiet or os.isatty(2):
        return None

    def announce(row: Any, done: int, total: int) -> None:
        click.echo(f"rkcheck: [{done}/{total}] {row.status} {printable(row.path)}", err=True)

    return announce
