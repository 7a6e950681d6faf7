"""The rich consoles rkcheck prints on, and the output settings of one run.

Colour (https://no-color.org, https://force-color.org): off with ``--no-color`` or a
non-empty ``NO_COLOR``; otherwise on with a non-empty ``FORCE_COLOR``; otherwise on only
when the stream is a terminal.  An empty ``NO_COLOR=`` changes nothing, as no-color.org
says.  Output that is not a terminal gets a fixed width, so that piped reports and the
docs' transcripts are stable, and no trailing spaces (rich pads table rows to the width).

Settings are plain values passed to whoever prints (never module-global state), so that
one run's ``--quiet`` cannot leak into the next run in the same process.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass
from typing import IO, TYPE_CHECKING, Callable, cast

from rkcheck.numbers.formatting import count_text  # noqa: F401  (the CLI prints counts through the reports)

if TYPE_CHECKING:  # imported by make_console: `rkcheck --help` needs no rich (start-up)
    from rich.console import Console

PIPE_WIDTH = 132


@dataclass(frozen=True)
class OutputSettings:
    """``--no-color`` / ``--quiet`` / ``--verbose`` of one run."""

    color: bool = True
    quiet: bool = False
    verbose: bool = False


def color_wanted(settings: OutputSettings, tty: bool, environ=None) -> bool:
    """Whether to colour a stream (module docstring has the rule)."""
    env = os.environ if environ is None else environ
    if not settings.color or env.get("NO_COLOR"):
        return False
    if env.get("FORCE_COLOR"):
        return True
    return tty


class _StripTrailingSpaces:
    """A text stream that drops spaces before each line break (for piped output: rich
    pads table rows and blank lines to the console width)."""

    def __init__(self, stream):
        self._stream = stream
        self._pending = ""

    def write(self, text: str) -> int:
        data = self._pending + text
        head, sep, tail = data.rpartition("\n")
        if sep:
            self._stream.write("\n".join(line.rstrip(" ") for line in head.split("\n")) + "\n")
        self._pending = tail
        return len(text)

    def flush(self) -> None:
        if self._pending:
            self._stream.write(self._pending)
            self._pending = ""
        self._stream.flush()

    def isatty(self) -> bool:
        return False

    def fileno(self) -> int:
        return self._stream.fileno()

    @property
    def encoding(self) -> str:
        return getattr(self._stream, "encoding", "utf-8")


def make_console(settings: OutputSettings = OutputSettings(), stderr: bool = False) -> Console:
    from rich.console import Console

    stream = sys.stderr if stderr else sys.stdout
    tty = stream.isatty()
    color = color_wanted(settings, tty)
    # rich asks for an IO[str] but writes through write/flush only (and asks isatty,
    # fileno, encoding), all of which _StripTrailingSpaces has
    return Console(
        file=stream if tty else cast(IO[str], _StripTrailingSpaces(stream)),
        no_color=not color,
        force_terminal=True if color and not tty else None,
        highlight=False,
        width=None if tty else PIPE_WIDTH,
        soft_wrap=False,
        emoji=False,
        color_system="auto" if color and tty else ("standard" if color else None),
    )


def as_piped_text(render: "Callable[[Console], None]") -> str:
    """What ``render`` prints to a console, laid out as piped output is (the same width,
    no colour, no trailing spaces): a report written with ``-o`` reads as the one printed
    through ``>``."""
    import io

    from rich.console import Console

    buffer = io.StringIO()
    stripped = _StripTrailingSpaces(buffer)
    console = Console(file=cast(IO[str], stripped), no_color=True, highlight=False, width=PIPE_WIDTH,
                      soft_wrap=False, emoji=False, color_system=None)
    render(console)
    stripped.flush()
    return buffer.getvalue()
