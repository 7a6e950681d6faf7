"""A scan's reports for continuous integration: JUnit XML (one testcase per file) and
GitHub Actions annotations (one per broken claim or failed file, at its line), with
what failed each file in a title and a message (:mod:`rkcheck.reports.scan` builds the
outcome documents they read).
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape, quoteattr

from rkcheck.reports.scan_json import totals
from rkcheck.reports.scan_outcomes import (
    _claim_line,
    _condition_line,
    _summary,
    broken_claims,
    claim_evidence,
    failing_conditions,
    failure_message,
    judged_by_claims,
)


def failure_title(o: dict[str, Any], fail_on: str = "claims") -> str:
    """What failed the file, in a few words (an annotation's title): its conditions, its
    consistency, or the ``--require`` gate."""
    s = _summary(o)
    if not judged_by_claims(o, fail_on) and failing_conditions(o, 1):
        return "rkcheck: energy conditions fail"
    if not judged_by_claims(o, fail_on) and s.get("inconsistent"):
        return "rkcheck: the method is inconsistent (Σb ≠ 1)"
    return f"rkcheck: --require {(s.get('require') or {}).get('level', 'any')} not met"


def failure_detail(o: dict[str, Any], fail_on: str = "claims", limit: int = 20) -> list[str]:
    """The lines of a JUnit ``<failure>``: each broken claim with what contradicts it, or
    (a file judged by its conditions) the failing conditions, at most ``limit`` of them."""
    if judged_by_claims(o, fail_on):
        lines = []
        for c in broken_claims(o):
            lines.append(f"claim {_claim_line(c)}")
            evidence = claim_evidence(o, c)
            lines += [f"  {e}" for e in evidence[:limit]]
            if len(evidence) > limit:
                lines.append(f"  … and {len(evidence) - limit} more")
        return lines or [failure_message(o, fail_on)]
    fails = failing_conditions(o, None)
    lines = [_condition_line(c) for c in fails[:limit]]
    if len(fails) > limit:
        lines.append(f"… and {len(fails) - limit} more")
    return lines or [failure_message(o, fail_on)]


def scan_junit(outcomes: list[dict[str, Any]], total_time: float, fail_on: str = "claims") -> str:
    """JUnit XML (the common Jenkins/Ant schema): one testcase per file."""
    t = totals(outcomes)
    cases = []
    for o in outcomes:
        name = quoteattr(o["path"])
        head = f'    <testcase classname="rkcheck" name={name} file={name} time="{o["time"]:.6f}"'
        if o["status"] == "ok":
            cases.append(head + "/>")
        elif o["status"] == "skipped":
            cases.append(head + f">\n      <skipped message={quoteattr(o['error'] or 'skipped')}/>\n    </testcase>")
        elif o["status"] == "error":
            msg = o["error"] or "error"
            cases.append(head + f">\n      <error message={quoteattr(msg)} type=\"UserError\">{escape(msg)}</error>\n    </testcase>")
        else:
            msg = failure_message(o, fail_on)
            detail = "\n".join(failure_detail(o, fail_on))
            cases.append(head + f">\n      <failure message={quoteattr(msg)} type=\"EnergyCheck\">{escape(detail)}</failure>\n    </testcase>")
    suite = (
        f'  <testsuite name="rkcheck" tests="{t["files"]}" failures="{t["failed"]}" errors="{t["error"]}" '
        f'skipped="{t["skipped"]}" time="{total_time:.6f}">'
    )
    return "\n".join(['<?xml version="1.0" encoding="UTF-8"?>',
                      f'<testsuites name="rkcheck scan" tests="{t["files"]}" failures="{t["failed"]}" '
                      f'errors="{t["error"]}" time="{total_time:.6f}">',
                      suite, *cases, "  </testsuite>", "</testsuites>"]) + "\n"


# -------------------------------------------------------------------- GitHub


def _gh_escape(text: str, prop: bool = False) -> str:
    text = text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        text = text.replace(":", "%3A").replace(",", "%2C")
    return text


def repository_root(path: str) -> Path | None:
    """The repository a file belongs to: the nearest folder above it holding ``.git`` (a
    folder, or a file in a worktree or submodule), else the nearest one holding a
    ``pyproject.toml``; None when there is neither."""
    here = Path(path).absolute().parent
    folders = [here, *here.parents]
    for marker in (".git", "pyproject.toml"):
        for d in folders:
            if (d / marker).exists():
                return d
    return None


def annotation_path(path: str) -> str:
    """A file as GitHub wants it in an annotation: relative to the repository root (which
    is the workflow's working copy), with ``/``, whatever folder rkcheck ran in and
    whether the path came from the command line or ``[tool.rkcheck]``.  A file outside
    any repository, and an ``@name``, are left as they are."""

    if path.startswith("@") or path == "-":
        return path
    root = repository_root(path)
    if root is None:
        return path
    full = Path(os.path.abspath(path))
    try:
        return full.relative_to(os.path.abspath(root)).as_posix()
    except ValueError:
        return path


def _annotation(level: str, path: str, line: int | None, title: str, message: str) -> str:
    props = f"file={_gh_escape(path, True)}"
    if line:
        props += f",line={line}"
    props += f",title={_gh_escape(title, True)}"
    return f"::{level} {props}::{_gh_escape(message)}"


def scan_github(outcomes: list[dict[str, Any]], fail_on: str = "claims") -> str:
    """GitHub Actions workflow commands: one ``::error`` per broken claim (at its line in
    ``[expect]``), per failing file without claims (at ``[tableau]``), per bad file; files
    are named relative to their repository's root (:func:`annotation_path`)."""

    out = []
    for o in outcomes:
        path, lines = annotation_path(o["path"]), o.get("lines") or {}
        if o["status"] == "error":
            line = None
            err = o["error"] or ""
            if err.startswith(o["path"] + ": "):  # the message names the file as the annotation does
                err = path + err[len(o["path"]):]
            m = re.search(r"line (\d+)", err)
            if m:
                line = int(m.group(1))
            out.append(_annotation("error", path, line, "rkcheck: cannot check", err))
        elif o["status"] == "failed":
            broken = broken_claims(o)
            for c in broken:
                key = c["place"].split("[")[0]
                line = lines.get(key) or lines.get("expect")
                out.append(_annotation("error", path, line, f"rkcheck: claim {c['claim']}",
                                       f"{c['place']}: claimed {c['claimed']}, found {c['found']}"
                                       + (f" ({c['note']})" if c.get("note") else "")))
            if not broken or not judged_by_claims(o, fail_on):
                line = lines.get("tableau") or lines.get("family")
                out.append(_annotation("error", path, line, failure_title(o, fail_on), failure_message(o, fail_on)))
        for w in (o.get("result") or {}).get("warnings", []):
            out.append(_annotation("warning", path, lines.get("tableau"), "rkcheck", w))
    return "\n".join(out) + ("\n" if out else "")


# ---------------------------------------------------------------------- text
