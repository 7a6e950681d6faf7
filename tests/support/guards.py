"""Guards that turn a hang into a test failure (guards, not timing targets)."""

from __future__ import annotations

import signal
from contextlib import contextmanager


@contextmanager
def hang_guard(seconds: int = 10):
    """Fail the test if the block runs longer than ``seconds`` (SIGALRM; main thread)."""

    def boom(signum, frame):  # pragma: no cover - only on a hang
        raise AssertionError(f"did not finish within {seconds} s")

    old = signal.signal(signal.SIGALRM, boom)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
