"""The rich consoles rkcheck prints on.

Colour is off when ``NO_COLOR`` is set, when ``--no-color`` is given, or when the stream
is not a terminal (rich's own rule).  Output that is not a terminal gets a fixed width
so that piped reports and the README examples are stable.
"""

from __future__ import annotations

import os
import sys

from rich.console import Console

PIPE_WIDTH = 132
_settings = {"color": True, "quiet": False, "verbose": False}


def configure(color: bool = True, quiet: bool = False, verbose: bool = False) -> None:
    _settings.update(color=color, quiet=quiet, verbose=verbose)


def is_quiet() -> bool:
    return bool(_settings["quiet"])


def is_verbose() -> bool:
    return bool(_settings["verbose"])


def make_console(stderr: bool = False) -> Console:
    stream = sys.stderr if stderr else sys.stdout
    tty = stream.isatty()
    no_color = not _settings["color"] or "NO_COLOR" in os.environ or not tty
    return Console(
        file=stream,
        no_color=no_color,
        highlight=False,
        width=None if tty else PIPE_WIDTH,
        soft_wrap=False,
        emoji=False,
        color_system=None if no_color else "auto",
    )
