"""Progress: one bar per check run, named, with its unit (primes, orders, files); a run's
bar never starts over."""

from __future__ import annotations

import os
import pty
import re
import subprocess
import sys

from support import reference as ref
from support.clirun import read_until_closed
from support.paths import REPO

from rkcheck.energy.claims import judge_tableau
from rkcheck.io.loader import load
from rkcheck.options import CheckOptions

RK4_CLAIMS = REPO / "docs" / "examples" / "ci" / "rk4-wrong.toml"  # claims for all H and for degree 2


class Recorder:
    def __init__(self):
        self.runs: list[tuple[str, str, list[tuple[int, int]]]] = []

    def begin(self, label, unit):
        self.runs.append((label, unit, []))

    def __call__(self, done, total):
        self.runs[-1][2].append((done, total))


def _runs(arithmetic):
    rec = Recorder()
    tab = load(str(RK4_CLAIMS))
    judge_tableau(tab, CheckOptions(degree=None, order=8, arithmetic=arithmetic), "auto", None, rec)
    return rec.runs


def test_one_bar_per_check_run_and_none_starts_over():
    # the main run (all H to order 8) covers the claim on all H (it needs order 5); the
    # claim on degree 2 needs a run of its own: two runs, each named by what it checks
    runs = _runs("exact")
    assert [label for label, _, _ in runs] == ["all H, order ≤ 8", "degree ≤ 2, order ≤ 8"]
    for _, unit, steps in runs:
        assert unit == "primes"  # a rational tableau: exact, one step per prime
        assert steps and len({t for _, t in steps}) == 1  # one total per bar
        done = [d for d, _ in steps]
        assert done == sorted(done) and done[-1] == steps[-1][1]  # forward only, to the end


def test_ball_runs_count_orders():
    # certified balls step over the orders 2 to 8 (trees with 3 to 9 vertices; order 1 has
    # only the superfluous edge, per the brute-force reference)
    assert ref.count_nonsuperfluous(2) == 0 and ref.count_nonsuperfluous(3) > 0
    runs = _runs("ball")
    assert len(runs) == 2
    for _, unit, steps in runs:
        assert unit == "orders" and steps[-1] == (7, 7)
        assert [d for d, _ in steps] == sorted(d for d, _ in steps)


def _stderr_on_a_terminal(*args: str) -> str:
    master, slave = pty.openpty()
    env = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "FORCE_COLOR")} | {"NO_COLOR": "1"}
    proc = subprocess.Popen([sys.executable, "-m", "rkcheck", *args], stdout=subprocess.DEVNULL, stderr=slave,
                            env=env, cwd=REPO)
    os.close(slave)
    output = read_until_closed(master)
    assert proc.wait(timeout=120) in (0, 1)
    return re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", output.decode(errors="replace"))


def test_the_terminal_shows_each_run_with_its_unit():
    text = _stderr_on_a_terminal("verify", str(RK4_CLAIMS))
    assert re.search(r"all H, order ≤ 8 .* (\d+)/\1 primes", text)
    assert re.search(r"degree ≤ 2, order ≤ 8 .* (\d+)/\1 primes", text)
    scan = _stderr_on_a_terminal("scan", str(RK4_CLAIMS.parent), "--jobs", "1")
    assert re.search(r"checking .* 2/2 files", scan)


def test_a_familys_long_computations_show_that_they_run(tmp_path):
    # a family's conditions, solve and sweep have no steps to count: a spinner with the
    # elapsed time says each is running (it printed nothing for minutes)
    family = REPO / "tableaux" / "families" / "sweep-s2-lobatto.toml"
    conditions = _stderr_on_a_terminal("verify", str(family), "--order", "5")
    assert "the conditions as polynomials in the parameters" in conditions
    solve = _stderr_on_a_terminal("solve", str(family), "--order", "3")
    assert "solving the family's conditions" in solve
    sweep = _stderr_on_a_terminal("sweep", str(family), "--grid", "beta=0:1:3", "--grid", "gamma=0:1:3")
    assert "the family's conditions over the grid" in sweep
