"""What a typed notebook or script does with the public API; tests/api/test_typing.py
runs mypy over it (and over rkcheck/api).  Not collected by pytest: no test_ prefix."""

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
