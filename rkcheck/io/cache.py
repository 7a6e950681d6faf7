"""The listing cache: condition listings kept on disk between runs, per (order, degree).

A listing is pure combinatorics (it does not depend on the tableau), costs seconds to
build at order 18 and loads in a fraction of that.  Each order is one file in the user
cache directory (:func:`cache_dir`):

* **never trusted**: a file is a magic line, a JSON header (format, the parameters it
  was built for, every array's dtype and length, a SHA-256 of header and content) and
  the raw arrays; anything that does not match exactly — truncated, corrupt, another
  format, other parameters — is ignored (and rebuilt by the caller).  No pickle: the
  arrays are read as plain little-endian integers;
* **safe under concurrent runs**: a file is written to a temporary name in the same
  directory and renamed into place (``os.replace``), so a reader sees the old file,
  the new one or none, never a part;
* **bounded**: after each save the oldest files (least recently used: a load touches
  the file) are removed until the directory holds at most :data:`MAX_CACHE_BYTES`
  (``RKCHECK_MAX_CACHE_BYTES``).

Saving is best effort: a read-only or full disk only means no cache.
"""

from __future__ import annotations

import os
import re
import stat
import sys
from dataclasses import dataclass
from io import BufferedReader
from pathlib import Path
from typing import Any

import numpy as np

from rkcheck.errors import UserError
from rkcheck.io.printable import printable
from rkcheck.numbers.formatting import human_bytes

#: the default bound on the cache directory's listing files (RKCHECK_MAX_CACHE_BYTES)
MAX_CACHE_BYTES = 2 * 1024**3
#: orders with fewer terms are built, not cached: they take milliseconds (order 12 and
#: below for all H), less than reading a file
MIN_CACHED_TERMS = 20_000

MAGIC = b"RKCHECK-LISTING\n"
_SUFFIX = ".rkl"
_TEMP_PREFIX = ".tmp-"
#: the names tempfile.mkstemp gives a file being saved (another program's are not ours)
_TEMP_NAME = re.compile(r"\.tmp-[a-z0-9_]{8}\.rkl")
#: the names :func:`_name` gives (the key's kind, format, vertices and degree)
_LISTING_NAME = re.compile(r"[a-z]+(?:-[a-z]+)*-f\d+-n\d+-m(?:none|\d+)\.rkl")
_MAX_HEADER = 1 << 20  # the header is a few kB (the coefficients of one order)
_ALIGN = 8
_DTYPES = {"int8", "int16", "int32", "int64"}


def cache_dir() -> Path:
    """Where listings are kept: ``RKCHECK_CACHE_DIR`` when set, else the platform's user
    cache directory (the platformdirs convention): ``$XDG_CACHE_HOME/rkcheck`` or
    ``~/.cache/rkcheck`` on Linux and other Unixes, ``~/Library/Caches/rkcheck`` on macOS,
    ``%LOCALAPPDATA%\\rkcheck\\Cache`` on Windows."""
    explicit = os.environ.get("RKCHECK_CACHE_DIR", "").strip()
    try:
        if explicit:
            return Path(explicit).expanduser()
        return _platform_cache_dir()
    except RuntimeError:  # pathlib's "Could not determine home directory": ~user of no user, no HOME
        where = f"RKCHECK_CACHE_DIR: cannot expand {printable(explicit[:80])!r}" if explicit else \
            "the listing cache: cannot find the home directory"
        raise UserError(f"{where}; set RKCHECK_CACHE_DIR to a directory, or run with --no-cache") from None


def _platform_cache_dir() -> Path:
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA", "").strip()
        return Path(base or Path.home() / "AppData" / "Local") / "rkcheck" / "Cache"
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "rkcheck"
    xdg = os.environ.get("XDG_CACHE_HOME", "").strip()
    # the XDG spec: a relative path is invalid and must be ignored
    return (Path(xdg) if xdg and os.path.isabs(xdg) else Path.home() / ".cache") / "rkcheck"


def cache_disabled() -> bool:
    """``RKCHECK_NO_CACHE`` set to anything but a false value (``""``, ``0``, ``false``,
    ``no``, ``off``, in any case): no listing is read or saved."""
    return os.environ.get("RKCHECK_NO_CACHE", "").strip().lower() not in ("", "0", "false", "no", "off")


def max_cache_bytes() -> int:
    """:data:`MAX_CACHE_BYTES`, or the environment's ``RKCHECK_MAX_CACHE_BYTES`` (a
    non-negative number of bytes; 0 keeps nothing)."""
    raw = os.environ.get("RKCHECK_MAX_CACHE_BYTES", "").strip().replace("_", "")
    if not raw:
        return MAX_CACHE_BYTES
    if not (raw.isascii() and raw.isdigit()) or len(raw) > 20:
        raise UserError("RKCHECK_MAX_CACHE_BYTES: expected a non-negative number of bytes of at most 20 digits, "
                        f"got {printable(raw[:40])!r}")
    return int(raw)


def _name(key: dict[str, Any]) -> str:
    """The file of a record: readable, and distinct per key (the header repeats the key,
    so that a renamed file is still recognised as foreign)."""
    degree = "none" if key.get("degree") is None else key["degree"]
    return f"{key['kind']}-f{key['format']}-n{key['vertices']}-m{degree}{_SUFFIX}"


def _canonical(header: dict[str, Any]) -> bytes:
    import json  # only when a listing is large enough to be cached: not at start-up

    return json.dumps(header, sort_keys=True, separators=(",", ":")).encode()


def encode(key: dict[str, Any], arrays: dict[str, np.ndarray], meta: dict[str, Any]) -> list[bytes | memoryview]:
    """The file's bytes, in pieces (the arrays are not copied)."""
    layout = []
    payload: list[bytes | memoryview] = []
    for name, a in arrays.items():
        a = np.ascontiguousarray(a, dtype=a.dtype.newbyteorder("<"))
        if a.dtype.name not in _DTYPES or a.ndim != 1:
            raise ValueError(f"{name}: only one-dimensional integer arrays are stored")
        layout.append([name, a.dtype.name, len(a)])
        payload.append(a.view(np.uint8).data)
        pad = -a.nbytes % _ALIGN
        if pad:
            payload.append(b"\0" * pad)
    header = {"key": key, "meta": meta, "arrays": layout}
    import hashlib

    digest = hashlib.sha256(_canonical(header))
    for piece in payload:
        digest.update(piece)
    header["sha256"] = digest.hexdigest()
    head = _canonical(header)
    return [MAGIC, len(head).to_bytes(8, "little"), head, *payload]


def decode(f: BufferedReader, size: int, key: dict[str, Any],
           into: dict[str, np.ndarray] | None = None) -> tuple[dict[str, np.ndarray], dict[str, Any]] | None:
    """The arrays and metadata of an open file of ``size`` bytes, or None unless it is
    intact and was written for exactly ``key``.  Each array is read into an array of its
    own (a file's bytes are never held whole), or into ``into[name]`` when that is a
    contiguous array of the file's type and length (the listing's own factors: then
    they are not copied there afterwards); that array is then the one returned, and
    holds unspecified values when None is returned."""
    import hashlib
    import json

    start = len(MAGIC) + 8
    lead = f.read(start)
    if len(lead) != start or lead[:len(MAGIC)] != MAGIC:
        return None
    head_size = int.from_bytes(lead[len(MAGIC):], "little")
    if head_size > _MAX_HEADER or start + head_size > size:
        return None
    try:
        header = json.loads(f.read(head_size))
    except (ValueError, UnicodeDecodeError, RecursionError):
        return None
    if (not isinstance(header, dict) or set(header) != {"key", "meta", "arrays", "sha256"}
            or header["key"] != key or not isinstance(header["meta"], dict)
            or not isinstance(header["arrays"], list)):
        return None
    claimed = header.pop("sha256")
    digest = hashlib.sha256(_canonical(header))
    arrays: dict[str, np.ndarray] = {}
    left = size - start - head_size
    for entry in header["arrays"]:
        if (not isinstance(entry, list) or len(entry) != 3 or not isinstance(entry[0], str)
                or entry[1] not in _DTYPES or type(entry[2]) is not int or entry[2] < 0 or entry[0] in arrays):
            return None
        dtype = np.dtype(entry[1]).newbyteorder("<")
        nbytes = entry[2] * dtype.itemsize
        padded = nbytes + (-nbytes % _ALIGN)
        if padded > left:
            return None
        a = _destination(into, entry[0], dtype, entry[2])
        view = a.view(np.uint8).data
        pad = bytearray(padded - nbytes)
        if f.readinto(view) != nbytes or f.readinto(pad) != len(pad):
            return None
        digest.update(view)
        digest.update(pad)
        if a.dtype != dtype:  # a native big-endian destination: its little-endian bytes turned
            a.byteswap(inplace=True)
        arrays[entry[0]] = a if a.dtype == dtype.newbyteorder("=") else a.astype(dtype.newbyteorder("="))
        left -= padded
    if left != 0 or not isinstance(claimed, str) or digest.hexdigest() != claimed:
        return None
    return arrays, header["meta"]


def _destination(into: dict[str, np.ndarray] | None, name: str, dtype: np.dtype, length: int) -> np.ndarray:
    """Where the array ``name`` of the file (``length`` values of the little-endian
    ``dtype``) is read to: ``into[name]`` when it fits exactly, else a new array."""
    out = None if into is None else into.get(name)
    if (out is not None and out.shape == (length,) and out.dtype.kind == dtype.kind
            and out.dtype.itemsize == dtype.itemsize and out.flags.c_contiguous and out.flags.writeable):
        return out
    return np.empty(length, dtype=dtype)


@dataclass(frozen=True)
class CacheInfo:
    """What ``rkcheck cache info`` reports."""

    path: Path
    files: int
    bytes: int
    limit: int
    disabled: bool  # RKCHECK_NO_CACHE is set


class ListingCache:
    """A :class:`~rkcheck.trees.stored.ListingStore` on disk, in ``directory``."""

    def __init__(self, directory: Path | None = None, limit: int | None = None, min_terms: int = MIN_CACHED_TERMS):
        self.directory = Path(directory) if directory is not None else cache_dir()
        self.limit = max_cache_bytes() if limit is None else limit
        self.min_terms = min_terms

    def path(self, key: dict[str, Any]) -> Path:
        return self.directory / _name(key)

    def load(self, key: dict[str, Any],
             into: dict[str, np.ndarray] | None = None) -> tuple[dict[str, np.ndarray], dict[str, Any]] | None:
        path = self.path(key)
        try:
            f = _open_regular(path)
            if f is None:
                return None
            with f:
                got = decode(f, os.fstat(f.fileno()).st_size, key, into)
            if got is not None:
                os.utime(path)  # recently used: evicted last
        except OSError:
            return None
        return got

    def save(self, key: dict[str, Any], arrays: dict[str, np.ndarray], meta: dict[str, Any]) -> str | None:
        pieces = encode(key, arrays, meta)
        size = sum(len(p) if isinstance(p, bytes) else p.nbytes for p in pieces)
        if size > self.limit:  # kept, it would evict everything else and still not fit
            return (f"the listing of the conditions with {key.get('vertices')} vertices takes {human_bytes(size)}, "
                    f"more than the listing cache may hold ({human_bytes(self.limit)}, RKCHECK_MAX_CACHE_BYTES): "
                    "it is built again on every run")
        import tempfile

        tmp = None
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=_TEMP_PREFIX, suffix=_SUFFIX, dir=self.directory)
            with os.fdopen(fd, "wb") as f:
                for piece in pieces:
                    f.write(piece)
            os.replace(tmp, self.path(key))
            tmp = None
            self.evict()
        except OSError:
            pass  # best effort: no cache is only slower
        finally:
            if tmp is not None:
                _unlink(Path(tmp))
        return None

    def files(self) -> list[tuple[Path, int, float]]:
        """(path, size, last use) of the listing files, oldest first."""
        out = []
        try:
            entries = list(os.scandir(self.directory))
        except OSError:
            return []
        for entry in entries:
            if _LISTING_NAME.fullmatch(entry.name):
                try:
                    st = entry.stat(follow_symlinks=False)
                except OSError:
                    continue
                if entry.is_file(follow_symlinks=False) and _starts_with_magic(Path(entry.path)):
                    out.append((Path(entry.path), st.st_size, st.st_mtime))
        return sorted(out, key=lambda x: x[2])

    def evict(self) -> None:
        """Remove the least recently used files until the rest fit in the limit."""
        files = self.files()
        total = sum(size for _, size, _ in files)
        for path, size, _ in files:
            if total <= self.limit:
                break
            _unlink(path)
            total -= size

    def info(self) -> CacheInfo:
        files = self.files()
        return CacheInfo(self.directory, len(files), sum(size for _, size, _ in files), self.limit, cache_disabled())

    def clear(self) -> int:
        """Remove every listing file (and temporary files left by an interrupted save);
        nothing else in the directory is touched.  Returns how many listing files."""
        files = self.files()
        for path, _, _ in files:
            _unlink(path)
        try:
            for entry in os.scandir(self.directory):
                if _TEMP_NAME.fullmatch(entry.name):
                    _unlink(Path(entry.path))
        except OSError:
            pass
        return len(files)


def _open_regular(path: Path) -> BufferedReader | None:
    """``path`` opened for reading when it is a regular file, else None: opening a named
    pipe (or a device) put there would wait for a writer that never comes."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            os.close(fd)
            return None
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def _starts_with_magic(path: Path) -> bool:
    """Whether the file begins as every listing file does: another program's file that
    happens to carry the suffix is neither counted nor removed."""
    try:
        f = _open_regular(path)
        if f is None:
            return False
        with f:
            return f.read(len(MAGIC)) == MAGIC
    except OSError:
        return False


def _unlink(path: Path) -> None:
    try:
        path.unlink()
    except OSError:  # gone already (another run evicted it) or not ours to remove
        pass
