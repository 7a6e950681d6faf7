"""Project configuration: ``[tool.rkcheck]`` in the nearest ``pyproject.toml``.

Found by walking up from the current directory.  Keys: ``paths`` and ``exclude`` (for
``scan``), ``degree``, ``order``, ``dps``, ``decimals``, ``format``, ``fail_on``, ``jobs``.
Precedence, most specific first: command-line flags, then the file's own ``[check]``
table, then ``[tool.rkcheck]``, then rkcheck's defaults.  Relative ``paths`` are
relative to the directory of that ``pyproject.toml``.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rkcheck.errors import UserError

KEYS = ("paths", "exclude", "degree", "order", "dps", "decimals", "format", "fail_on", "jobs")
FORMATS = ("text", "json", "csv", "junit", "github")


@dataclass
class Config:
    source: str | None = None  # the pyproject.toml it came from
    root: Path | None = None
    paths: list[str] = field(default_factory=list)
    exclude: list[str] = field(default_factory=list)
    check: dict[str, Any] = field(default_factory=dict)  # degree / order / dps / decimals
    format: str | None = None
    fail_on: str | None = None
    jobs: int | None = None


def find_pyproject(start: Path | None = None) -> Path | None:
    here = (start or Path.cwd()).resolve()
    for d in [here, *here.parents]:
        candidate = d / "pyproject.toml"
        if candidate.is_file():
            return candidate
    return None


def _strings(value: Any, place: str) -> list[str]:
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(x, str) for x in value):
        return list(value)
    raise UserError("expected a string or a list of strings", place)


def load_config(start: Path | None = None) -> Config:
    """The ``[tool.rkcheck]`` table of the nearest ``pyproject.toml`` (empty if none)."""
    path = find_pyproject(start)
    if path is None:
        return Config()
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as err:
        raise UserError(f"cannot read [tool.rkcheck]: {err}", source=str(path)) from None
    table = data.get("tool", {}).get("rkcheck")
    if table is None:
        return Config()
    src = str(path)
    if not isinstance(table, dict):
        raise UserError("[tool.rkcheck] must be a table", source=src)
    cfg = Config(source=src, root=path.parent)
    for key, value in table.items():
        place = f"tool.rkcheck.{key}"
        key_n = key.replace("-", "_")
        if key_n not in KEYS:
            raise UserError(f"unknown key (known: {', '.join(KEYS)})", place, src)
        if key_n == "paths":
            cfg.paths = [str((path.parent / p)) for p in _strings(value, place)]
        elif key_n == "exclude":
            cfg.exclude = _strings(value, place)
        elif key_n == "degree":
            if value in ("none", "all"):
                cfg.check["degree"] = None
            elif isinstance(value, int) and not isinstance(value, bool) and value >= 1:
                cfg.check["degree"] = value
            else:
                raise UserError(f"expected a positive integer or 'none', got {value!r}", place, src)
        elif key_n in ("order", "dps", "jobs"):
            if not (isinstance(value, int) and not isinstance(value, bool) and value >= 1):
                raise UserError(f"expected a positive integer, got {value!r}", place, src)
            if key_n == "jobs":
                cfg.jobs = value
            else:
                cfg.check[key_n] = value
        elif key_n == "decimals":
            if value not in ("rounded", "exact"):
                raise UserError(f"expected 'rounded' or 'exact', got {value!r}", place, src)
            cfg.check["decimals"] = value
        elif key_n == "format":
            if value not in FORMATS:
                raise UserError(f"expected one of {', '.join(FORMATS)}, got {value!r}", place, src)
            cfg.format = value
        elif key_n == "fail_on":
            if value not in ("auto", "conditions", "claims", "never"):
                raise UserError(f"expected auto, conditions, claims or never, got {value!r}", place, src)
            cfg.fail_on = value
    return cfg
