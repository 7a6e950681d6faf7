"""What every command shares: option decorators, exit codes, the output settings of the
run, progress bars, and loading a tableau.

Commands stay thin: they parse options (here), call one function of the public API
(:mod:`rkcheck.api`), and hand its result to a report (:mod:`rkcheck.reports`); they
import nothing else of rkcheck (tests/test_layout.py).  Heavy modules (numpy, mpmath,
the reports) are imported inside the commands that need them, so that ``rkcheck
verify`` starts quickly.
"""

from __future__ import annotations

import functools
from contextlib import contextmanager
from typing import Any, Callable, Iterator

import click

from rkcheck.errors import OptionError, UserError
from rkcheck.options import (
    DECIMALS_MODES,
    DEFAULT_MAX_STAGES,
    DPS_RANGE,
    FAIL_ON,
    MAX_DEGREE,
    MAX_ORDER,
    MAX_STAGES_RANGE,
    parse_degree,
    parse_require,
)
from rkcheck.reports.console import OutputSettings, make_console

EXIT_OK, EXIT_FAIL, EXIT_USAGE, EXIT_INTERNAL, EXIT_INTERRUPTED = 0, 1, 2, 3, 130


def exit_codes(fail: str | None = None, interrupted: str = "interrupted (Ctrl-C, SIGTERM)",
               usage: str = "a bad file, entry, option or limit (one line on stderr)") -> str:
    """The end of a command's --help: every exit code the command can give, with its
    meaning (``fail``: what exit 1 means, for the commands that judge; None: never 1;
    a newline in a meaning continues it on an indented line)."""
    rows = [(EXIT_OK, "success" if fail is None else "all good")]
    if fail is not None:
        rows.append((EXIT_FAIL, fail))
    rows += [(EXIT_USAGE, usage),
             (EXIT_INTERNAL, "internal error: a bug in rkcheck (please report it)"),
             (EXIT_INTERRUPTED, interrupted)]
    return "\b\nExit codes:\n" + "\n".join(f"  {code:<4} " + meaning.replace("\n", "\n       ") for code, meaning in rows)


class DegreeType(click.ParamType):
    """A polynomial degree m >= 1, or ``none`` for all Hamiltonians (parsed to None)."""

    name = "m|none"

    def convert(self, value: Any, param, ctx) -> int | None:
        try:
            return parse_degree(value, "degree")
        except UserError:
            self.fail(f"{value!r} is not a degree (an integer from 1 to {MAX_DEGREE}, or 'none')", param, ctx)


DEGREE = DegreeType()


# ------------------------------------------------------------------ output settings


def settings() -> OutputSettings:
    """The output settings of the command being run."""
    ctx = click.get_current_context(silent=True)
    obj = ctx.obj if ctx is not None else None
    return obj if isinstance(obj, OutputSettings) else OutputSettings()


def output_options(f: Callable) -> Callable:
    """--quiet / --verbose / --no-color, accepted by every command (and the group); a
    flag on the command overrides the same flag on the group."""

    @click.option("--no-color", is_flag=True, default=None, help="No colour (also: NO_COLOR=1, or output not a terminal).")
    @click.option("--verbose", "-v", is_flag=True, default=None, help="More detail (timings, notes).")
    @click.option("--quiet", "-q", is_flag=True, default=None, help="Problems only: failing conditions that decide the verdict, broken claims, "
              "files that fail or cannot be read; then the verdict line.")
    @functools.wraps(f)
    def wrapper(*args: Any, no_color: bool | None, verbose: bool | None, quiet: bool | None, **kwargs: Any) -> Any:
        ctx = click.get_current_context()
        inherited = ctx.parent.obj if ctx.parent is not None and isinstance(ctx.parent.obj, OutputSettings) else OutputSettings()
        ctx.obj = OutputSettings(
            color=inherited.color if no_color is None else not no_color,
            quiet=inherited.quiet if quiet is None else quiet,
            verbose=inherited.verbose if verbose is None else verbose,
        )
        try:
            return f(*args, **kwargs)
        except UserError as err:
            # an error of the check itself (not of reading the file) still names the
            # file it is about: one line names file and place, whatever raised it
            file = kwargs.get("file")
            about_options = isinstance(err, OptionError) or type(err).__name__ == "ResourceError"
            if isinstance(file, str) and not err.source and not about_options:
                raise err.located(source=file) from None
            raise

    return wrapper


def stdout_console():
    return make_console(settings())


def echo_json(doc: Any) -> None:
    """``doc`` as a JSON report on standard output, written in pieces as they are made:
    a report of millions of conditions is never held whole as text (nor, where its
    rows are a generator, as rows)."""
    from rkcheck.reports.jsontext import chunks

    for part in chunks(doc):
        click.echo(part, nl=False)
    click.echo()


def echo_json_rows(doc: dict[str, Any], rows: str = "conditions") -> None:
    """``doc`` as JSON (:func:`echo_json`), its list ``rows`` written as its rows are
    made: a Ctrl-C or SIGTERM meanwhile ends the list, the document closes with
    ``"<rows>_complete": false``, and the program ends with exit 130.  A document
    without the list (``conditions --count``) is written as it is."""
    import itertools
    import sys

    if rows not in doc:
        echo_json(doc)
        return

    with interrupts_deferred() as signal:
        doc[rows] = itertools.takewhile(lambda _: not signal.asked, iter(doc[rows]))
        doc[f"{rows}_complete"] = lambda: not signal.asked
        echo_json(doc)
    if signal.asked:
        click.echo(f"rkcheck: interrupted while writing; the report lists the {rows} written before "
                   f'(JSON "{rows}_complete": false)', err=True)
        sys.exit(EXIT_INTERRUPTED)


def _stderr_is_terminal() -> bool:
    import sys

    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


class _Bars:
    """Progress bars on a rich ``Progress``: ``update(done, total)`` moves the current
    bar; ``begin(label, unit)`` starts a new one (a new check run: the bars of the runs
    before stay, complete, until the work ends)."""

    def __init__(self, progress: Any, label: str, unit: str) -> None:
        self.progress, self.label, self.unit = progress, label, unit
        self.task: Any = None

    def begin(self, label: str, unit: str) -> None:
        self.task = self.progress.add_task(label, total=None, unit=unit)

    def __call__(self, done: int, total: int) -> None:
        if self.task is None:
            self.begin(self.label, self.unit)
        self.progress.update(self.task, completed=done, total=total)


class _NoBars:
    """What a hidden progress bar is: every call does nothing."""

    def begin(self, label: str, unit: str) -> None:
        pass

    def __call__(self, done: int, total: int) -> None:
        pass


@contextmanager
def progress_steps(label: str, unit: str) -> Iterator[Callable[[int, int], None]]:
    """Rich progress bars on stderr driven by ``update(done, total)`` and labelled with
    what one step is (``unit``: files, orders, primes); ``update.begin(label, unit)``
    starts the bar of a new run (a check and each claim run with other options).
    Hidden when stderr is not a terminal or --quiet; they disappear when the work is
    done."""
    console = make_console(settings(), stderr=True)
    # the stream itself, not console.is_terminal: FORCE_COLOR makes rich treat a pipe as a
    # terminal, and a progress bar in a log file is noise
    if settings().quiet or not _stderr_is_terminal():
        yield _NoBars()
        return
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeRemainingColumn,
    )

    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TextColumn("{task.fields[unit]}"),
                  TimeRemainingColumn(), console=console, transient=True) as bar:
        yield _Bars(bar, label, unit)


@contextmanager
def busy(label: str) -> Iterator[None]:
    """A spinner with the elapsed time on stderr, for work whose length is not known in
    steps (family coefficients at large s, ranks, sweeps): hidden when stderr is not a
    terminal or --quiet; it disappears when the work is done."""
    console = make_console(settings(), stderr=True)
    if settings().quiet or not _stderr_is_terminal():  # the stream itself, as for progress_steps
        yield
        return
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    with Progress(SpinnerColumn(), TextColumn(label), TimeElapsedColumn(), console=console, transient=True) as bar:
        bar.add_task(label, total=None)
        yield


# ------------------------------------------------------------------ check options


def order_option(default: int | None = None, required: bool = False, help: str | None = None) -> Callable:
    # no default at all unless one is given: click (8.3 on) takes an explicit default=None
    # as a value, and then a required option left out is no longer an error
    given: dict[str, Any] = {} if default is None else {"default": default}
    return click.option(
        "--order", "-N", type=click.IntRange(1, MAX_ORDER), required=required, show_default=default is not None,
        help=help or "Check conditions up to this energy order, i.e. free trees with <= N+1 vertices"
        + (" [default: file's [check], else 8]." if default is None else "."), **given,
    )


def degree_option(default: Any = None, help: str | None = None) -> Callable:
    return click.option(
        "--degree", "-m", type=DEGREE, default=default, show_default=default is not None,
        help=help or "Polynomial Hamiltonians of degree <= m ('none' = all Hamiltonians) "
        "[default: file's [check], else none].",
    )


def max_stages_option(f: Callable) -> Callable:
    return click.option(
        "--max-stages", type=click.IntRange(*MAX_STAGES_RANGE), default=DEFAULT_MAX_STAGES, show_default=True,
        help="Refuse tableaux with more stages than this.",
    )(f)


def decimals_option(default: str | None = None) -> Callable:
    return click.option(
        "--decimals", type=click.Choice(list(DECIMALS_MODES)), default=default, show_default=default is not None,
        help="What a decimal literal stands for. auto (default): one with >= 6 significant digits is "
        "within half a unit of its last digit, or within half an ulp of the double it is the shortest "
        "repr of (what Python/numpy print); rounded: the half unit only; float64: every nonzero "
        "decimal is a double and stands for its rounding interval; exact: face value.",
    )


def dps_option(default: int | None = None) -> Callable:
    return click.option(
        "--dps", type=click.IntRange(*DPS_RANGE), default=default, show_default=default is not None,
        help="Working precision in decimal digits for non-rational tableaux"
        + ("" if default is not None else " [default: file's [check], else 50]") + ".",
    )


def max_conditions_option(f: Callable) -> Callable:
    return click.option(
        "--max-conditions", type=click.IntRange(1), default=None,
        help="Refuse checks with more conditions than this [default: whatever fits in the memory "
        "available]; setting it also skips the memory check.",
    )(f)


def arithmetic_option(f: Callable) -> Callable:
    return click.option(
        "--arithmetic", type=click.Choice(["auto", "exact", "ball"]), default="auto", show_default=True,
        help="'auto' = exact when the entries are exact numbers, else certified balls; 'exact' refuses "
        "data that is not exact; 'ball' = certified balls at --dps in any case.",
    )(f)


class RequireType(click.ParamType):
    """The proof gate: any, proof or digits:D (rkcheck.options.parse_require)."""

    name = "any|proof|digits:D"

    def convert(self, value, param, ctx):
        if not isinstance(value, str):
            return value
        try:
            return parse_require(value, "--require")
        except UserError as err:
            self.fail(err.message, param, ctx)


def require_option(f: Callable) -> Callable:
    return click.option(
        "--require", type=RequireType(), default="any", show_default=True,
        help="What counts as a pass. any: holds, or holds to D >= 1 digits; proof: only exact holds and exact "
        "certificates (a 'holds to D digits' fails the gate, exit 1); digits:D: numerical holds need "
        "at least D digits. Also [check] require.",
    )(f)


def check_options(f: Callable) -> Callable:
    """--degree / --order / --dps / --decimals / --require / --max-stages / --max-conditions /
    --arithmetic / --no-cache, shared by the checking commands."""
    for decorator in (cache_option, arithmetic_option, require_option, max_conditions_option, max_stages_option,
                      decimals_option(), dps_option(), order_option(), degree_option()):
        f = decorator(f)
    return f


def cache_option(f: Callable) -> Callable:
    """--no-cache: neither read nor save condition listings in the listing cache (also
    RKCHECK_NO_CACHE=1); without it the command uses the cache."""

    @click.option("--no-cache", is_flag=True, default=False,
                  help="Build the condition listings afresh; neither read nor save the listing cache "
                       "(also RKCHECK_NO_CACHE=1; see 'rkcheck cache info').")
    @functools.wraps(f)
    def wrapper(*args: Any, no_cache: bool, **kwargs: Any) -> Any:
        from rkcheck.api.settings import listing_cache_scope

        with listing_cache_scope(not no_cache):
            return f(*args, **kwargs)

    return wrapper


def budget(max_conditions: int | None):
    """The resource budget of a check run from the command line: the memory this
    machine has available, an explicit --max-conditions, and estimates of long checks
    said on stderr (unless --quiet)."""
    from rkcheck.api.settings import budget as machine_budget

    return machine_budget(max_conditions, announce_estimate())


def announce_estimate() -> Callable[[str], None] | None:
    """Where the estimate of a long check is said: stderr, unless --quiet."""
    if settings().quiet:
        return None
    return lambda text: click.echo(f"rkcheck: {text}", err=True)


def fail_on_option(f: Callable) -> Callable:
    return click.option(
        "--fail-on", type=click.Choice(FAIL_ON), default=None,
        help="What makes the exit code 1: 'auto' = broken claims for files with an [expect] table, "
        "failing conditions otherwise; 'conditions'; 'claims'; 'never'. [default: verify auto, scan claims]",
    )(f)


def flag_values(*names: str) -> dict[str, Any]:
    """The check options the user gave on the command line, parsed (``degree`` None =
    'none'), by name; options left at their default are absent, so that the file's
    ``[check]`` and ``[tool.rkcheck]`` can supply them (rkcheck.options)."""
    from click.core import ParameterSource

    ctx = click.get_current_context()
    names = names or ("degree", "order", "dps", "decimals", "fail_fast", "require", "arithmetic")
    out: dict[str, Any] = {}
    for name in names:
        if name in ctx.params and ctx.get_parameter_source(name) in (ParameterSource.COMMANDLINE, ParameterSource.ENVIRONMENT):
            out[name] = ctx.params[name]
    return out


# ------------------------------------------------------------------ inputs


def load_tableau(path: str, max_stages: int = DEFAULT_MAX_STAGES, input_format: str | None = None):
    """FILE or @name through the public API's :func:`rkcheck.load` (the CLI
    reads tableaux the way a library user does)."""
    from rkcheck.api.tableaux import load

    return load(path, max_stages=max_stages, format=input_format)


def project_config():
    """``[tool.rkcheck]`` of the nearest pyproject.toml, through the API."""
    from rkcheck.api.settings import project_config as load_project_config

    return load_project_config()


def chart_file(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """A ``--chart`` option's file: a name, not an empty text (which would draw nothing
    and say nothing)."""
    if value is not None and not value.strip():
        raise click.BadParameter("expected a file name (OUT.png, OUT.svg or OUT.pdf)")
    return value


class Stop:
    """Whether SIGINT or SIGTERM arrived (:func:`interrupts_deferred`)."""

    asked = False


@contextmanager
def interrupts_deferred() -> Iterator[Stop]:
    """SIGINT and SIGTERM only noted, for a writer that must end what it has begun (a
    JSON document whose rows go out as they are made stops its rows and closes); the
    handlers before are put back after.  Outside the main thread: nothing deferred."""
    import signal
    import threading

    stop = Stop()
    if threading.current_thread() is not threading.main_thread():
        yield stop
        return

    def note(signum: int, frame: Any) -> None:
        stop.asked = True

    before = {sig: signal.signal(sig, note) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield stop
    finally:
        for sig, handler in before.items():
            signal.signal(sig, handler)
