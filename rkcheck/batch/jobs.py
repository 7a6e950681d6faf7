"""Where many independent jobs run: in this process, in local worker processes, or on a
Dask distributed cluster — one small interface for all three.

An :class:`Executor` maps a function over a list of items and yields ``(index, result)``
pairs as the jobs finish (in any order; the caller restores the input order).  A job
that cannot give a result — its worker process died, the function raised, the result
could not be sent back — is not lost: the caller's ``failed(item, why)`` turns it into
a result (a scan's error row), and the other jobs go on.  Ctrl-C (KeyboardInterrupt)
while waiting, or closing the generator early, stops the work: local workers are
terminated, Dask futures cancelled.  Use it as::

    with executor_for(scheduler, jobs) as pool:
        with closing(pool.map_unordered(fn, items, failed)) as results:
            for index, result in results:
                ...

``fn`` must be a module-level function (or a :func:`functools.partial` of one): local
workers are forked, and Dask pickles it to workers that import ``rkcheck`` themselves.
"""

from __future__ import annotations

import os
from typing import Callable, Generator, Sequence, TypeVar

from rkcheck.errors import UserError, is_out_of_memory

T = TypeVar("T")
R = TypeVar("R")

#: Environment variable naming a Dask scheduler (``tcp://host:8786``): scans run there.
SCHEDULER_ENV = "RKCHECK_SCHEDULER"
#: SCHEDULER_CONNECT_TIMEOUT: how long to wait for the scheduler to answer and for its
#: first worker to join, in seconds; ``RKCHECK_SCHEDULER_TIMEOUT`` changes it.
SCHEDULER_CONNECT_TIMEOUT = 10.0
SCHEDULER_TIMEOUT_ENV = "RKCHECK_SCHEDULER_TIMEOUT"
#: The extra that installs Dask.
CLUSTER_EXTRA = "rkcheck[cluster]"


class Executor:
    """Runs jobs; see the module text.  ``workers`` is how many run at once (for Dask:
    the cluster's worker threads when connected); ``where`` says where, for reports."""

    workers: int = 1
    where: str = "this process"

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T],
                      failed: Callable[[T, str], R]) -> Generator[tuple[int, R], None, None]:
        raise NotImplementedError

    def close(self) -> None:
        """Release what the executor holds (a cluster connection); idempotent."""

    def __enter__(self) -> "Executor":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class Failure:
    """What a worker sends back instead of a result: why there is none."""

    def __init__(self, why: str):
        self.why = why


def internal_error(err: BaseException) -> str:
    """A job's failure outside the check's own handling: a bug — or the machine's memory
    running out (an allocation, or a library's segments that cannot be mapped)."""
    if is_out_of_memory(err):
        return "out of memory; lower --order or --degree, or run fewer --jobs"
    return f"internal error: {type(err).__name__}: {err} (a bug in rkcheck; please report it)"


class SerialExecutor(Executor):
    """Every job in this process, one after the other (``--jobs 1``)."""

    def map_unordered(self, fn, items, failed):
        for index, item in enumerate(items):
            try:
                result = fn(item)
            except Exception as err:  # a bug in one job: its result says so, the others go on
                result = failed(item, internal_error(err))
            yield index, result



def scheduler_timeout() -> float:
    """SCHEDULER_CONNECT_TIMEOUT, or ``RKCHECK_SCHEDULER_TIMEOUT`` (seconds, > 0)."""
    text = os.environ.get(SCHEDULER_TIMEOUT_ENV, "").strip()
    if not text:
        return SCHEDULER_CONNECT_TIMEOUT
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 0 < value <= 3600:
        raise UserError(f"expected a number of seconds above 0 and at most 3600, got {text!r}"[:120], SCHEDULER_TIMEOUT_ENV)
    return value
