"""What the project and the machine allow a run: ``[tool.rkcheck]`` of the nearest
``pyproject.toml``, the memory available, and the resource guard.

These are the helpers the public functions (and the CLI, for ``verify``) use so that
every command reads the project's settings and refuses oversized work the same way.
"""

from __future__ import annotations

import functools
import os
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Iterator, ParamSpec, TypeVar

from rkcheck.errors import OptionError, as_option
from rkcheck.io.config import Config as ProjectConfig

if TYPE_CHECKING:
    from rkcheck.energy.budget import Budget
    from rkcheck.io.cache import ListingCache

P = ParamSpec("P")
R = TypeVar("R")


def project_config() -> ProjectConfig:
    """``[tool.rkcheck]`` of the nearest ``pyproject.toml`` above the working directory
    (empty when there is none); a bad table raises :class:`~rkcheck.errors.UserError`
    naming the file and the key (docs/commands/scan.md, "Configuration")."""
    from rkcheck.io.config import load_config

    return load_config()


def budget(max_conditions: int | None = None, announce: Callable[[str], None] | None = None) -> "Budget":
    """The resource budget of a check on this machine: the memory available to this
    process (cgroup limits included), an explicit limit on the number of conditions
    (``--max-conditions``; it replaces the memory test), and where to say the estimate of
    a check longer than 5 s (``announce(text)``; None: say nothing)."""
    from rkcheck.energy.budget import Budget
    from rkcheck.io.machine import available_memory

    return Budget(available_memory(), max_conditions, announce)


def watching_memory(fn: Callable[P, R]) -> Callable[P, R]:
    """``fn`` with its computations on polynomials stopped, as a
    :class:`~rkcheck.errors.ResourceError`, before they run out of this machine's memory
    (:mod:`rkcheck.numbers.room`; FLINT would abort the process)."""

    @functools.wraps(fn)
    def watched(*args: P.args, **kwargs: P.kwargs) -> R:
        from rkcheck.io.machine import available_memory
        from rkcheck.numbers.room import room_read_by

        with room_read_by(available_memory):
            return fn(*args, **kwargs)

    return watched


def guard(order: int, degree: int | None) -> None:
    """Refuse (:class:`~rkcheck.errors.ResourceError`, the CLI's one line) an order
    whose condition tables would not fit in the memory available: the guard of the
    commands that build the tables without a budget of their own (bench, perturb,
    catalog)."""
    from rkcheck.energy.budget import check_budget, estimate

    check_budget(estimate(order, degree, "exact", listing=True), budget(), order)


def use_listing_cache(enabled: bool = True, directory: str | os.PathLike[str] | None = None) -> None:
    """Keep the condition listings built from now on in the listing cache (the user
    cache directory, ``RKCHECK_CACHE_DIR``, or ``directory``) and read them from there;
    ``enabled=False`` (or the environment's ``RKCHECK_NO_CACHE=1``): neither.  The CLI
    turns it on for each command unless ``--no-cache``; a program using the API opts in
    here (listings already in memory are not affected)."""
    from rkcheck.trees.listing import use_store

    use_store(_store(enabled, directory))


@contextmanager
def listing_cache_scope(enabled: bool = True) -> Iterator[None]:
    """:func:`use_listing_cache` for the duration of a ``with`` block (one CLI command)."""
    from rkcheck.trees.listing import use_store

    previous = use_store(_store(enabled, None))
    try:
        yield
    finally:
        use_store(previous)


def _store(enabled: bool, directory: str | os.PathLike[str] | None) -> "ListingCache | None":
    from rkcheck.io.cache import ListingCache, cache_disabled
    from rkcheck.options import parse_flag

    enabled = as_option(lambda: parse_flag(enabled, "enabled"))
    if directory is not None and not isinstance(directory, (str, os.PathLike)):
        raise OptionError(f"expected a folder (str or os.PathLike) or None, got {type(directory).__name__}",
                          "directory")
    if not enabled or cache_disabled():
        return None
    return ListingCache(None if directory is None else Path(directory))


def listing_cache(directory: str | os.PathLike[str] | None = None) -> "ListingCache":
    """The listing cache (``rkcheck cache info|clear``)."""
    from rkcheck.io.cache import ListingCache

    return ListingCache(None if directory is None else Path(directory))


__all__ = ["ProjectConfig", "budget", "guard", "listing_cache", "listing_cache_scope", "project_config", "use_listing_cache"]
