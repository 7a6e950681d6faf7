"""One exact check split over the workers of an executor (``verify --scheduler``).

An exact check evaluates every condition modulo several primes (and, in a number field,
at several roots of each): each *pass* over the listing computes some of these channels,
independently of the others (:mod:`rkcheck.evaluation.passes`).  The passes of one
check go to the workers as jobs; each worker rebuilds the same listing — of rooted trees
(or read from its own listing cache), or by centroid — for the same order and degree,
and sends back the residues of its pass.
The verdicts do not depend on where a pass ran: the residues are the same numbers.

Passes, not orders, are what is split: in a listing of rooted trees the weights of every
order are built from those of all the orders below it, so an order cannot be computed
apart from the others, while two passes share nothing but the listing.  A pass whose worker is lost (the cluster gave
up on it) is computed in this process instead: the check is never left incomplete.
"""

from __future__ import annotations

from contextlib import closing
from typing import Any, Iterator, cast

import numpy as np

from rkcheck.batch.jobs import Executor


class _Lost:
    """A pass whose worker gave no result (why: the executor's message)."""

    def __init__(self, job: Any, why: str):
        self.why = why


def executor_passes(executor: Executor, cache: bool):
    """A :class:`~rkcheck.evaluation.protocols.PassRunner` that runs the passes on
    ``executor``'s workers; ``cache``: the workers read and keep listings in their own
    listing cache (as this process does when it uses one)."""

    def run(scaled: Any, listing: Any,
            jobs: list[tuple[list[tuple[int, int]], list[int]]]) -> Iterator[tuple[int, dict[int, np.ndarray]]]:
        # a listing travels as the recipe it pickles to (its kind and key), made there
        # after the worker's store is set: rebuilt, read from that cache, or reused
        items = [(scaled, listing.__reduce__(), pairs, orders, cache) for pairs, orders in jobs]
        with closing(executor.map_unordered(_channel_pass, items, _Lost)) as results:
            for g, got in results:
                if isinstance(got, _Lost):  # the pass runs here instead
                    yield g, scaled.residues_at(listing, *jobs[g])
                else:
                    yield g, cast("dict[int, np.ndarray]", got)

    return run


def _channel_pass(item: tuple) -> dict[int, np.ndarray]:
    """One pass in a worker: the residues of its channels for its orders."""
    from rkcheck.trees.listing import use_store

    scaled, (make, key), pairs, orders, cache = item
    if cache:
        from rkcheck.io.cache import ListingCache, cache_disabled

        use_store(None if cache_disabled() else ListingCache())
    return scaled.residues_at(make(*key), pairs, orders)
