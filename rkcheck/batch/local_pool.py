"""The default executor: local worker processes, forked after the parent built what
they share, fed one job at a time (see :mod:`rkcheck.batch.jobs`)."""

from __future__ import annotations

import os
import signal
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any, Callable

from rkcheck.batch.jobs import Executor, Failure, internal_error


def _worker_main(conn, fn: Callable[[Any], Any]) -> None:
    """One worker: run ``fn`` on the items the parent sends, one at a time, until told to stop."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C ...
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # ... and stops us with SIGTERM
    if hasattr(signal, "pthread_sigmask"):  # held back since the fork (_signals_held), now our own
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _HELD)
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        index, item = task
        try:
            result = fn(item)
        except Exception as err:
            result = Failure(internal_error(err))
        try:
            conn.send((index, result))
        except (EOFError, OSError):
            return
        except Exception as err:  # the result cannot be pickled: still one result, not a lost worker
            conn.send((index, Failure(f"internal error: the result cannot be sent back ({type(err).__name__}: {err})")))


@dataclass
class _Worker:
    process: Any
    conn: Any
    task: tuple[int, Any] | None = None


def death_message(exitcode: int | None) -> str:
    """Why a local worker gave no result: ``the worker process ... was killed by SIGKILL``."""
    if exitcode is not None and exitcode < 0:
        try:
            how = f"was killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            how = f"was killed by signal {-exitcode}"
    else:
        how = f"exited with code {exitcode}"
    return f"the worker process {how} (out of memory?)"


class LocalExecutor(Executor):
    """``jobs`` worker processes, forked (where the system can) after ``prepare()`` ran in
    this process, so that they start with what it built (the scan's condition tables).
    Each worker takes one item at a time, in input order; a worker that dies holding an
    item makes that item ``failed(item, why)`` and is replaced."""

    def __init__(self, jobs: int, prepare: Callable[[], None] | None = None):
        import multiprocessing as mp

        self.workers = max(1, jobs)
        self.where = f"{self.workers} local worker processes"
        self.prepare = prepare
        self.ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else None)

    def map_unordered(self, fn, items, failed):
        queue = list(enumerate(items))[::-1]  # pop() from the end = input order
        workers: list[_Worker] = []
        remaining = len(items)
        try:
            if self.prepare is not None and items:
                self.prepare()
            for _ in range(min(self.workers, len(items))):
                self._start(workers, fn)
            while remaining:
                self._dispatch(workers, queue)
                for index, result in self._collect(workers, queue, fn, failed):
                    remaining -= 1
                    yield index, result
        finally:
            _stop(workers)

    def _start(self, workers: list[_Worker], fn) -> None:
        parent_end, child_end = self.ctx.Pipe()
        proc = self.ctx.Process(target=_worker_main, args=(child_end, fn), daemon=True)
        # known before it exists: a Ctrl-C during the fork must not leave an unknown worker
        workers.append(_Worker(proc, parent_end))
        with _signals_held():
            proc.start()
            child_end.close()

    @staticmethod
    def _dispatch(workers: list[_Worker], queue: list) -> None:
        """Give every idle worker the next item."""
        for w in workers:
            if w.task is None and queue:
                w.task = queue.pop()
                try:
                    w.conn.send(w.task)
                except (EOFError, OSError):
                    pass  # died already: found by _collect() through its sentinel

    def _collect(self, workers: list[_Worker], queue: list, fn, failed) -> list[tuple[int, Any]]:
        """Wait until a busy worker answers or dies; what finished, as (index, result)."""
        from multiprocessing.connection import wait

        busy = [w for w in workers if w.task is not None]
        ready = set(wait([w.conn for w in busy] + [w.process.sentinel for w in busy]))
        done = []
        for w in busy:
            if w.conn not in ready and w.process.sentinel not in ready:
                continue
            try:
                if w.conn.poll():
                    index, result = w.conn.recv()
                    item = w.task[1]  # type: ignore[index]
                    w.task = None
                    done.append((index, failed(item, result.why) if isinstance(result, Failure) else result))
                    continue
            except (EOFError, OSError):
                pass
            if not w.process.is_alive():  # died holding its item: a new worker takes its place
                index, item = w.task  # type: ignore[misc]
                w.process.join()
                done.append((index, failed(item, death_message(w.process.exitcode))))
                w.conn.close()
                workers.remove(w)
                if queue:
                    self._start(workers, fn)
        return done


#: the signals a worker holds back from its fork until it has its own dispositions
_HELD = {signal.SIGINT, signal.SIGTERM}


@contextmanager
def _signals_held():
    """Hold Ctrl-C and SIGTERM back while a worker starts.  Ctrl-C reaches the whole
    process group, and :func:`_stop` terminates a busy worker with SIGTERM: a worker
    still inside multiprocessing's start-up has the parent's handlers, which raise
    KeyboardInterrupt, and would die there with a traceback.  Forked with both blocked,
    the worker unblocks them once it ignores SIGINT and dies quietly by SIGTERM; the
    parent receives a signal that came meanwhile when the new worker is on the list that
    :func:`_stop` stops."""
    if not hasattr(signal, "pthread_sigmask"):  # no POSIX signal masks (Windows)
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _stop(workers: list[_Worker]) -> None:
    """Stop every worker: idle ones are told to, busy ones are terminated; none is left."""
    for w in workers:
        try:
            if w.task is None:
                w.conn.send(None)
            else:
                w.process.terminate()
        except (EOFError, OSError, ValueError):
            pass
    for w in workers:
        if w.process.pid is None:  # interrupted before it started
            w.conn.close()
            continue
        w.process.join(timeout=5)
        if w.process.is_alive():
            w.process.kill()
            w.process.join()
        w.conn.close()


def default_jobs() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
