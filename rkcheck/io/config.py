"""Project configuration: ``[tool.rkcheck]`` in the nearest ``pyproject.toml``.

Found by walking up from the current directory.  Keys: ``paths`` and ``exclude`` (for
``scan``), ``degree``, ``order``, ``dps``, ``decimals``, ``format``, ``fail_on``, ``jobs``,
``allow_empty``, ``scheduler`` (a Dask scheduler address for ``scan``).
Precedence, most specific first: command-line flags, then the file's own ``[check]``
table, then ``[tool.rkcheck]``, then rkcheck's defaults.  Relative ``paths`` are
relative to the directory of that ``pyproject.toml``.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rkcheck.errors import UserError
from rkcheck.io.bounded import bounded_read, max_file_bytes
from rkcheck.io.printable import printable
from rkcheck.options import (
    FAIL_ON,
    JOBS_RANGE,
    SCAN_FORMATS,
    parse_choice,
    parse_int_in,
    parse_strings,
    validate_check_table,
)

#: Keys of [tool.rkcheck] beyond the check options of :data:`rkcheck.options.CHECK_KEYS`.
EXTRA_KEYS = ("paths", "exclude", "format", "fail_on", "jobs", "allow_empty", "scheduler")


@dataclass
class Config:
    """The ``[tool.rkcheck]`` table of a pyproject.toml (defaults when there is none)."""

    source: str | None = None  # the pyproject.toml it came from
    root: Path | None = None
    paths: list[str] = field(default_factory=list)
    exclude: list[str] = field(default_factory=list)
    check: dict[str, Any] = field(default_factory=dict)  # degree / order / dps / decimals
    format: str | None = None
    fail_on: str | None = None
    jobs: int | None = None
    allow_empty: bool = False  # a scan that finds no file passes instead of exit 2
    scheduler: str | None = None  # a Dask scheduler for scan (tcp://host:8786)


def find_pyproject(start: Path | None = None) -> Path | None:
    here = (start or Path.cwd()).resolve()
    for d in [here, *here.parents]:
        candidate = d / "pyproject.toml"
        if candidate.is_file():
            return candidate
    return None


def load_config(start: Path | None = None) -> Config:
    """The ``[tool.rkcheck]`` table of the nearest ``pyproject.toml`` (empty if none)."""
    path = find_pyproject(start)
    if path is None:
        return Config()
    try:
        with open(path, "rb") as fh:  # bounded: pyproject.toml may be a link to a device
            data = tomllib.loads(bounded_read(fh, max_file_bytes(), str(path)).decode("utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError, ValueError) as err:
        raise UserError(f"cannot read [tool.rkcheck]: {printable(str(err))}", source=str(path)) from None
    except RecursionError:
        raise UserError("cannot read [tool.rkcheck]: nesting too deep", source=str(path)) from None
    src = str(path)
    tool = data.get("tool", {})
    if not isinstance(tool, dict):  # `tool = "x"`: not ours to judge, but not a crash either
        raise UserError("[tool] must be a table", "tool", src)
    table = tool.get("rkcheck")
    if table is None:
        return Config()
    if not isinstance(table, dict):
        raise UserError("[tool.rkcheck] must be a table", source=src)
    cfg = Config(source=src, root=path.parent)
    cfg.check = validate_check_table(table, "tool.rkcheck", src, extra_keys=EXTRA_KEYS)
    for key, value in table.items():
        place = f"tool.rkcheck.{key}"
        key_n = key.replace("-", "_")
        if key_n == "paths":
            given = parse_strings(value, place, src)
            if "" in given:  # the project's folder otherwise, as `scan ''` would be the current one
                raise UserError("an empty path: give a file or folder (. for the project's folder)", place, src)
            cfg.paths = [_shown_path(path.parent / p) for p in given]
        elif key_n == "exclude":
            cfg.exclude = parse_strings(value, place, src)
        elif key_n == "jobs":
            cfg.jobs = parse_int_in(value, JOBS_RANGE, place, src)
        elif key_n == "format":
            cfg.format = parse_choice(value, SCAN_FORMATS, place, src)
        elif key_n == "fail_on":
            cfg.fail_on = parse_choice(value, FAIL_ON, place, src)
        elif key_n == "allow_empty":
            if not isinstance(value, bool):
                raise UserError(f"expected true or false, got {value!r}"[:80], place, src)
            cfg.allow_empty = value
        elif key_n == "scheduler":
            if not isinstance(value, str) or not 0 < len(value.strip()) <= 1000:
                raise UserError(f"expected a scheduler address such as 'tcp://host:8786', got {value!r}"[:120], place, src)
            cfg.scheduler = value.strip()
    return cfg


def _shown_path(p: Path) -> str:
    """A configured path as a scan names its files: relative to the current folder when
    it lies under it (as ``rkcheck scan tabs`` names them), so that reports and JUnit names
    do not depend on where the project is checked out; absolute otherwise."""
    rel = os.path.relpath(p)
    return str(p) if rel == os.pardir or rel.startswith(os.pardir + os.sep) else rel
