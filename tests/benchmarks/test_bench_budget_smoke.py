"""benchmarks/bench_budget.py runs against the current engine (its quick orders) and
finds the estimates on the high side there: each check's peak memory, read by the
kernel for the child, is below what the check estimated for itself — also for the
continuous methods checked through surrogates of a hundred stages and more, whose
images of A in every channel a model blind to the stages missed (147 MB against 84),
and for a kernel in rounded decimals, whose entries the box encloses and differentiates
first (128 MB against 100 when they were left out)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "bench_budget.py"


def test_every_case_runs_within_its_estimate():
    proc = subprocess.run([sys.executable, str(SCRIPT), "--quick"], capture_output=True, text=True, cwd=ROOT,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr
    lines = [line for line in proc.stdout.splitlines() if line.startswith("|")]
    header = [h.strip() for h in lines[0].strip("|").split("|")]
    rows = [dict(zip(header, (c.strip() for c in line.strip("|").split("|")))) for line in lines[2:]]
    assert {r["method"] for r in rows} >= {"RK4", "AVF Gauss-3", "HBVM(6, 2), 60-digit decimals", "M = I_20",
                                           "degree-20 kernel, 6-digit decimals"}
    assert all(r["order"] == "8" for r in rows if not r["method"].startswith("M = I_") and "kernel" not in r["method"])
    for r in rows:
        assert float(r["peak MB"]) < float(r["estimated MB"]), r
