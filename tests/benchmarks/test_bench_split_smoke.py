"""benchmarks/bench_split.py runs against the current engine: a small order, local processes
only; it compares the reports of the runs itself (a disagreement exits non-zero)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_the_split_benchmark_prints_one_row_per_way_and_the_runs_agree():
    proc = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_split.py"), "--order", "8"],
                          capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    rows = [line.strip("|").split("|") for line in proc.stdout.splitlines() if line.startswith("| --jobs")]
    assert [r[0].strip() for r in rows] == ["--jobs 1", "--jobs 2"]
    for _, wall, speedup, cpu, peak in rows:
        assert float(wall) > 0 and float(cpu) > 0 and 20 < float(peak) < 2000
        # printed from the unrounded times: within what the 2-decimal times allow
        base, own, half = float(rows[0][1]), float(wall), 0.005
        assert (base - half) / (own + half) - 0.005 <= float(speedup.strip().rstrip("×")) <= (base + half) / (own - half) + 0.005
