"""Jobs on a Dask distributed cluster (``rkcheck[cluster]``): the :class:`Executor` of
``--scheduler tcp://host:8786``.

The workers import ``rkcheck`` themselves, so every worker needs the same rkcheck
version as this process (checked when connecting).  Each worker process keeps its tree
and condition tables between jobs, as a local worker does.  Worker threads of one
process share those tables, which are not built for concurrent use: jobs in one worker
process run one at a time (start workers with ``--nthreads 1 --nworkers N`` to use N
cores).  When a worker dies, the scheduler gives its jobs to the others; a job that has
killed ``distributed.scheduler.allowed-failures`` + 1 workers (3 + 1 by default) is
given up and becomes ``failed(item, why)``.
"""

from __future__ import annotations

import threading
import uuid
from typing import Any, Callable

from rkcheck.batch.jobs import CLUSTER_EXTRA, Executor, internal_error, scheduler_timeout
from rkcheck.errors import UserError

#: One job at a time per worker process: the tables a check builds are shared, unlocked.
_ONE_AT_A_TIME = threading.Lock()


def _run_one(fn: Callable[[Any], Any], item: Any) -> Any:
    with _ONE_AT_A_TIME:
        return fn(item)


def _worker_version() -> str:
    from rkcheck.version import __version__

    return __version__


def _import_distributed():
    try:
        import distributed
    except ImportError:
        raise UserError(f"--scheduler needs Dask: pip install '{CLUSTER_EXTRA}'", "scheduler") from None
    return distributed


def _probe(address: str, timeout: float) -> None:
    """Reach the scheduler within ``timeout`` seconds (connect and handshake), or raise
    UserError: a sync Client that fails to connect leaves a half-built client behind
    whose clean-up blocks and prints at exit."""
    import asyncio

    from distributed.comm import connect

    async def probe() -> None:
        comm = await connect(address, timeout=timeout)
        await comm.close()

    try:
        asyncio.run(asyncio.wait_for(probe(), timeout))
    except (ValueError, TypeError) as err:  # not an address: "missing port number", unknown scheme
        raise UserError(f"not a scheduler address: {err}", "scheduler") from None
    except (OSError, asyncio.TimeoutError, Exception) as err:
        why = "no answer" if isinstance(err, asyncio.TimeoutError) else f"{type(err).__name__}: {err}"
        raise UserError(f"cannot reach the Dask scheduler at {address} within {timeout:g} s ({why}); "
                        f"the limit SCHEDULER_CONNECT_TIMEOUT is set by RKCHECK_SCHEDULER_TIMEOUT", "scheduler") from None


class DaskExecutor(Executor):
    """Jobs as Dask futures on the cluster at ``address``; see the module text."""

    def __init__(self, address: str):
        distributed = _import_distributed()
        timeout = scheduler_timeout()
        _probe(address, timeout)
        try:
            self.client = distributed.Client(address, timeout=timeout, set_as_default=False)
        except Exception as err:
            raise UserError(f"cannot connect to the Dask scheduler at {address}: {type(err).__name__}: {err}",
                            "scheduler") from None
        try:
            self._check_workers(address, timeout)
        except BaseException:
            self.close()
            raise
        self.where = f"the Dask scheduler at {address}"

    def _check_workers(self, address: str, timeout: float) -> None:
        from rkcheck.version import __version__

        try:
            self.client.wait_for_workers(1, timeout=timeout)
        except Exception:
            raise UserError(f"the Dask scheduler at {address} has no worker (waited {timeout:g} s, the limit "
                            "SCHEDULER_CONNECT_TIMEOUT)", "scheduler") from None
        try:
            versions = self.client.run(_worker_version)
        except Exception as err:
            raise UserError(f"the workers of {address} cannot run rkcheck ({type(err).__name__}: {err}); "
                            f"install rkcheck {__version__} on every worker", "scheduler") from None
        wrong = sorted({v for v in versions.values() if v != __version__})
        if wrong:
            raise UserError(f"the workers of {address} run rkcheck {', '.join(wrong)}, this is {__version__}: "
                            "install the same version everywhere", "scheduler")
        self.workers = max(1, len(versions))

    def map_unordered(self, fn, items, failed):
        from distributed import as_completed

        tag = uuid.uuid4().hex[:12]
        keys = [f"rkcheck-{tag}-{i}" for i in range(len(items))]
        futures = self.client.map(_run_one, [fn] * len(items), list(items), key=keys, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        pending = set(index)
        try:
            for future in as_completed(futures, loop=self.client.loop):
                i = index[future.key]
                pending.discard(future.key)
                result = self._result(future, items[i], failed)
                future.release()
                yield i, result
        finally:
            if pending:  # Ctrl-C or an early close: the rest is not wanted any more
                try:
                    self.client.cancel([f for f in futures if f.key in pending], force=True)
                except Exception:
                    pass

    @staticmethod
    def _result(future: Any, item: Any, failed: Callable[[Any, str], Any]) -> Any:
        from distributed import KilledWorker

        if future.status == "finished":
            try:
                return future.result()
            except Exception as err:  # the result could not be brought back
                return failed(item, f"internal error: the result cannot be sent back ({type(err).__name__}: {err})")
        try:
            raised = future.exception()
        except Exception as exc:  # cancelled: the scheduler forgot it (restarted?)
            return failed(item, f"the Dask scheduler dropped this job ({type(exc).__name__})")
        if isinstance(raised, KilledWorker):
            return failed(item, "the Dask workers running it died each time it was tried (out of memory?); "
                                "the limit is distributed.scheduler.allowed-failures")
        return failed(item, internal_error(raised))

    def close(self) -> None:
        client = getattr(self, "client", None)
        if client is not None:
            self.client = None
            try:
                client.close(timeout=scheduler_timeout())
            except Exception:
                pass
