"""One pure computation under a wall-clock limit that holds even inside a C library.

A time check between the steps of a Python loop cannot stop one long call into FLINT
(isolating the roots of a polynomial with 8 000-bit coefficients and clustered roots ran
for minutes in a single call).  :func:`call_within` therefore runs the computation in a
forked child process and reads its pickled result back through a pipe; at the deadline
the child is killed and :class:`Overrun` raised.  Exceptions raised in the child are
raised again in the parent, as they were (a :class:`~rkcheck.errors.UserError` keeps its
place and file).  Where there is no ``fork`` (Windows) the computation runs in this
process, bounded only by its own time checks.

The pickle read back comes from this process's own child, never from a file or a user.
"""

from __future__ import annotations

import os
import pickle
import select
import signal
import time
from collections.abc import Callable
from typing import Any

#: set to False to run every computation in this process (a debugger, a profiler)
FORK = hasattr(os, "fork")


class Overrun(Exception):
    """The computation did not finish within its time."""


def _child(write_fd: int, fn: Callable[..., Any], args: tuple[Any, ...]) -> None:
    """In the forked child: compute, send ``(True, result)`` or ``(False, exception)``, exit.
    What the child writes to standard output goes to standard error: a C library that
    aborts (FLINT, out of memory) prints its last words there, and a report being
    written to standard output (JSON) must not take them in."""
    try:
        os.dup2(2, 1)
        try:
            payload = pickle.dumps((True, fn(*args)), protocol=pickle.HIGHEST_PROTOCOL)
        except BaseException as exc:  # noqa: BLE001 - every outcome goes back to the parent
            # the exception alone: its traceback and chained exceptions stay here (a library
            # that pickles tracebacks, as distributed's tblib does, would otherwise send the
            # thousand frames of a RecursionError it was raised from)
            exc.__traceback__ = exc.__context__ = exc.__cause__ = None
            try:
                payload = pickle.dumps((False, exc), protocol=pickle.HIGHEST_PROTOCOL)
            except Exception:  # noqa: BLE001 - an exception that does not pickle: its text does
                payload = pickle.dumps((False, RuntimeError(f"{type(exc).__name__}: {exc}")))
        view = memoryview(payload)
        while view:
            view = view[os.write(write_fd, view):]
    finally:
        os._exit(0)  # never back into the parent's code (no atexit, no flushing its buffers)


def call_within(seconds: float, fn: Callable[..., Any], *args: Any) -> Any:
    """``fn(*args)``, computed in a child process that is killed after ``seconds``
    (then :class:`Overrun`).  ``fn``'s result and exceptions must pickle."""
    if not FORK:
        return fn(*args)
    read_fd, write_fd = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read_fd)
        _child(write_fd, fn, args)
    os.close(write_fd)
    chunks: list[bytes] = []
    finished = False
    deadline = time.monotonic() + seconds
    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([read_fd], [], [], left)[0]:
                raise Overrun
            data = os.read(read_fd, 1 << 20)
            if not data:
                finished = True
                break
            chunks.append(data)
    finally:
        os.close(read_fd)
        if not finished:
            os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    if not chunks:  # killed from outside (out of memory under a limit, a signal)
        raise MemoryError("the computation's process ended without a result")
    ok, value = pickle.loads(b"".join(chunks))
    if ok:
        return value
    raise value
