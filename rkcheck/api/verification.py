"""``verify``: the check of ``rkcheck verify``, for Python callers, and the one function
the CLI calls too — so both resolve options the same way and give the same JSON.

Options come from, most specific first: the arguments of :func:`verify` (the CLI's
flags), the tableau's own ``[check]`` table, ``[tool.rkcheck]`` of the nearest
``pyproject.toml`` (only with ``project=True``, as the CLI does), then the defaults
(degree none, order 8, 50 digits, decimals "auto") — :mod:`rkcheck.options`.
"""

from __future__ import annotations

import os
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, Callable, Iterator, Mapping

from rkcheck.energy.check import CheckResult
from rkcheck.energy.results import Condition
from rkcheck.errors import OptionError, UserError, as_option, is_digits_limit
from rkcheck.methods.tableau import Tableau
from rkcheck.options import (
    ARITHMETICS,
    DECIMALS_MODES,
    DPS_RANGE,
    FAIL_ON,
    JOBS_RANGE,
    MAX_ORDER,
    parse_choice,
    parse_degree,
    parse_flag,
    parse_int_in,
    parse_positive,
    parse_require,
    resolve_check_options,
)

if TYPE_CHECKING:
    from rkcheck.energy.budget import Budget


@contextmanager
def printable_numbers() -> Iterator[None]:
    """Writing exact numbers as text: Python refuses integers of more digits than
    ``sys.get_int_max_str_digits()`` (4 300 by default; the CLI raises it, a library
    leaves the process's setting alone), which becomes a :class:`UserError` saying so."""
    import sys

    try:
        yield
    except ValueError as err:
        if not is_digits_limit(err):
            raise
        raise UserError(f"a number has more than {sys.get_int_max_str_digits():,} digits, more than Python writes "
                        "as text (sys.set_int_max_str_digits raises the limit)") from None


def numbers_as_errors(fn: Callable[..., Any]) -> Callable[..., Any]:
    """``fn`` with :func:`printable_numbers` around each call: a rational of more digits
    than Python writes as text, given as an argument (``eps=[Fraction(1, 10**5000)]``)
    and written on its way to the parser, is a :class:`UserError`, not a ValueError."""
    import functools

    @functools.wraps(fn)
    def checked(*args: Any, **kwargs: Any) -> Any:
        with printable_numbers():
            return fn(*args, **kwargs)

    return checked


class _Unset:
    """The default of an option left to the tableau's ``[check]`` table and the defaults."""

    def __repr__(self) -> str:
        return "UNSET"


UNSET: Any = _Unset()


class Verification(CheckResult):
    """The result of :func:`verify` (and of ``rkcheck verify``): the check of every
    energy condition, the orders, the AVF verdict and certificate, and the tableau's
    ``[expect]`` claims — a :class:`~rkcheck.energy.check.CheckResult` with the JSON
    document added.

    ``conditions`` and ``failures`` are sequences of
    :class:`~rkcheck.energy.results.Condition` (built as they are read: there may be
    millions)."""

    def to_dict(self) -> dict[str, Any]:
        """The document of ``rkcheck verify --format json`` (same keys and values)."""
        from rkcheck.reports.jsondoc import check_doc

        with printable_numbers():
            return check_doc(self)

    def to_json(self) -> str:
        """Exactly what ``rkcheck verify --format json`` prints (without its newline)."""
        from rkcheck.reports.jsondoc import dumps

        return dumps(self.to_dict())

    def __repr__(self) -> str:
        from rkcheck.numbers.formatting import count_text

        return (f"<Verification of {self.tableau.name!r}: {self.verdict}, energy order {self.energy_order_label}, "
                f"{count_text(len(self.failures))} of {count_text(len(self.conditions))} conditions fail>")


# ------------------------------------------------------------------ options


_option = as_option


def check_flags(degree: Any = UNSET, order: Any = UNSET, dps: Any = UNSET, decimals: Any = UNSET,
                fail_fast: bool = False, require: Any = UNSET, arithmetic: Any = UNSET) -> dict[str, Any]:
    """The options given explicitly, validated like the CLI's flags (an
    :class:`~rkcheck.errors.OptionError` naming the option otherwise)."""
    flags: dict[str, Any] = {}
    if degree is not UNSET:
        flags["degree"] = _option(lambda: parse_degree(degree, "degree"))
    if order is not UNSET:  # the words of the [check] table's errors (docs/errors.md)
        flags["order"] = _option(lambda: parse_int_in(order, (1, MAX_ORDER), "order"))
    if dps is not UNSET:
        flags["dps"] = _option(lambda: parse_int_in(dps, DPS_RANGE, "dps"))
    if decimals is not UNSET:
        flags["decimals"] = _option(lambda: parse_choice(decimals, DECIMALS_MODES, "decimals"))
    if require is not UNSET:
        flags["require"] = _option(lambda: parse_require(require, "require"))
    if arithmetic is not UNSET:
        flags["arithmetic"] = _option(lambda: parse_choice(arithmetic, ARITHMETICS, "arithmetic"))
    if _option(lambda: parse_flag(fail_fast, "fail_fast")):
        flags["fail_fast"] = True
    return flags


def run_check(tableau: Tableau, flags: Mapping[str, Any], project: Mapping[str, Any] | None = None,
              fail_on: str = "auto", budget: "Budget | None" = None,
              progress: Callable[[int, int], None] | None = None,
              scheduler: str | None = None, jobs: int = 1) -> Verification:
    """The check behind :func:`verify` and ``rkcheck verify``: options resolved
    (flags, ``[check]``, ``project``, defaults), then every condition and every claim,
    its exact passes on ``scheduler``'s cluster or ``jobs`` local processes when given.
    Ctrl-C raises :class:`~rkcheck.errors.CheckInterrupted` with what finished."""
    from rkcheck.energy.claims import judge_tableau

    options = resolve_check_options(flags, tableau.info.check, project or {})
    with _passes_elsewhere(scheduler, jobs):
        result = judge_tableau(tableau, options, fail_on, budget, progress, Verification)
    assert isinstance(result, Verification)
    return result


@contextmanager
def _passes_elsewhere(scheduler: str | None, jobs: int) -> Iterator[None]:
    """The exact passes of the checks in the block on the cluster at ``scheduler``, or
    on ``jobs`` local processes (forked: they share this process's listing); neither:
    here."""
    address = None if scheduler is None or scheduler.strip() in ("", "local") else scheduler.strip()
    if address is None and jobs <= 1:
        yield
        return
    from rkcheck.batch.executors import executor_for
    from rkcheck.batch.passes import executor_passes
    from rkcheck.evaluation.passes import passes_run_by
    from rkcheck.trees.listing import current_store

    with executor_for(address, jobs) as executor, passes_run_by(executor_passes(executor, current_store() is not None)):
        yield


def verify(
    tableau: Tableau | str | os.PathLike[str],
    *,
    degree: int | str | None = UNSET,
    order: int = UNSET,
    dps: int = UNSET,
    decimals: str = UNSET,
    require: str = UNSET,
    fail_fast: bool = False,
    fail_on: str = "auto",
    arithmetic: str = UNSET,
    project: bool = False,
    max_conditions: int | None = None,
    scheduler: str | None = None,
    jobs: int = 1,
) -> Verification:
    """Check every energy condition of ``tableau`` (a Tableau, a path or ``"@name"``)
    up to ``order`` for polynomial Hamiltonians of degree ≤ ``degree`` (None or "none":
    all Hamiltonians), plus the classical and quadrature orders, the AVF verdict and
    certificate (with a degree), and the tableau's claims — the same work and the same
    result as ``rkcheck verify``.

    Options left out come from the tableau's ``[check]`` table, then (``project=True``)
    ``[tool.rkcheck]`` of the nearest pyproject.toml, then the defaults: degree none,
    order 8, dps 50, decimals "auto" (definitions §5), require "any" (the proof gate:
    "proof" or "digits:D" make numerical holds count as failures, like ``--require``).
    ``arithmetic``: "auto", "exact" or "ball".  ``max_conditions`` refuses larger checks; the memory available
    bounds them anyway (:class:`~rkcheck.errors.ResourceError`).

    A large exact check can be split: its passes (one per group of primes, each a pass
    over every condition) run on the Dask cluster at ``scheduler`` (``"tcp://host:8786"``;
    only when given — the environment's ``RKCHECK_SCHEDULER`` is for scans) or on
    ``jobs`` local processes, each with its own weights.  The result is the same.

    Bad options raise :class:`~rkcheck.errors.OptionError`, bad tableaux
    :class:`~rkcheck.errors.TableauError` (both :class:`~rkcheck.errors.RkcheckError`)."""
    from rkcheck.api.tableaux import as_tableau
    from rkcheck.energy.budget import Budget
    from rkcheck.io.machine import available_memory

    flags = check_flags(degree, order, dps, decimals, fail_fast, require, arithmetic)
    fail_on = _option(lambda: parse_choice(fail_on, FAIL_ON, "fail_on"))
    jobs = _option(lambda: parse_int_in(jobs, JOBS_RANGE, "jobs"))
    if scheduler is not None and not isinstance(scheduler, str):
        raise OptionError(f"expected an address such as 'tcp://host:8786', got {scheduler!r}", "scheduler")
    if max_conditions is not None:
        max_conditions = _option(lambda: parse_positive(max_conditions, "max_conditions"))
    project_check: dict[str, Any] = {}
    if _option(lambda: parse_flag(project, "project")):
        from rkcheck.io.config import load_config

        config = load_config()
        project_check = config.check
        if fail_on == "auto" and config.fail_on:
            fail_on = config.fail_on
    tab = as_tableau(tableau, continuous=True)
    return run_check(tab, flags, project_check, fail_on, Budget(available_memory(), max_conditions, None),
                     scheduler=scheduler, jobs=jobs)


__all__ = ["Condition", "Verification", "verify"]
