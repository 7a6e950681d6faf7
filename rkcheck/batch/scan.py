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
    result: Any = None
    claims: list | None = None


def options_for(tab, flags: dict[str, Any], project: dict[str, Any]):
    """Check options of one file: flags, else its ``[check]``, else ``[tool.rkcheck]``."""
    return resolve_check_options(flags, tab.check, project)


def _is_tableau_document(data: dict[str, Any]) -> bool:
    return any(k in data for k in ("tableau", "family", "method"))


def scan_file(path: str, flags: dict[str, Any], project: dict[str, Any], fail_on: str,
              max_stages: int = DEFAULT_MAX_STAGES) -> FileOutcome:
    """Check one file; never raises for a bad file (it becomes an ``error`` outcome)."""
    from rkcheck.energy.claims import judge_tableau
    from rkcheck.io.loader import (
        build_tableau,
        detect_format,
        locate_lines,
        parse_document,
        read_text,
    )

    t0 = time.perf_counter()
    out = FileOutcome(path)
    try:
        text = read_text(path)
        fmt = detect_format(path, text)
        try:
            data = parse_document(text, fmt)
        except UserError as err:
            raise err.located(source=path) from None
        out.lines = locate_lines(text, fmt)
        if not _is_tableau_document(data):
            out.status, out.error = "skipped", "not a tableau file (no [tableau], [family] or [method] table)"
            return out
        tab = build_tableau(data, path, max_stages)
        tab.lines = out.lines
        out.result, out.claims, failed = judge_tableau(tab, options_for(tab, flags, project), fail_on)
        out.status = "failed" if failed else "ok"
    except UserError as err:
        out.error = str(err.located(source=path) if not err.source else err)
    except RecursionError:
        out.error = f"{path}: nesting too deep"
    finally:
        out.time = round(time.perf_counter() - t0, 6)
    return out


# ------------------------------------------------------------------- workers

_WORKER: dict[str, Any] = {}


def _init_worker(flags: dict[str, Any], project: dict[str, Any], fail_on: str, max_stages: int) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C
    _WORKER.update(flags=flags, project=project, fail_on=fail_on, max_stages=max_stages)


def _work(path: str) -> FileOutcome:
    return scan_file(path, _WORKER["flags"], _WORKER["project"], _WORKER["fail_on"], _WORKER["max_stages"])


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
) -> tuple[list[FileOutcome], bool]:
    """All outcomes in input order, and whether the scan was interrupted (Ctrl-C)."""
    results: list[FileOutcome] = []
    if jobs <= 1 or len(files) <= 1:
        try:
            for f in files:
                r = scan_file(f, flags, project, fail_on, max_stages)
                results.append(r)
                on_result(r)
        except KeyboardInterrupt:
            return results, True
        return results, False

    import multiprocessing as mp

    warm_tables(flags, project)
    method = "fork" if "fork" in mp.get_all_start_methods() else None
    ctx = mp.get_context(method)
    pool = ctx.Pool(jobs, initializer=_init_worker, initargs=(flags, project, fail_on, max_stages))
    interrupted = False
    try:
        for r in pool.imap(_work, files, chunksize=1):
            results.append(r)
            on_result(r)
        pool.close()
    except KeyboardInterrupt:
        interrupted = True
        pool.terminate()
    finally:
        pool.join()
    return results, interrupted


def default_jobs() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def exit_status(outcomes: Iterable[FileOutcome]) -> int:
    """1 if any file failed or could not be checked, else 0."""
    return max((STATUS_RANK.get(o.status, 1) for o in outcomes), default=0)
