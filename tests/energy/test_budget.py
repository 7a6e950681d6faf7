"""The resource guard: estimates from exact counts, refusals before any work."""

from __future__ import annotations

import re

import pytest
from support.clirun import run_cli
from support.counts import conditions_with
from support.limits import run_limited
from support.paths import TABLEAUX

from rkcheck.energy.budget import Budget, ResourceError, check_budget, estimate
from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load

# order 25 in a child under 300 MB and 10 CPU seconds: its 447 652 296 conditions take
# some 40 GB even enumerated by centroid (their residues and records alone), so the child
# can only answer by refusing before any work
ORDER_25 = """
import sys
from rkcheck.energy.budget import Budget, ResourceError
from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load
budget = Budget(available_bytes=24 * 2**30) if sys.argv[2] == "budget" else None
try:
    check(load(sys.argv[1]), CheckOptions(order=25), budget=budget)
except ResourceError as err:
    print(err)
"""


def test_order_25_is_refused_before_any_work():
    run = run_limited(["-c", ORDER_25, str(TABLEAUX / "explicit" / "rk4.toml"), "budget"], memory_mb=300, cpu_seconds=10)
    assert run.code == 0, run.err
    assert re.fullmatch(r"order 25 needs about [0-9.]+ GB more for 447,652,296 conditions but 25\.8 GB is available; .*\n",
                        run.out), run.out


def test_without_a_budget_order_25_does_not_fit_the_same_limits():
    # the control: the limits above do stop a check that starts working
    run = run_limited(["-c", ORDER_25, str(TABLEAUX / "explicit" / "rk4.toml"), "none"], memory_mb=300, cpu_seconds=10)
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


def test_an_address_space_limit_is_memory_the_check_cannot_have():
    # under ulimit -v 1 GB order 20 (about 2 GB) is refused before any work, naming what
    # is available under the limit, and no more than the limit itself
    r = run_limited(["-m", "rkcheck", "verify", "@rk4", "--order", "20", "--no-cache"], memory_mb=1024, cpu_seconds=60)
    assert r.code == 2 and len(r.err.strip().splitlines()) == 1, r.err
    found = re.search(r"order 20 needs about ([\d.]+) GB more for [\d,]+ conditions but (\d+) MB is available", r.err)
    assert found and float(found.group(1)) > 1 and int(found.group(2)) < 1024, r.err


def test_too_little_memory_to_load_the_libraries_is_out_of_memory_not_a_bug():
    # under 45 MB of address space numpy's shared objects cannot be mapped: the machine's
    # limit, said in one line with exit 2
    r = run_limited(["-m", "rkcheck", "verify", "@rk4", "--order", "6"], memory_mb=45, cpu_seconds=60)
    assert r.code == 2, r.err
    assert r.err.strip().splitlines() == ["rkcheck: error: out of memory: the memory limit (ulimit -v) leaves too "
                                          "little to load numpy; raise it (docs/errors.md)"]


def test_a_small_check_runs_in_the_memory_left_once_rkcheck_has_started():
    # under 140 MB of address space about 30 MB are left after start-up: RK4 at order 8
    # takes a few of them, but its estimate counted the 80 MiB the started process already
    # holds, and it was refused ("needs about 84 MB … but 33 MB is available")
    r = run_limited(["-m", "rkcheck", "verify", "@rk4", "--order", "8", "--no-cache"], memory_mb=140, cpu_seconds=60)
    assert r.code == 0, r.err
    # every condition of order ≤ 8 checked (free trees of 3 … 9 vertices, OEIS A000055),
    # and RK4's energy order is its classical order, 4
    last = r.out.strip().splitlines()[-1]
    assert f"of {sum(conditions_with(n) for n in range(3, 10))} conditions fail; energy order 4)" in last, last


@pytest.mark.parametrize("memory_mb", [60, 80, 100, 120])
def test_a_memory_limit_too_small_to_start_is_one_line_and_exit_2(memory_mb):
    # numpy's OpenBLAS, short of memory for its buffers while numpy loads (under about
    # 90 MB of address space here), ended the process with its own line and exit 1 —
    # the exit code of a failing method, which a CI gate would have read as a verdict
    r = run_limited(["-m", "rkcheck", "verify", "@rk4", "--order", "4"], memory_mb=memory_mb, cpu_seconds=60)
    assert r.code in (0, 2), (r.code, r.err)
    if r.code == 2:
        assert len(r.err.strip().splitlines()) == 1 and r.err.startswith("rkcheck: error: "), r.err


def test_ball_memory_grows_with_precision_and_stages():
    # wider mid-points and more stage values per stored weight take more bytes
    base = estimate(18, None, "ball", stages=3, dps=50).bytes
    assert estimate(18, None, "ball", stages=3, dps=300).bytes > base
    assert estimate(18, None, "ball", stages=6, dps=50).bytes > base
    # and never less than the exact check's listing, which the balls read as well
    assert base > estimate(18, None, "exact", 3).bytes


def test_forced_balls_at_order_20_are_not_refused_where_they_fit():
    # benchmarks/bench_budget.py --order-20: the worst case (a 3-stage method whose
    # conditions hold, every one evaluated in balls) peaks at 4.8 GB; an estimate above
    # 8 GB refused it on a machine with 8 GB free (the earlier model said 11.8 GB)
    est = estimate(20, None, "ball", stages=3, dps=50)
    check_budget(est, Budget(available_bytes=8 * 10**9), 20)
    assert 4.8e9 < est.bytes < 8e9


def test_a_decimal_box_counts_its_directions():
    # each interval entry is a direction of derivatives carried beside every stored weight
    plain = estimate(16, None, "ball", stages=6, dps=70)
    box = estimate(16, None, "ball", stages=6, dps=70, directions=42)
    assert box.bytes > plain.bytes and box.seconds > plain.seconds
    # one pass of derivatives takes at most MAX_GRADIENT_BYTES: more directions, more passes
    from rkcheck.evaluation.slopes import MAX_GRADIENT_BYTES

    huge = estimate(20, None, "ball", stages=6, dps=70, directions=10**6)
    assert abs(huge.bytes - estimate(20, None, "ball", stages=6, dps=70).bytes - MAX_GRADIENT_BYTES) <= 1


def test_a_refusal_the_claims_cause_names_them(capsys):
    # at degree 2, order 30 has 15 conditions; the file's claims at degree 4 are what
    # does not fit, and the message says so instead of blaming --degree
    import rkcheck

    degrees = {c.degree for c in rkcheck.load("@gauss-2").info.claims if c.kind == "energy_order"}
    assert 4 in degrees
    r = run_cli(capsys, "verify", "@gauss-2", "--order", "30", "--degree", "2", "-q", "--fail-on", "conditions")
    assert r.code == 2 and r.err.count("\n") == 1, r.err
    assert "[expect] claims for degree 4 are checked to order 30" in r.err and "or --degree" not in r.err
    assert run_cli(capsys, "verify", "@gauss-2", "--order", "30", "--degree", "2", "-q").code == 2


@pytest.mark.parametrize("remedy", [Budget().remedy, "lower --order or --degrees"], ids=["verify", "catalog"])
def test_a_refusal_the_claims_cause_drops_the_degree_from_any_remedy(remedy):
    # lowering the degree of the command cannot help a claim that names its own degree;
    # catalog's words ("--degrees") lost the option and kept its "s" ("lower --orders")
    from rkcheck.energy.budget import Estimate
    from rkcheck.energy.claims import _claim_run

    def refuse(tableau, options):
        check_budget(Estimate(1, 1, 1, 0.0, 2**40), Budget(available_bytes=2**30, remedy=remedy), options.order)

    with pytest.raises(ResourceError) as err:
        _claim_run(refuse, load(str(TABLEAUX / "explicit" / "rk4.toml")), CheckOptions(order=30, degree=4),
                   CheckOptions(order=30, degree=2))
    message = str(err.value)
    assert "the file's [expect] claims for degree 4 are checked to order 30 too: " in message, message
    assert "; lower --order" in message and "--degree" not in message and "--orders" not in message
