"""Many tableaux at once: ``scan`` (every file under some folders, checked in parallel)
and ``catalog`` (orders per degree, for a Markdown table) — the work of ``rkcheck scan``
and ``rkcheck catalog``, for Python callers.
"""

from __future__ import annotations

import os
import time
from contextlib import nullcontext
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Callable, Sequence

from rkcheck.api.settings import ProjectConfig, budget, guard, project_config
from rkcheck.api.verification import (
    UNSET,
    Verification,
    _option,
    check_flags,
    printable_numbers,
)
from rkcheck.errors import OptionError, RkcheckError, UserError
from rkcheck.options import (
    DEFAULT_MAX_STAGES,
    FAIL_ON,
    JOBS_RANGE,
    MAX_STAGES_RANGE,
    ORDER_RANGE,
    SCAN_SORTS,
    parse_callback,
    parse_choice,
    parse_degree,
    parse_flag,
    parse_int_in,
    parse_positive,
    shown_value,
)

if TYPE_CHECKING:
    from rkcheck.batch.catalog import CatalogRow
    from rkcheck.batch.scan import FileOutcome

# ------------------------------------------------------------------ scan


@dataclass(frozen=True)
class ScanRow:
    """One file of a scan: ``status`` is ``ok``, ``failed`` (fails under ``fail_on``),
    ``error`` (could not be read or checked: ``error`` is its one-line message) or
    ``skipped`` (a TOML/JSON document that is not a tableau, such as pyproject.toml);
    ``verification`` is the file's check when it was checked (as :func:`rkcheck.verify`
    gives it), else None; ``seconds`` the time the file took."""

    path: str
    status: str
    error: str | None
    seconds: float
    verification: Verification | None

    @staticmethod
    def of(outcome: "FileOutcome") -> "ScanRow":
        verification = None
        if outcome.result is not None:
            verification = Verification.of(outcome.result, failed=outcome.status == "failed")
        return ScanRow(outcome.path, outcome.status, outcome.error, outcome.time, verification)


@dataclass(frozen=True)
class ScanResult:
    """What :func:`scan` gives: the rows in path order (or ranked, ``sort="energy"``),
    whether Ctrl-C cut the scan short (then the rows are the files that finished), the
    wall time, and the options as the JSON report records them.

    ``outcomes`` are the underlying :class:`~rkcheck.batch.scan.FileOutcome` values (the
    reports' input); ``rows`` is the stable surface."""

    outcomes: "list[FileOutcome]"
    interrupted: bool
    elapsed: float
    options: dict[str, Any]
    fail_on: str
    sort: str

    @property
    def rows(self) -> list[ScanRow]:
        return [ScanRow.of(o) for o in self.outcomes]

    @property
    def failed(self) -> bool:
        """True when ``rkcheck scan`` would exit 1: a file fails under ``fail_on`` or could
        not be checked (never with ``fail_on="never"``)."""
        from rkcheck.batch.scan import exit_status

        return self.fail_on != "never" and exit_status(self.outcomes) == 1

    @property
    def ok(self) -> bool:
        return not self.failed

    def report(self, format: str = "json") -> str:
        """The report of ``rkcheck scan --format FORMAT`` (json, csv, junit, github; text:
        the table as plain text, as ``--output`` writes it)."""
        from rkcheck.reports import scan as scan_report

        if format not in ("text", "json", "csv", "junit", "github"):
            raise UserError(f"expected text, json, csv, junit or github, got {format!r}", "format")
        with printable_numbers():
            if format == "text":
                return scan_report.scan_text(self.outcomes, self.elapsed, self.interrupted,
                                             constants=self.sort == "energy", fail_on=self.fail_on)
            return scan_report.scan_document(format, self.outcomes, self.interrupted, self.options, self.elapsed)

    def __repr__(self) -> str:
        counts: dict[str, int] = {}
        for o in self.outcomes:
            counts[o.status] = counts.get(o.status, 0) + 1
        told = ", ".join(f"{v} {k}" for k, v in sorted(counts.items())) or "no files"
        return f"<ScanResult: {told}{' (interrupted)' if self.interrupted else ''}>"


def _config(project: bool | ProjectConfig) -> ProjectConfig:
    if isinstance(project, ProjectConfig):
        return project
    if not isinstance(project, bool):
        raise OptionError(f"expected True, False or a ProjectConfig, got {type(project).__name__}", "project")
    return project_config() if project else ProjectConfig()


def scan_roots(paths: Sequence[str | os.PathLike[str]], project: bool | ProjectConfig = False) -> list[str]:
    """The roots a scan starts from: ``paths``, else the ``paths`` of ``[tool.rkcheck]``
    (with ``project``); none at all is an error (the CLI's message)."""
    roots = _paths(paths) or _config(project).paths
    if not roots:
        raise UserError("give PATH... or set paths in [tool.rkcheck]", "scan")
    return roots


def files_read(inputs: Sequence[str]) -> list[str]:
    """The files a command reads for ``inputs``: each file, the tableau files under each
    folder (as a scan finds them), the file of each shipped ``@name`` where it is one on
    disk; ``-`` (standard input) is none.  What cannot be found is left out: the command
    itself says so."""
    from rkcheck.io.discovery import find_tableau_files
    from rkcheck.io.library import find

    out: list[str] = []
    for item in inputs:
        try:
            if item.startswith("@"):
                entry = find(item[1:])
                if entry is not None and isinstance(entry.resource, os.PathLike):
                    out.append(os.fspath(entry.resource))
            elif item not in ("", "-"):
                out += [f for f in find_tableau_files([item]) if f != "-"]
        except (RkcheckError, OSError):
            continue
    return out


def is_rkcheck_report_file(path: str) -> bool:
    """Whether the file holds a JSON report rkcheck wrote (a scan's, a check's): a report
    written again where the last one was is no input lost, even in a folder scanned."""
    import json

    try:
        with open(path, encoding="utf-8") as f:
            data = json.loads(f.read(1 << 24))
    except (OSError, ValueError):
        return False
    return isinstance(data, dict) and "schema" in data and "rkcheck" in data


def _paths(paths: Any) -> list[str]:
    """``paths`` as a list of path strings: one path (not a sequence of its characters) or
    several; anything else is refused naming the argument."""
    if isinstance(paths, (str, bytes, os.PathLike)):
        paths = [paths]
    try:
        out = [os.fsdecode(p) for p in paths]
    except TypeError:
        raise UserError("expected a path or a list of paths (str or os.PathLike)", "paths") from None
    if "" in out:  # read as the current folder otherwise: an unset variable in a CI script
        raise UserError("an empty path: give a file or folder (. for the current one)", "paths")
    return out


def _patterns(exclude: Any) -> list[str]:
    """``exclude`` as a list of glob patterns: one pattern, or several."""
    if isinstance(exclude, str):
        return [exclude]
    if isinstance(exclude, (list, tuple)) and all(isinstance(p, str) for p in exclude):
        return list(exclude)
    raise UserError(f"expected a glob pattern or a list of them, got {exclude!r}", "exclude")


def scan(
    paths: Sequence[str | os.PathLike[str]] = (),
    *,
    degree: int | str | None = UNSET,
    order: int = UNSET,
    dps: int = UNSET,
    decimals: str = UNSET,
    require: str = UNSET,
    arithmetic: str = UNSET,
    fail_fast: bool = False,
    exclude: Sequence[str] = (),
    fail_on: str | None = None,
    jobs: int | None = None,
    sort: str = "path",
    max_stages: int = DEFAULT_MAX_STAGES,
    max_conditions: int | None = None,
    project: bool | ProjectConfig = False,
    allow_empty: bool | None = None,
    progress: Callable[[int, int], None] | None = None,
    on_file: Callable[[ScanRow, int, int], None] | None = None,
    scheduler: str | None = None,
    json_in_workers: bool = False,
) -> ScanResult:
    """Check every ``*.toml``/``*.json`` tableau under ``paths`` (folders recursively,
    files, ``"@name"``) — the work of ``rkcheck scan``, with the same rows, order and exit
    status.

    Never raises for a bad file: it is a row with status ``error`` and its one-line
    message (a file that is not a tableau is ``skipped``).  Raises
    :class:`~rkcheck.errors.RkcheckError` only for what stops the whole scan: a bad
    option, a path that does not exist, no paths at all, or default options whose
    condition tables would not fit in memory (``ResourceError``).

    Check options (``degree``, ``order``, ``dps``, ``decimals``, ``require``,
    ``arithmetic``, ``fail_fast``) mean what
    they mean for :func:`~rkcheck.api.verification.verify` (definitions §3, §5); left
    out, each file's ``[check]`` table and then the defaults apply.  ``fail_on`` (default
    ``"claims"``) says what makes a file ``failed``; ``jobs`` worker processes (default:
    every core); ``exclude`` glob patterns on path or name; ``sort="energy"`` ranks the
    rows by energy order, then by the error constant C.  ``project=True`` (or a
    :class:`ProjectConfig`) applies ``[tool.rkcheck]`` of the nearest pyproject.toml
    (paths, exclude, check options, fail_on, jobs) under the arguments, as the CLI does.

    ``scheduler`` (``"tcp://host:8786"``; default: the environment variable
    ``RKCHECK_SCHEDULER``, else ``scheduler`` in ``[tool.rkcheck]``) runs the files on
    that Dask cluster instead of local processes (``pip install 'rkcheck[cluster]'``),
    with the same rows; a worker lost mid-scan has its files checked by the others.
    Without Dask, or with a scheduler that does not answer within
    SCHEDULER_CONNECT_TIMEOUT, it raises :class:`~rkcheck.errors.RkcheckError`.

    ``json_in_workers=True`` builds each file's JSON report in the worker that checked
    it, so that ``report("json")`` only assembles them (what ``rkcheck scan --format
    json`` does: on many small files the encoding costs more than the checks).

    ``progress(done, total)`` is called when the files are known and after each one;
    ``on_file(row, done, total)`` after each file.  Ctrl-C stops the workers (cancels
    the cluster's jobs) and returns the files that finished, with ``interrupted`` set."""
    from rkcheck.batch.executors import default_jobs, executor_for, resolve_scheduler
    from rkcheck.batch.scan import run_scan
    from rkcheck.io.discovery import find_tableau_files
    from rkcheck.reports.scan_json import encoded_result

    config = _config(project)
    progress = _option(lambda: parse_callback(progress, "progress"))
    on_file = _option(lambda: parse_callback(on_file, "on_file"))
    json_in_workers = _option(lambda: parse_flag(json_in_workers, "json_in_workers"))
    roots = scan_roots(paths, config)
    flags = check_flags(degree, order, dps, decimals, fail_fast, require, arithmetic)
    fail_on = _option(lambda: parse_choice(fail_on or config.fail_on or "claims", FAIL_ON, "fail_on"))
    if jobs is not None:
        jobs = _option(lambda: parse_int_in(jobs, JOBS_RANGE, "jobs"))
    jobs = jobs or config.jobs or default_jobs()
    sort = _option(lambda: parse_choice(sort, SCAN_SORTS, "sort"))
    max_stages = _option(lambda: parse_int_in(max_stages, MAX_STAGES_RANGE, "max_stages"))
    files_budget = _scan_budget(flags, max_conditions)
    patterns = _patterns(exclude) + config.exclude
    address = resolve_scheduler(scheduler, config.scheduler)
    t0 = time.perf_counter()
    outcomes: list[FileOutcome] = []
    interrupted = False
    try:
        files = find_tableau_files(roots, patterns)
        empty_ok = config.allow_empty if allow_empty is None else _option(lambda: parse_flag(allow_empty, "allow_empty"))
        if not files and not empty_ok:
            raise UserError(_nothing_found(roots, patterns), "scan")
        on_result = _reporter(len(files), progress, on_file)
        # connected here: an unreachable scheduler stops the scan before any file
        with executor_for(address, jobs) if address and files else nullcontext() as executor:
            outcomes, interrupted = run_scan(files, flags, config.check, fail_on, jobs, max_stages, on_result,
                                             files_budget, executor=executor,
                                             document=encoded_result if json_in_workers else None)
    except KeyboardInterrupt:  # before or between files: the result still says what finished
        interrupted = True
    if not interrupted and not empty_ok:
        _refuse_if_nothing_checked(outcomes)
    elapsed = time.perf_counter() - t0
    if sort == "energy":  # methods of equal energy order compared by their error constant
        from rkcheck.batch.ranking import rank_outcomes

        outcomes = rank_outcomes(outcomes)
    options = dict(flags, fail_on=fail_on, jobs=jobs, paths=roots)
    if address:
        options["scheduler"] = address
    return ScanResult(outcomes, interrupted, elapsed, options, fail_on, sort)


def _refuse_if_nothing_checked(outcomes: list["FileOutcome"]) -> None:
    """A gate that checks nothing does not pass silently: files found, every one of them
    skipped, is refused as finding none is."""
    if outcomes and all(o.status == "skipped" for o in outcomes):
        found = "the one file found is not" if len(outcomes) == 1 else f"none of the {len(outcomes)} files found is"
        raise UserError(f"{found} a tableau (rkcheck verify FILE says why "
                        "of one); nothing was checked (--allow-empty, or allow_empty = true in [tool.rkcheck], "
                        "lets such a scan pass)", "scan")


def _nothing_found(roots: list[str], exclude: list[str]) -> str:
    """Why a scan has no file to check, in one line: the roots, and how many files the
    exclusions took away."""
    from rkcheck.io.discovery import find_tableau_files
    from rkcheck.io.printable import printable

    shown = ", ".join(printable(r) for r in roots[:3]) + (f" and {len(roots) - 3} more" if len(roots) > 3 else "")
    excluded = len(find_tableau_files(roots, [])) if exclude else 0
    why = f" ({excluded} excluded by --exclude / exclude)" if excluded else ""
    return (f"no *.toml or *.json file under {shown}{why}: nothing to check "
            "(--allow-empty, or allow_empty = true in [tool.rkcheck], lets an empty scan pass)")


def _scan_budget(flags: dict[str, Any], max_conditions: int | None) -> Any:
    """The resource guard of every file: each is judged against it with the options it
    is checked with, and one that does not fit is an error row.  An order given to the
    scan itself is every file's (it overrides their ``[check]``): one that does not fit
    refuses the scan before any file; without one, a file's own ``[check]`` may fit where
    the default order does not."""
    from rkcheck.energy.budget import check_budget, estimate

    if max_conditions is not None:
        max_conditions = _option(lambda: parse_positive(max_conditions, "max_conditions"))
    files_budget = budget(max_conditions)
    if "order" in flags:
        check_budget(estimate(flags["order"], flags.get("degree"), "exact"), files_budget, flags["order"])
    return files_budget


def _reporter(total: int, progress: Callable[[int, int], None] | None,
              on_file: Callable[[ScanRow, int, int], None] | None) -> Callable[["FileOutcome"], None]:
    """What to call after each file: ``progress(done, total)`` (also once now, at 0) and
    ``on_file(row, done, total)``."""
    if progress is not None:
        progress(0, total)
    done = [0]

    def on_result(outcome: "FileOutcome") -> None:
        done[0] += 1
        if progress is not None:
            progress(done[0], total)
        if on_file is not None:
            on_file(ScanRow.of(outcome), done[0], total)

    return on_result


# ------------------------------------------------------------------ catalog

DEFAULT_CATALOG_DEGREES: tuple[int | None, ...] = (2, 3, 4, 6, None)


@dataclass(frozen=True)
class Catalog:
    """What :func:`catalog` gives: one :class:`~rkcheck.batch.catalog.CatalogRow` per file
    (``name``, ``stages``, ``classical``, ``quadrature``, ``energy`` by degree label,
    ``avf_degrees``, ``claims``, ``symplectic``, ``symmetric``, ``constants``, or
    ``error``), the degree labels (``m=4``, ``all H``), the order checked, and the family
    files found and left out (``families``)."""

    rows: "list[CatalogRow]"
    labels: list[str]
    degrees: list[int | None]
    order: int
    families: list[str] = field(default_factory=list)

    def to_markdown(self, command: str = "rkcheck.catalog()") -> str:
        """The Markdown page of ``rkcheck catalog`` (``command``, what made it, is
        recorded in its header)."""
        from rkcheck.reports.markdown import catalog_markdown

        if not isinstance(command, str) or not command.strip():
            raise OptionError("expected the command that made the catalogue (a non-empty string)", "command")
        return catalog_markdown(self.rows, self.labels, self.order, command, self.families)

    def __repr__(self) -> str:
        from rkcheck.numbers.formatting import counted

        return f"<Catalog: {counted(len(self.rows), 'file')}, {', '.join(self.labels)}, order {self.order}>"


def catalog(
    paths: Sequence[str | os.PathLike[str]] = (),
    *,
    degrees: Sequence[int | str | None] = DEFAULT_CATALOG_DEGREES,
    order: int = 8,
    progress: Callable[[int, int], None] | None = None,
) -> Catalog:
    """The catalogue of ``rkcheck catalog``: every tableau file under ``paths`` (without
    paths, the tableaux shipped with rkcheck — the names ``@name`` accepts), each checked
    for every degree bound m in ``degrees`` (None or ``"none"``: all Hamiltonians) up to
    energy order ``order``: classical, quadrature and energy orders (definitions §3–4),
    whether it is AVF, its claims, symplecticity and symmetry, and the energy error
    constants.  A file that cannot be read is a row with its ``error``; families (files
    with free ``[parameters]``) are left out.  With a single
    folder, row paths are relative to it.  ``progress(done, total)`` is called as files
    finish.  Refuses orders whose tables do not fit in memory (``ResourceError``)."""
    from pathlib import Path as FsPath

    from rkcheck.batch.catalog import catalog_row
    from rkcheck.io.discovery import find_tableau_files
    from rkcheck.io.library import library_root

    roots = _paths(paths)
    if not roots:
        root_dir = library_root()
        if root_dir is None:
            raise UserError("no tableaux are installed with rkcheck; give a PATH")
        roots = [str(root_dir)]
    order = _option(lambda: parse_int_in(order, ORDER_RANGE, "order"))
    progress = _option(lambda: parse_callback(progress, "progress"))
    if isinstance(degrees, (str, bytes)) or not isinstance(degrees, (Sequence, set, frozenset)):
        raise OptionError(f"expected a list of degrees, got {shown_value(degrees)}", "degrees")
    degs = [_option(lambda: parse_degree(d, "degrees")) for d in degrees]
    if not degs:
        raise UserError("expected at least one degree", "degrees")
    guard(order, None if None in degs else max(d for d in degs if d is not None))  # the resource guard
    # families (free [parameters]) are not one tableau: `rkcheck solve` is their catalogue
    kinds = {f: _catalogued_as(f) for f in find_tableau_files(roots, exclude=["README*", "*/README*"])}
    families = [f for f, kind in kinds.items() if kind == "family"]
    files = [f for f, kind in kinds.items() if kind == "row"]
    if not files:
        from rkcheck.numbers.formatting import counted

        also = (f"; {counted(len(families), 'family', 'families')} (free [parameters]: rkcheck solve is their catalogue)"
                if families else "")
        raise UserError(f"no tableau file (*.toml, *.json) under {', '.join(roots)}: nothing to catalogue{also}",
                        "catalog")
    root = FsPath(roots[0]) if len(roots) == 1 and FsPath(roots[0]).is_dir() else None
    rows = []
    if progress is not None:
        progress(0, len(files))
    # every file's check within the memory available, as a scan's
    each = replace(budget(), remedy="lower --order or --degrees")
    for f in files:
        row = catalog_row(f, degs, order, budget=each)
        if root is not None:
            row.path = str(FsPath(f).relative_to(root))
        rows.append(row)
        if progress is not None:
            progress(len(rows), len(files))
    labels = ["all H" if d is None else f"m={d}" for d in degs]
    shown = [str(FsPath(f).relative_to(root)) if root is not None else f for f in families]
    return Catalog(rows, labels, degs, order, shown)


def _catalogued_as(path: str) -> str:
    """What a file found in a folder is to a catalogue, from one read of it: ``"skip"``
    for a file that is no tableau file (``package.json``, a report rkcheck wrote), passed
    over as a scan passes over it; ``"family"`` for free ``[parameters]``; else ``"row"``
    — one that cannot be read too: its row says why."""
    from rkcheck.batch.scan import skip_reason
    from rkcheck.io.documents import detect_format, read_text
    from rkcheck.io.loader import read_document

    try:
        text = read_text(path)
        data = read_document(text, path, detect_format(path, text), DEFAULT_MAX_STAGES)
    except (UserError, RecursionError, MemoryError):
        return "row"
    if skip_reason(data) is not None:
        return "skip"
    return "family" if "parameters" in data else "row"


__all__ = ["Catalog", "ScanResult", "ScanRow", "catalog", "scan"]