"""Jobs on a Dask distributed cluster (``rkcheck[cluster]``): the :class:`Executor` of
``--scheduler tcp://host:8786``.

The workers import ``rkcheck`` themselves, so every worker needs the same rkcheck
version as this process (checked when connecting).  Each worker process keeps its tree
and condition tables between jobs, as a local worker does.  Worker threads of one
process share those tables, which are not built for concurrent use: jobs in one worker
process run one at a time (start workers with ``--nthreads 1 --nworkers N`` to use N
cores).  Items go to the cluster in small chunks (:func:`chunk_size`): one Dask task
per item would pay a round trip through the scheduler per item.  When a worker dies,
the scheduler gives its tasks to the others; a task that has killed
``distributed.scheduler.allowed-failures`` + 1 workers (3 + 1 by default) is given up:
a chunk of several items is then tried once more item by item, so that only the item
that kills its workers becomes ``failed(item, why)``.
"""

from __future__ import annotations

import logging
import pickle
import threading
import uuid
from typing import Any, Callable

from rkcheck.batch.jobs import CLUSTER_EXTRA, Executor, Failure, internal_error, scheduler_timeout
from rkcheck.errors import OptionError

#: One job at a time per worker process: the tables a check builds are shared, unlocked.
_ONE_AT_A_TIME = threading.Lock()


#: At most this many items in one Dask task.  One task per item costs a round trip
#: through the scheduler per item (milliseconds on a quiet machine, tens of them on a
#: loaded one); a few items per task amortise it while the progress stays fine-grained.
MAX_CHUNK = 16


def chunk_size(items: int, threads: int) -> int:
    """Items per task: about 8 tasks per worker thread, 1 to MAX_CHUNK items each."""
    return max(1, min(MAX_CHUNK, items // (8 * max(1, threads))))


def _run_chunk(fn: Callable[[Any], Any], batch: list) -> bytes:
    """``fn`` on each item of ``batch``, one at a time in this worker process; an item
    whose ``fn`` raises gives a :class:`Failure`, the others their result.  The list
    comes back pickled: Dask would first try (and fail) to encode each result with
    msgpack and then pickle it piece by piece, at several times the cost of one pickle."""
    out: list = []
    with _ONE_AT_A_TIME:
        for item in batch:
            try:
                out.append(fn(item))
            except Exception as err:
                out.append(Failure(internal_error(err)))
    try:
        return pickle.dumps(out, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:  # one result that does not pickle must not take the others with it
        return pickle.dumps([_sendable(r) for r in out], protocol=pickle.HIGHEST_PROTOCOL)


def _sendable(result: Any) -> Any:
    """``result``, or the Failure that says why it cannot be sent back."""
    try:
        pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception as err:
        return Failure(f"internal error: the result cannot be sent back ({type(err).__name__}: {err})")
    return result


def _worker_version() -> str:
    from rkcheck.version import __version__

    return __version__


def _import_distributed():
    try:
        import distributed
    except ImportError:
        raise OptionError(f"--scheduler needs Dask: pip install '{CLUSTER_EXTRA}'", "scheduler") from None
    return distributed


def _probe(address: str, timeout: float) -> None:
    """Reach the scheduler within ``timeout`` seconds (connect and handshake), or raise
    OptionError: a sync Client that fails to connect leaves a half-built client behind
    whose clean-up blocks and prints at exit."""
    import asyncio

    from distributed.comm import connect

    async def probe() -> None:
        comm = await connect(address, timeout=timeout)
        await comm.close()

    try:
        asyncio.run(asyncio.wait_for(probe(), timeout))
    except (ValueError, TypeError) as err:  # not an address: "missing port number", unknown scheme
        raise OptionError(f"not a scheduler address: {err}", "scheduler") from None
    except Exception as err:  # refused, timed out, not a Dask scheduler
        why = "no answer" if isinstance(err, asyncio.TimeoutError) else f"{type(err).__name__}: {err}"
        raise OptionError(f"cannot reach the Dask scheduler at {address} within {timeout:g} s ({why}); "
                        f"the limit SCHEDULER_CONNECT_TIMEOUT is set by RKCHECK_SCHEDULER_TIMEOUT", "scheduler") from None


class DaskExecutor(Executor):
    """Jobs as Dask futures on the cluster at ``address``; see the module text."""

    def __init__(self, address: str):
        distributed = _import_distributed()
        timeout = scheduler_timeout()
        _probe(address, timeout)
        # what Dask logs on its own recoveries ("Couldn't gather keys" when a worker dies
        # holding results) is not the user's business: the scan's rows say what happened
        # (Dask's configuration gives several of its loggers levels of their own)
        names = [n for n in logging.Logger.manager.loggerDict if n == "distributed" or n.startswith("distributed.")]
        self._log_levels = {n: logging.getLogger(n).level for n in names + ["distributed"]}
        for n in self._log_levels:
            logging.getLogger(n).setLevel(logging.CRITICAL)
        try:
            self.client = distributed.Client(address, timeout=timeout, set_as_default=False)
        except Exception as err:
            self.close()
            raise OptionError(f"cannot connect to the Dask scheduler at {address}: {type(err).__name__}: {err}",
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
            raise OptionError(f"the Dask scheduler at {address} has no worker (waited {timeout:g} s, the limit "
                            "SCHEDULER_CONNECT_TIMEOUT)", "scheduler") from None
        try:
            versions = self.client.run(_worker_version)
        except Exception as err:
            raise OptionError(f"the workers of {address} cannot run rkcheck ({type(err).__name__}: {err}); "
                            f"install rkcheck {__version__} on every worker", "scheduler") from None
        wrong = sorted({v for v in versions.values() if v != __version__})
        if wrong:
            raise OptionError(f"the workers of {address} run rkcheck {', '.join(wrong)}, this is {__version__}: "
                            "install the same version everywhere", "scheduler")
        self.workers = max(1, len(versions))
        self.threads = max(1, sum(self.client.nthreads().values()))

    def map_unordered(self, fn, items, failed):
        from distributed import as_completed

        tag = uuid.uuid4().hex[:12]
        size = chunk_size(len(items), self.threads)
        chunks = {f"rkcheck-{tag}-{k}": list(range(k, min(k + size, len(items)))) for k in range(0, len(items), size)}
        futures = self._submit(fn, items, chunks)
        pending = dict(futures)
        try:
            done = as_completed(list(futures.values()), loop=self.client.loop)
            for future in done:
                del pending[future.key]
                indices = chunks[future.key]
                results = self._results(future, [items[i] for i in indices], failed)
                future.release()
                if results is None:  # a chunk that killed its workers: each file once more, alone
                    alone = {f"{future.key}-{i}": [i] for i in indices}
                    chunks.update(alone)
                    more = self._submit(fn, items, alone)
                    pending.update(more)
                    done.update(more.values())
                    continue
                yield from zip(indices, results)
        finally:
            if pending:  # Ctrl-C or an early close: the rest is not wanted any more
                try:
                    self.client.cancel(list(pending.values()), force=True)
                except Exception:
                    pass

    def _submit(self, fn, items, chunks: dict[str, list[int]]) -> dict[str, Any]:
        keys = list(chunks)
        batches = [[items[i] for i in chunks[k]] for k in keys]
        futures = self.client.map(_run_chunk, [fn] * len(keys), batches, key=keys, pure=False)
        return {f.key: f for f in futures}

    @staticmethod
    def _results(future: Any, batch: list, failed: Callable[[Any, str], Any]) -> list | None:
        """The results of one finished chunk, failures turned into ``failed(item, why)``;
        None when the chunk killed its workers and holds more than one item."""
        from distributed import KilledWorker

        try:
            # waits when the result was lost with a dead worker after it finished: the
            # scheduler computes it again
            results = pickle.loads(future.result())
        except KilledWorker:
            if len(batch) > 1:
                return None
            return [failed(batch[0], "the Dask workers running it died each time it was tried (out of memory?); "
                                     "the limit is distributed.scheduler.allowed-failures")]
        except BaseException as err:
            if isinstance(err, KeyboardInterrupt):
                raise
            if future.cancelled():  # the scheduler forgot it (restarted?)
                why = "the Dask scheduler dropped this job"
            else:  # the tasks catch what a check raises: this is the transport failing
                why = f"internal error: the result cannot be brought back ({type(err).__name__}: {err})"
            return [failed(item, why) for item in batch]
        return [failed(item, r.why) if isinstance(r, Failure) else r for item, r in zip(batch, results)]

    def close(self) -> None:
        client = getattr(self, "client", None)
        if client is not None:
            self.client = None
            try:
                client.close(timeout=scheduler_timeout())
            except Exception:
                pass
        for name, level in getattr(self, "_log_levels", {}).items():
            logging.getLogger(name).setLevel(level)
        self._log_levels = {}
