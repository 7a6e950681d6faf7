"""benchmarks/bench_engine.py runs against the current engine (it once imported removed
modules and nobody noticed): order 6, no degree bound, no start-up timing.  The counts it
prints are checked against the brute-force reference (tests/support/reference.py)."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

from support import reference as ref

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "bench_engine.py"


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True, cwd=ROOT, timeout=120)


def test_order_6_row_has_the_reference_counts_and_sane_measurements():
    started = time.monotonic()
    proc = run("--orders", "6", "--degrees", "none", "--startup-runs", "0", "--repeat", "1")
    elapsed = time.monotonic() - started
    assert proc.returncode == 0, proc.stderr
    lines = [line for line in proc.stdout.splitlines() if line.startswith("|")]
    header = [h.strip() for h in lines[0].strip("|").split("|")]
    cells = dict(zip(header, (c.strip().replace("\u202f", "") for c in lines[2].strip("|").split("|"))))
    # energy conditions to order 6: free trees with 3..7 vertices, superfluous ones removed
    conditions = [c for n in range(3, 8) for c in ref.energy_conditions(n)]
    assert (cells["order"], cells["m"]) == ("6", "none")
    assert int(cells["conditions"]) == len(conditions) == 20
    assert int(cells["terms"]) == sum(len(c["terms"]) for c in conditions)
    seconds = {k: float(cells[k]) for k in ("listing s", "exact s", "balls50 s", "float64 s", "check s")}
    # seconds, not another unit: no phase took longer than the whole run (however loaded
    # the machine, both clocks slow down together)
    assert all(0 <= v <= elapsed for v in seconds.values())
    # the ratio is printed from the unrounded times: it lies in the range the 3-decimal times allow
    balls, exact, half = seconds["balls50 s"], seconds["exact s"], 0.0005
    if exact > half:
        assert (balls - half) / (exact + half) - 0.005 <= float(cells["balls/exact"]) <= (balls + half) / (exact - half) + 0.005
    assert 20 < float(cells["check peak MB"]) <= float(cells["max peak MB"]) < 2000


def test_orders_beyond_20_are_refused_before_any_work():
    proc = run("--orders", "21", "--startup-runs", "0", "--repeat", "1")
    assert proc.returncode == 2 and "between 2 and 20" in proc.stderr


def test_the_fuzzer_runs_its_families_and_counts_every_run():
    # a handful of cases per family, each in its own forked process with a timeout
    proc = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "fuzz.py"), "--entries", "4", "--files", "3",
                           "--options", "3", "--importers", "3", "--timeout", "60"],
                          capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    rows = {line.split()[0]: [int(x) for x in line.split()[1:]] for line in proc.stdout.splitlines()
            if line.split()[:1] in (["entries"], ["files"], ["options"], ["importers"])}
    # columns: exit 0, 1, 2, 3, other, timeout, traceback; every case is counted once
    assert {k: sum(v[:6]) for k, v in rows.items()} == {"entries": 4, "files": 3, "options": 3, "importers": 3}
    assert all(v[3] == v[4] == v[5] == v[6] == 0 for v in rows.values())
