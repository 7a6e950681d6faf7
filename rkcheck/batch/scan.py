"""Checking many files: one outcome per file, in worker processes, in a fixed order.

:func:`scan_file` checks one file and never raises for a bad file: a file that does not
load is an outcome with ``status = "error"`` and its one-line message; a valid TOML/JSON
document without ``[tableau]``/``[family]``/``[method]`` is ``"skipped"`` (a
``pyproject.toml`` in the same folder is not a failure).  :func:`run_scan` runs it over
a process pool whose workers keep their tree and condition tables between files (and,
forked after the parent built the tables for the scan's default options, start with
them).  Outcomes are plain dicts, ready for JSON, and arrive in input order; Ctrl-C
stops the pool and returns the outcomes that finished.
"""

from __future__ import annotations

import os
import signal
import time
from typing import Any, Callable, Iterable

from rkcheck.errors import UserError
from rkcheck.options import DEFAULT_MAX_STAGES, DEFAULT_ORDER, resolve_check_options

STATUS_RANK = {"ok": 0, "skipped": 0, "failed": 1, "error": 1}


def options_for(tab, cli: dict[str, Any], project: dict[str, Any]):
    """Check options of one file: flags, else its ``[check]``, else ``[tool.rkcheck]``."""
    return resolve_check_options(cli, tab.check, project)


def _is_tableau_document(data: dict[str, Any]) -> bool:
    return any(k in data for k in ("tableau", "family", "method"))


def scan_file(path: str, cli: dict[str, Any], project: dict[str, Any], fail_on: str) -> dict[str, Any]:
    """Check one file; the outcome dict always has path, status, error and time."""
    from rkcheck.energy.claims import judge_tableau
    from rkcheck.io.loader import (
        build_tableau,
        detect_format,
        locate_lines,
        parse_document,
        read_text,
    )

    t0 = time.perf_counter()
    out: dict[str, Any] = {"path": path, "status": "error", "error": None, "time": 0.0, "lines": {}}
    try:
        text = read_text(path)
        fmt = detect_format(path, text)
        try:
            data = parse_document(text, fmt)
        except UserError as err:
            raise err.located(source=path) from None
        out["lines"] = locate_lines(text, fmt)
        if not _is_tableau_document(data):
            out.update(status="skipped", error="not a tableau file (no [tableau], [family] or [method] table)")
            return out
        tab = build_tableau(data, path, cli.get("max_stages", DEFAULT_MAX_STAGES))
        tab.lines = out["lines"]
        from rkcheck.reports.jsondoc import check_doc

        result, claims, failed = judge_tableau(tab, options_for(tab, cli, project), fail_on)
        out["result"] = check_doc(result, claims)
        out["status"] = "failed" if failed else "ok"
    except UserError as err:
        out["error"] = str(err.located(source=path) if not err.source else err)
    except RecursionError:
        out["error"] = f"{path}: nesting too deep"
    finally:
        out["time"] = round(time.perf_counter() - t0, 6)
    return out


# ------------------------------------------------------------------- workers

_WORKER: dict[str, Any] = {}


def _init_worker(cli: dict[str, Any], project: dict[str, Any], fail_on: str) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C
    _WORKER.update(cli=cli, project=project, fail_on=fail_on)


def _work(path: str) -> dict[str, Any]:
    return scan_file(path, _WORKER["cli"], _WORKER["project"], _WORKER["fail_on"])


def warm_tables(cli: dict[str, Any], project: dict[str, Any]) -> None:
    """Build the condition table of the scan's default options before forking workers."""
    from rkcheck.trees.conditions import condition_table

    degree = cli.get("degree", project.get("degree"))
    order = cli.get("order", project.get("order", DEFAULT_ORDER))
    condition_table(order, degree)


def run_scan(
    files: list[str],
    cli: dict[str, Any],
    project: dict[str, Any],
    fail_on: str,
    jobs: int,
    on_result: Callable[[dict[str, Any]], None] = lambda r: None,
) -> tuple[list[dict[str, Any]], bool]:
    """All outcomes in input order, and whether the scan was interrupted (Ctrl-C)."""
    results: list[dict[str, Any]] = []
    if jobs <= 1 or len(files) <= 1:
        try:
            for f in files:
                r = scan_file(f, cli, project, fail_on)
                results.append(r)
                on_result(r)
        except KeyboardInterrupt:
            return results, True
        return results, False

    import multiprocessing as mp

    warm_tables(cli, project)
    method = "fork" if "fork" in mp.get_all_start_methods() else None
    ctx = mp.get_context(method)
    pool = ctx.Pool(jobs, initializer=_init_worker, initargs=(cli, project, fail_on))
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


def exit_status(outcomes: Iterable[dict[str, Any]]) -> int:
    """1 if any file failed or could not be checked, else 0."""
    return max((STATUS_RANK.get(o["status"], 1) for o in outcomes), default=0)
