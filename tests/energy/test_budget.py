"""The resource guard: estimates from exact counts, refusals before any work."""

from __future__ import annotations

import re

import pytest
from support.clirun import run_cli
from support.limits import run_limited
from support.paths import TABLEAUX

from rkcheck.energy.budget import Budget, ResourceError, check_budget, estimate
from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load

# order 24 in a child under 300 MB and 10 CPU seconds: listing its 167 871 332 conditions
# alone would take about 100 GB, so the child can only answer by refusing before any work
ORDER_24 = """
import sys
from rkcheck.energy.budget import Budget, ResourceError
from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load
budget = Budget(available_bytes=24 * 2**30) if sys.argv[2] == "budget" else None
try:
    check(load(sys.argv[1]), CheckOptions(order=24), budget=budget)
except ResourceError as err:
    print(err)
"""


def test_order_24_is_refused_before_any_work():
    run = run_limited(["-c", ORDER_24, str(TABLEAUX / "explicit" / "rk4.toml"), "budget"], memory_mb=300, cpu_seconds=10)
    assert run.code == 0, run.err
    assert re.fullmatch(r"order 24 needs about [0-9.]+ GB for 167,871,332 conditions but 25\.8 GB is available; .*\n",
                        run.out), run.out


def test_without_a_budget_order_24_does_not_fit_the_same_limits():
    # the control: the limits above do stop a check that starts working
    run = run_limited(["-c", ORDER_24, str(TABLEAUX / "explicit" / "rk4.toml"), "none"], memory_mb=300, cpu_seconds=10)
    assert run.code != 0 and run.out == ""
    assert run.killed or "MemoryError" in run.err or "Unable to allocate" in run.err, run.err


def test_max_conditions_refuses_and_overrides_the_memory_check():
    tab = load(str(TABLEAUX / "explicit" / "rk4.toml"))
    with pytest.raises(ResourceError, match="80,936 conditions, above --max-conditions 1000"):
        check(tab, CheckOptions(order=16), budget=Budget(max_conditions=1000))
    # an explicit limit replaces the memory check: tiny memory, large limit, runs
    res = check(tab, CheckOptions(order=6), budget=Budget(available_bytes=1, max_conditions=100))
    assert res.energy_order == 4


def test_long_checks_are_announced_and_short_ones_are_not():
    said = []
    est = estimate(20, None, "exact", 16)
    check_budget(est, Budget(announce=said.append), 20)
    assert said and "3,489,323 conditions" in said[0]
    said.clear()
    check_budget(estimate(8, None, "exact", 5), Budget(announce=said.append), 8)
    assert said == []


def test_cli_refusal_is_one_line_exit_2(capsys):
    r = run_cli(capsys, "verify", str(TABLEAUX / "explicit" / "rk4.toml"), "--order", "16", "--max-conditions", "10")
    assert r.code == 2 and len(r.err.strip().splitlines()) == 1
    assert "--max-conditions" in r.err
