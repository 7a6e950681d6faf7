"""Choosing where a batch of jobs runs: a Dask cluster when a scheduler is given
(``--scheduler``, ``RKCHECK_SCHEDULER``, ``[tool.rkcheck] scheduler``), else local
processes.  The interface is :class:`rkcheck.batch.jobs.Executor`; everything a caller
needs is importable from here."""

from __future__ import annotations

import os
from typing import Callable

from rkcheck.batch.jobs import (
    CLUSTER_EXTRA,
    SCHEDULER_CONNECT_TIMEOUT,
    SCHEDULER_ENV,
    SCHEDULER_TIMEOUT_ENV,
    Executor,
    SerialExecutor,
    scheduler_timeout,
)
from rkcheck.batch.local_pool import LocalExecutor, default_jobs


def resolve_scheduler(given: str | None, configured: str | None = None) -> str | None:
    """The scheduler address to use: ``given`` (an option), else ``RKCHECK_SCHEDULER``,
    else ``configured`` (``[tool.rkcheck] scheduler``); unset or empty ones are skipped.
    None: run locally, also when the first one set is ``local`` (so that an option can
    override the environment)."""
    for value in (given, os.environ.get(SCHEDULER_ENV), configured):
        if value is not None and str(value).strip():
            address = str(value).strip()
            return None if address == "local" else address
    return None


def executor_for(scheduler: str | None, jobs: int, prepare: Callable[[], None] | None = None) -> Executor:
    """A Dask executor connected to ``scheduler`` when one is given, else ``jobs`` local
    processes (``jobs <= 1``: this process).  Raises :class:`UserError` (one line) when
    Dask is not installed or the scheduler cannot be reached."""
    if scheduler:
        from rkcheck.batch.dask_executor import DaskExecutor

        return DaskExecutor(scheduler)
    if jobs <= 1:
        return SerialExecutor()
    return LocalExecutor(jobs, prepare)



__all__ = ["CLUSTER_EXTRA", "SCHEDULER_CONNECT_TIMEOUT", "SCHEDULER_ENV", "SCHEDULER_TIMEOUT_ENV", "Executor",
           "LocalExecutor", "SerialExecutor", "default_jobs", "executor_for", "resolve_scheduler",
           "scheduler_timeout"]
