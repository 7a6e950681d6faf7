"""benchmarks/bench_arith.py runs against the current engine: order 6, the exact and the
decimal RK4 cases; the condition count it prints is the brute-force reference's
(tests/support/reference.py) and its ratio is that of its own CPU columns."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from support import reference as ref

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "bench_arith.py"


def test_order_6_rows_have_the_reference_count_and_consistent_ratios():
    proc = subprocess.run([sys.executable, str(SCRIPT), "--orders", "6", "--cases", "rk4-exact", "rk4-decimal"],
                          capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    lines = [line for line in proc.stdout.splitlines() if line.startswith("|")]
    header = [h.strip() for h in lines[0].strip("|").split("|")]
    rows = [dict(zip(header, (c.strip() for c in line.strip("|").split("|")))) for line in lines[2:]]
    assert [r["case"] for r in rows] == ["rk4-exact", "rk4-decimal"]
    conditions = sum(len(ref.energy_conditions(n)) for n in range(3, 8))
    assert all(int(r["conditions"]) == conditions == 20 for r in rows)
    exact, decimal = (float(r["CPU s"]) for r in rows)
    assert exact >= 0 and decimal >= 0
    if exact >= 0.05:  # the ratio is printed from unrounded times: within the rounding of both
        assert abs(float(rows[1]["CPU / exact"]) - decimal / exact) <= 0.01 + 0.01 * decimal / exact
    assert rows[0]["ns per term·channel"] and not rows[1]["ns per term·channel"]  # exact only
