"""The rich consoles rkcheck prints on, and the output settings of one run.

Colour is off when ``NO_COLOR`` is set, when ``--no-color`` is given, or when the stream
is not a terminal (rich's own rule).  Output that is not a terminal gets a fixed width
so that piped reports and the README examples are stable.

Settings are plain values passed to whoever prints (never module-global state), so that
one run's ``--quiet`` cannot leak into the next run in the same process.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass

from rich.console import Console

PIPE_WIDTH = 132


@dataclass(frozen=True)
class OutputSettings:
    """``--no-color`` / ``--quiet`` / ``--verbose`` of one run."""

    color: bool = True
    quiet: bool = False
    verbose: bool = False


def make_console(settings: OutputSettings = OutputSettings(), stderr: bool = False) -> Console:
    stream = sys.stderr if stderr else sys.stdout
    tty = stream.isatty()
    no_color = not settings.color or "NO_COLOR" in os.environ or not tty
    return Console(
        file=stream,
        no_color=no_color,
        highlight=False,
        width=None if tty else PIPE_WIDTH,
        soft_wrap=False,
        emoji=False,
        color_system=None if no_color else "auto",
    )
