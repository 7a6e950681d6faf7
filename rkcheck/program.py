"""The ``rkcheck`` program (the console script and ``python -m rkcheck``).

Only a program that ends when its command does may tune process-wide settings; a
library import of rkcheck changes nothing.  So the tuning lives here, and runs before
the command line's modules (click, rich, numpy) are imported.
"""

from __future__ import annotations

# the C module, not `signal`: `signal` imports `enum`, which a fresh interpreter may not
# have loaded yet, and a Ctrl-C while it loads would be a traceback from this very line
import _signal  # type: ignore[import-not-found]  # no stub: a C module of CPython
import gc
import os


def _early_interrupt(signum, frame) -> None:  # pragma: no cover - timing-dependent by nature
    """Ctrl-C or SIGTERM while the program is still starting (importing click, rich, ...):
    nothing has begun, so end quietly with exit 130 instead of an import traceback."""
    os.write(2, b"rkcheck: interrupted\n")
    os._exit(130)


def _quiet_start() -> None:
    _signal.signal(_signal.SIGINT, _early_interrupt)
    _signal.signal(_signal.SIGTERM, _early_interrupt)


# at once, not when main() is called: only the program imports this module, and every
# import before main() is a window for a Ctrl-C traceback
_quiet_start()


def tune_process() -> None:
    """The settings of the program's process (not of a library user's)."""
    _quiet_start()
    # numpy's bundled OpenBLAS starts a worker thread per core when numpy is imported, and
    # each idle worker spins for 2^28 cycles (~0.1 s) before it sleeps: on a 2-core machine
    # that takes a core from every command's start-up (~60 ms of a ~0.4 s verify).  2^4
    # cycles: idle workers sleep at once and are woken (microseconds) when a large matrix
    # product needs them; BLAS still uses every core.  Set before numpy is loaded
    # (OpenBLAS reads it then); a value the user set wins.
    os.environ.setdefault("OPENBLAS_THREAD_TIMEOUT", "4")
    # Start-up allocates ~50 000 containers (modules, classes, functions) that live until
    # exit; with the default first threshold (700) the cyclic collector runs ~70 times
    # over them (12-22 ms of a verify's start-up).  Young cyclic garbage is rare here
    # (refcounting frees the rest at once), so a later first collection costs nothing in
    # memory and collections still run.
    gc.set_threshold(100_000, *gc.get_threshold()[1:])


def _numpy_loads() -> bool:
    """Whether numpy loads within this process's limit on its address space (``ulimit
    -v``), tried in a forked child, which has the same limit and already uses what this
    process uses.  Short of memory for its buffers as numpy loads it, OpenBLAS ends the
    process itself (exit 1 — the exit code of a failing method — and a line of its own),
    where no Python code can catch it.  Without a limit nothing is tried."""
    import resource

    limits = [resource.getrlimit(r)[0] for r in (resource.RLIMIT_AS, resource.RLIMIT_DATA)]
    if all(limit == resource.RLIM_INFINITY for limit in limits) or not hasattr(os, "fork"):
        return True
    child = os.fork()
    if child == 0:  # pragma: no cover - the child ends in os._exit, coverage never sees it
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, 1)
            os.dup2(devnull, 2)
            import numpy  # noqa: F401

            os._exit(0)
        except BaseException:
            os._exit(1)
    _, status = os.waitpid(child, 0)
    return os.waitstatus_to_exitcode(status) == 0


def main() -> None:
    """Tune the process, then run the command line; when it is done, the process ends:
    the interpreter's last full collection would walk every object still alive only to
    find that nothing is garbage (35-45 ms after a verify), so they are frozen (exit still
    flushes the streams and runs atexit handlers)."""
    tune_process()
    if not _numpy_loads():
        os.write(2, b"rkcheck: error: out of memory: the memory limit (ulimit -v) leaves too little to load numpy; "
                    b"raise it (docs/errors.md)\n")
        os._exit(2)
    from rkcheck.cli.main import (
        main as run_command_line,  # after the tuning: numpy reads it
    )

    try:
        run_command_line()
    finally:
        gc.freeze()
