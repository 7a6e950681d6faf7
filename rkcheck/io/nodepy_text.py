"""nodepy's text tableaux (Feagin's coefficient files) -> a tableau document.

nodepy's ``loadmethod.load_rk_from_file`` reads files of sections introduced by a line
ending in ``c[k]``, ``A[k,j]``, ``b[k]`` or ``bhat[k]``, each followed by lines
``k value`` (vectors) or ``k j value`` (the matrix), indices 0-based; entries not given
are 0.  This reader takes the same files, keeps every value as the decimal text it is
(Feagin's 60-digit decimals are then read as rounded to their last digit, definitions
§5), and ignores ``bhat`` (the embedded method is not checked).
"""

from __future__ import annotations

from typing import Any

from rkcheck.errors import TableauError
from rkcheck.options import DEFAULT_MAX_STAGES

SUFFIXES = (".txt", ".nodepy")
_SECTIONS = {"c[k]": "c", "A[k,j]": "A", "b[k]": "b", "bhat[k]": "bhat"}


def looks_like_nodepy(text: str) -> bool:
    """Whether the text has nodepy's section headers."""
    return any(line.split()[-1:] in (["A[k,j]"], ["b[k]"]) for line in text.splitlines())


def parse_nodepy_text(text: str, name: str, max_stages: int = DEFAULT_MAX_STAGES) -> dict[str, Any]:
    """The file's ``A``, ``b`` and ``c`` as a tableau document (entries as text); an
    index beyond ``max_stages`` is refused before anything is allocated."""
    section: str | None = None
    values: dict[str, dict[tuple[int, ...], str]] = {k: {} for k in ("A", "b", "c", "bhat")}
    for no, line in enumerate(text.splitlines(), start=1):
        words = line.split()
        if not words:
            continue
        if words[-1] in _SECTIONS:
            section = _SECTIONS[words[-1]]
            continue
        if section is None:
            continue
        width = 3 if section == "A" else 2
        # ASCII digits only: '²'.isdigit() is true, but int('²') fails
        if len(words) != width or not all(w.isascii() and w.isdigit() for w in words[:-1]):
            raise TableauError(f"expected {width - 1} index(es) and a value in section {section}", f"line {no}")
        key = tuple(int(w) for w in words[:-1])
        if max(key) >= max_stages:
            raise TableauError(f"stage index {max(key)} means {max(key) + 1} stages, which exceeds the limit of "
                               f"{max_stages} (raise it with --max-stages, or max_stages= in Python)", f"line {no}")
        if key in values[section]:  # as a JSON file's duplicate key: which one was meant is not ours to guess
            index = ",".join(str(k) for k in key)
            raise TableauError(f"{section}[{index}] is given twice (first as {values[section][key]!r})", f"line {no}")
        values[section][key] = words[-1]
    if not values["b"]:
        raise TableauError("no b[k] section: not a nodepy tableau file")
    indices = [k for sec in ("A", "b", "c") for key in values[sec] for k in key]
    s = max(indices) + 1
    A = [[values["A"].get((i, j), "0") for j in range(s)] for i in range(s)]
    b = [values["b"].get((i,), "0") for i in range(s)]
    doc: dict[str, Any] = {"method": {"name": name}, "tableau": {"A": A, "b": b}}
    if values["c"]:
        doc["tableau"]["c"] = [values["c"].get((i,), "0") for i in range(s)]
    return doc
