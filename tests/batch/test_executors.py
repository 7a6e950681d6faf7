"""The executor interface every batch of independent jobs uses (scan, sweeps): each
implementation gives every item's result once, with its input index, and turns a job
that raises into ``failed(item, why)`` without losing the others."""

from __future__ import annotations

import math
import os
import signal
from contextlib import closing
from functools import partial

import pytest

from rkcheck.batch.executors import LocalExecutor, SerialExecutor, executor_for

ITEMS = [5, -1, 0, 7, 3, 10, -4, 2]  # math.factorial raises ValueError for a negative number


def expected() -> dict[int, object]:
    return {i: ("failed", "internal error: ValueError") if n < 0 else math.factorial(n) for i, n in enumerate(ITEMS)}


def collect(executor) -> dict[int, object]:
    def failed(item, why):
        return ("failed", why.split(":")[0] + ": " + why.split(":")[1].strip())

    got: dict[int, object] = {}
    with executor, closing(executor.map_unordered(math.factorial, ITEMS, failed)) as results:
        for index, result in results:
            assert index not in got  # each item once
            got[index] = result
    return got


@pytest.mark.parametrize("make", [SerialExecutor, partial(LocalExecutor, 3)], ids=["serial", "local processes"])
def test_local_executors_give_every_result_once(make):
    assert collect(make()) == expected()


def test_the_choice_of_executor():
    assert isinstance(executor_for(None, 1), SerialExecutor)
    pool = executor_for(None, 4)
    assert isinstance(pool, LocalExecutor) and pool.workers == 4


def test_a_dask_executor_gives_the_same_results():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        assert collect(executor_for(cluster.scheduler_address, 1)) == expected()


def test_a_local_worker_that_dies_is_one_failed_item_and_is_replaced():
    # os.kill(own pid, n) kills the worker for n = SIGKILL and returns None for n = 0
    me = os.getpid()
    items = [0, int(signal.SIGKILL), 0, 0]
    pool = LocalExecutor(2)
    with closing(pool.map_unordered(partial(_kill_self_with, me), items, lambda item, why: why)) as results:
        got = dict(results)
    assert got[0] is None and got[2] is None and got[3] is None
    assert got[1] == "the worker process was killed by SIGKILL (out of memory?)"


def _kill_self_with(parent: int, signum: int):
    assert os.getpid() != parent  # in a worker, never in the test's own process
    return os.kill(os.getpid(), signum) if signum else None


def test_a_dask_chunk_whose_result_cannot_be_sent_back_loses_only_that_item():
    """A cluster's chunk comes back as one pickle; an item whose result does not pickle
    becomes a Failure saying so, and the chunk's other results arrive intact."""
    import pickle

    from rkcheck.batch.dask_executor import _run_chunk
    from rkcheck.batch.jobs import Failure

    back = pickle.loads(_run_chunk(_unpicklable_for_two, [1, 2, 3]))
    assert back[0] == 1 and back[2] == 9
    assert isinstance(back[1], Failure) and "cannot be sent back" in back[1].why


def _unpicklable_for_two(x):
    return (lambda: x) if x == 2 else x * x


@pytest.mark.skipif(not hasattr(signal, "pthread_sigmask"), reason="POSIX signal masks")
def test_a_worker_stopped_while_it_starts_dies_quietly(monkeypatch, capfd):
    # A scan stops a busy worker with SIGTERM, and the CLI's own SIGTERM and Ctrl-C
    # handlers raise KeyboardInterrupt. A worker that is still inside multiprocessing's
    # start-up (held there by a slow stdin close) has inherited those handlers: stopped
    # then, it must die by SIGTERM, without a traceback, not by KeyboardInterrupt.
    import multiprocessing.util
    import time

    def interrupt(signum, frame):
        raise KeyboardInterrupt

    def slow_close_stdin():
        time.sleep(0.5)

    previous = signal.signal(signal.SIGTERM, interrupt)
    try:
        monkeypatch.setattr(multiprocessing.util, "_close_stdin", slow_close_stdin)
        pool = LocalExecutor(1)
        workers: list = []
        pool._start(workers, math.factorial)
        time.sleep(0.1)  # forked, still starting
        workers[0].process.terminate()
        workers[0].process.join(5)
    finally:
        signal.signal(signal.SIGTERM, previous)
    assert workers[0].process.exitcode == -signal.SIGTERM
    assert "Traceback" not in capfd.readouterr().err
