"""Suite-wide settings: the listing cache lives in a temporary directory of this run,
never in the user's cache, and so does Dask's scratch space (the cluster tests' workers
would otherwise leave ``dask-scratch-space`` in the system's temporary folder); both are
removed at the end."""

from __future__ import annotations

import os
import shutil
import tempfile

_SCRATCH: str | None = None


def pytest_configure(config) -> None:
    global _SCRATCH
    _SCRATCH = tempfile.mkdtemp(prefix="rkcheck-test-")
    # environment variables: subprocesses and Dask's workers inherit them, and Dask reads
    # DASK_* when it is first imported (no test has imported it yet)
    os.environ["RKCHECK_CACHE_DIR"] = os.path.join(_SCRATCH, "cache")
    os.environ["DASK_TEMPORARY_DIRECTORY"] = os.path.join(_SCRATCH, "dask")
    os.environ.pop("RKCHECK_NO_CACHE", None)


def pytest_unconfigure(config) -> None:
    if _SCRATCH is not None:
        shutil.rmtree(_SCRATCH, ignore_errors=True)
