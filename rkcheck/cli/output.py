"""Where a report goes: standard output, or a file replaced atomically — checked before
any work (its folder exists, it is not one of the command's own inputs)."""

from __future__ import annotations

from contextlib import contextmanager
from typing import Any, Iterator, Sequence

import click

from rkcheck.errors import UserError, is_digits_limit, too_many_digits


@contextmanager
def printed_for(source: str | None) -> Iterator[None]:
    """A report printed for the file ``source``: a number of more digits than Python
    writes is the one line naming that file (:func:`~rkcheck.errors.too_many_digits`),
    a limit the numbers met, not a bug."""
    try:
        yield
    except ValueError as err:
        if not is_digits_limit(err):
            raise
        raise too_many_digits(source) from None


def check_output_target(output: str | None, inputs: Sequence[str] = ()) -> None:
    """Refuse, before any work, an output file whose folder does not exist or is a file
    (rather than after a whole scan), or that is one of the command's ``inputs`` (the
    report would replace the tableau it was made from)."""
    if output == "":
        raise UserError("expected a file name ('-' for standard output), got an empty one", "--output")
    if output is None or output == "-":
        return
    from pathlib import Path

    target = Path(output)
    folder = target.resolve().parent if target.is_symlink() else (target.parent if str(target.parent) else Path("."))
    if not folder.is_dir():
        raise UserError("cannot write the report: its folder does not exist", source=output)
    if target.is_dir():
        raise UserError("cannot write the report: is a directory", source=output)
    if target.exists() and inputs:
        from rkcheck.api.batch import files_read, is_rkcheck_report_file

        read = any(_same_file(target, f) for f in files_read(list(inputs)))
        if read and not is_rkcheck_report_file(str(target)):
            raise UserError("cannot write the report: it is an input of this command, which it would replace; "
                            "write it to another file", source=output)


def _same_file(target: Any, path: str) -> bool:
    """Whether ``path`` is the file ``target``, through links and other spellings."""
    import os

    try:
        return os.path.samefile(target, path)
    except (OSError, ValueError):
        return False


def write_text(text: str, output: str | None) -> None:
    """Write a report to stdout (no output or ``-``) or to a file.

    A regular file (or a new one) is replaced atomically: written to a temporary file in
    the same folder with the permissions the umask gives, then renamed, so a reader never
    sees half a report.  A symbolic link is followed (its target is replaced, the link
    stays); anything else that exists and is not a regular file (``/dev/null``, a FIFO, a
    terminal) is written to directly, never replaced.
    """
    check_output_target(output)  # an empty name is not standard output
    if output is None or output == "-":
        click.echo(text, nl=False)
        return
    try:
        _write_file(text, output)
    except OSError as err:  # named by the user's path, not the temporary file's
        raise UserError(f"cannot write the report: {err.strerror or err}", source=output) from None


def _write_file(text: str, output: str) -> None:
    import os
    import stat
    import tempfile
    from pathlib import Path

    try:
        # the path itself, links followed by the system: /dev/stdout on a pipe resolves to
        # no file name (realpath gives /proc/…/fd/pipe:[…]) but opens fine
        mode = os.stat(output).st_mode
    except FileNotFoundError:
        mode = None
    if mode is not None and stat.S_ISFIFO(mode):
        _write_pipe(text, output)
        return
    if mode is not None and not stat.S_ISREG(mode):
        with open(output, "w", encoding="utf-8", errors="surrogateescape") as fh:
            fh.write(text)
        return
    target = Path(os.path.realpath(output))
    umask = os.umask(0)
    os.umask(umask)
    try:
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=".rkcheck-", suffix=".tmp")
    except OSError as err:  # /proc, a folder that takes no new file: say so of the file asked for
        raise UserError(f"cannot write the report beside it ({err.strerror}): rkcheck writes a temporary file in "
                        "its folder, then renames it", source=output) from None
    try:
        os.fchmod(fd, (stat.S_IMODE(mode) if mode is not None else 0o666 & ~umask))
        with os.fdopen(fd, "w", encoding="utf-8", errors="surrogateescape") as fh:
            fh.write(text)
        os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def _write_pipe(text: str, output: str) -> None:
    """A named pipe: written when something reads it, refused at once when nothing does
    (opening it to write would wait for a reader without end)."""
    import errno
    import os

    try:
        fd = os.open(output, os.O_WRONLY | os.O_NONBLOCK)
    except OSError as err:
        if err.errno == errno.ENXIO:
            raise UserError("a named pipe that nothing reads: start its reader first", source=output) from None
        raise
    os.set_blocking(fd, True)
    with os.fdopen(fd, "w", encoding="utf-8", errors="surrogateescape") as fh:
        fh.write(text)
