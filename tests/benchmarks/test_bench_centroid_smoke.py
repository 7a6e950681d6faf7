"""benchmarks/bench_centroid.py runs against the current engine: its rows count the
non-superfluous free trees of SPEC §3 (3 … 12 vertices: 1, 1, 3, 4, 11, 19, 47, 97, 235,
531), and RK4, of energy order 4, has no failing condition below 6 vertices and some at 6."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "bench_centroid.py"


def test_rows_count_the_conditions_and_rk4s_failures():
    proc = subprocess.run([sys.executable, str(SCRIPT), "--vertices", "12", "--primes", "2"], capture_output=True,
                          text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    rows = re.findall(r"^\| (\d+) \| ([\d,]+) \| ([\d,]+) \|", proc.stdout, re.M)
    assert [int(c.replace(",", "")) for _, c, _ in rows] == [1, 1, 3, 4, 11, 19, 47, 97, 235, 531]
    failing = [int(f.replace(",", "")) for _, _, f in rows]
    assert failing[:3] == [0, 0, 0] and failing[3] > 0
