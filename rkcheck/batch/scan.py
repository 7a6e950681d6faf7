"""Checking many files: one outcome per file, in worker processes, in a fixed order.

:func:`scan_file` checks one file and never raises for a bad file: a file that does not
load is an outcome with ``status = "error"`` and its one-line message; a valid TOML/JSON
document without ``[tableau]``/``[family]``/``[method]`` is ``"skipped"`` (a
``pyproject.toml`` in the same folder is not a failure).  :func:`run_scan` runs it on an
:class:`~rkcheck.batch.executors.Executor`: by default a local process pool whose
workers keep their tree and condition tables between files (and, forked after the
parent built the tables for the scan's default options, start with them), or the
workers of a Dask cluster.  Outcomes are :class:`FileOutcome` values (the check result
itself, not a report: rendering is :mod:`rkcheck.reports.scan`'s job) and arrive in
input order; Ctrl-C stops the workers and returns the outcomes that finished.
"""

from __future__ import annotations

import difflib
import os
import pickle
import time
from contextlib import closing
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

from rkcheck.batch.executors import Executor, executor_for
from rkcheck.batch.executors import (
    default_jobs as default_jobs,  # where callers found it before
)
from rkcheck.batch.jobs import internal_error
from rkcheck.errors import UserError
from rkcheck.io.printable import printable
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
    #: the result's ``verify --format json`` document, already encoded, when the scan
    #: asked the worker for it (the JSON report then splices it in: encoding the
    #: documents was most of a JSON scan's time in the parent process)
    document: str | None = None

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        if self.document is not None and state.get("_result") is not None:
            # the receiving process reports from the document and seldom reads the result
            # itself: it travels pickled, and is unpickled only when read (unpickling
            # every result cost the parent of a JSON scan about a millisecond a file)
            state["_result"] = _Packed(pickle.dumps(state["_result"], protocol=pickle.HIGHEST_PROTOCOL))
        return state


@dataclass(frozen=True)
class _Packed:
    """A check result still pickled (see :meth:`FileOutcome.__getstate__`)."""

    data: bytes


def _result_of(outcome: FileOutcome) -> Any:
    value = outcome.__dict__.get("_result")
    if isinstance(value, _Packed):
        value = outcome.__dict__["_result"] = pickle.loads(value.data)
    return value


def _set_result(outcome: FileOutcome, value: Any) -> None:
    outcome.__dict__["_result"] = value


# the field's value lives in ``_result``: this property unpickles a packed one on first read
FileOutcome.result = property(_result_of, _set_result, doc="The CheckResult, with its claims judged.")


def options_for(tab, flags: dict[str, Any], project: dict[str, Any]):
    """Check options of one file: flags, else its ``[check]``, else ``[tool.rkcheck]``."""
    return resolve_check_options(flags, tab.info.check, project)


def _is_tableau_document(data: dict[str, Any]) -> bool:
    """A table the loader reads, or the short form (``A`` and ``b`` at the top level), as
    ``verify`` accepts it; any other document (``package.json``, ``pyproject.toml``) is
    skipped — unless it is made of rkcheck's tables and near misses of them only
    (``[tabelau]`` beside ``[expect]``): a misspelt tableau file is an error, not a file
    to pass over."""
    if any(k in data for k in ("tableau", "family", "method", "continuous")) or ("A" in data and "b" in data):
        return True
    near = {str(k): m[0] for k in data if (m := difflib.get_close_matches(str(k), RKCHECK_TABLES, n=1, cutoff=0.8))}
    misses = [k for k in near if k not in RKCHECK_TABLES]
    if misses and all(str(k) in near for k in data):
        key = misses[0]
        raise UserError(f"unknown table [{printable(key)}] (did you mean [{near[key]}]?): the file is not read as "
                        "a tableau", key)
    return False


def skip_reason(data: dict[str, Any]) -> str | None:
    """Why a document found in a folder is passed over, not checked (None: it is a
    tableau file, or meant as one)."""
    from rkcheck.io.documents import is_rkcheck_report

    if is_rkcheck_report(data):  # a report written into the folder scanned: scan ... -o dir/r.json
        return "a JSON report of rkcheck, not a tableau file"
    if not _is_tableau_document(data):
        return "not a tableau file (no [tableau], [continuous], [family] or [method] table, no top-level A and b)"
    return None


#: the tables an rkcheck file is made of (a near miss of one is an error in a scan)
RKCHECK_TABLES = ("tableau", "continuous", "family", "method", "expect", "check", "constants", "parameters")


def scan_file(path: str, flags: dict[str, Any], project: dict[str, Any], fail_on: str,
              max_stages: int = DEFAULT_MAX_STAGES, budget=None,
              document: Callable[[Any], str] | None = None) -> FileOutcome:
    """Check one file; never raises for a bad file (it becomes an ``error`` outcome).
    ``budget`` (:class:`rkcheck.energy.budget.Budget`) refuses a file whose own
    ``[check]`` asks for more than fits: that file's row says so.  ``document(result)``,
    when given, encodes the result's report here, in the worker (a failure leaves it to
    the report, which says so in the file's row)."""
    from rkcheck.energy.claims import judge_tableau
    from rkcheck.io.documents import detect_format, locate_lines, read_text
    from rkcheck.io.loader import build_tableau, load_named, read_document
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
            data = read_document(text, path, fmt, max_stages)  # CSV and nodepy as verify reads them
            out.lines = locate_lines(text, fmt)
            passed_over = skip_reason(data)
            if passed_over is not None:
                out.status, out.error = "skipped", passed_over
                return out
            built: Any = build_tableau(data, path, max_stages)
            if not isinstance(built, Tableau) and not getattr(built, "is_continuous", False):
                out.status, out.error = "skipped", "a family with free [parameters] (check it with rkcheck solve)"
                return out
            tab = built.replace(info=built.info.replace(lines=out.lines))
        out.result = judge_tableau(tab, options_for(tab, flags, project), fail_on, budget)
        out.status = "failed" if out.result.failed else "ok"
        if document is not None:
            try:
                out.document = document(out.result)
            except Exception:  # the report builds it again and turns the failure into this row's error
                out.document = None
    except UserError as err:
        out.error = str(err.located(source=path) if not err.source else err)
    except RecursionError:
        out.error = f"{path}: nesting too deep"
    except Exception as err:  # memory running out, or a bug: this file's row says so, the other files go on
        out.error = f"{path}: {internal_error(err)}"
    finally:
        out.time = round(time.perf_counter() - t0, 6)
    return out


# ------------------------------------------------------------------- running


def _check_path(args: tuple, path: str) -> FileOutcome:
    """:func:`scan_file` with the scan's fixed arguments first (a module-level function
    and a tuple: what a forked worker or a Dask worker can be given)."""
    return scan_file(path, *args)


def _lost(path: str, why: str) -> FileOutcome:
    """The row of a file whose check gave no outcome (its worker died, or a bug)."""
    if why.startswith("internal error"):
        return FileOutcome(path, error=f"{path}: {why}")
    worker = "the worker process "
    if why.startswith(worker):  # "the worker process checking this file was killed by SIGKILL"
        why = worker + "checking this file " + why[len(worker):]
    return FileOutcome(path, error=f"{path}: {why}; the other files went on")


def warm_tables(flags: dict[str, Any], project: dict[str, Any], budget=None) -> None:
    """Build the condition table of the scan's default options before forking workers
    (each inherits it) — unless ``budget`` refuses it or it does not fit: then nothing
    is shared, and each file meets the limit in its own row."""
    from dataclasses import replace

    from rkcheck.energy.budget import check_budget, estimate
    from rkcheck.trees.listing import condition_listing

    degree = flags.get("degree", project.get("degree"))
    order = flags.get("order", project.get("order", DEFAULT_ORDER))
    try:
        if budget is not None:
            check_budget(estimate(order, degree, "exact", listing=True), replace(budget, announce=None), order)
        condition_listing(order, degree)
    except (UserError, MemoryError):
        return


def run_scan(
    files: list[str],
    flags: dict[str, Any],
    project: dict[str, Any],
    fail_on: str,
    jobs: int,
    max_stages: int = DEFAULT_MAX_STAGES,
    on_result: Callable[[FileOutcome], None] = lambda r: None,
    budget=None,
    executor: Executor | None = None,
    document: Callable[[Any], str] | None = None,
) -> tuple[list[FileOutcome], bool]:
    """All outcomes in input order, and whether the scan was interrupted (Ctrl-C or
    SIGTERM: then the outcomes are those that finished, still in input order).
    ``budget`` goes to every file's check (see :func:`scan_file`).  The files run on
    ``executor`` when given (a Dask cluster: :mod:`rkcheck.batch.executors`), else on
    ``jobs`` local worker processes (never more than files; 1: in this process).
    ``document`` encodes each result's report in the worker (see :func:`scan_file`)."""
    from functools import partial

    if executor is None:
        jobs = max(1, min(jobs, len(files)))
        executor = executor_for(None, jobs, partial(warm_tables, flags, project, budget))
    check = partial(_check_path, (flags, project, fail_on, max_stages, budget, document))
    done: dict[int, FileOutcome] = {}
    interrupted = False
    try:
        with closing(executor.map_unordered(check, files, _lost)) as results:
            for index, outcome in results:
                done[index] = outcome
                on_result(outcome)
    except KeyboardInterrupt:
        interrupted = True
    return [done[i] for i in sorted(done)], interrupted


def exit_status(outcomes: Iterable[FileOutcome]) -> int:
    """1 if any file failed or could not be checked, else 0."""
    return max((STATUS_RANK.get(o.status, 1) for o in outcomes), default=0)
