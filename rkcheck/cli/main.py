"""The ``rkcheck`` group, its commands, and the entry point that turns every error into
one line on stderr and an exit code (0 ok, 1 fail, 2 user error, 3 bug, 130 interrupted)."""

from __future__ import annotations

import io
import os
import signal
import sys
import warnings
from typing import Any

import click

from rkcheck.cli.common import (
    EXIT_INTERNAL,
    EXIT_INTERRUPTED,
    EXIT_OK,
    EXIT_USAGE,
    exit_codes,
    output_options,
)
from rkcheck.errors import UserError, is_digits_limit, is_out_of_memory, too_many_digits
from rkcheck.io.printable import printable
from rkcheck.version import __version__

#: Each command and the module that defines it.  Importing a command's module is deferred
#: until the command is run (or listed by ``--help``): ``verify`` on a small file then
#: loads neither the families nor the simulation code (start-up).
COMMANDS = {
    "verify": "rkcheck.cli.check", "show": "rkcheck.cli.check", "conditions": "rkcheck.cli.check",
    "explain": "rkcheck.cli.check", "new": "rkcheck.cli.library", "scan": "rkcheck.cli.scan",
    "catalog": "rkcheck.cli.library", "bench": "rkcheck.cli.studies", "perturb": "rkcheck.cli.studies",
    "kernel": "rkcheck.cli.studies", "simulate": "rkcheck.cli.dynamics", "workprec": "rkcheck.cli.dynamics",
    "solve": "rkcheck.cli.families", "sweep": "rkcheck.cli.families", "discretize": "rkcheck.cli.continuous",
    "cache": "rkcheck.cli.cache",
}


class LazyGroup(click.Group):
    """A group whose commands are imported on first use (click's documented lazy-loading
    pattern); the help lists them in the order of :data:`COMMANDS`."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        module = COMMANDS.get(cmd_name)
        if module is None:
            return None
        import importlib

        command = getattr(importlib.import_module(module), cmd_name)
        assert isinstance(command, click.Command)
        return command


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
             epilog=exit_codes("verify, scan, simulate --energy-order: the check fails (each command's --help says how)"))
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


#: Python refuses to convert integers of more than 4 300 digits to or from text (a guard
#: against quadratic-time conversions).  rkcheck's own values are bounded (entries by
#: MAX_BITS, about 60 000 digits), but exact residuals can be longer: allow this many
#: digits (about 0.2 s per conversion) and refuse beyond with one line.
MAX_PRINTED_DIGITS = 100_000


def _interrupt_once(signum: int, frame) -> None:
    """SIGINT and SIGTERM: the first one interrupts (KeyboardInterrupt, so that what
    finished is still reported); later ones are ignored, so that a second Ctrl-C cannot
    cut the partial report short."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    raise KeyboardInterrupt


def install_signal_handlers() -> None:
    """SIGTERM is handled like SIGINT; only in the main thread of the main
    interpreter (the API and tests may call :func:`main` from elsewhere)."""
    import threading

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, _interrupt_once)
        signal.signal(signal.SIGTERM, _interrupt_once)


def _error(text: str, code: int) -> None:
    click.echo(f"rkcheck: error: {printable(text)}", err=True)
    sys.exit(code)


def main(argv: list[str] | None = None) -> None:
    """Entry point: one-line errors with exit code 2, never a traceback for user errors."""
    limit = sys.get_int_max_str_digits()
    if limit and limit < MAX_PRINTED_DIGITS:  # 0 = no limit: leave it
        sys.set_int_max_str_digits(MAX_PRINTED_DIGITS)
    previous = {sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
    install_signal_handlers()
    try:
        with warnings.catch_warnings():
            # numpy's "overflow encountered" is how a float radius becomes inf, which the
            # certified arithmetic reads as "no claim" (and then refuses or raises the
            # precision): an expected event, not a message for the user
            warnings.filterwarnings("ignore", message="overflow encountered", category=RuntimeWarning)
            warnings.filterwarnings("ignore", message="invalid value encountered", category=RuntimeWarning)
            stdout, sys.stdout = sys.stdout, _ReaderMayLeave(sys.stdout)
            try:
                _run(argv)
            finally:
                sys.stdout = stdout
    finally:
        import threading

        sys.set_int_max_str_digits(limit)  # as it was: main() may run inside a program (the tests)
        if threading.current_thread() is threading.main_thread():
            for sig, handler in previous.items():
                signal.signal(sig, handler)


def _run(argv: list[str] | None) -> None:
    try:
        cli.main(args=argv, prog_name="rkcheck", standalone_mode=False)
    except UserError as err:
        _error(str(err), EXIT_USAGE)
    except click.UsageError as err:
        if type(err).__name__ == "NoArgsIsHelpError":  # click >= 8.2: bare `rkcheck`
            click.echo(err.ctx.get_help() if err.ctx else err.format_message())
            sys.exit(EXIT_USAGE)
        where = f"{err.ctx.command_path}: " if err.ctx is not None else ""
        _error(f"{where}{err.format_message()} (see --help)", EXIT_USAGE)
    except click.Abort as err:  # click's word for a Ctrl-C (or end of input) it caught itself
        interrupted = isinstance(err.__context__, KeyboardInterrupt)
        click.echo("rkcheck: interrupted" if interrupted else "rkcheck: aborted", err=True)
        sys.exit(EXIT_INTERRUPTED)
    except click.exceptions.Exit as err:
        sys.exit(err.exit_code)
    except click.ClickException as err:
        _error(err.format_message(), EXIT_USAGE)
    except BrokenPipeError:  # `rkcheck ... | head`
        _quiet_stdout()
        sys.exit(EXIT_OK)
    except KeyboardInterrupt:
        click.echo("rkcheck: interrupted", err=True)
        sys.exit(EXIT_INTERRUPTED)
    except RecursionError:  # input nested beyond Python's stack (the grammar bounds parentheses, not chains)
        _error("an expression is nested too deeply for this command (a chain of thousands of terms?)", EXIT_USAGE)
    except (MemoryError, ImportError) as err:  # an ImportError too: a library that could not be mapped
        if not is_out_of_memory(err):
            _internal(err)
        _error("out of memory; lower --order, --degree or --dps (docs/errors.md)", EXIT_USAGE)
    except OSError as err:  # -o into a missing folder, a full disk, ...: the environment, not a bug
        where = f"{err.filename}: " if getattr(err, "filename", None) else ""
        _error(f"{where}{err.strerror or err}", EXIT_USAGE)
    except ValueError as err:
        if not is_digits_limit(err):
            _internal(err)
        _error(str(too_many_digits()), EXIT_USAGE)
    except Exception as err:  # a bug in rkcheck, not a user error
        _internal(err)


def _on_stdout(err: OSError) -> OSError:
    """``err`` as an error of standard output (its message then says so)."""
    if not getattr(err, "filename", None):
        err.filename = "standard output"
    return err


class _ReaderMayLeave:
    """Standard output that, once its reader has gone (``rkcheck verify … | head``),
    drops what is still written: the command then ends with its verdict's exit code, where
    click turned the broken pipe into exit 1 whatever the verdict."""

    def __init__(self, stream: Any):
        self._stream, self._gone = stream, False

    def write(self, text: str) -> int:
        if not self._gone:
            try:
                raw = getattr(self._stream, "buffer", None)
                if isinstance(raw, io.FileIO):  # unbuffered (python -u): a write(2) a signal cut short
                    self._write_all(raw, text)  # would be lost, the text layer does not look at the count
                    return len(text)
                return int(self._stream.write(text))
            except BrokenPipeError:
                self._leave()
            except OSError as err:  # a full disk, an I/O error: the one line names where
                raise _on_stdout(err) from None
        return len(text)

    def _write_all(self, raw: io.FileIO, text: str) -> None:
        self._stream.flush()
        data = memoryview(text.encode(self._stream.encoding, self._stream.errors or "strict"))
        while data:
            n = raw.write(data)
            if n is None:  # a non-blocking descriptor that is full: wait for the reader
                import select

                select.select([], [raw], [])
                continue
            data = data[n:]

    def flush(self) -> None:
        if not self._gone:
            try:
                self._stream.flush()
            except BrokenPipeError:
                self._leave()
            except OSError as err:
                raise _on_stdout(err) from None

    def _leave(self) -> None:
        self._gone = True
        _quiet_stdout(self._stream)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _quiet_stdout(stream: Any = None) -> None:
    """After a broken pipe, point stdout at /dev/null so that the interpreter's final flush
    does not print a second BrokenPipeError."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, (stream or sys.stdout).fileno())
    except (OSError, ValueError, AttributeError):
        pass


def _internal(err: BaseException) -> None:
    if os.environ.get("RKCHECK_DEBUG"):
        raise err
    click.echo(
        printable(f"rkcheck: internal error: {type(err).__name__}: {err}") + " — this is a bug in rkcheck; please "
        "report it with the command and the file (RKCHECK_DEBUG=1 shows the traceback)",
        err=True,
    )
    sys.exit(EXIT_INTERNAL)
