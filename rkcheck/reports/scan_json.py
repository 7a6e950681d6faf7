"""The scan's JSON report, and each file's document encoded where it was checked.

``rkcheck scan --format json`` writes one document: the options, the totals and per
file its path, status, error, time and under ``result`` the ``verify --format json``
object.  Indented JSON is encoded by Python's own (pure-Python) encoder, as costly as
checking a small tableau, so a scan's workers encode their files' results
(:func:`encoded_result`) and :func:`scan_json` splices the texts in, byte for byte the
document that encoding everything at once gives.
"""

from __future__ import annotations

import json
import re
import secrets
from dataclasses import dataclass
from typing import Any

from rkcheck.reports.jsondoc import SCHEMA, check_doc
from rkcheck.version import __version__


@dataclass(frozen=True)
class Encoded:
    """A file's ``result`` already encoded as JSON by the worker that checked it
    (:func:`encoded_result`); only the JSON report takes it as it is."""

    text: str


#: how far a file's ``result`` sits in the scan's JSON report: its keys are at depth 3
_NESTED = "\n" + " " * 6


def encoded_result(result: Any) -> str:
    """``verify --format json`` of one check, encoded and indented as the scan's JSON
    report nests it (a scan's workers call this, so that the report only splices the
    texts together)."""
    return json.dumps(check_doc(result), indent=2, ensure_ascii=False).replace("\n", _NESTED)


def json_row(d: dict[str, Any]) -> str:
    """A row as JSON (a worker's encoded result is known to encode)."""
    return json.dumps({**d, "result": None} if isinstance(d["result"], Encoded) else d, ensure_ascii=False)


def scan_json(outcomes: list[dict[str, Any]], interrupted: bool, options: dict[str, Any]) -> str:
    files = []
    encoded: dict[str, str] = {}
    nonce = secrets.token_hex(8)  # stands in for an encoded result; no file's text can hold it
    for k, o in enumerate(outcomes):
        result = o.get("result")
        if isinstance(result, Encoded):
            result = f"{nonce}:{k}"
            encoded[result] = o["result"].text
        files.append({
            "file": o["path"], "status": o["status"], "error": o["error"], "time": o["time"],
            "result": result,
        })
    doc = {
        "schema": SCHEMA,
        "rkcheck": __version__,
        "kind": "scan",
        "options": options,
        "interrupted": interrupted,
        "totals": totals(outcomes),
        "files": files,
    }
    text = json.dumps(doc, indent=2, ensure_ascii=False)
    if not encoded:
        return text
    return _RESULT_LINE.sub(lambda m: m.group(1) + encoded[m.group(2)], text)


#: the line of a file's ``result`` in the scan's JSON when it holds a placeholder
_RESULT_LINE = re.compile(r'^(      "result": )"([0-9a-f]{16}:[0-9]+)"$', re.MULTILINE)


def totals(outcomes: list[dict[str, Any]]) -> dict[str, int]:
    t = {"files": len(outcomes), "ok": 0, "failed": 0, "error": 0, "skipped": 0}
    for o in outcomes:
        t[o["status"]] = t.get(o["status"], 0) + 1
    return t
