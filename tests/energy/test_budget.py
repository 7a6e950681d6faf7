"""The resource guard: estimates from exact counts, refusals before any work."""

from __future__ import annotations

import time

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

from rkcheck.energy.budget import Budget, ResourceError, check_budget, estimate
from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load


def test_order_24_is_refused_in_well_under_a_second():
    tab = load(str(TABLEAUX / "explicit" / "rk4.toml"))
    t0 = time.perf_counter()
    with pytest.raises(ResourceError, match="order 24 needs about .* for 167,871,332 conditions"):
        check(tab, CheckOptions(order=24), budget=Budget(available_bytes=24 * 2**30))
    assert time.perf_counter() - t0 < 0.5


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
