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
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

_NUMBERS = (int, float, bool, type(None))
_SCALARS = (str, *_NUMBERS)
_STEP = "  "
#: the size of the pieces :func:`chunks` hands out (characters)
CHUNK = 1 << 20
#: one encoder for every line: json.dumps with a non-default option builds one per call
_ENCODER = json.JSONEncoder(ensure_ascii=False)


@dataclass(frozen=True)
class Encoded:
    """A value already written by :func:`dumps` (at depth 0)."""

    text: str


def dumps(doc: Any) -> str:
    """``doc`` as indented JSON (non-ASCII characters as they are)."""
    return "".join(_pieces(doc, 0))


def chunks(doc: Any, size: int = CHUNK) -> Iterator[str]:
    """The text of :func:`dumps` in pieces of about ``size`` characters, made as they
    are written out."""
    part: list[str] = []
    held = 0
    for piece in _pieces(doc, 0):
        part.append(piece)
        held += len(piece)
        if held >= size:
            yield "".join(part)
            part, held = [], 0
    if part:
        yield "".join(part)


def _line(value: Any) -> str:
    return _ENCODER.encode(value)


def _numbers(value: Any) -> bool:
    return isinstance(value, list) and all(isinstance(v, _NUMBERS) for v in value)


def _row(value: Any) -> bool:
    return isinstance(value, dict) and all(isinstance(v, _SCALARS) or _numbers(v) for v in value.values())


def _key(key: Any) -> str:
    # JSON's keys are strings: a number, a boolean or None as json.dumps writes it
    return _line(key if isinstance(key, str) else json.dumps(key))


def _pieces(value: Any, depth: int) -> Iterator[str]:
    pad = "\n" + _STEP * (depth + 1)
    if isinstance(value, dict) and value:
        sep = "{"
        for k, v in value.items():
            yield f"{sep}{pad}{_key(k)}: "
            yield from _pieces(v, depth + 1)
            sep = ","
        yield "\n" + _STEP * depth + "}"
    elif isinstance(value, Iterator) or (isinstance(value, (list, tuple)) and value and not _numbers(list(value))):
        sep = "["
        for v in value:
            yield sep + pad
            if _row(v):
                yield _line(v)
            else:
                yield from _pieces(v, depth + 1)
            sep = ","
        yield "[]" if sep == "[" else "\n" + _STEP * depth + "]"
    elif callable(value):  # known only once what comes before it is written
        yield from _pieces(value(), depth)
    elif isinstance(value, Encoded):
        yield value.text.replace("\n", "\n" + _STEP * depth)
    else:
        yield _line(value)
