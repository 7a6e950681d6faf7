"""Tableau files (TOML or JSON, same structure) -> :class:`~rkcheck.methods.tableau.Tableau`.

This is the only module of the core that reads files.  Every problem becomes a
:class:`~rkcheck.errors.UserError` naming the file and the place, 1-based like the
coefficients ``a_ij`` (``A[2][3]: unexpected ')' at column 7``).  File content is
parsed by :mod:`rkcheck.numbers.grammar`, never evaluated by Python.

Bare TOML/JSON floats are read digit for digit (the parser hands us their text, not a
binary64 double), with a warning because other tools will read them as doubles.

Short form: a document with ``A``, ``b`` (and ``c``) at the top level and no
``[tableau]`` table is read as if they were in ``[tableau]`` (what most people write in
JSON: ``{"A": [[...]], "b": [...]}``).  Other formats: ``.csv``/``.tsv`` Butcher arrays
(:mod:`rkcheck.io.delimited`) and nodepy's text tableaux (:mod:`rkcheck.io.nodepy_text`)
become the same document and are validated here the same way.  ``@name`` loads a
shipped tableau (:mod:`rkcheck.io.library`) or a classical method
(:mod:`rkcheck.methods.classics`).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rkcheck.errors import UserError
from rkcheck.io.documents import (
    KNOWN_TABLES,
    SHORT_FORM_KEYS,
    SMALLEST_FILE,
    BareFloat,
    bare_floats_warning,
    detect_format,
    ignored_keys,
    is_rkcheck_report,
    locate_lines,
    parse_document,
    read_text,
)
from rkcheck.io.printable import printable
from rkcheck.methods.claims import parse_claims
from rkcheck.methods.tableau import MethodInfo, Tableau
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Constants, Entry
from rkcheck.numbers.formatting import count_text

if TYPE_CHECKING:
    from rkcheck.methods.parametric import Family

from rkcheck.options import (
    DEFAULT_MAX_STAGES,
    INPUT_FORMATS,
    MAX_STAGES_RANGE,
    parse_int_in,
    parse_strings,
    validate_check_table,
)

#: the tables that each define a whole method: a file gives one of them
_METHOD_TABLES = ("tableau", "family", "continuous")


# ------------------------------------------------------------------ validation


def _table(data: dict[str, Any], name: str, required: bool = False) -> dict[str, Any]:
    value = data.get(name)
    if value is None:
        if required:
            raise UserError(f"missing [{name}] table")
        return {}
    if not isinstance(value, dict):
        raise UserError(f"[{name}] must be a table, not {_kind(value)}", name)
    return value


def _kind(value: Any) -> str:
    if value is None:  # JSON's null
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, (int, BareFloat)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    return type(value).__name__


def _entry_text(value: Any, place: str) -> tuple[str, bool]:
    """The text of an entry and whether it was a bare number."""
    if isinstance(value, bool) or not isinstance(value, (int, str)):
        raise UserError(f"expected a number or a string, got {_kind(value)}", place)
    if isinstance(value, BareFloat):
        if value.lower().lstrip("+-") in ("inf", "nan"):
            raise UserError(f"{value} is not a finite number", place)
        return str(value), True
    if isinstance(value, int):  # a bare integer of any length the document allowed (str() stops at 4 300 digits)
        if abs(value).bit_length() > ex.MAX_BITS:
            raise UserError(ex.too_large("integer", f"{count_text(abs(value).bit_length())} bits"), place)
        return ex.digits_text(value), True
    return value, False


def _parse_entry(value: Any, place: str, constants: Constants,
                 memo: dict[tuple[str, bool], Entry] | None = None) -> Entry:
    """The entry at ``place``; ``memo``: entries already parsed in this file by their text
    (a large sparse tableau repeats "0" a million times; an Entry is immutable)."""
    text, bare = _entry_text(value, place)
    if memo is not None and (text, bare) in memo:
        return memo[text, bare]
    try:
        entry = Entry.parse(text, constants, bare_number=bare)
    except UserError as err:
        raise err.located(place) from None
    if memo is not None:
        memo[text, bare] = entry
    return entry


def _vector(value: Any, name: str, s: int, constants: Constants,
            memo: dict[tuple[str, bool], Entry] | None = None) -> tuple[Entry, ...]:
    if not isinstance(value, list):
        raise UserError(f"expected a list of {s} entries, got {_kind(value)}", name)
    if len(value) != s:
        raise UserError(f"has {len(value)} entries, expected {s} (one per stage)", name)
    return tuple(_parse_entry(x, f"{name}[{i}]", constants, memo) for i, x in enumerate(value, start=1))


def _constant_definitions(table: dict[str, Any]) -> dict[str, ex.Expr]:
    """The ``[constants]`` table parsed: each name an identifier, each value an entry."""
    defs: dict[str, ex.Expr] = {}
    for name, value in table.items():
        place = f"constants.{name}"
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name) or name in ex.FUNCTIONS:
            raise UserError("a constant's name must be an identifier (letters, digits, _) other than a function name (sqrt, root)", place)
        text, _ = _entry_text(value, place)
        try:
            defs[name] = ex.parse(text)
        except UserError as err:
            raise err.located(place) from None
    return defs


def _constants(table: dict[str, Any]) -> Constants:
    constants = Constants(_constant_definitions(table))
    constants.exact_values()  # report a broken constant at its own place, used or not
    return constants


def build_tableau(
    data: dict[str, Any],
    source: str,
    max_stages: int = DEFAULT_MAX_STAGES,
) -> "Tableau | Family":
    """Validate a parsed document and build the tableau (errors carry the source)."""
    try:
        return _build(data, source, max_stages)
    except UserError as err:
        raise err.as_tableau_error().located(source=source) from None


def _build(
    data: dict[str, Any],
    source: str,
    max_stages: int,
) -> "Tableau | Family":
    if is_rkcheck_report(data):
        raise UserError("this is a JSON report of rkcheck (`--format json`), not a tableau file; "
                        "`rkcheck show FILE --format tableau-json` (or `toml`) writes one that reads back")
    data, warnings = _tables(data)
    name, info = _method_info(data, source)

    given = [key for key in _METHOD_TABLES if key in data]
    if len(given) > 1:  # each defines the whole method: which one was meant is not for us to guess
        raise UserError(f"give one of [{'], ['.join(_METHOD_TABLES)}], not {' and '.join(f'[{k}]' for k in given)}")
    if "family" in data and "parameters" in data:
        raise UserError("a named [family] is one method: it takes no free [parameters] (give those with a "
                        "[tableau] or [continuous] table)")
    if "family" in data:
        from rkcheck.methods.families import build_family  # when needed: start-up time

        # a name of its own, else the family's title (not the file's stem)
        own = name if name != Path(source).stem else None
        return build_family(_table(data, "family"), own, info.replace(warnings=tuple(warnings)))

    if "continuous" in data:  # a continuous-stage method (or a family of kernels)
        from rkcheck.io.continuous import from_document

        raw = _table(data, "constants")
        if "parameters" in data:  # constants may use the parameters: resolved by the family
            return from_document(data, name, info, warnings, _table(data, "parameters"), raw,
                                 _constant_definitions(raw))
        return from_document(data, name, info.replace(constants=_constants(raw)), warnings)
    if "tableau" not in data:
        raise UserError(f"missing [tableau] table (or [family]); the smallest tableau file is {SMALLEST_FILE}")
    tab = _table(data, "tableau", required=True)
    warnings += ignored_keys(tab, ("A", "b", "c"), "tableau")
    if "parameters" in data:
        return _build_family(data, tab, name, info.replace(warnings=tuple(warnings)), max_stages)
    constants = _constants(_table(data, "constants"))
    A, b, c = _entries(tab, constants, max_stages)
    warnings += _bare_floats((*(x for row in A for x in row), *b, *(c or ())))
    return Tableau(A=A, b=b, c=c, name=name, info=info.replace(constants=constants, warnings=tuple(warnings)))


def _tables(data: dict[str, Any]) -> tuple[dict[str, Any], list[str]]:
    """The document with its short form (A/b/c at the top level) read as its [tableau]
    table, and a warning per unknown table or top-level key."""
    def unknown(key: Any) -> str:
        what = f"table [{printable(key)}]" if isinstance(data[key], dict) else f"key {printable(key)}"
        return f"unknown {what} ignored (known tables: {', '.join(KNOWN_TABLES)})"

    given = [k for k in SHORT_FORM_KEYS if k in data]  # the short form's, never unknown
    warnings = [unknown(key) for key in data if key not in KNOWN_TABLES and key not in given]
    if "tableau" not in data and "family" not in data and given:
        data = {k: v for k, v in data.items() if k not in SHORT_FORM_KEYS} | {
            "tableau": {k: data[k] for k in SHORT_FORM_KEYS if k in data}}
    elif given:  # A, b or c beside a table that defines the method: not tables of their own
        where = next((f"[{k}]" for k in _METHOD_TABLES if k in data), "the file's method")
        warnings.append(f"{', '.join(given)} at the top level ignored: the method is given by {where}")
    return data, warnings


def _method_info(data: dict[str, Any], source: str) -> tuple[str, MethodInfo]:
    """The method's name (the file's stem unless given) and what the file says about it:
    description, references, [check] options and [expect] claims."""
    method = _table(data, "method")
    name = method.get("name", Path(source).stem if source != "-" else "stdin")
    if not isinstance(name, str):
        raise UserError("expected a string", "method.name")
    description = method.get("description", "")
    if not isinstance(description, str):
        raise UserError("expected a string", "method.description")
    references = tuple(parse_strings(method["references"], "method.references")) if "references" in method else ()
    # shown on terminals: no control characters or lone surrogates from the file
    name, description = printable(name), printable(description)
    references = tuple(printable(r) for r in references)
    check = validate_check_table(_table(data, "check"))
    expect = _table(data, "expect")
    claims = parse_claims(expect)
    return name, MethodInfo(description=description, references=references, source=source, check=check,
                            expect=expect, claims=tuple(claims))


def _bare_floats(entries) -> list[str]:
    """A warning when entries are bare TOML/JSON floats, which other tools read as doubles."""
    return bare_floats_warning([e.text for e in entries if e.bare_number])


def _build_family(data: dict[str, Any], tab: dict[str, Any], name: str, info: MethodInfo,
                  max_stages: int) -> "Family":
    """A tableau with free parameters (:mod:`rkcheck.methods.parametric`)."""
    from rkcheck.methods.parametric import build_family, parse_parameters

    raw_constants = _table(data, "constants")
    parameters = parse_parameters(_table(data, "parameters"), raw_constants)
    # constants may use the parameters: parsed here, resolved with them by the family
    constants = _constant_definitions(raw_constants)
    if "c" in tab:
        info = info.replace(warnings=info.warnings + ("tableau.c ignored: a family's nodes are its row sums",))
    A, b = _entry_texts(tab, max_stages)
    written = [x for row in tab["A"] for x in row] + list(tab["b"])
    info = info.replace(warnings=info.warnings + tuple(bare_floats_warning([x for x in written if isinstance(x, BareFloat)])))
    return build_family(name, parameters, A, b, constants, info)


def _entry_texts(tab: dict[str, Any], max_stages: int) -> tuple[list[list[str]], list[str]]:
    """A and b of a ``[tableau]`` table as texts, shape validated."""
    if "A" not in tab:
        raise UserError("missing A", "tableau")
    if "b" not in tab:
        raise UserError("missing b", "tableau")
    rows = tab["A"]
    if not isinstance(rows, list) or not rows:
        raise UserError("expected a non-empty list of rows", "A")
    s = len(rows)
    if s > max_stages:
        raise UserError(f"{s} stages exceeds the limit of {max_stages} (raise it with --max-stages, or max_stages= in Python)", "A")
    A = []
    for i, row in enumerate(rows, start=1):
        if not isinstance(row, list) or len(row) != s:
            raise UserError(f"expected a row of {s} entries (A must be square)", f"A[{i}]")
        A.append([_entry_text(x, f"A[{i}][{j}]")[0] for j, x in enumerate(row, start=1)])
    if not isinstance(tab["b"], list) or len(tab["b"]) != s:
        raise UserError(f"expected a list of {s} entries (one per stage)", "b")
    return A, [_entry_text(x, f"b[{i}]")[0] for i, x in enumerate(tab["b"], start=1)]


def _entries(tab: dict[str, Any], constants: Constants, max_stages: int):
    """A, b and c of a ``[tableau]`` table, validated (square A, one b and c per stage)."""
    if "A" not in tab:
        raise UserError("missing A", "tableau")
    if "b" not in tab:
        raise UserError("missing b", "tableau")
    rows = tab["A"]
    if not isinstance(rows, list):
        raise UserError(f"expected a list of rows, got {_kind(rows)}", "A")
    s = len(rows)
    if s == 0:
        raise UserError("the tableau is empty (A has no rows)", "A")
    if s > max_stages:
        raise UserError(f"{s} stages exceeds the limit of {max_stages} (raise it with --max-stages, or max_stages= in Python)", "A")
    if all(isinstance(row, list) and not row for row in rows):
        raise UserError("the tableau is empty (A's rows have no entries)", "A")
    for i, row in enumerate(rows, start=1):
        if not isinstance(row, list):
            raise UserError(f"expected a row (a list), got {_kind(row)}", f"A[{i}]")
        if len(row) != s:
            raise UserError(f"row has {len(row)} entries, expected {s} (A must be square)", f"A[{i}]")
    memo: dict[tuple[str, bool], Entry] = {}
    A = tuple(
        tuple(_parse_entry(x, f"A[{i}][{j}]", constants, memo) for j, x in enumerate(row, start=1))
        for i, row in enumerate(rows, start=1)
    )
    b = _vector(tab["b"], "b", s, constants, memo)
    c = _vector(tab["c"], "c", s, constants, memo) if "c" in tab else None
    return A, b, c


def read_document(text: str, source: str, fmt: str, max_stages: int = DEFAULT_MAX_STAGES) -> dict[str, Any]:
    """The document of a tableau text in any input format: TOML and JSON parsed, a CSV
    or nodepy text read into the same tables; errors name ``source``."""
    try:
        if fmt in ("csv", "nodepy"):
            from rkcheck.io.delimited import parse_delimited
            from rkcheck.io.nodepy_text import parse_nodepy_text

            stem = Path(source).stem if source not in ("-", "<string>") else "stdin"
            return parse_delimited(text, stem) if fmt == "csv" else parse_nodepy_text(text, stem, max_stages)
        return parse_document(text, fmt)
    except UserError as err:
        raise err.located(source=source) from None


def _within_file_limit(text: str, source: str) -> None:
    """A text is held to the limit of a file (its UTF-8 bytes, counted only where they
    could exceed it)."""
    from rkcheck.io.bounded import max_file_bytes

    limit = max_file_bytes()
    size = len(text) if len(text) > limit or 4 * len(text) <= limit else len(text.encode("utf-8", "surrogatepass"))
    if size > limit:
        raise UserError(f"text too large ({count_text(size)} bytes; the limit MAX_FILE_BYTES is {count_text(limit)}; "
                        "set RKCHECK_MAX_FILE_BYTES to change it)", source=source)


def loads(
    text: str,
    source: str = "<string>",
    fmt: str | None = None,
    max_stages: int = DEFAULT_MAX_STAGES,
) -> Tableau:
    """Parse tableau text (``fmt``: one of :data:`INPUT_FORMATS`, default by the source's
    suffix and the content)."""
    parse_int_in(max_stages, MAX_STAGES_RANGE, "max_stages")
    _within_file_limit(text, source)
    text = text.removeprefix("\ufeff")  # a byte order mark, as spreadsheets and editors write it
    fmt = fmt or detect_format(source, text)
    if fmt not in INPUT_FORMATS:
        raise UserError(f"unknown input format {fmt!r} (known: {', '.join(INPUT_FORMATS)})", source=source)
    tableau = build_tableau(read_document(text, source, fmt, max_stages), source, max_stages)
    if getattr(tableau, "is_continuous", False):  # a ContinuousMethod: verify takes it like a tableau
        method: Any = tableau
        return method.replace(info=method.info.replace(lines=locate_lines(text, fmt)))
    if not isinstance(tableau, Tableau):
        raise UserError("this file has free [parameters]: it is a family, not one tableau; check it with "
                        "`rkcheck verify FILE` on the file itself (standard input and pipes are read once, as one "
                        "tableau), `rkcheck conditions FILE` or `rkcheck solve` (Python: rkcheck.load_family)",
                        source=source)
    return tableau.replace(info=tableau.info.replace(lines=locate_lines(text, fmt)))


def load_family(path: str, max_stages: int = DEFAULT_MAX_STAGES) -> "Family":
    """A family file (with ``[parameters]``): a :class:`~rkcheck.methods.parametric.Family`."""
    from rkcheck.methods.parametric import Family

    if path.startswith("@"):
        from rkcheck.io import library

        entry = library.find(path[1:])
        if entry is None:
            raise UserError(f"no family called {path} in the library", source=path)
        text, source = entry.read_text(), f"@{entry.key}"
    else:
        text, source = read_text(path), path
    try:
        data = parse_document(text, detect_format(source, text))
    except UserError as err:
        raise err.located(source=source) from None
    if "parameters" not in data:
        raise UserError("not a family: the file has no [parameters] table", source=source)
    family = build_tableau(data, source, max_stages)
    assert isinstance(family, Family)
    return family


def _is_pipe(path: str) -> bool:
    import stat

    try:
        return not path.startswith("@") and stat.S_ISFIFO(Path(path).stat().st_mode)
    except OSError:
        return False


def is_family_file(path: str) -> bool:
    """Whether a file (or ``@name``) declares free parameters; False when unreadable (the
    caller's own load reports why) and for standard input and named pipes (bash's
    ``<(…)``): those can be read once only, as a tableau."""
    if path == "-" or _is_pipe(path):
        return False
    try:
        if path.startswith("@"):
            from rkcheck.io import library

            entry = library.find(path[1:])
            text, source = (entry.read_text(), entry.key) if entry is not None else ("", path)
        else:
            text, source = read_text(path), path
        data = parse_document(text, detect_format(source, text)) if text else {}
    except (UserError, OSError):
        return False
    return isinstance(data, dict) and "parameters" in data


def load(
    path: str,
    max_stages: int = DEFAULT_MAX_STAGES,
    fmt: str | None = None,
) -> Tableau:
    """Load a tableau file; ``-`` reads standard input; ``@name`` a shipped tableau or a
    classical method (:func:`load_named`)."""
    if path.startswith("@"):
        return load_named(path[1:], max_stages)
    text = read_text(path)
    return loads(text, source=path, fmt=fmt, max_stages=max_stages)


def load_named(name: str, max_stages: int = DEFAULT_MAX_STAGES) -> Tableau:
    """``@name``: the shipped tableau of that name (:mod:`rkcheck.io.library`), else the
    classical method (:mod:`rkcheck.methods.classics`), else an
    :class:`~rkcheck.errors.UnknownMethodError` with the nearest names."""
    from rkcheck.errors import UnknownMethodError
    from rkcheck.io import library
    from rkcheck.methods.classics import NAMES, classic_tableau

    entry = library.find(name)
    if entry is not None:
        return loads(entry.read_text(), source=f"@{entry.key}", fmt=entry.resource.name.rsplit(".", 1)[-1],
                     max_stages=max_stages)
    if name.strip().lower() in NAMES:
        return classic_tableau(name)
    near = library.suggestions(name, list(NAMES))
    hint = f"; did you mean {', '.join('@' + n for n in near)}?" if near else ""
    raise UnknownMethodError(f"no tableau called @{name} in the library{hint}")
