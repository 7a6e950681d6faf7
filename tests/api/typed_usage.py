"""What a typed notebook or script does with the public API; tests/api/test_typing.py
runs mypy over it (and over the package).  Not collected by pytest: no test_ prefix."""

from __future__ import annotations

from fractions import Fraction
from typing import Sequence

import rkcheck


def use() -> str:
    tab: rkcheck.Tableau = rkcheck.from_arrays([[0, 0], [Fraction(1, 2), 0]], [0, 1], name="midpoint")
    result: rkcheck.Verification = rkcheck.verify(tab, degree=4, order=6, dps=30)
    order: int = result.energy_order
    label: str = result.energy_order_label
    failures: Sequence[rkcheck.Condition] = result.failures
    first: rkcheck.Condition = failures[0]
    digits: int | None = first.digits
    trees: list[rkcheck.FreeTree] = rkcheck.free_trees(6, max_degree=3)
    cond: rkcheck.EnergyCondition = rkcheck.energy_condition(trees[0], tab)
    residual: Fraction | None = cond.residual
    names: list[str] = rkcheck.library()
    try:
        rkcheck.load("@nope")
    except rkcheck.RkcheckError as err:
        label += str(err)
    return f"{order}{label}{digits}{residual}{names[0]}" + result.to_json() + rkcheck.write(tab, "latex")


def use_commands() -> list[object]:
    """One function per command of the CLI, with the types a caller relies on."""
    gauss: rkcheck.Tableau = rkcheck.new("gauss", stages=2)
    text: str = rkcheck.new_toml("rk4", name="mine")
    scanned: rkcheck.ScanResult = rkcheck.scan(["tableaux"], order=4, jobs=1)
    rows: list[rkcheck.ScanRow] = scanned.rows
    checked: rkcheck.Verification | None = rows[0].verification
    cat: rkcheck.Catalog = rkcheck.catalog(degrees=[2, None], order=4)
    ker: rkcheck.Kernel = rkcheck.kernel(4, 2)
    rank: int = ker.rank
    sweep: rkcheck.Perturbation = rkcheck.perturb(gauss, "random", degree=4, eps=[Fraction(1, 100)])
    slope: float | None = sweep.slope
    timed: rkcheck.Bench = rkcheck.bench("@heun", order=4, dps=[15], repeat=1)
    drift: rkcheck.Simulation = rkcheck.simulate(gauss, rkcheck.hamiltonian("harmonic"), h=Fraction(1, 10))
    fit: rkcheck.EnergyOrderFit = rkcheck.empirical_energy_order("@rk4", "harmonic")
    measured: float | None = fit.empirical_order
    wp: rkcheck.WorkPrecision = rkcheck.work_precision(["@rk4", gauss], "harmonic", T=1, steps=[10, 20])
    listed: rkcheck.ConditionList = rkcheck.conditions(6, 3)
    counts: dict[int, int] = listed.counts
    return [text, checked, cat, rank, slope, timed, drift.max_energy_error, measured, wp.rows, counts]
