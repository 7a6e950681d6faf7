"""Finding tableau files: recursive, deterministic, with exclusions (``scan``, ``catalog``)."""

from __future__ import annotations

import fnmatch
import os
from pathlib import Path
from typing import Any

from rkcheck.errors import UserError

SUFFIXES = (".toml", ".json")


def _excluded(path: Path, patterns: list[str], root: Path | None = None) -> bool:
    """Whether a pattern matches the path as given, the file's name, or — under a folder
    scanned — the path within that folder (``drafts/*`` excludes ``tableaux/drafts/x.toml``
    of a scan of ``tableaux``)."""
    texts = [path.as_posix(), path.name] + ([path.relative_to(root).as_posix()] if root is not None else [])
    return any(fnmatch.fnmatch(text, p) for p in patterns for text in texts)


def _unreadable_folders(root: Path) -> list[Path]:
    """Folders under ``root`` (itself included) that cannot be listed: ``rglob`` skips
    them silently, so a scan of an unreadable folder would report 0 files."""
    bad: list[Path] = []
    for _ in os.walk(root, onerror=lambda err: bad.append(Path(err.filename))):
        pass
    return sorted(bad)


def find_tableau_files(paths: list[str], exclude: list[str] | None = None) -> list[str]:
    """Every ``*.toml``/``*.json`` under ``paths`` (files given explicitly are kept whatever
    their suffix; ``@name`` stands for a shipped tableau or classical method), sorted,
    without duplicates, minus the ``exclude`` glob patterns (matched against the path, the
    file name, and the path within a folder scanned)."""
    exclude = list(exclude or [])
    found: list[Path] = []
    for raw in paths:
        p = Path(raw)
        if p.is_dir():
            unreadable = _unreadable_folders(p)
            if p in unreadable:
                raise UserError("cannot read this folder (permission denied)", source=raw)
            found.extend(unreadable)  # each becomes an error row of the scan, not 0 files
            for f in sorted(p.rglob("*")):
                # a dangling link, a link loop, a named pipe or a device is kept: it becomes
                # an error row, not a silently missing file; a link to a folder is not
                # followed (is_dir follows it: it is left out, as a folder is)
                if not f.is_dir() and f.suffix.lower() in SUFFIXES and not _excluded(f, exclude, p):
                    if not any(part.startswith(".") for part in f.relative_to(p).parts):
                        found.append(f)
        elif raw.startswith("@"):  # a shipped tableau or classical method by name
            from rkcheck.io.loader import load_named

            load_named(raw[1:])  # an unknown name is refused here, with the nearest names
            found.append(p)
        elif p.exists() or raw == "-":
            if not _excluded(p, exclude):
                found.append(p)
        else:
            raise UserError("no such file or directory", source=raw)
    seen: set[Any] = set()
    out = []
    for f in found:  # one file however it was spelt (a.toml, ../p/a.toml, /abs/a.toml, a link): checked once
        key = _identity(f)
        if key not in seen:
            seen.add(key)
            out.append(f.as_posix())
    return out


def _identity(f: Path) -> Any:
    """The file itself: its device and inode (links, hard ones too, and other spellings
    are one), else its resolved path; ``-`` and ``@name`` as written."""
    name = f.as_posix()
    if name == "-" or name.startswith("@"):
        return name
    try:
        st = os.stat(f)
        return (st.st_dev, st.st_ino)
    except OSError:  # a dangling link, an unreadable entry: by its path (it becomes an error row)
        return os.path.realpath(f)
