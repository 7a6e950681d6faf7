"""The ``rkcheck`` command line: options in, core call, report out.

Heavy modules (numpy, mpmath, matplotlib, the reports) are imported inside the
commands that need them, so that ``rkcheck verify`` starts quickly.  Every
:class:`~rkcheck.errors.UserError` and click usage error ends as one line on stderr and
exit code 2.
"""

from __future__ import annotations

import functools
import sys
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Callable, Iterator

import click

from rkcheck import __version__
from rkcheck.energy.claims import FAIL_ON
from rkcheck.errors import UserError

EXIT_OK, EXIT_FAIL, EXIT_USAGE, EXIT_INTERNAL = 0, 1, 2, 3
MAX_ORDER = 20


class DegreeType(click.ParamType):
    """A polynomial degree m >= 1, or ``none`` for all Hamiltonians."""

    name = "m|none"

    def convert(self, value: Any, param, ctx) -> int | str:
        if isinstance(value, int):
            return value
        text = str(value).strip().lower()
        if text in ("none", "all", "any"):
            return "none"
        try:
            m = int(text)
        except ValueError:
            self.fail(f"{value!r} is not a degree (a positive integer or 'none')", param, ctx)
        if m < 1:
            self.fail(f"degree must be at least 1, got {m}", param, ctx)
        return m


DEGREE = DegreeType()


def output_options(f: Callable) -> Callable:
    """--quiet / --verbose / --no-color, accepted by every command (and the group)."""

    @click.option("--no-color", is_flag=True, default=None, help="No colour (also: NO_COLOR=1, or output not a terminal).")
    @click.option("--verbose", "-v", is_flag=True, default=None, help="More detail (timings, notes).")
    @click.option("--quiet", "-q", is_flag=True, default=None, help="Only the essential lines.")
    @functools.wraps(f)
    def wrapper(*args: Any, no_color: bool | None, verbose: bool | None, quiet: bool | None, **kwargs: Any) -> Any:
        from rkcheck.reports import console

        current = console._settings
        console.configure(
            color=not no_color if no_color is not None else current["color"],
            quiet=quiet if quiet is not None else current["quiet"],
            verbose=verbose if verbose is not None else current["verbose"],
        )
        return f(*args, **kwargs)

    return wrapper


def check_options(f: Callable) -> Callable:
    """--degree / --order / --dps / --decimals / --max-stages, shared by the checking commands."""
    f = click.option(
        "--max-stages", type=click.IntRange(1), default=64, show_default=True,
        help="Refuse tableaux with more stages than this.",
    )(f)
    f = click.option(
        "--decimals", type=click.Choice(["rounded", "exact"]), default=None,
        help="Decimal literals with >= 6 significant digits: 'rounded' (default) = within half a unit "
        "of the last digit; 'exact' = at face value.",
    )(f)
    f = click.option(
        "--dps", type=click.IntRange(10, 5000), default=None,
        help="Working precision in decimal digits for non-rational tableaux [default: file's [check], else 50].",
    )(f)
    f = click.option(
        "--order", "-N", type=click.IntRange(1, MAX_ORDER), default=None,
        help="Check conditions up to this energy order, i.e. free trees with <= N+1 vertices "
        "[default: file's [check], else 8].",
    )(f)
    f = click.option(
        "--degree", "-m", type=DEGREE, default=None,
        help="Polynomial Hamiltonians of degree <= m ('none' = all Hamiltonians) "
        "[default: file's [check], else none].",
    )(f)
    return f


def fail_on_option(f: Callable) -> Callable:
    return click.option(
        "--fail-on", type=click.Choice(FAIL_ON), default=None,
        help="What makes the exit code 1: 'auto' = broken claims for files with an [expect] table, "
        "failing conditions otherwise; 'conditions'; 'claims'; 'never'. [default: verify auto, scan claims]",
    )(f)


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


# ------------------------------------------------------------------ helpers


def load_tableau(path: str, max_stages: int):
    from rkcheck.io.loader import load

    return load(path, max_stages=max_stages)


def cli_check_values(degree, order, dps, decimals, fail_fast=False, max_stages=64) -> dict[str, Any]:
    """The check options given on the command line (only those given)."""
    out: dict[str, Any] = {"max_stages": max_stages}
    if degree is not None:
        out["degree"] = None if degree == "none" else degree
    if order is not None:
        out["order"] = order
    if dps is not None:
        out["dps"] = dps
    if decimals is not None:
        out["decimals"] = decimals
    if fail_fast:
        out["fail_fast"] = True
    return out


def project_config():
    from rkcheck.io.config import load_config

    return load_config()


@contextmanager
def _progress(label: str, total: int) -> Iterator[Callable[[], None]]:
    """A rich progress bar on stderr (hidden when stderr is not a terminal or --quiet)."""
    from rkcheck.reports.console import is_quiet, make_console

    console = make_console(stderr=True)
    if is_quiet() or not console.is_terminal:
        yield lambda: None
        return
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeRemainingColumn,
    )

    with Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  console=console, transient=True) as progress:
        task = progress.add_task(label, total=total)
        yield lambda: progress.advance(task)


def _stdout():
    from rkcheck.reports.console import make_console

    return make_console()


# ----------------------------------------------------------------- commands


@cli.command()
@click.argument("file", metavar="FILE")
@check_options
@click.option("--all", "show_all", is_flag=True, help="List every condition, not only the failing ones.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--fail-fast", is_flag=True, help="Stop after the first order with a failing condition.")
@fail_on_option
@output_options
def verify(file, degree, order, dps, decimals, max_stages, show_all, fmt, fail_fast, fail_on) -> None:
    """Check every energy condition of the tableau in FILE ('-' = stdin), and the
    claims of its [expect] table.

    \b
    Exit code (--fail-on auto): a file with claims is judged by its claims, a file
    without claims by its conditions (an AVF certificate counts as holding):
      0  all good   1  a claim is broken / a condition fails   2  bad file or option
    """
    from rkcheck.batch.scan import options_for
    from rkcheck.energy.claims import judge_tableau

    config = project_config()
    tab = load_tableau(file, max_stages)
    options = options_for(tab, cli_check_values(degree, order, dps, decimals, fail_fast), config.check)
    fail_on = fail_on or config.fail_on or "auto"
    result, claim_results, failed = judge_tableau(tab, options, fail_on)
    if fmt == "json":
        from rkcheck.reports.jsondoc import check_doc, dumps

        click.echo(dumps(check_doc(result, claim_results)))
    else:
        from rkcheck.reports.console import is_quiet, is_verbose
        from rkcheck.reports.text import render_check

        render_check(result, _stdout(), show_all=show_all, quiet=is_quiet(), claims=claim_results,
                     verbose=is_verbose(), fail_on=fail_on)
    sys.exit(EXIT_FAIL if failed else EXIT_OK)


@cli.command()
@click.argument("file", metavar="FILE")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--decimals", type=click.Choice(["rounded", "exact"]), default="rounded", show_default=True)
@click.option("--max-stages", type=click.IntRange(1), default=64, show_default=True)
@output_options
def show(file, fmt, decimals, max_stages) -> None:
    """Print the tableau in FILE as a Butcher table, with its kind and any warnings."""
    from rkcheck.methods.tableau import consistency_warnings
    from rkcheck.numbers.precision import bits_for_dps

    tab = load_tableau(file, max_stages)
    warnings = list(tab.warnings) + consistency_warnings(tab, bits_for_dps(50), decimals)
    if fmt == "json":
        from rkcheck.reports.jsondoc import SCHEMA, dumps, method_doc, tableau_doc

        doc = {"schema": SCHEMA, "file": file, "method": method_doc(tab), "tableau": tableau_doc(tab, decimals), "warnings": warnings}
        click.echo(dumps(doc))
        return
    from rkcheck.reports.text import render_tableau

    render_tableau(tab, _stdout(), decimals, warnings)


@cli.command()
@click.option("--order", "-N", type=click.IntRange(1, MAX_ORDER), required=True, help="Energy order (free trees with <= N+1 vertices).")
@click.option("--degree", "-m", type=DEGREE, default="none", show_default=True, help="Maximum vertex degree m ('none' = no bound).")
@click.option("--count", is_flag=True, help="Only count the conditions per order.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@output_options
def conditions(order, degree, count, fmt) -> None:
    """List the energy conditions (non-superfluous free trees) up to an order."""
    from rkcheck.trees.conditions import condition_table

    table = condition_table(order, None if degree == "none" else degree)
    counts = table.counts_by_order()
    if fmt == "json":
        from rkcheck.reports.jsondoc import dumps

        doc: dict[str, Any] = {
            "schema": 1,
            "order": order,
            "degree": None if degree == "none" else degree,
            "total": len(table),
            "counts": [{"order": k, "vertices": k + 1, "conditions": v} for k, v in counts.items()],
        }
        if not count:
            doc["conditions"] = [
                {
                    "id": c.id, "level_sequence": list(c.level_sequence), "bracket": c.bracket,
                    "vertices": c.vertices, "order": c.order, "max_degree": c.max_degree, "rootings": len(c.terms),
                }
                for c in table.conditions
            ]
        click.echo(dumps(doc))
        return
    from rkcheck.reports.text import render_condition_list

    render_condition_list(table, _stdout(), count)


@cli.command()
@click.argument("tree_id", metavar="ID")
@click.option("--tableau", "tableau_file", metavar="FILE", default=None, help="Evaluate every term on this tableau.")
@click.option("--dps", type=click.IntRange(10, 5000), default=50, show_default=True)
@click.option("--decimals", type=click.Choice(["rounded", "exact"]), default="rounded", show_default=True)
@click.option("--max-stages", type=click.IntRange(1), default=64, show_default=True)
@output_options
def explain(tree_id, tableau_file, dps, decimals, max_stages) -> None:
    """Show one energy condition: the free tree of ID, its rootings, signs, σ and weights.

    ID is a level sequence of any rooting of the tree, e.g. 1,2,3,3,2 (as printed in
    the id column of verify and conditions).
    """
    from rkcheck.energy.explain import explain as do_explain
    from rkcheck.reports.text import render_explanation
    from rkcheck.trees.rooted import parse_level_sequence

    try:
        seq = parse_level_sequence(tree_id)
    except ValueError as err:
        raise UserError(str(err), "ID") from None
    if len(seq) > MAX_ORDER + 1:
        raise UserError(f"at most {MAX_ORDER + 1} vertices", "ID")
    tab = load_tableau(tableau_file, max_stages) if tableau_file else None
    render_explanation(do_explain(seq, tab, dps, decimals), _stdout(), tab)


@cli.command()
@click.argument("family", metavar="FAMILY", type=click.Choice(
    ["avf", "gauss", "lobatto-iiia", "lobatto-iiib", "radau-iia", "radau-ia", "hbvm", "kernel"]))
@click.option("--stages", "-s", "s", type=click.IntRange(1, 64), default=None, help="Number of stages s.")
@click.option("-k", "k", type=click.IntRange(1, 64), default=None, help="HBVM: number of Gauss nodes k (>= s).")
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
    """Write a complete tableau file (TOML) for a method FAMILY.

    \b
    Examples:
      rkcheck new gauss -s 3                      # exact: sqrt(15) closed forms
      rkcheck new hbvm -k 6 -s 2 -o hbvm-6-2.toml # 60-digit decimals (no closed form)
      rkcheck new avf -s 2 --rule radau-ii        # rational: plain fractions
      rkcheck new kernel --zeta 1/3 --beta 1e-12  # the seed's counterexample family
      rkcheck new gauss -s 2 | rkcheck verify - --degree 4
    """
    from rkcheck.io.writers import render_toml
    from rkcheck.methods.families import parse_spec

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
    command = "rkcheck new " + " ".join(sys.argv[2:]) if len(sys.argv) > 2 else f"rkcheck new {family}"
    text = render_toml(spec, mode, digits or 60, name, command)
    if output and output != "-":
        with open(output, "w", encoding="utf-8") as fh:
            fh.write(text)
    else:
        click.echo(text, nl=False)


@cli.command()
@click.argument("paths", nargs=-1, metavar="[PATH...]")
@check_options
@click.option("--jobs", "-j", type=click.IntRange(1, 256), default=None, help="Worker processes [default: all cores].")
@click.option("--exclude", multiple=True, metavar="GLOB", help="Skip files matching GLOB (path or name); repeatable.")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "csv", "junit", "github"]), default=None,
              help="Output format [default: [tool.rkcheck] format, else text].")
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write the report to this file (written even when interrupted).")
@fail_on_option
@output_options
def scan(paths, degree, order, dps, decimals, max_stages, jobs, exclude, fmt, output, fail_on) -> None:
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
    import time as _time

    from rkcheck.batch.scan import default_jobs, exit_status, run_scan
    from rkcheck.io.discovery import find_tableau_files

    config = project_config()
    roots = list(paths) or config.paths
    if not roots:
        raise UserError("give PATH... or set paths in [tool.rkcheck]", "scan")
    files = find_tableau_files(roots, list(exclude) + config.exclude)
    cli_values = cli_check_values(degree, order, dps, decimals, max_stages=max_stages)
    fmt = fmt or config.format or "text"
    fail_on = fail_on or config.fail_on or "claims"
    jobs = jobs or config.jobs or default_jobs()
    t0 = _time.perf_counter()
    with _progress("checking", len(files)) as advance:
        outcomes, interrupted = run_scan(files, cli_values, config.check, fail_on, jobs, lambda r: advance())
    elapsed = _time.perf_counter() - t0
    from rkcheck.reports import scan as scanout

    options = {k: v for k, v in cli_values.items() if k != "max_stages"}
    options.update(fail_on=fail_on, jobs=jobs, paths=roots)
    if fmt == "text":
        if output and output != "-":
            from rich.console import Console

            with open(output, "w", encoding="utf-8") as fh:
                scanout.render_scan_text(outcomes, Console(file=fh, no_color=True, width=140), elapsed, interrupted)
        else:
            from rkcheck.reports.console import is_verbose

            scanout.render_scan_text(outcomes, _stdout(), elapsed, interrupted, verbose=is_verbose())
    else:
        text = {
            "json": lambda: scanout.scan_json(outcomes, interrupted, options) + "\n",
            "csv": lambda: scanout.scan_csv(outcomes),
            "junit": lambda: scanout.scan_junit(outcomes, elapsed),
            "github": lambda: scanout.scan_github(outcomes),
        }[fmt]()
        _write_report(text, output)
    if interrupted:
        click.echo("rkcheck: interrupted; the report holds the files that finished", err=True)
        sys.exit(130)
    sys.exit(EXIT_OK if fail_on == "never" else exit_status(outcomes))


def _write_report(text: str, output: str | None) -> None:
    """Write a report to stdout or, atomically, to a file."""
    if not output or output == "-":
        click.echo(text, nl=False)
        return
    import os
    import tempfile

    target = Path(output)
    fd, tmp = tempfile.mkstemp(dir=target.parent if str(target.parent) else ".", prefix=".rkcheck-", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(tmp, target)


@cli.command()
@click.argument("paths", nargs=-1, required=True, metavar="PATH...")
@click.option("--degrees", default="2,3,4,6,none", show_default=True,
              help="Comma-separated degrees m for the energy-order columns ('none' = all Hamiltonians).")
@click.option("--order", "-N", type=click.IntRange(1, MAX_ORDER), default=8, show_default=True)
@click.option("--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), default=None,
              help="Write to this file ('-' = stdout, the default).")
@output_options
def catalog(paths, degrees, order, output) -> None:
    """Write a Markdown catalogue of tableau files (how tableaux/README.md is made).

    \b
    Example:
      rkcheck catalog tableaux/ -o tableaux/README.md
    """
    from rkcheck.batch.catalog import catalog_row
    from rkcheck.io.discovery import find_tableau_files
    from rkcheck.reports.markdown import catalog_markdown

    degs: list[int | None] = []
    for part in degrees.split(","):
        d = DEGREE.convert(part, None, None)
        degs.append(None if d == "none" else d)
    files = find_tableau_files(list(paths), exclude=["README*", "*/README*"])
    root = Path(paths[0]) if len(paths) == 1 and Path(paths[0]).is_dir() else None
    rows = []
    with _progress("catalog", len(files)) as advance:
        for f in files:
            row = catalog_row(f, degs, order)
            if root is not None:
                row.path = str(Path(f).relative_to(root))
            rows.append(row)
            advance()
    labels = ["all H" if d is None else f"m={d}" for d in degs]
    command = "rkcheck catalog " + " ".join(sys.argv[2:]) if len(sys.argv) > 2 else "rkcheck catalog"
    text = catalog_markdown(rows, labels, order, command)
    if output and output != "-":
        Path(output).write_text(text, encoding="utf-8")
    else:
        click.echo(text, nl=False)


def _dps_list(text: str) -> list[int]:
    try:
        values = [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise UserError(f"expected a comma-separated list of integers, got {text!r}", "--dps") from None
    if not values or any(d < 10 or d > 5000 for d in values):
        raise UserError("each dps must be between 10 and 5000", "--dps")
    return values


def _degree_value(degree, tab):
    if degree is None:
        return tab.check.get("degree") if tab is not None else None
    return None if degree == "none" else degree


@cli.command()
@click.argument("file", metavar="FILE")
@click.option("--degree", "-m", type=DEGREE, default=None, help="Degree m ('none' = all) [default: file's [check]].")
@click.option("--order", "-N", type=click.IntRange(1, MAX_ORDER), default=None, help="Order N [default: file's [check], else 8].")
@click.option("--dps", "dps_text", default="15,30,50,100,200,400", show_default=True, help="mpmath precisions to run.")
@click.option("--repeat", type=click.IntRange(1, 50), default=3, show_default=True, help="Best of this many runs.")
@click.option("--chart", metavar="OUT.png|.svg", default=None, help="Draw time against certified digits (needs matplotlib).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@output_options
def bench(file, degree, order, dps_text, repeat, chart, fmt) -> None:
    """Run the same check on every backend: float64 screen, certified balls at each --dps, exact.

    One row per backend: wall time, conditions per second, the weakest certified digits,
    the certified failures, and whether the verdicts agree with the most precise backend.
    """
    from rkcheck.studies.accuracy import bench_backends, bench_json

    tab = load_tableau(file, 64)
    deg = _degree_value(degree, tab)
    N = order if order is not None else tab.check.get("order", 8)
    rows, t_tables = bench_backends(tab, deg, N, _dps_list(dps_text), repeat=repeat)
    title = f"{tab.name}: degree {'none' if deg is None else deg}, order {N}, {rows[0].conditions} conditions"
    if chart:
        from rkcheck.reports.charts import bench_chart

        bench_chart(rows, title, chart)
    if fmt == "json":
        from rkcheck.reports.jsondoc import dumps

        click.echo(dumps({"schema": 1, "file": file, "degree": deg, "order": N, **bench_json(rows, t_tables)}))
        return
    from rkcheck.reports.studies import render_bench

    render_bench(rows, t_tables, _stdout(), title)
    if chart:
        click.echo(f"chart written to {chart}")


@cli.command()
@click.argument("file", metavar="FILE")
@click.option("--direction", required=True, metavar="random|kernel|entry:i,j",
              help="Perturb A along a fixed-seed random matrix, the zero-row-sum kernel direction of the "
              "double-bush map (needs --degree >= 3), or one entry.")
@click.option("--degree", "-m", type=DEGREE, default=None, help="Degree m [default: file's [check]].")
@click.option("--order", "-N", type=click.IntRange(1, MAX_ORDER), default=None, help="Order N [default: file's [check], else 8].")
@click.option("--eps", "eps_text", default="1e-1..1e-30", show_default=True,
              help="ε values: 1e-1..1e-40 (every decade), 1e-2..1e-30:2 (every 2nd), or a list 1e-3,1e-6.")
@click.option("--dps", "dps_text", default="15,50", show_default=True, help="mpmath precisions whose detection is reported.")
@click.option("--seed", type=int, default=2024, show_default=True, help="Seed of the random direction.")
@click.option("--chart", metavar="OUT.png|.svg", default=None, help="Draw max|R| against ε with each backend's floor.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@output_options
def perturb(file, direction, degree, order, eps_text, dps_text, seed, chart, fmt) -> None:
    """Perturb the tableau's A by ε·D and watch the energy conditions fail.

    For each ε: max |R| over the failing conditions, the first failing order, and which
    backends still certify the failure. Prints the fitted slope of log max|R| against
    log ε (1 for generic directions, 2 for kernel directions: the seed's quadratic
    failure) and each backend's detection threshold ε*.
    """
    from rkcheck.studies.accuracy import direction as make_direction
    from rkcheck.studies.accuracy import parse_eps, perturb_sweep

    tab = load_tableau(file, 64)
    deg = _degree_value(degree, tab)
    N = order if order is not None else tab.check.get("order", 8)
    D, desc = make_direction(tab, direction, deg, seed)
    res = perturb_sweep(tab, D, desc, parse_eps(eps_text), deg, N, _dps_list(dps_text))
    title = f"{tab.name} + ε·D: degree {'none' if deg is None else deg}, order {N}"
    if chart:
        from rkcheck.reports.charts import perturb_chart

        perturb_chart(res, title, chart)
    if fmt == "json":
        from rkcheck.numbers.formatting import decimal_string
        from rkcheck.reports.jsondoc import dumps

        doc = {
            "schema": 1, "file": file, "direction": desc, "degree": deg, "order": N, "slope": res.slope,
            "thresholds": {k: None if v is None else str(v) for k, v in res.thresholds.items()},
            "floors": res.floors,
            "rows": [{"eps": str(r.eps), "max_residual": None if r.max_residual is None else decimal_string(r.max_residual, 12),
                      "first_failing_order": r.first_failing_order, "failing": r.failing, "detected": r.detected}
                     for r in res.rows],
        }
        click.echo(dumps(doc))
        return
    from rkcheck.reports.studies import render_perturb

    render_perturb(res, _stdout(), title)
    if chart:
        click.echo(f"chart written to {chart}")


@cli.command()
@click.option("--stages", "-s", type=click.IntRange(1, 12), default=None, help="Number of stages s.")
@click.option("--degree", "-m", type=click.IntRange(3, 40), required=True, help="Polynomial degree m (>= 3).")
@click.option("--rule", default="gauss", show_default=True, help="gauss | radau-i | radau-ii | lobatto | zeta:<value>.")
@click.option("--tableau", "tableau_file", metavar="FILE", default=None, help="Use this tableau's b and c = A·1 instead of a rule.")
@click.option("--dps", type=click.IntRange(15, 2000), default=50, show_default=True)
@output_options
def kernel(stages, degree, rule, tableau_file, dps) -> None:
    """Rank and kernel of the double-bush map M (seed Lemma 2) on s×s matrices.

    Exact for rational rules; otherwise numerical, with the singular values around the
    cut printed so that the gap is visible. Also the part of ker M with zero row sums
    (seed Lemma "onedim"): the directions A → A + βN that keep every linear condition.

    \b
    Examples:
      rkcheck kernel -s 2 -m 4                  # Gauss, m = 2s: rank s²−1, kernel (1−c)bᵀ
      rkcheck kernel -s 3 -m 5 --rule radau-i   # ζ = −1: rank s²−s−1
      rkcheck kernel -m 3 --tableau tableaux/avf/avf-radau-ii-2.toml
    """
    from rkcheck.energy.double_bush import kernel_of, rule_values, tableau_rule
    from rkcheck.reports.studies import render_kernel

    if tableau_file:
        tab = load_tableau(tableau_file, 64)
        b, c, exact = tableau_rule(tab, dps)
        title = f"double-bush map of {tab.name} (b and c = A·1), degree {degree}"
    else:
        if stages is None:
            raise UserError("give --stages/-s (or --tableau FILE)")
        b, c, exact = rule_values(rule, stages, dps)
        title = f"double-bush map at the {stages}-point {rule} rule, degree {degree}"
    render_kernel(kernel_of(b, c, degree, exact, dps), _stdout(), title)


def _fraction_option(text: str, place: str):
    from fractions import Fraction

    from rkcheck.numbers.entries import Entry

    try:
        e = Entry.parse(text)
    except UserError as err:
        raise err.located(place) from None
    if e.exact is None or e.exact <= 0:
        raise UserError(f"expected a positive rational number, got {text!r}", place)
    return Fraction(e.exact)


@cli.command()
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--problem", "-p", "problem_spec", required=True,
              help="harmonic | henon-heiles | quartic | fpu | random:degree=m[,dim=d][,seed=S].")
@click.option("--h", "h_text", default="1/10", show_default=True, help="Step size (a rational: 0.1, 1/16).")
@click.option("--steps", type=click.IntRange(1, 10_000_000), default=1000, show_default=True)
@click.option("--dps", type=click.IntRange(15, 2000), default=None,
              help="Integrate in mpmath at this precision [default: float64; --energy-order: 40, or more "
              "when verify's first failing residual is too small to be seen in one step].")
@click.option("--energy-order", is_flag=True,
              help="One step from random points at h = 2^-3..2^-10: fit the empirical energy order and "
              "compare it with verify's algebraic one (exit 1 when they disagree).")
@click.option("--points", type=click.IntRange(1, 100), default=4, show_default=True, help="--energy-order: starting points.")
@click.option("--seed", type=int, default=7, show_default=True, help="--energy-order: seed of the starting points.")
@click.option("--chart", metavar="OUT.png|.svg", default=None, help="Draw |ΔH| over time (or against h).")
@click.option("--max-stages", type=click.IntRange(1), default=64, show_default=True)
@output_options
def simulate(files, problem_spec, h_text, steps, dps, energy_order, points, seed, chart, max_stages) -> None:
    """Integrate a polynomial Hamiltonian with each tableau and watch the energy.

    \b
    Without --energy-order: |H(y_n) − H(y_0)| over time, a short table per tableau.
    With --energy-order: the empirical energy order (slope − 1 of log|ΔH| against
    log h, fitted on the asymptotic small steps) against verify's algebraic energy
    order for the problem's degree; an energy-preserving method shows "ΔH at solver
    precision". Exit 1 on a disagreement.

    \b
    Examples:
      rkcheck simulate tableaux/explicit/rk4.toml --problem random:degree=4 --energy-order
      rkcheck simulate tableaux/collocation/gauss-2.toml tableaux/avf/avf-gauss-2.toml \\
          --problem henon-heiles --h 1/10 --steps 2000 --chart drift.png
    """
    from rkcheck.dynamics.hamiltonians import problem
    from rkcheck.reports.simulation import render_energy_fit, render_series

    ham = problem(problem_spec)
    tabs = [load_tableau(f, max_stages) for f in files]
    console = _stdout()
    if energy_order:
        from rkcheck.dynamics.simulate import energy_order_agreement

        disagree = 0
        series = []
        for tab in tabs:
            fit, agreement = energy_order_agreement(tab, ham, dps=dps, points=points, seed=seed)
            render_energy_fit(tab, ham, fit, agreement, console)
            disagree += not agreement.agree
            series.append((tab.name, [float(r.h) for r in fit.rows], [float(r.delta) for r in fit.rows]))
        if chart:
            from rkcheck.reports.charts import energy_chart

            energy_chart(series, f"one-step energy error on {ham.name}", chart, xlabel="h", ylabel="|ΔH| (geometric mean)", loglog=True)
            click.echo(f"chart written to {chart}")
        sys.exit(EXIT_FAIL if disagree else EXIT_OK)
    from rkcheck.dynamics.simulate import energy_series, start_point

    h = _fraction_option(h_text, "--h")
    y0 = start_point(ham)
    all_series = []
    for tab in tabs:
        t, dH = energy_series(tab, ham, y0, h, steps, dps)
        render_series(tab, ham, h, steps, dps, t, dH, console)
        all_series.append((tab.name, t, dH))
    if chart:
        from rkcheck.reports.charts import energy_chart

        energy_chart(all_series, f"energy error on {ham.name}, h = {h}, {'float64' if not dps else f'{dps} digits'}", chart)
        click.echo(f"chart written to {chart}")


@cli.command()
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--problem", "-p", "problem_spec", required=True, help="As for simulate.")
@click.option("--T", "T_text", default="10", show_default=True, help="Final time.")
@click.option("--steps", "steps_text", default="20,40,80,160,320,640", show_default=True,
              help="Comma-separated numbers of steps (step sizes T/N).")
@click.option("--chart", metavar="OUT.png|.svg", default=None, help="Draw error and energy error against time.")
@click.option("--max-stages", type=click.IntRange(1), default=64, show_default=True)
@output_options
def workprec(files, problem_spec, T_text, steps_text, chart, max_stages) -> None:
    """Work–precision: error at T and energy error against wall time, one line per tableau.

    Each tableau runs in float64 over the step counts; the error is measured against a
    reference solution computed with 6-stage Gauss collocation (order 12) at 20 digits.
    """
    from rkcheck.dynamics.hamiltonians import problem
    from rkcheck.dynamics.simulate import work_precision
    from rkcheck.reports.simulation import render_workprec

    ham = problem(problem_spec)
    T = _fraction_option(T_text, "--T")
    try:
        counts = [int(x) for x in steps_text.split(",") if x.strip()]
    except ValueError:
        raise UserError(f"expected comma-separated integers, got {steps_text!r}", "--steps") from None
    if not counts or min(counts) < 1:
        raise UserError("step counts must be positive", "--steps")
    tabs = [load_tableau(f, max_stages) for f in files]
    wp = work_precision(tabs, ham, T, counts)
    render_workprec(wp, ham, _stdout())
    if chart:
        from rkcheck.reports.charts import workprec_chart

        workprec_chart(wp, f"work–precision on {ham.name}, T = {T}", chart)
        click.echo(f"chart written to {chart}")


# ------------------------------------------------------------------- main


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
        sys.exit(130)
    except click.exceptions.Exit as err:
        sys.exit(err.exit_code)
    except click.ClickException as err:
        click.echo(f"rkcheck: error: {err.format_message()}", err=True)
        sys.exit(EXIT_USAGE)
    except BrokenPipeError:  # `rkcheck ... | head`
        sys.exit(EXIT_OK)
    except KeyboardInterrupt:
        click.echo("rkcheck: interrupted", err=True)
        sys.exit(130)
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
