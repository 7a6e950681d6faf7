"""Suite-wide settings: the listing cache lives in a temporary directory of this run,
never in the user's cache (and is removed at the end)."""

from __future__ import annotations

import os
import shutil
import tempfile

_CACHE_DIR: str | None = None


def pytest_configure(config) -> None:
    global _CACHE_DIR
    _CACHE_DIR = tempfile.mkdtemp(prefix="rkcheck-test-cache-")
    os.environ["RKCHECK_CACHE_DIR"] = _CACHE_DIR  # subprocesses inherit it
    os.environ.pop("RKCHECK_NO_CACHE", None)


def pytest_unconfigure(config) -> None:
    if _CACHE_DIR is not None:
        shutil.rmtree(_CACHE_DIR, ignore_errors=True)
