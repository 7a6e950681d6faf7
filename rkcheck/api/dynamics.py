"""Energy in practice: integrate polynomial Hamiltonians with a tableau and watch H —
drift over time and the empirical energy order (``rkcheck simulate``), error and energy
error against work (``rkcheck workprec``), for Python callers.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Sequence

from rkcheck.api.tableaux import TableauLike, as_tableau
from rkcheck.api.verification import _option
from rkcheck.dynamics.simulate import WorkPrecision
from rkcheck.errors import OptionError, UserError
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.formatting import exact_string
from rkcheck.options import (
    DEFAULT_MAX_STAGES,
    MAX_STAGES_RANGE,
    POINTS_RANGE,
    STEPS_RANGE,
    STUDY_DPS_RANGE,
    parse_int_in,
    parse_integer,
    parse_step_counts,
)

if TYPE_CHECKING:
    from rkcheck.dynamics.hamiltonians import Hamiltonian
    from rkcheck.dynamics.simulate import Agreement, EnergyFit

#: The step counts ``work_precision`` runs by default (step sizes T/N).
WORKPREC_STEPS: tuple[int, ...] = (20, 40, 80, 160, 320, 640)


def hamiltonian(spec: str) -> "Hamiltonian":
    """A polynomial Hamiltonian H(q, p) by name: ``harmonic`` (degree 2), ``henon-heiles``
    (3), ``quartic`` (4), ``fpu`` (4), or ``random:degree=m[,dim=d][,seed=S]`` (every
    monomial of degree ≤ m with a random coefficient k/8) — the ``--problem`` of
    ``rkcheck simulate`` and ``workprec``.  Its ``degree`` is the m of definitions §3."""
    from rkcheck.dynamics.hamiltonians import problem

    if not isinstance(spec, str):
        raise OptionError(f"expected a problem name, got {spec!r}", "--problem")
    return _option(lambda: problem(spec))


def _problem(problem: "str | Hamiltonian") -> "Hamiltonian":
    from rkcheck.dynamics.hamiltonians import Hamiltonian

    if isinstance(problem, str):
        return hamiltonian(problem)
    if not isinstance(problem, Hamiltonian):
        raise OptionError(f"expected a problem's name (\"henon-heiles\", \"random:degree=4\") or a Hamiltonian, "
                          f"got {type(problem).__name__}", "problem")
    return problem


def _rational(value: Any, place: str) -> Fraction:
    """A positive rational number (``"1/100"``, ``"0.1"``, 10, ``Fraction(1, 16)``), as the
    CLI's ``--h`` and ``--T`` read it."""
    from rkcheck.numbers.entries import Entry

    if isinstance(value, Fraction) or (isinstance(value, int) and not isinstance(value, bool)):
        from rkcheck.numbers.grammar import fraction_text

        value = fraction_text(value)  # at any length
    if not isinstance(value, str):
        raise OptionError(f"expected a positive rational number, got {value!r}", place)
    try:
        e = Entry.parse(value)
    except UserError as err:
        raise err.located(place) from None
    if e.exact is None or e.exact <= 0:
        raise OptionError(f"expected a positive rational number, got {value!r}", place)
    return Fraction(e.exact)


# ------------------------------------------------------------------ simulate


@dataclass(frozen=True)
class Simulation:
    """What :func:`simulate` gives: the energy error ``|H(y_n) − H(y_0)|`` at about 200
    recorded times (floats), for one tableau, problem, step size and precision."""

    tableau: Tableau
    problem: "Hamiltonian"
    h: Fraction
    steps: int
    dps: int | None
    times: list[float]
    energy_errors: list[float]

    @property
    def max_energy_error(self) -> float:
        return max(self.energy_errors)

    def __repr__(self) -> str:
        from rkcheck.numbers.formatting import count_text

        return (f"<Simulation of {self.tableau.name!r} on {self.problem.name}: h = {self.h}, {count_text(self.steps)} steps, "
                f"max |ΔH| = {self.max_energy_error:.3e}>")


def simulate(tableau: TableauLike, problem: "str | Hamiltonian", *, h: str | int | Fraction = "1/10",
             steps: int = 1000, dps: int | None = None) -> Simulation:
    """Integrate ``problem`` (:func:`hamiltonian` names it) with ``tableau`` for ``steps``
    steps of size ``h`` (a positive rational) from the problem's fixed starting point, in
    float64 (``dps=None``) or mpmath at ``dps`` digits, and record ``|H(y_n) − H(y_0)|``:
    ``rkcheck simulate`` without ``--energy-order``.  Implicit stages are solved by
    Newton's method; a run that diverges or a Newton failure raises a
    :class:`~rkcheck.errors.UserError` naming the tableau's source."""
    from rkcheck.dynamics.simulate import energy_series, start_point

    ham = _problem(problem)
    tab = as_tableau(tableau)
    h_value = _rational(h, "--h")
    steps = _option(lambda: parse_int_in(steps, STEPS_RANGE, "steps"))
    if dps is not None:
        dps = _option(lambda: parse_int_in(dps, STUDY_DPS_RANGE, "dps"))
    try:
        times, errors = energy_series(tab, ham, start_point(ham), h_value, steps, dps)
    except UserError as err:  # diverged, Newton failed: say which tableau
        raise err.located(source=tab.info.source) from None
    return Simulation(tab, ham, h_value, steps, dps, times, errors)


@dataclass(frozen=True)
class EnergyOrderFit:
    """What :func:`empirical_energy_order` gives: |ΔH| after one step per step size h
    (``fit.rows``), the fitted slope and empirical energy order (slope − 1), or
    ``at_solver_precision`` when ΔH never rises above the solver's precision; and the
    comparison with verify's algebraic energy order for the problem's degree."""

    tableau: Tableau
    problem: "Hamiltonian"
    fit: "EnergyFit"
    agreement: "Agreement"

    @property
    def empirical_order(self) -> float | None:
        return self.fit.empirical_order

    @property
    def at_solver_precision(self) -> bool:
        return self.fit.at_solver_precision

    @property
    def algebraic_order(self) -> str:
        """verify's energy order for the problem's degree: ``all``, ``≥ N`` or ``n``."""
        return self.agreement.algebraic

    @property
    def agree(self) -> bool:
        return self.agreement.agree

    @property
    def message(self) -> str:
        return self.agreement.message

    def __repr__(self) -> str:
        return f"<EnergyOrderFit of {self.tableau.name!r} on {self.problem.name}: {self.message}>"


def empirical_energy_order(tableau: TableauLike, problem: "str | Hamiltonian", *, dps: int | None = None,
                           points: int = 4, seed: int = 7) -> EnergyOrderFit:
    """The energy order measured: one step from ``points`` random points (``seed``) at
    h = 2⁻³ … 2⁻¹⁰ in mpmath; the slope of log|ΔH| against log h is n + 1 for energy
    order n (``H(y₁) − H(y₀) = O(h^(n+1))``, definitions §3), fitted on the asymptotic
    small steps — compared with verify's algebraic energy order for the problem's degree
    (they agree when they round to the same integer, or both say the energy is
    preserved): ``rkcheck simulate --energy-order``.  The precision is 40 digits, or
    more when the first failing residual is too small to be seen in one step, or
    ``dps`` if larger."""
    from rkcheck.dynamics.simulate import energy_order_agreement

    ham = _problem(problem)
    tab = as_tableau(tableau)
    if dps is not None:
        dps = _option(lambda: parse_int_in(dps, STUDY_DPS_RANGE, "dps"))
    points = _option(lambda: parse_int_in(points, POINTS_RANGE, "points"))
    seed = _option(lambda: parse_integer(seed, "seed"))
    fit, agreement = energy_order_agreement(tab, ham, dps=dps, points=points, seed=seed)
    return EnergyOrderFit(tab, ham, fit, agreement)


# ------------------------------------------------------------------ work–precision


def work_precision(tableaux: Sequence[TableauLike], problem: "str | Hamiltonian", *, T: str | int | Fraction = 10,
                   steps: str | Sequence[int] = WORKPREC_STEPS, max_stages: int = DEFAULT_MAX_STAGES) -> WorkPrecision:
    """Work against precision, as ``rkcheck workprec`` measures it: each tableau runs in
    float64 to time ``T`` (a positive rational) with each number of ``steps`` (step size
    T/N); the error at T is measured against a reference solution by 6-stage Gauss
    collocation (order 12) at 20 digits, the energy error is max |H(y_n) − H(y_0)|.
    Paths and ``"@name"`` are loaded with ``max_stages``."""
    from rkcheck.dynamics.simulate import work_precision as run

    ham = _problem(problem)
    T_value = _rational(T, "--T")
    counts = _option(lambda: parse_step_counts(steps))
    max_stages = _option(lambda: parse_int_in(max_stages, MAX_STAGES_RANGE, "max_stages"))
    if isinstance(tableaux, (str, os.PathLike, Tableau)) or not isinstance(tableaux, (list, tuple)):
        raise OptionError("expected a list of tableaux", "tableaux")
    if not T_value <= MAX_TIME:
        raise OptionError(f"expected a final time up to {MAX_TIME:,}, got {exact_string(T_value)}", "--T")
    tabs = [as_tableau(t, max_stages) for t in tableaux]
    return run(tabs, ham, T_value, counts)


#: ``workprec --T``: the longest final time (its steps, T/N, must stay floats)
MAX_TIME = 10**6



__all__ = ["EnergyOrderFit", "Simulation", "WorkPrecision", "empirical_energy_order", "hamiltonian", "simulate", "work_precision"]