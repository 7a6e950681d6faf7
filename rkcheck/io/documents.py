"""Reading a tableau file's text into a document: the file (``-``: standard input) read
as UTF-8 within its size limit, its format told by suffix or content, TOML or JSON
parsed into a dict, and the lines of its tables and keys located for annotations.

Bare TOML/JSON floats are kept as their text (:class:`BareFloat`), digit for digit: the
parser hands us the text, never a binary64 double.  What the document *means* is
:mod:`rkcheck.io.loader`'s job.
"""

from __future__ import annotations

import io
import re
import sys
import tomllib
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterator

from rkcheck.errors import UserError
from rkcheck.io.bounded import bounded_read, max_file_bytes, read_fifo
from rkcheck.io.printable import printable
from rkcheck.numbers.formatting import count_text
from rkcheck.numbers.grammar import MAX_BITS, int_of_digits, too_large

#: the tables a tableau file may have
KNOWN_TABLES = ("method", "constants", "parameters", "tableau", "check", "expect", "family", "continuous")
SMALLEST_FILE = '[tableau] A = [["1/2"]] b = [1]  (TOML), or {"A": [["1/2"]], "b": [1]} (JSON)'


def is_rkcheck_report(data: dict[str, Any]) -> bool:
    """A JSON report rkcheck wrote (any command's ``--format json``): its ``schema``
    number says so — a check's has a ``tableau`` and a ``method`` too, a family's a
    ``family``, yet none is a tableau file."""
    return isinstance(data.get("schema"), int) and not isinstance(data.get("schema"), bool)


def case_twin(key: Any, known: tuple[str, ...]) -> str | None:
    """The known name ``key`` is in another case (``B`` for ``b``), or None."""
    return next((k for k in known if isinstance(key, str) and key != k and k.lower() == key.lower()), None)


def ignored_keys(table: dict[str, Any], known: tuple[str, ...], name: str) -> list[str]:
    """Warnings for the keys of ``[name]`` that nothing reads.  A key that is a known one
    in another case (``B`` for ``b``) is refused: ignored, it would check another method
    than the one written, and say so only in a warning."""
    out = []
    for key in table:
        if key in known:
            continue
        twin = case_twin(key, known)
        if twin is not None:
            raise UserError(f"unknown key: keys are case-sensitive, and this one would be ignored; write {twin}",
                            f"{name}.{printable(key)}")
        out.append(f"unknown key {name}.{printable(key)} ignored (known: {', '.join(known)})")
    return out


class BareFloat(str):
    """The text of a bare TOML/JSON float, kept digit for digit."""


def bare_floats_warning(texts: list[str]) -> list[str]:
    """A warning when some entries, written as bare TOML/JSON numbers (``texts``), are
    floats, which other tools read as binary64 doubles."""
    bare = [t for t in texts if any(ch in t for ch in ".eE")]
    if not bare:
        return []
    if len(bare) == 1:
        return [f"1 entry is a bare float ({bare[0]}): rkcheck reads it digit for digit, but other tools read it "
                "as a binary64 double; write it as a string to be unambiguous"]
    return [f"{count_text(len(bare))} entries are bare floats (e.g. {bare[0]}): rkcheck reads them digit for digit, "
            "but other tools read them as binary64 doubles; write them as strings to be unambiguous"]


def _bare_float(text: str) -> BareFloat:
    return BareFloat(text.replace("_", ""))


#: digits of a bare integer: past the largest value an entry may have (MAX_BITS)
MAX_BARE_DIGITS = int(MAX_BITS * 0.30103) + 2


def _bare_int(text: str) -> int:
    """A bare JSON integer of any length up to :data:`MAX_BARE_DIGITS` (Python refuses
    more than ``sys.get_int_max_str_digits()`` in one conversion; the CLI raises that
    limit for itself, a library leaves it alone)."""
    digits = text.lstrip("-")
    if len(digits) > MAX_BARE_DIGITS:
        raise ValueError(_too_long(count_text(len(digits))))
    value = int_of_digits(digits)
    return -value if text.startswith("-") else value


def _too_long(digits: str) -> str:
    return too_large("integer", f"{digits} digits")


@contextmanager
def _long_integers() -> Iterator[None]:
    """TOML's bare integers up to :data:`MAX_BARE_DIGITS` (tomllib has no hook for them):
    Python's limit on one conversion is raised while the text is parsed, and put back."""
    limit = sys.get_int_max_str_digits()
    raise_it = 0 < limit < MAX_BARE_DIGITS
    if raise_it:
        sys.set_int_max_str_digits(MAX_BARE_DIGITS)
    try:
        yield
    finally:
        if raise_it:
            sys.set_int_max_str_digits(limit)


def _reject_constant(text: str) -> Any:
    raise ValueError(f"{text} is not a finite number")


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """A JSON object, refusing a key given twice (json keeps the last one silently; TOML
    refuses duplicates itself)."""
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise ValueError(f"key {printable(key)!r} is given twice")
        out[key] = value
    return out


# ------------------------------------------------------------------ reading


def read_text(path: str) -> str:
    """Read a file (``-`` = standard input) as UTF-8, at most :func:`max_file_bytes`
    bytes, as a UserError on failure."""
    import stat

    limit = max_file_bytes()
    if path == "":  # read as the current folder otherwise: an unset variable in a CI script
        raise UserError("an empty path: give a tableau file (or - for standard input)", "path")
    try:
        if path == "-":
            stdin = getattr(sys.stdin, "buffer", None)
            if stdin is None:  # a text stream put in place by a caller (tests, an embedding program)
                text = sys.stdin.read(limit + 1)
                bounded_read(io.BytesIO(text.encode("utf-8", "surrogateescape")), limit, path)
                return text
            return bounded_read(stdin, limit, path).decode("utf-8-sig")  # -sig: a leading BOM is dropped
        p = Path(path)
        mode = p.stat().st_mode
        if stat.S_ISDIR(mode):
            raise UserError("is a directory, not a tableau file", source=path)
        if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
            raise UserError("is a device, not a tableau file", source=path)
        if stat.S_ISREG(mode) and p.stat().st_size > limit:
            raise UserError(f"file too large ({count_text(p.stat().st_size)} bytes; the limit MAX_FILE_BYTES is {count_text(limit)}; "
                            "set RKCHECK_MAX_FILE_BYTES to change it)", source=path)
        if stat.S_ISFIFO(mode):  # bash's <(…) too
            return read_fifo(path, limit).decode("utf-8-sig")
        with open(p, "rb") as fh:
            return bounded_read(fh, limit, path).decode("utf-8-sig")  # spreadsheets write a BOM
    except FileNotFoundError:
        raise UserError("no such file", source=path) from None
    except PermissionError:
        raise UserError("permission denied", source=path) from None
    except UnicodeDecodeError as err:
        raise UserError(f"not UTF-8 text (byte {err.start})", source=path) from None
    except OSError as err:
        raise UserError(f"cannot read: {err.strerror}", source=path) from None


def detect_format(path: str, text: str) -> str:
    """The input format of a file: by suffix, else by content (JSON object, nodepy
    section headers, else TOML)."""
    from rkcheck.io import delimited, nodepy_text

    suffix = Path(path).suffix.lower()
    if suffix in (".toml", ".json"):
        return suffix[1:]
    if suffix in delimited.SUFFIXES:
        return "csv"
    if suffix in nodepy_text.SUFFIXES and nodepy_text.looks_like_nodepy(text):
        return "nodepy"
    if text.lstrip().startswith("{"):
        return "json"
    return "nodepy" if nodepy_text.looks_like_nodepy(text) else "toml"


def parse_document(text: str, fmt: str) -> dict[str, Any]:
    """TOML or JSON text -> dict, syntax errors as UserError with their line.  An empty
    file is one error in either format (a scan does not pass over it: it is a tableau file
    left empty, not some other document)."""
    if not text.strip():
        raise UserError(f"the file is empty; the smallest tableau file is {SMALLEST_FILE}")
    if fmt == "json":
        import json  # TOML files (the usual input) do not need it: start-up
    try:
        if fmt == "json":
            data = json.loads(text, parse_float=_bare_float, parse_int=_bare_int, parse_constant=_reject_constant,
                              object_pairs_hook=_unique_keys)
        else:
            with _long_integers():
                data = tomllib.loads(text, parse_float=_bare_float)
    except tomllib.TOMLDecodeError as err:
        msg = str(err)
        m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
        if m:
            msg = msg[: m.start()].strip()
            raise UserError(f"TOML syntax error: {msg}", f"line {m.group(1)}, column {m.group(2)}") from None
        raise UserError(f"TOML syntax error: {msg}") from None
    except ValueError as err:  # NaN/Infinity or a duplicate key in JSON, an integer too long in either
        if fmt == "json" and isinstance(err, json.JSONDecodeError):
            raise UserError(f"JSON syntax error: {err.msg}", f"line {err.lineno}, column {err.colno}") from None
        if "integer string conversion" in str(err):  # TOML: past MAX_BARE_DIGITS
            raise UserError(f"TOML: {_too_long(f'more than {count_text(MAX_BARE_DIGITS)}')}") from None
        raise UserError(f"{fmt.upper()}: {err}") from None
    except RecursionError:
        raise UserError("nesting too deep") from None
    if not isinstance(data, dict):
        raise UserError("the top level must be a table/object")
    if not data:  # comments only, or {}: as empty as an empty file
        raise UserError(f"the file is empty (no table, no key); the smallest tableau file is {SMALLEST_FILE}")
    refuse_case_twins(data)
    return data


#: the keys of the short form, a tableau at the top level ({"A": …, "b": …})
SHORT_FORM_KEYS = ("A", "b", "c")


def refuse_case_twins(data: dict[str, Any]) -> None:
    """Refuse a table named as one of rkcheck's in another case (``[Parameters]``), and
    the short form written with its keys in another case (``{"A": …, "B": …}``): read
    as some other document, the file would be checked as another method than the one
    written — a family as a tableau — or passed over by a scan.  Every route that reads
    a document (verify, scan, solve, the family test) comes through here."""
    for key in data:
        twin = case_twin(key, KNOWN_TABLES)
        if twin is not None:
            raise UserError(f"unknown table: table names are case-sensitive, and this one would be ignored; write "
                            f"[{twin}]", printable(key))
    keys = [k for k in data if isinstance(k, str)]
    lowered = {k.lower() for k in keys}
    if not {"a", "b"} <= lowered or any(k.lower() not in ("a", "b", "c") for k in keys):
        return  # not the short form, misspelt: keys of some other document
    for key in keys:
        short = case_twin(key, SHORT_FORM_KEYS)
        if short is not None and short not in data:
            raise UserError(f"unknown key: keys are case-sensitive, and this one would be ignored; write {short}",
                            printable(key))


def locate_lines(text: str, fmt: str) -> dict[str, int]:
    """Line numbers (1-based) of the tables and their keys, for annotations.

    Keys are ``"tableau"``, ``"expect"``, ``"expect.energy_order"``, ...  A best effort
    on the raw text; a missing key simply has no line.
    """
    lines: dict[str, int] = {}
    if fmt == "toml":
        table = ""
        for no, line in enumerate(text.splitlines(), start=1):
            m = re.match(r"\s*\[\s*([A-Za-z0-9_.\-]+)\s*\]", line)
            if m:
                table = m.group(1)
                lines.setdefault(table, no)
                continue
            m = re.match(r"\s*([A-Za-z0-9_\-]+|\"[^\"]+\")\s*=", line)
            if m:
                key = m.group(1).strip('"')
                lines.setdefault(f"{table}.{key}" if table else key, no)
    else:
        stack: list[str] = []
        for no, line in enumerate(text.splitlines(), start=1):
            for m in re.finditer(r"\"([^\"]+)\"\s*:", line):
                key = m.group(1)
                if key in KNOWN_TABLES:
                    stack = [key]
                    lines.setdefault(key, no)
                elif stack:
                    lines.setdefault(f"{stack[0]}.{key}", no)
    return lines
