"""Colour and plain output: NO_COLOR (non-empty only, no-color.org), FORCE_COLOR,
--no-color, and piped output without colour codes or trailing spaces, for every command."""

from __future__ import annotations

import io
import os
import pty
import subprocess
import sys

import pytest
from support.clirun import read_until_closed
from support.paths import TABLEAUX

from rkcheck.reports.console import OutputSettings, _StripTrailingSpaces, color_wanted

ON, OFF = OutputSettings(color=True), OutputSettings(color=False)


@pytest.mark.parametrize(
    "settings, tty, env, want",
    [
        (ON, True, {}, True),
        (ON, False, {}, False),  # a pipe: plain
        (ON, True, {"NO_COLOR": "1"}, False),
        (ON, True, {"NO_COLOR": ""}, True),  # empty NO_COLOR changes nothing (no-color.org)
        (ON, False, {"FORCE_COLOR": "1"}, True),
        (ON, False, {"FORCE_COLOR": ""}, False),
        (ON, False, {"FORCE_COLOR": "1", "NO_COLOR": "1"}, False),  # NO_COLOR wins
        (OFF, True, {"FORCE_COLOR": "1"}, False),  # --no-color wins
    ],
)
def test_colour_rule(settings, tty, env, want):
    assert color_wanted(settings, tty, env) is want


def test_trailing_spaces_are_dropped_line_by_line():
    out = io.StringIO()
    s = _StripTrailingSpaces(out)
    s.write("a   \nb")
    s.write("  c  \n   \nd ")
    s.flush()
    assert out.getvalue() == "a\nb  c\n\nd "


T = str(TABLEAUX)
COMMANDS = {
    "verify": ["verify", f"{T}/explicit/rk4.toml", "--order", "5"],
    "verify -q": ["verify", "-q", f"{T}/explicit/rk4.toml", "--order", "5"],
    "show": ["show", f"{T}/explicit/rk4.toml"],
    "conditions": ["conditions", "--order", "4"],
    "explain": ["explain", "1,2,2"],
    "new": ["new", "gauss", "-s", "2"],
    "scan": ["scan", f"{T}/explicit/rk4.toml", "--jobs", "1"],
    "catalog": ["catalog", f"{T}/explicit"],
    "bench": ["bench", f"{T}/collocation/gauss-2.toml", "--order", "4"],
    "kernel": ["kernel", "-s", "2", "--degree", "4"],
    "simulate": ["simulate", f"{T}/explicit/rk4.toml", "--problem", "harmonic", "--steps", "20"],
    "error": ["verify", f"{T}/nope.toml"],
}


def run(args, env, stdout=subprocess.PIPE):
    full_env = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "FORCE_COLOR")} | env
    return subprocess.run([sys.executable, "-m", "rkcheck", *args], stdout=stdout, stderr=subprocess.PIPE,
                          env=full_env, timeout=120)


@pytest.mark.parametrize("args", list(COMMANDS.values()), ids=list(COMMANDS))
def test_piped_output_is_plain(args):
    proc = run(args, {})
    assert proc.returncode in (0, 1, 2), proc.stderr
    text = proc.stdout.decode() + proc.stderr.decode()
    assert "\x1b" not in text
    assert not [line for line in text.splitlines() if line.endswith(" ")]


def tty_output(args, env) -> str:
    """stdout of ``rkcheck ARGS`` on a pseudo-terminal."""
    master, slave = pty.openpty()
    try:
        proc = run(args, env, stdout=slave)
    finally:
        os.close(slave)
    output = read_until_closed(master)
    assert proc.returncode in (0, 1), proc.stderr
    return output.decode(errors="replace")


def test_terminal_output_is_coloured_unless_no_color():
    args = COMMANDS["verify"]
    assert "\x1b[" in tty_output(args, {})
    assert "\x1b[" in tty_output(args, {"NO_COLOR": ""})
    assert "\x1b[" not in tty_output(args, {"NO_COLOR": "1"})
    assert "\x1b[" not in tty_output(args + ["--no-color"], {})


def test_force_color_colours_a_pipe_but_draws_no_progress_bar():
    proc = run(COMMANDS["verify"], {"FORCE_COLOR": "1"})
    assert b"\x1b[" in proc.stdout
    assert proc.stderr == b""  # no progress bar or cursor codes in a log
