"""Butcher tableaux as delimited text (CSV, TSV) -> a tableau document.

Two layouts are recognised by their shape, so no option is needed:

* **Butcher array** (what a spreadsheet or ``numpy.savetxt`` of the usual picture gives):
  ``s + 1`` rows of ``s + 1`` cells; rows 1…s are ``c_i, a_i1 … a_is``, the last row is
  ``(anything), b_1 … b_s`` (its first cell is usually empty or 0 and is ignored).
* **GeometricIntegrators / RungeKutta.jl** ``writeTableauToFile`` files (``.tsv``): an
  optional header line ``# order stages type``, then ``s`` rows of ``s + 2`` cells
  ``c_i, b_i, a_i1 … a_is``.

Cells are separated by commas, tabs, semicolons or runs of spaces; ``#`` starts a
comment line.  Every cell is an entry in rkcheck's own grammar (``1/6``, ``0.25``,
``1/2 - sqrt(3)/6``): numbers are read as the text they are, never as binary doubles.
The result is the same dictionary a TOML/JSON tableau file gives, so the loader
validates it with the same one-line errors (``A[2][3]: …``).
"""

from __future__ import annotations

import csv
import re
from typing import Any

from rkcheck.errors import TableauError

SUFFIXES = (".csv", ".tsv")


def _cells(line: str, delimiter: str | None) -> list[str]:
    if delimiter is not None:  # quoted cells ("1,5", "a""b"), as spreadsheets write them
        return [c.strip() for c in next(csv.reader([line], delimiter=delimiter, skipinitialspace=True), [])]
    if "," in line or ";" in line or "\t" in line:
        return [c.strip() for c in re.split(r"[,;\t]", line)]
    return line.split()


def _quoted_delimiter(lines: list[str]) -> str | None:
    """With quoted cells, the one separator (comma, semicolon or tab) that occurs outside
    the quotes most often; None without quotes (then any of them separates)."""
    if not any('"' in line for line in lines):
        return None
    counts = dict.fromkeys(",;\t", 0)
    for line in lines:
        outside = re.sub(r'"(?:[^"]|"")*"?', "", line)
        for sep in counts:
            counts[sep] += outside.count(sep)
    best = max(counts, key=lambda sep: counts[sep])
    return best if counts[best] else ","


def parse_delimited(text: str, name: str) -> dict[str, Any]:
    """Delimited text -> ``{"method": {...}, "tableau": {"A", "b", "c"}}`` (see the module
    docstring for the two layouts); a shape that fits neither is a :class:`TableauError`."""
    rows: list[list[str]] = []
    line_of: list[int] = []
    data = [(no, line) for no, line in enumerate(text.removeprefix("\ufeff").splitlines(), start=1)
            if line.strip() and not line.lstrip().startswith("#")]
    delimiter = _quoted_delimiter([line for _, line in data])
    for no, line in data:
        rows.append(_cells(line, delimiter))
        line_of.append(no)
    if not rows:
        raise TableauError("no rows: expected a Butcher array (s+1 rows of s+1 cells: c | A, then · | b)")
    widths = {len(r) for r in rows}
    n = len(rows)
    if widths == {1} and n == 1:  # a Butcher array of no stage
        raise TableauError("1 row of 1 cell: expected a Butcher array (s+1 rows of s+1 cells, s ≥ 1: c | A, then · | b)")
    if widths == {n}:  # Butcher array: (s+1) x (s+1)
        body, last = rows[:-1], rows[-1]
        c = [r[0] for r in body]
        A = [r[1:] for r in body]
        b = last[1:]
    elif widths == {n + 2}:  # GeometricIntegrators: s rows of c, b, a_i1 … a_is
        c = [r[0] for r in rows]
        b = [r[1] for r in rows]
        A = [r[2:] for r in rows]
    else:
        for r, no in zip(rows, line_of):
            if len(r) != len(rows[0]):
                raise TableauError(f"row has {len(r)} cells, the first row {len(rows[0])}", f"line {no}")
        raise TableauError(
            f"{n} rows of {len(rows[0])} cells fit no layout: expected a Butcher array (s+1 rows of s+1 cells: "
            "c_i, a_i1 … a_is, and a last row ·, b_1 … b_s) or s rows of s+2 cells (c_i, b_i, a_i1 … a_is)")
    for place, values in (("c", c), ("b", b)):
        for i, v in enumerate(values, start=1):
            if v == "":
                raise TableauError("empty cell", f"{place}[{i}]")
    for i, row in enumerate(A, start=1):
        for j, v in enumerate(row, start=1):
            if v == "":
                raise TableauError("empty cell", f"A[{i}][{j}]")
    return {"method": {"name": name}, "tableau": {"A": A, "b": b, "c": c}}
