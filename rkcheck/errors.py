"""The errors rkcheck raises on purpose, one hierarchy under :class:`RkcheckError`.

* :class:`UserError` (also exported as ``rkcheck.InputError``) is a problem with what the
  user gave rkcheck (a file, an entry, an option).  The CLI prints it as one line
  ``FILE: PLACE: message`` and exits with code 2; it never shows a traceback.  Its
  subclasses say more: :class:`TableauError` (a tableau that cannot be built),
  :class:`OptionError` (a check option out of range), :class:`UnknownMethodError`
  (``@name`` not in the library), :class:`ResourceError` (a check that would not fit in
  the memory available); the integrator's ``NewtonError`` is a UserError too.
* Anything else that escapes is a bug (the CLI's exit code 3).
* :class:`CheckInterrupted` is not an error: Ctrl-C during a check, carrying what
  finished (a ``KeyboardInterrupt``, so it stops a library caller as Ctrl-C does).

Library callers catch ``rkcheck.RkcheckError`` for everything rkcheck refuses, and read
``str(err)``: the same one line the CLI prints after ``rkcheck: error:``.
"""

from __future__ import annotations

from typing import Any, Sequence


class RkcheckError(Exception):
    """Base of every error rkcheck raises on purpose (never for a bug)."""


class UserError(RkcheckError):
    """An error in the user's input, reported as one line and exit code 2.

    ``place`` says where inside the file (``A[2][3]``, ``line 4``); ``source`` names
    the file.  Both are optional and are filled in by the layer that knows them: the
    expression parser knows the column, the loader knows the entry and the file.
    """

    def __init__(self, message: str, place: str | None = None, source: str | None = None):
        super().__init__(message)
        self.message = message
        self.place = place
        self.source = source

    def located(self, place: str | None = None, source: str | None = None) -> "UserError":
        """Return a copy with the place prefixed (outer places come first) and the source set."""
        new_place: str | None = f"{place}: {self.place}" if place and self.place else (place or self.place)
        # keep the subclass (a TableauError stays one when the loader adds the file)
        copy = UserError.__new__(type(self))
        UserError.__init__(copy, self.message, new_place, source or self.source)
        return copy

    def __str__(self) -> str:
        # one printable line, as the CLI prints it: a path or key may hold a newline or
        # an escape sequence
        parts = [p for p in (self.source, self.place, self.message) if p]
        return printable(": ".join(parts))

    def as_tableau_error(self) -> "UserError":
        """The same error as a :class:`TableauError` — what building a method from its
        content raises — unless it is of a narrower kind already (a bad ``[check]``
        option stays an :class:`OptionError`)."""
        if type(self) is not UserError:
            return self
        return TableauError(self.message, self.place, self.source)


class TableauError(UserError):
    """A tableau that cannot be built from what was given (shape, entry, table)."""


class OptionError(UserError):
    """A check option (degree, order, dps, decimals, ...) that is not valid."""


class ResourceError(UserError):
    """A check that would not fit in the machine's memory (exit code 2)."""


class UnknownMethodError(UserError):
    """An ``@name`` that names no tableau of the installed library."""


class RkcheckWarning(UserWarning):
    """What rkcheck warns Python callers about (``warnings.warn``): input it read in a
    way that deserves a word, such as floats (read as the decimal they print as, or at
    their exact binary value).  Filter it like any ``UserWarning``."""


def is_out_of_memory(err: BaseException) -> bool:
    """Memory running out, however it surfaced: an allocation (``MemoryError``), or a
    library whose segments could not be mapped when imported (an ``ImportError`` under
    ``ulimit -v``)."""
    text = str(err)
    return isinstance(err, MemoryError) or (isinstance(err, (ImportError, OSError)) and (
        "failed to map segment" in text or "Cannot allocate memory" in text))


def is_digits_limit(err: BaseException) -> bool:
    """Python's refusal to write an integer of more digits than
    ``sys.get_int_max_str_digits()`` as text (a ValueError, raised wherever one is
    printed): a limit the user's numbers met, not a bug."""
    return isinstance(err, ValueError) and "integer string conversion" in str(err)


def too_many_digits(source: str | None = None) -> UserError:
    """The one line for :func:`is_digits_limit`, naming the file whose report it is."""
    import sys

    return UserError(f"a number of the report has more than {sys.get_int_max_str_digits():,} digits, too many to "
                     "print (docs/errors.md)", source=source)


def not_applying(names: Sequence[str]) -> str:
    """``--zeta does not apply``, ``-s, -k do not apply``: the options an error or a
    warning refuses, named, the verb agreeing."""
    return f"{', '.join(names)} {'does' if len(names) == 1 else 'do'} not apply"


def warn(message: str) -> None:
    """``warnings.warn`` a :class:`RkcheckWarning`, attributed to the first caller outside
    the rkcheck package (the user's line, however deep the call came from)."""
    import os
    import sys
    import warnings

    root = os.path.dirname(os.path.abspath(__file__)) + os.sep
    frame: Any = sys._getframe(0)
    level = 1
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(root):
        frame, level = frame.f_back, level + 1
    warnings.warn(RkcheckWarning(message), stacklevel=level)


def as_option(parse: Any) -> Any:
    """``parse()``, its :class:`UserError` raised again as an :class:`OptionError` (an
    API argument's: ``except OptionError`` catches every bad argument)."""
    try:
        return parse()
    except OptionError:
        raise
    except UserError as err:
        raise OptionError(err.message, err.place, err.source) from None


class CheckInterrupted(KeyboardInterrupt):
    """Ctrl-C during a check: ``result`` holds the orders that were finished (a
    KeyboardInterrupt for library callers, a partial report for the CLI).  ``result`` is
    a :class:`rkcheck.energy.check.CheckResult`."""

    def __init__(self, result: Any):
        super().__init__()
        self.result = result


def printable(text: str) -> str:
    """Text that came from a file, made safe to print on one line
    (:mod:`rkcheck.io.printable`): every non-printable character (controls, line breaks,
    lone surrogates, format characters) written as its Python escape (``\\n``,
    ``\\x1b``, ``\\ud800``); printable text, including non-ASCII letters, is unchanged."""
    if text.isprintable():
        return text
    return "".join(ch if ch.isprintable() else _escape(ch) for ch in text)


def _escape(ch: str) -> str:
    # U+DC80..U+DCFF is how Python keeps a byte that is not UTF-8 in a file name or an
    # argument (surrogateescape): show the byte itself, as ls and git do
    if "\udc80" <= ch <= "\udcff":
        return f"\\x{ord(ch) - 0xDC00:02x}"
    return ascii(ch)[1:-1]
