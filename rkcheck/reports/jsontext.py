"""The text of a JSON report: indented by two spaces, with the long lists a report has
(conditions, orders, grid points) one item to a line.

Python's indenting encoder is pure Python: a report with half a million conditions
spent minutes in it.  Here every array of numbers and every flat object inside an
array (a row: its values numbers, strings or arrays of numbers) is one line encoded by
the C encoder, and only the document's frame is walked in Python.  The value is the
same JSON; only the layout differs from ``json.dumps(doc, indent=2)``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

_NUMBERS = (int, float, bool, type(None))
_SCALARS = (str, *_NUMBERS)
_STEP = "  "
#: one encoder for every line: json.dumps with a non-default option builds one per call
_ENCODER = json.JSONEncoder(ensure_ascii=False)


@dataclass(frozen=True)
class Encoded:
    """A value already written by :func:`dumps` (at depth 0)."""

    text: str


def dumps(doc: Any) -> str:
    """``doc`` as indented JSON (non-ASCII characters as they are)."""
    out: list[str] = []
    _write(doc, 0, out)
    return "".join(out)


def _line(value: Any) -> str:
    return _ENCODER.encode(value)


def _numbers(value: Any) -> bool:
    return isinstance(value, list) and all(isinstance(v, _NUMBERS) for v in value)


def _row(value: Any) -> bool:
    return isinstance(value, dict) and all(isinstance(v, _SCALARS) or _numbers(v) for v in value.values())


def _key(key: Any) -> str:
    # JSON's keys are strings: a number, a boolean or None as json.dumps writes it
    return _line(key if isinstance(key, str) else json.dumps(key))


def _write(value: Any, depth: int, out: list[str]) -> None:
    pad = "\n" + _STEP * (depth + 1)
    if isinstance(value, dict) and value:
        sep = "{"
        for k, v in value.items():
            out.append(f"{sep}{pad}{_key(k)}: ")
            _write(v, depth + 1, out)
            sep = ","
        out.append("\n" + _STEP * depth + "}")
    elif isinstance(value, (list, tuple)) and value and not _numbers(list(value)):
        sep = "["
        for v in value:
            out.append(sep + pad)
            if _row(v):
                out.append(_line(v))
            else:
                _write(v, depth + 1, out)
            sep = ","
        out.append("\n" + _STEP * depth + "]")
    elif isinstance(value, Encoded):
        out.append(value.text.replace("\n", "\n" + _STEP * depth))
    else:
        out.append(_line(value))
