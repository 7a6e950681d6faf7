"""Run the rkcheck CLI in-process (fast) or as a real subprocess (end to end)."""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass

from rkcheck.cli import main


@dataclass
class Run:
    code: int
    out: str
    err: str


def run_cli(capsys, *args: str) -> Run:
    """``rkcheck ARGS`` in this process; returns exit code, stdout and stderr."""
    capsys.readouterr()
    try:
        main(list(args))
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    captured = capsys.readouterr()
    return Run(code, captured.out, captured.err)


def run_subprocess(*args: str, stdin: str | None = None, cwd: str | None = None, timeout: float = 120) -> Run:
    env = dict(os.environ, NO_COLOR="1")
    proc = subprocess.run(
        [sys.executable, "-m", "rkcheck", *args],
        input=stdin, capture_output=True, text=True, cwd=cwd, env=env, timeout=timeout,
    )
    return Run(proc.returncode, proc.stdout, proc.stderr)


def read_until_closed(fd: int) -> bytes:
    """Everything written to a pseudo-terminal's master ``fd`` until its other end is
    closed (Linux reports that as EIO, an OSError), then the fd closed."""
    chunks = []
    while True:
        try:
            data = os.read(fd, 65536)
        except OSError:
            break
        if not data:
            break
        chunks.append(data)
    os.close(fd)
    return b"".join(chunks)
