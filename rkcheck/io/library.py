"""The curated tableaux, addressable by name anywhere: ``@gauss-3``, ``@rk4``.

The files live in the repository's ``tableaux/`` folder (the one source of truth that
``rkcheck catalog`` documents).  A built wheel carries a copy as package data in
``rkcheck/library/`` (``setup.py`` copies it at build time), read through
:mod:`importlib.resources`, so ``rkcheck verify @gauss-3`` works after
``pip install rkcheck``; in a clone or an editable install the ``tableaux/`` folder next
to the package is used directly.

Names are matched without regard to case, ``-``, ``_``, spaces or dots, so ``@gauss3``,
``@Gauss-3`` and ``@collocation/gauss-3`` all name ``collocation/gauss-3.toml``.  A name
the files do not have but :mod:`rkcheck.methods.classics` does (``@sdirk2``) is built
from the classics table.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass
from importlib import resources
from importlib.resources.abc import Traversable
from pathlib import Path

from rkcheck.errors import UnknownMethodError

SUFFIXES = (".toml", ".json")


@dataclass(frozen=True)
class LibraryEntry:
    """One shipped tableau: ``key`` is its path below the library root without suffix
    (``collocation/gauss-3``); ``resource`` reads it wherever it is installed."""

    key: str
    resource: Traversable

    @property
    def name(self) -> str:
        return self.key.rsplit("/", 1)[-1]

    def read_text(self) -> str:
        return self.resource.read_text(encoding="utf-8")


def normalise(name: str) -> str:
    """The form names are compared in: lower case, no ``-``, ``_``, spaces or dots."""
    return re.sub(r"[-_\s.]", "", name.lower())


def library_root() -> Traversable | None:
    """Where the shipped tableaux are: package data of a wheel, else the clone's folder."""
    packaged = resources.files("rkcheck") / "library"
    if packaged.is_dir():
        return packaged
    clone = Path(__file__).resolve().parents[2] / "tableaux"
    return clone if clone.is_dir() else None


def _walk(node: Traversable, prefix: str) -> list[LibraryEntry]:
    out: list[LibraryEntry] = []
    for child in sorted(node.iterdir(), key=lambda t: t.name):
        if child.name.startswith("."):
            continue
        if child.is_dir():
            out.extend(_walk(child, f"{prefix}{child.name}/"))
        elif any(child.name.endswith(s) for s in SUFFIXES) and not child.name.startswith("README"):
            stem = child.name.rsplit(".", 1)[0]
            out.append(LibraryEntry(prefix + stem, child))
    return out


def entries() -> list[LibraryEntry]:
    """Every shipped tableau, sorted by key (empty when nothing is installed)."""
    root = library_root()
    return _walk(root, "") if root is not None else []


def find(name: str) -> LibraryEntry | None:
    """The shipped tableau called ``name`` (``gauss3``, ``collocation/gauss-3``), or None.

    Raises :class:`~rkcheck.errors.UnknownMethodError` when the name is ambiguous."""
    wanted = normalise(name)
    everything = entries()
    full = [e for e in everything if normalise(e.key) == wanted]
    if full:
        return full[0]
    short = [e for e in everything if normalise(e.name) == wanted]
    if len(short) > 1:
        keys = ", ".join("@" + e.key for e in short)
        raise UnknownMethodError(f"@{name} is ambiguous: {keys}")
    return short[0] if short else None


#: At most this many names start with what was asked for in a suggestion (``@gauss``:
#: every ``gauss-s``); misspellings add up to three close names.
MAX_PREFIX_SUGGESTIONS = 6


def _natural(name: str) -> list:
    """Sort key: ``gauss-2`` before ``gauss-10``."""
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", name)]


def suggestions(name: str, extra: list[str] | None = None) -> list[str]:
    """Known names for the error message: those that start with ``name`` (``@gauss``
    gives ``gauss-2`` … ``gauss-5``, in natural order), then up to three close to it (a
    misspelling)."""
    names = sorted({e.name for e in entries()} | set(extra or []))
    by_norm = {normalise(n): n for n in names}
    wanted = normalise(name)
    prefix = sorted((n for k, n in by_norm.items() if wanted and k.startswith(wanted) and k != wanted), key=_natural)
    close = [by_norm[c] for c in difflib.get_close_matches(wanted, list(by_norm), n=3, cutoff=0.6)]
    return prefix[:MAX_PREFIX_SUGGESTIONS] + [n for n in close if n not in prefix][:max(0, 3 - len(prefix))]
