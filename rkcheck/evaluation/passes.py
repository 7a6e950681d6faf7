"""The passes of an exact evaluation over the listing: the channels (a prime and a root
of the minimal polynomial modulo it) split into passes of as many as fit
(:meth:`~rkcheck.evaluation.scaled.ScaledTableau.channels_per_pass`), each run here or,
within :func:`passes_run_by`, by a runner (the workers of a cluster); a root whose
images are a stage permutation of an earlier root's is not evaluated but copied."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any

import numpy as np

from rkcheck.evaluation.protocols import PassRunner
from rkcheck.evaluation.scaled import ScaledTableau
from rkcheck.trees.centroid import Listing

#: where the passes of :func:`~rkcheck.evaluation.modular.exact_condition_sums` run when
#: not in this process (:func:`passes_run_by`)
_RUNNER: ContextVar[PassRunner | None] = ContextVar("rkcheck_pass_runner", default=None)


@contextmanager
def passes_run_by(runner: PassRunner | None) -> Iterator[None]:
    """Within the block, exact evaluations with several passes give them to ``runner``
    (the workers of a cluster) instead of running them here, one after the other; the
    residues, and so every verdict, are the same."""
    token = _RUNNER.set(runner)
    try:
        yield
    finally:
        _RUNNER.reset(token)


def _run_passes(scaled: ScaledTableau, listing: Listing,
                groups: list[tuple[list[Any], list[int]]]) -> Iterator[tuple[int, dict[int, np.ndarray]]]:
    """``(index, sums)`` of every pass: here in order, or by the runner in force."""
    jobs = [([(p, r) for _, _, p, r in group], orders) for group, orders in groups]
    runner = _RUNNER.get()
    if runner is None or len(jobs) < 2:  # one pass gains nothing from being sent away
        for g, (pairs, orders) in enumerate(jobs):
            yield g, scaled.residues_at(listing, pairs, orders)
        return
    yield from runner(scaled, listing, jobs)


Channel = tuple[int, int, int, int]  # (prime i, root j, p, r)


def pass_groups(scaled: ScaledTableau, listing: Listing, chosen: list[tuple[int, list[int]]],
                orders_for: Callable[[int], list[int]], top: int
                ) -> tuple[list[tuple[list[Channel], list[int]]], dict[tuple[int, int], list[Channel]]]:
    """The channels of the primes ``chosen`` (prime i, root j) to evaluate, split into
    passes of as many as :meth:`ScaledTableau.channels_per_pass` allows: ``(group,
    orders)`` with ``group`` the pass's ``(i, j, p, r)`` and ``orders`` those of its
    first prime (``orders_for(i)``); and the copies: a root whose images are a stage
    permutation of an earlier root's of the same prime
    (:meth:`ScaledTableau.channel_sources`) is not evaluated, it has that root's
    residues (by source ``(i, j)``, see :func:`with_copies`)."""
    flat, copies = flat_channels(scaled, chosen)
    if not flat:
        return [], copies
    width = scaled.channels_per_pass(listing, top)
    return [(flat[g:g + width], orders_for(flat[g][0])) for g in range(0, len(flat), width)], copies


def flat_channels(scaled: ScaledTableau, chosen: list[tuple[int, list[int]]]
                   ) -> tuple[list[Channel], dict[tuple[int, int], list[Channel]]]:
    """The channels ``(i, j, p, r)`` of the primes ``chosen`` to evaluate, and the copies
    of each by source ``(i, j)`` (:func:`pass_groups`)."""
    flat: list[Channel] = []
    copies: dict[tuple[int, int], list[Channel]] = {}
    for i, (p, roots) in enumerate(chosen):
        sources = scaled.channel_sources(p)
        for j, r in enumerate(roots):
            if sources[j] == j:
                flat.append((i, j, p, r))
            else:
                copies.setdefault((i, sources[j]), []).append((i, j, p, r))
    return flat, copies


def with_copies(scaled: ScaledTableau, group: list[Channel], sums: dict[int, np.ndarray],
                 copies: dict[tuple[int, int], list[Channel]]) -> tuple[list[Channel], dict[int, np.ndarray]]:
    """A pass's channels and residues with those of the roots that copy its roots."""
    if not copies:
        return group, sums
    column = {key[:2]: c for c, key in enumerate(group)}
    group = sorted(group + [x for key in group for x in copies.get(key[:2], [])])
    take = [column[(i, scaled.channel_sources(p)[j])] for i, j, p, _ in group]
    return group, {n: x[:, take] for n, x in sums.items()}


def channel_passes(scaled: ScaledTableau, listing: Listing, chosen: list[tuple[int, list[int]]],
                   orders_for: Callable[[int], list[int]],
                   top: int) -> Iterator[tuple[list[Any], dict[int, np.ndarray]]]:
    """The passes of :func:`pass_groups`, evaluated here or by the runner in force
    (:func:`passes_run_by`), as they finish: yields ``(group, sums)`` with ``sums[n]``
    the residues ``(conditions, len(group))`` of the pass's orders, copied roots included."""
    groups, copies = pass_groups(scaled, listing, chosen, orders_for, top)
    for g, sums in _run_passes(scaled, listing, groups):
        yield with_copies(scaled, groups[g][0], sums, copies)
        del sums  # a pass's residues are not kept while the next one runs
