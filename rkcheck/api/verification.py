"""``verify``: the check of ``rkcheck verify``, for Python callers, and the one function
the CLI calls too — so both resolve options the same way and give the same JSON.

Options come from, most specific first: the arguments of :func:`verify` (the CLI's
flags), the tableau's own ``[check]`` table, ``[tool.rkcheck]`` of the nearest
``pyproject.toml`` (only with ``project=True``, as the CLI does), then the defaults
(degree none, order 8, 50 digits, decimals "auto") — :mod:`rkcheck.options`.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Callable, Iterator, Mapping, Sequence, overload

from rkcheck.errors import OptionError, UserError
from rkcheck.methods.tableau import Tableau
from rkcheck.options import (
    DECIMALS_MODES,
    DPS_RANGE,
    FAIL_ON,
    MAX_ORDER,
    CheckOptions,
    parse_choice,
    parse_degree,
    parse_positive,
    parse_require,
    resolve_check_options,
)

if TYPE_CHECKING:
    from rkcheck.energy.avf import AvfVerdict
    from rkcheck.energy.budget import Budget
    from rkcheck.energy.check import CheckResult, ConditionResult
    from rkcheck.energy.claims import ClaimResult
    from rkcheck.energy.lineintegral import Certificate

ARITHMETIC = ("auto", "exact", "ball")


class _Unset:
    """The default of an option left to the tableau's ``[check]`` table and the defaults."""

    def __repr__(self) -> str:
        return "UNSET"


UNSET: Any = _Unset()


@dataclass(frozen=True)
class Condition:
    """One checked energy condition (definitions §3): the free tree by its canonical id
    (level sequence of the rooting at the centre), its verdict (definitions §5), and its
    residual R for that designated rooting.

    ``residual`` is the exact value when the check was exact (a ``Fraction``, or an exact
    algebraic number), else None; ``enclosure`` is ``(mid, radius)``, rational, always
    given: R lies in ``[mid − radius, mid + radius]``."""

    id: str
    level_sequence: tuple[int, ...]
    bracket: str
    vertices: int
    max_degree: int
    state: str  # "holds" | "holds_to_digits" | "fails"
    digits: int | None
    residual: Any
    enclosure: tuple[Fraction, Fraction]

    @property
    def order(self) -> int:
        """The energy order this condition belongs to: vertices − 1."""
        return self.vertices - 1

    @property
    def holds(self) -> bool:
        """``holds`` or ``holds to D digits``."""
        return self.state != "fails"

    @staticmethod
    def of(r: "ConditionResult") -> "Condition":
        c, e = r.condition, r.enclosure
        return Condition(c.id, tuple(c.level_sequence), c.bracket, c.vertices, c.max_degree, r.verdict.state,
                         r.verdict.digits, r.value, (Fraction(e.mid), Fraction(e.rad)))


class _Conditions(Sequence[Condition]):
    """A lazy view: conditions are built when read (there may be millions)."""

    def __init__(self, results: Sequence["ConditionResult"]):
        self._results = results

    def __len__(self) -> int:
        return len(self._results)

    @overload
    def __getitem__(self, i: int) -> Condition: ...

    @overload
    def __getitem__(self, i: slice) -> list[Condition]: ...

    def __getitem__(self, i: int | slice) -> Condition | list[Condition]:
        if isinstance(i, slice):
            return [Condition.of(r) for r in self._results[i]]
        return Condition.of(self._results[i])

    def __iter__(self) -> Iterator[Condition]:
        return (Condition.of(r) for r in self._results)

    def __repr__(self) -> str:
        return f"<{len(self)} conditions>"


@dataclass(frozen=True)
class Verification:
    """The result of :func:`verify`: the check of every energy condition, the orders, the
    AVF verdict and certificate, and the tableau's ``[expect]`` claims.

    ``result`` is the underlying :class:`~rkcheck.energy.check.CheckResult` (the reports'
    input); the properties below are the stable surface."""

    result: "CheckResult"
    claims: "list[ClaimResult] | None"
    failed: bool  # what the CLI's exit code 1 means under ``fail_on``

    @property
    def tableau(self) -> Tableau:
        return self.result.tableau

    @property
    def options(self) -> CheckOptions:
        """The options the check ran with, after resolution."""
        return self.result.options

    @property
    def ok(self) -> bool:
        """True when the CLI would exit 0 (``fail_on='auto'``: claims if the tableau has
        any, else every condition holds or a certificate proves them)."""
        return not self.failed

    @property
    def verdict(self) -> str:
        """All checked conditions at once: ``fails`` if any fails, else
        ``holds_to_digits`` if any holds only to digits, else ``holds``."""
        from rkcheck.energy.check import overall

        return overall(self.result).state

    @property
    def energy_order(self) -> int:
        """Largest n ≤ order with every condition up to n+1 vertices holding (definitions §3)."""
        return self.result.energy_order

    @property
    def energy_order_label(self) -> str:
        """``all`` (a certificate proves every order), ``≥ N`` (nothing fails up to the
        checked order N) or the exact energy order."""
        return self.result.energy_order_label

    @property
    def energy_order_all(self) -> bool:
        return self.result.energy_order_all

    @property
    def conditions(self) -> Sequence[Condition]:
        """Every checked condition, by vertices and then canonical id."""
        return _Conditions(self.result.results)

    @property
    def failures(self) -> Sequence[Condition]:
        """The conditions that certainly fail, in the same order."""
        return _Conditions(self.result.failures)

    @property
    def avf(self) -> "AvfVerdict | None":
        """Whether the tableau equals AVF for the degree (None without a degree bound)."""
        return self.result.avf

    @property
    def certificate(self) -> "Certificate | None":
        """The certificate proving every order for the degree: line-integral (σ = 1 is
        AVF), or for degree 2 the stability-function certificate (R(z)R(−z) ≡ 1)."""
        return self.result.certificate

    @property
    def classical_order(self) -> int:
        return self.result.classical.order

    @property
    def quadrature_order(self) -> int:
        return self.result.quadrature.order

    @property
    def warnings(self) -> list[str]:
        return self.result.warnings

    def to_dict(self) -> dict[str, Any]:
        """The document of ``rkcheck verify --format json`` (same keys and values)."""
        from rkcheck.reports.jsondoc import check_doc

        return check_doc(self.result, self.claims)

    def to_json(self) -> str:
        """Exactly what ``rkcheck verify --format json`` prints (without its newline)."""
        from rkcheck.reports.jsondoc import dumps

        return dumps(self.to_dict())

    def __repr__(self) -> str:
        return (f"<Verification of {self.tableau.name!r}: {self.verdict}, energy order {self.energy_order_label}, "
                f"{len(self.failures)} of {len(self.result.results)} conditions fail>")


# ------------------------------------------------------------------ options


def _option(parse: Callable[[], Any]) -> Any:
    try:
        return parse()
    except UserError as err:
        raise OptionError(err.message, err.place, err.source) from None


def check_flags(degree: Any = UNSET, order: Any = UNSET, dps: Any = UNSET, decimals: Any = UNSET,
                fail_fast: bool = False, require: Any = UNSET) -> dict[str, Any]:
    """The options given explicitly, validated like the CLI's flags (an
    :class:`~rkcheck.errors.OptionError` naming the option otherwise)."""
    flags: dict[str, Any] = {}
    if degree is not UNSET:
        flags["degree"] = _option(lambda: parse_degree(degree, "degree"))
    if order is not UNSET:
        flags["order"] = _option(lambda: parse_positive(order, "order"))
        if flags["order"] > MAX_ORDER:
            raise OptionError(f"at most {MAX_ORDER}, got {order}", "order")
    if dps is not UNSET:
        flags["dps"] = _option(lambda: parse_positive(dps, "dps"))
        if not DPS_RANGE[0] <= flags["dps"] <= DPS_RANGE[1]:
            raise OptionError(f"expected {DPS_RANGE[0]} to {DPS_RANGE[1]} digits, got {dps}", "dps")
    if decimals is not UNSET:
        flags["decimals"] = _option(lambda: parse_choice(decimals, DECIMALS_MODES, "decimals"))
    if require is not UNSET:
        flags["require"] = _option(lambda: parse_require(require, "require"))
    if fail_fast:
        flags["fail_fast"] = True
    return flags


def run_check(tableau: Tableau, flags: Mapping[str, Any], project: Mapping[str, Any] | None = None,
              fail_on: str = "auto", budget: "Budget | None" = None,
              progress: Callable[[int, int], None] | None = None, arithmetic: str = "auto") -> Verification:
    """The check behind :func:`verify` and ``rkcheck verify``: options resolved
    (flags, ``[check]``, ``project``, defaults), then every condition and every claim.
    Ctrl-C raises :class:`~rkcheck.errors.CheckInterrupted` with what finished."""
    from rkcheck.energy.claims import judge_tableau

    options = resolve_check_options(flags, tableau.check, project or {})
    result, claims, failed = judge_tableau(tableau, options, fail_on, budget, progress, arithmetic)
    return Verification(result, claims, failed)


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
    arithmetic: str = "auto",
    project: bool = False,
    max_conditions: int | None = None,
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
    bounds them anyway (:class:`~rkcheck.energy.budget.ResourceError`).

    Bad options raise :class:`~rkcheck.errors.OptionError`, bad tableaux
    :class:`~rkcheck.errors.TableauError` (both :class:`~rkcheck.errors.RkcheckError`)."""
    from rkcheck.api.tableaux import as_tableau
    from rkcheck.energy.budget import Budget
    from rkcheck.io.machine import available_memory

    flags = check_flags(degree, order, dps, decimals, fail_fast, require)
    fail_on = _option(lambda: parse_choice(fail_on, FAIL_ON, "fail_on"))
    arithmetic = _option(lambda: parse_choice(arithmetic, ARITHMETIC, "arithmetic"))
    if max_conditions is not None:
        max_conditions = _option(lambda: parse_positive(max_conditions, "max_conditions"))
    project_check: dict[str, Any] = {}
    if project:
        from rkcheck.io.config import load_config

        config = load_config()
        project_check = config.check
        if fail_on == "auto" and config.fail_on:
            fail_on = config.fail_on
    tab = as_tableau(tableau)
    return run_check(tab, flags, project_check, fail_on, Budget(available_memory(), max_conditions, None),
                     None, arithmetic)
