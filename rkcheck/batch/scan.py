"""Checking many files: one outcome per file, in worker processes, in a fixed order.

:func:`scan_file` checks one file and never raises for a bad file: a file that does not
load is an outcome with ``status = "error"`` and its one-line message; a valid TOML/JSON
document without ``[tableau]``/``[family]``/``[method]`` is ``"skipped"`` (a
``pyproject.toml`` in the same folder is not a failure).  :func:`run_scan` runs it over
a process pool whose workers keep their tree and condition tables between files (and,
forked after the parent built the tables for the scan's default options, start with
them).  Outcomes are :class:`FileOutcome` values (the check result itself, not a
report: rendering is :mod:`rkcheck.reports.scan`'s job) and arrive in input order;
Ctrl-C stops the pool and returns the outcomes that finished.
"""

from __future__ import annotations

import os
import signal
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

from rkcheck.errors import UserError
from rkcheck.options import DEFAULT_MAX_STAGES, DEFAULT_ORDER, resolve_check_options

STATUS_RANK = {"ok": 0, "skipped": 0, "failed": 1, "error": 1}


@dataclass
class FileOutcome:
    """What checking one file gave: ``status`` is ok, failed, error or skipped; ``result``
    and ``claims`` are the check result and claim results when the file was checked;
    ``lines`` maps table and key names to their line in the file (for annotations)."""

    path: str
    status: str = "error"
    error: str | None = None
    time: float = 0.0
    lines: dict[str, int] = field(default_factory=dict)
    result: Any = None  # the CheckResult, with its claims judged


def options_for(tab, flags: dict[str, Any], project: dict[str, Any]):
    """Check options of one file: flags, else its ``[check]``, else ``[tool.rkcheck]``."""
    return resolve_check_options(flags, tab.info.check, project)


def _is_tableau_document(data: dict[str, Any]) -> bool:
    """A table the loader reads, or the short form (``A`` and ``b`` at the top level), as
    ``verify`` accepts it; any other document (``package.json``, ``pyproject.toml``) is
    skipped."""
    return any(k in data for k in ("tableau", "family", "method", "continuous")) or ("A" in data and "b" in data)


def scan_file(path: str, flags: dict[str, Any], project: dict[str, Any], fail_on: str,
              max_stages: int = DEFAULT_MAX_STAGES, budget=None) -> FileOutcome:
    """Check one file; never raises for a bad file (it becomes an ``error`` outcome).
    ``budget`` (:class:`rkcheck.energy.budget.Budget`) refuses a file whose own
    ``[check]`` asks for more than fits: that file's row says so."""
    from rkcheck.energy.claims import judge_tableau
    from rkcheck.io.loader import (
        build_tableau,
        detect_format,
        load_named,
        locate_lines,
        parse_document,
        read_text,
    )
    from rkcheck.methods.tableau import Tableau

    t0 = time.perf_counter()
    out = FileOutcome(path)
    try:
        if os.path.isdir(path):  # discovery lists a folder only when it could not be read
            raise UserError("cannot read this folder (permission denied?)", source=path)
        if path.startswith("@"):  # a shipped tableau or classical method by name
            tab = load_named(path[1:], max_stages)
        else:
            text = read_text(path)
            fmt = detect_format(path, text)
            try:
                data = parse_document(text, fmt)
            except UserError as err:
                raise err.located(source=path) from None
            out.lines = locate_lines(text, fmt)
            if not _is_tableau_document(data):
                out.status, out.error = "skipped", "not a tableau file (no [tableau], [continuous], [family] or [method] table, no top-level A and b)"
                return out
            built: Any = build_tableau(data, path, max_stages)
            if not isinstance(built, Tableau) and not getattr(built, "is_continuous", False):
                out.status, out.error = "skipped", "a family with free [parameters] (check it with rkcheck solve)"
                return out
            tab = built.replace(info=built.info.replace(lines=out.lines))
        out.result = judge_tableau(tab, options_for(tab, flags, project), fail_on, budget)
        out.status = "failed" if out.result.failed else "ok"
    except UserError as err:
        out.error = str(err.located(source=path) if not err.source else err)
    except RecursionError:
        out.error = f"{path}: nesting too deep"
    except MemoryError:
        out.error = f"{path}: out of memory; lower --order or --degree"
    except Exception as err:  # a bug: this file's row says so, the other files go on
        out.error = f"{path}: internal error: {type(err).__name__}: {err} (a bug in rkcheck; please report it)"
    finally:
        out.time = round(time.perf_counter() - t0, 6)
    return out


# ------------------------------------------------------------------- workers


def _worker_main(conn, flags: dict[str, Any], project: dict[str, Any], fail_on: str, max_stages: int,
                 budget=None) -> None:
    """One worker: check the files the parent sends, one at a time, until told to stop."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C ...
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # ... and stops us with SIGTERM
    if hasattr(signal, "pthread_sigmask"):  # held back since the fork (_sigint_held), now ignored
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        index, path = task
        outcome = scan_file(path, flags, project, fail_on, max_stages, budget)
        try:
            conn.send((index, outcome))
        except (EOFError, OSError):
            return
        except Exception as err:  # the result cannot be pickled: still one row, not a lost worker
            conn.send((index, FileOutcome(path, error=f"{path}: internal error: the result cannot be sent back "
                                                     f"({type(err).__name__}: {err})", time=outcome.time)))


@dataclass
class _Worker:
    process: Any
    conn: Any
    task: tuple[int, str] | None = None


def _death_message(path: str, exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            how = f"was killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            how = f"was killed by signal {-exitcode}"
    else:
        how = f"exited with code {exitcode}"
    return f"{path}: the worker process checking this file {how} (out of memory?); the other files went on"


def warm_tables(flags: dict[str, Any], project: dict[str, Any]) -> None:
    """Build the condition table of the scan's default options before forking workers."""
    from rkcheck.trees.listing import condition_listing

    degree = flags.get("degree", project.get("degree"))
    order = flags.get("order", project.get("order", DEFAULT_ORDER))
    condition_listing(order, degree)


def run_scan(
    files: list[str],
    flags: dict[str, Any],
    project: dict[str, Any],
    fail_on: str,
    jobs: int,
    max_stages: int = DEFAULT_MAX_STAGES,
    on_result: Callable[[FileOutcome], None] = lambda r: None,
    budget=None,
) -> tuple[list[FileOutcome], bool]:
    """All outcomes in input order, and whether the scan was interrupted (Ctrl-C or
    SIGTERM: then the outcomes are those that finished, still in input order).
    ``budget`` goes to every file's check (see :func:`scan_file`)."""
    jobs = max(1, min(jobs, len(files)))  # never more workers than files
    if jobs <= 1:
        results: list[FileOutcome] = []
        try:
            for f in files:
                r = scan_file(f, flags, project, fail_on, max_stages, budget)
                results.append(r)
                on_result(r)
        except KeyboardInterrupt:
            return results, True
        return results, False
    pool = _Pool(files, (flags, project, fail_on, max_stages, budget), on_result)
    interrupted = False
    try:
        warm_tables(flags, project)
        for _ in range(jobs):
            pool.start_worker()
        while len(pool.done) < len(files):
            pool.dispatch()
            pool.collect()
    except KeyboardInterrupt:
        interrupted = True
    finally:
        _stop(pool.workers)
    return [pool.done[i] for i in sorted(pool.done)], interrupted


class _Pool:
    """Worker processes fed one file at a time; a worker that dies holding a file makes
    that file an error row and is replaced."""

    def __init__(self, files: list[str], worker_args: tuple, on_result: Callable[[FileOutcome], None]):
        import multiprocessing as mp

        self.ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else None)
        self.queue = list(enumerate(files))[::-1]  # pop() from the end = input order
        self.worker_args = worker_args
        self.on_result = on_result
        self.done: dict[int, FileOutcome] = {}
        self.workers: list[_Worker] = []

    def start_worker(self) -> None:
        parent_end, child_end = self.ctx.Pipe()
        proc = self.ctx.Process(target=_worker_main, args=(child_end, *self.worker_args), daemon=True)
        # known before it exists: a Ctrl-C during the fork must not leave an unknown worker
        self.workers.append(_Worker(proc, parent_end))
        with _sigint_held():
            proc.start()
            child_end.close()

    def finish(self, index: int, outcome: FileOutcome) -> None:
        self.done[index] = outcome
        self.on_result(outcome)

    def dispatch(self) -> None:
        """Give every idle worker the next file."""
        for w in self.workers:
            if w.task is None and self.queue:
                w.task = self.queue.pop()
                try:
                    w.conn.send(w.task)
                except (EOFError, OSError):
                    pass  # died already: found by collect() through its sentinel

    def collect(self) -> None:
        """Wait until a busy worker answers or dies, and take what it gives."""
        from multiprocessing.connection import wait

        busy = [w for w in self.workers if w.task is not None]
        ready = set(wait([w.conn for w in busy] + [w.process.sentinel for w in busy]))
        for w in busy:
            if w.conn not in ready and w.process.sentinel not in ready:
                continue
            try:
                if w.conn.poll():
                    index, outcome = w.conn.recv()
                    w.task = None
                    self.finish(index, outcome)
                    continue
            except (EOFError, OSError):
                pass
            if not w.process.is_alive():
                self.replace_dead(w)

    def replace_dead(self, w: _Worker) -> None:
        """The worker died while holding ``w.task``: that file is an error row, and a new
        worker takes the dead one's place."""
        assert w.task is not None  # busy, and no outcome came back
        index, path = w.task
        w.process.join()
        self.finish(index, FileOutcome(path, error=_death_message(path, w.process.exitcode)))
        w.conn.close()
        self.workers.remove(w)
        if self.queue:
            self.start_worker()


@contextmanager
def _sigint_held():
    """Hold Ctrl-C back while a worker starts.  It reaches the whole process group: a
    worker still inside multiprocessing's start-up, before it ignores SIGINT, would die
    there with a traceback.  Forked with SIGINT blocked, the worker unblocks it once it
    ignores it; the parent receives a Ctrl-C that came meanwhile when the new worker is
    on the list that :func:`_stop` stops."""
    if not hasattr(signal, "pthread_sigmask"):  # no POSIX signal masks (Windows)
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
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


def exit_status(outcomes: Iterable[FileOutcome]) -> int:
    """1 if any file failed or could not be checked, else 0."""
    return max((STATUS_RANK.get(o.status, 1) for o in outcomes), default=0)
