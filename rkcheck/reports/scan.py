"""Scan reports: text (rich), JSON and CSV here; JUnit XML and GitHub Actions annotations
in :mod:`rkcheck.reports.scan_ci`.

Every format is built from the same outcome documents (:func:`outcome_docs` of the
:class:`~rkcheck.batch.scan.FileOutcome` values); the JSON per-file object under
``result`` is exactly ``verify --format json``.
"""

from __future__ import annotations

import csv
import io
from fractions import Fraction
from typing import Any, Callable

from rkcheck.errors import is_digits_limit, too_many_digits
from rkcheck.io.printable import printable
from rkcheck.numbers.formatting import (
    counted,
    decimal_digits,
    decimal_string,
    digits_text,
)
from rkcheck.reports.jsondoc import check_doc
from rkcheck.reports.scan_ci import scan_github, scan_junit
from rkcheck.reports.scan_json import Encoded, json_row, scan_json, totals
from rkcheck.reports.scan_outcomes import (
    _summary,
    broken_claims,
    failure_message,
)

CSV_COLUMNS = [
    "file", "status", "method", "stages", "structure", "degree", "order", "classical_order",
    "quadrature_order", "energy_order", "energy_order_all", "equals_avf", "conditions_checked",
    "conditions_failed", "first_failure", "claims", "claims_ok", "broken_claims", "time", "error",
    "symplectic", "symmetric", "error_constant",
]


def outcome_docs(outcomes, row_check: Callable[[dict[str, Any]], Any] | None = None,
                 encoded: bool = False, failing_only: bool = False) -> list[dict[str, Any]]:
    """Plain documents of the outcomes: path, status, error, time, lines, and under
    ``result`` the ``verify --format json`` object of each checked file — or, with
    ``encoded``, the :class:`Encoded` text a worker made of it, where there is one
    (``failing_only``: the failing conditions only, :func:`check_doc`).

    A file whose document (or, given ``row_check``, its row of the report) cannot be
    built becomes an ``error`` row with the reason, like a file that could not be read:
    one file never aborts the report of the others.  The outcome itself is marked so,
    and the scan's exit code counts it."""
    docs = []
    for o in outcomes:
        # the path as shown (a name that is not UTF-8, an escape or a newline in it would
        # otherwise reach the terminal, the annotations and the JSON/XML as raw bytes)
        doc = {"path": printable(o.path), "status": o.status, "error": o.error and printable(o.error),
               "time": o.time, "lines": o.lines, "result": None}
        try:
            done = getattr(o, "document", None)
            if encoded and done is not None:  # the result itself is not read (not even unpickled)
                doc["result"] = Encoded(done)
            elif o.result is not None:
                doc["result"] = check_doc(o.result, failing_only)
            if row_check is not None:
                row_check(doc)
        except Exception as err:  # a bug (or a value no format can say): this row says so
            o.status, o.result = "error", None
            o.error = (str(too_many_digits(o.path)) if is_digits_limit(err) else
                       f"{o.path}: internal error while writing its report: {type(err).__name__}: {err} "
                       "(a bug in rkcheck; please report it)")
            doc.update(status=o.status, error=o.error, result=None)
        docs.append(doc)
    return docs


def _row_renderer(fmt: str, elapsed: float = 0.0) -> Callable[[dict[str, Any]], Any]:
    """How one row of a format is rendered (tried per file before the whole report)."""
    return {"json": json_row, "csv": lambda d: scan_csv([d]),
            "junit": lambda d: scan_junit([d], elapsed), "github": lambda d: scan_github([d]),
            "text": lambda d: (_scan_row(d, str, True), failure_message(d) if d["status"] == "failed" else None),
            }[fmt]


def scan_document(fmt: str, outcomes, interrupted: bool, options: dict[str, Any], elapsed: float) -> str:
    """The scan report in a machine format: json, csv, junit or github."""
    if fmt not in ("json", "csv", "junit", "github"):
        raise ValueError(f"unknown scan format {fmt!r}")
    docs = outcome_docs(outcomes, _row_renderer(fmt, elapsed), encoded=fmt == "json")
    if fmt == "json":
        return scan_json(docs, interrupted, options) + "\n"
    if fmt == "csv":
        return scan_csv(docs)
    if fmt == "junit":
        return scan_junit(docs, elapsed, options.get("fail_on", "claims"))
    if fmt == "github":
        return scan_github(docs, options.get("fail_on", "claims"))
    raise ValueError(f"unknown scan format {fmt!r}")


def scan_text(outcomes, elapsed: float, interrupted: bool, constants: bool = False, fail_on: str = "claims") -> str:
    """The text report as plain text (for ``--output``), as it prints when piped."""
    from rkcheck.reports.console import as_piped_text

    return as_piped_text(lambda console: render_scan_text(outcomes, console, elapsed, interrupted,
                                                          constants=constants, fail_on=fail_on))


def energy_text(o: dict[str, Any]) -> str:
    return _summary(o).get("energy_order_label", "")


# ----------------------------------------------------------------------- CSV


def _csv_bool(value: bool | None) -> str:
    """A yes/no column: ``true``/``false`` as in TOML and JSON, empty when not applicable."""
    return "" if value is None else ("true" if value else "false")


def scan_csv(outcomes: list[dict[str, Any]]) -> str:
    """One row per file, one vocabulary per column (docs/commands/scan.md): booleans
    ``true``/``false``, verdicts ``holds``/``holds_to_digits``/``fails``, empty when the
    column does not apply (a file that was not checked, no AVF verdict without a degree)."""
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=CSV_COLUMNS, lineterminator="\n")
    w.writeheader()
    for o in outcomes:
        r = o.get("result") or {}
        s = r.get("summary", {})
        opts = r.get("options", {})
        claims = r.get("claims")
        first = s.get("first_failure")
        w.writerow({
            "file": o["path"], "status": o["status"], "method": (r.get("method") or {}).get("name", ""),
            "stages": (r.get("tableau") or {}).get("stages", ""),
            "structure": (r.get("tableau") or {}).get("structure", ""),
            "degree": "none" if r and opts.get("degree") is None else opts.get("degree", ""),
            "order": opts.get("order", ""),
            "classical_order": s.get("classical_order", ""), "quadrature_order": s.get("quadrature_order", ""),
            "energy_order": s.get("energy_order", ""), "energy_order_all": _csv_bool(s.get("energy_order_all")),
            "equals_avf": _csv_bool(s.get("equals_avf")),
            "conditions_checked": s.get("conditions_checked", ""), "conditions_failed": s.get("conditions_failed", ""),
            "first_failure": first["id"] if first else "",
            "claims": "" if claims is None else len(claims),
            "claims_ok": _csv_bool(s.get("claims_ok")),
            "broken_claims": "; ".join(f"{c['place']}: claimed {c['claimed']}, found {c['found']}" for c in broken_claims(o)),
            "time": o["time"], "error": o["error"] or "",
            "symplectic": (s.get("symplectic") or {}).get("state", ""),
            "symmetric": (s.get("symmetric") or {}).get("state", ""),
            "error_constant": (s.get("error_constant") or {}).get("value", ""),
        })
    return buf.getvalue()


# --------------------------------------------------------------------- JUnit


def classical_cell(s: dict[str, Any]) -> str:
    """The classical order as the energy column writes orders: ``4``, ``≥ 4`` (nothing
    failed up to the order checked), ``0; 4 to 6 digits`` (reached only to digits)."""
    if not s:
        return ""
    order, reach, digits = s.get("classical_order", ""), s.get("classical_order_to_digits"), s.get("classical_order_digits")
    open_ended = "≥ " if s.get("classical_first_failure") is None else ""
    if digits is None or reach is None:
        return f"{open_ended}{order}"
    return f"{order}; {open_ended}{reach} to {digits_text(digits)}"


def compact_constant(value: Fraction | str) -> str:
    """An error constant in a few characters: ``0.15``, ``0.042``, ``1.5e-4``, ``2e+200``
    (exact decimal rounding: a constant past 1e308 is no float)."""
    value = Fraction(value)
    if value == 0:
        return "0"
    if Fraction(1, 100) <= value < 100:
        return decimal_string(value, 2)
    n, e = decimal_digits(value, 2)
    return f"{n // 10}.{n % 10}e{e}"


def render_scan_text(outcomes, console, total_time: float, interrupted: bool, verbose: bool = False,
                     constants: bool = False, fail_on: str = "claims", quiet: bool = False) -> None:
    """The scan table; ``constants``: with a column C (the energy error constant), as
    ``scan --sort energy`` shows it; ``quiet``: problems only (the rows of files that
    fail or cannot be checked, no table when there are none), then the totals."""
    outcomes = outcome_docs(outcomes, _row_renderer("text"), failing_only=True)  # a row reads no holding one
    root, shown = _common_root([o["path"] for o in outcomes])
    rows = [o for o in outcomes if not quiet or o["status"] in ("failed", "error")]
    if rows or not quiet:
        t = _scan_table(f"files under {root}/" if root else None, constants, console.width)
        for o in rows:
            t.add_row(*_scan_row(o, shown, constants))
        _keep_verdict_widths(t)
        console.print(t)
    _print_notes(outcomes, shown, verbose, console, fail_on)
    console.print(_totals_line(outcomes, total_time, interrupted), soft_wrap=True)  # one line for tail -1


def _common_root(paths: list[str]) -> tuple[str, Any]:
    """The folder all paths share (none for a single file) and how a path is shown
    relative to it."""
    import os

    # absolute paths beside relative ones (a folder and @rk4) share no folder: each is
    # shown as given
    mixed = len({os.path.isabs(p) for p in paths}) > 1
    root = os.path.commonpath(paths) if len(paths) > 1 and not mixed else ""
    if root and not os.path.isdir(root):
        root = os.path.dirname(root)

    def shown(path: str) -> str:
        return os.path.relpath(path, root) if root else path

    return root, shown


#: the narrowest the scan table's file column gets, whatever the terminal's width; the
#: width the columns after the method's take, with their padding
FILE_COLUMN_MIN = 16
VERDICT_COLUMNS = 60


def _scan_table(title: str | None, constants: bool, width: int) -> Any:
    from rich import box
    from rich.table import Table

    t = Table(box=box.SIMPLE_HEAD, pad_edge=False, title=title, title_justify="left")
    # a long path folds, and on a narrow terminal the method's name gives way first (the
    # verdict columns cannot shrink): without room for it, rich would squeeze the file
    # column to nothing, and rows could not be told apart
    t.add_column("file", overflow="fold", min_width=FILE_COLUMN_MIN)
    method = max(1, min(26, width - FILE_COLUMN_MIN - VERDICT_COLUMNS - (8 if constants else 0)))
    t.add_column("method", no_wrap=True, overflow="ellipsis", max_width=method)
    for col in ("s", "m", "classical", "energy") + (("C",) if constants else ()):
        t.add_column(col, justify="right", no_wrap=True)
    t.add_column("AVF", justify="center", no_wrap=True)
    t.add_column("claims", justify="center", no_wrap=True)
    t.add_column("time", justify="right", no_wrap=True)
    return t


def _scan_row(o: dict[str, Any], shown, constants: bool) -> list[Any]:
    """One file's cells: an error or skipped row, or its verdicts."""
    from rich.text import Text

    from rkcheck.reports.cells import plain

    r = o.get("result") or {}
    s = r.get("summary", {})
    if o["status"] in ("error", "skipped"):
        style = "bold red" if o["status"] == "error" else "dim"
        family = "[parameters]" in (o.get("error") or "")
        label = "ERROR (see below)" if o["status"] == "error" else (
            "skipped: a family" if family else "skipped: not a tableau")
        blanks = [""] * (7 if constants else 6)
        return plain(shown(o["path"]), Text(label, style=style), *blanks, f"{o['time']:.2f}")
    avf = {True: "yes", False: "no", None: "—"}[s.get("equals_avf")]
    claims = s.get("claims_ok")
    claims_t = Text("—") if claims is None else (Text("ok", style="green") if claims else Text("BROKEN", style="bold red"))
    energy = Text(energy_text(o), style="red" if s.get("first_failure") and o["status"] == "failed" else "")
    deg = s.get("degree")
    classical = classical_cell(s)
    ec = s.get("error_constant")
    extra = ["—" if not ec else compact_constant(ec["value"])] if constants else []
    t = r.get("tableau") or {}  # s: the stage count, or ∞ for a continuous-stage method (Butcher: infinitely many stages)
    stages = "∞" if t.get("structure") == "continuous" else t.get("stages", "")
    return plain(shown(o["path"]), (r.get("method") or {}).get("name", ""), stages,
                 "—" if deg is None else deg, classical, energy, *extra, avf, claims_t, f"{o['time']:.2f}")


def _keep_verdict_widths(t: Any) -> None:
    """rich shrinks every column of a table wider than the console, truncating short ones
    ("ener…"): the verdict columns keep their full width, the file path folds instead."""
    from rich.cells import cell_len
    from rich.text import Text

    for column in t.columns[2:]:
        texts = [str(column.header)] + [c.plain if isinstance(c, Text) else str(c) for c in column.cells]
        column.min_width = max(cell_len(x) for x in texts)


def _print_notes(outcomes: list[dict[str, Any]], shown, verbose: bool, console, fail_on: str = "claims") -> None:
    """Below the table: each error and failure, and with ``verbose`` the warnings."""
    from rich.text import Text

    for o in outcomes:  # each note one line however long, for grep
        if o["status"] == "error":
            console.print(Text(f"error: {o['error']}", style="red"), soft_wrap=True)
        elif o["status"] == "failed":
            console.print(Text(f"failed: {shown(o['path'])}: {failure_message(o, fail_on)}", style="red"),
                          soft_wrap=True)
        if verbose:
            for w in (o.get("result") or {}).get("warnings", []):
                console.print(Text(f"warning: {shown(o['path'])}: {w}", style="yellow"))


def _totals_line(outcomes: list[dict[str, Any]], total_time: float, interrupted: bool) -> Any:
    from rich.text import Text

    tot = totals(outcomes)
    line = Text(
        f"{counted(tot['files'], 'file')}: {tot['ok']} ok, {tot['failed']} failed, "
        f"{counted(tot['error'], 'error')}, "
        f"{tot['skipped']} skipped; {total_time:.1f} s",
        style="bold red" if tot["failed"] or tot["error"] else "bold green",
    )
    if interrupted:
        line.append("  (interrupted: partial results)", style="bold yellow")
    return line
