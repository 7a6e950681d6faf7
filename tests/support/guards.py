"""Guards that turn a hang into a test failure (guards, not timing targets)."""

from __future__ import annotations

import signal
from contextlib import contextmanager


@contextmanager
def _alarm(which: int, signum: int, seconds: int, what: str):
    def boom(signum, frame):  # pragma: no cover - only on a hang
        raise AssertionError(f"did not finish within {seconds} {what}")

    old = signal.signal(signum, boom)
    signal.setitimer(which, seconds)
    try:
        yield
    finally:
        signal.setitimer(which, 0)
        signal.signal(signum, old)


@contextmanager
def hang_guard(seconds: int = 10):
    """Fail the test if the block runs longer than ``seconds`` of wall time (SIGALRM; main
    thread).  For blocks that wait on other processes; computation: :func:`cpu_guard`."""
    with _alarm(signal.ITIMER_REAL, signal.SIGALRM, seconds, "s"):
        yield


@contextmanager
def cpu_guard(seconds: int = 10):
    """Fail the test if the block uses more than ``seconds`` of this process's CPU time
    (SIGPROF; main thread): a runaway computation, however loaded the machine is.  It does
    not see time spent waiting, so it is for blocks that compute in this process."""
    with _alarm(signal.ITIMER_PROF, signal.SIGPROF, seconds, "CPU seconds"):
        yield
