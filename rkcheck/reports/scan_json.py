"""The scan's JSON report, and each file's document encoded where it was checked.

``rkcheck scan --format json`` writes one document: the options, the totals and per
file its path, status, error, time and under ``result`` the ``verify --format json``
object.  Indenting JSON is Python work (:mod:`rkcheck.reports.jsontext`), as costly
as checking a small tableau, so a scan's workers encode their files' results
(:func:`encoded_result`) and :func:`scan_json` splices the texts in, byte for byte the
document that encoding everything at once gives.
"""

from __future__ import annotations

import json
from typing import Any

from rkcheck.reports.jsondoc import SCHEMA, check_doc
from rkcheck.reports.jsontext import Encoded, dumps
from rkcheck.version import __version__


def encoded_result(result: Any) -> str:
    """``verify --format json`` of one check, encoded (a scan's workers call this, so
    that the report only splices the texts together, as :class:`Encoded` values)."""
    return dumps(check_doc(result))


def json_row(d: dict[str, Any]) -> str:
    """A row as JSON (a worker's encoded result is known to encode)."""
    return json.dumps({**d, "result": None} if isinstance(d["result"], Encoded) else d, ensure_ascii=False)


def scan_json(outcomes: list[dict[str, Any]], interrupted: bool, options: dict[str, Any]) -> str:
    files = [{"file": o["path"], "status": o["status"], "error": o["error"], "time": o["time"],
              "result": o.get("result")} for o in outcomes]
    doc = {
        "schema": SCHEMA,
        "rkcheck": __version__,
        "kind": "scan",
        "options": options,
        "interrupted": interrupted,
        "totals": totals(outcomes),
        "files": files,
    }
    return dumps(doc)


def totals(outcomes: list[dict[str, Any]]) -> dict[str, int]:
    t = {"files": len(outcomes), "ok": 0, "failed": 0, "error": 0, "skipped": 0}
    for o in outcomes:
        t[o["status"]] = t.get(o["status"], 0) + 1
    return t
