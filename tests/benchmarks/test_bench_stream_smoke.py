"""benchmarks/bench_stream.py runs against the current engine: order 8, every case.  The
cases check the same tableau in different ways, so their results must agree: the full
runs report the same failing conditions whatever the cache, and fail-fast stops after
the first order (explicit Euler fails at 3 vertices: definitions §3, Σ b_i c_i = 1/2)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "bench_stream.py"


def test_order_8_cases_agree():
    proc = subprocess.run([sys.executable, str(SCRIPT), "--orders", "8"], capture_output=True, text=True, cwd=ROOT,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    lines = [line for line in proc.stdout.splitlines() if line.startswith("| 8 ")]
    header = [h.strip() for h in next(l for l in proc.stdout.splitlines() if l.startswith("| order")).strip("|").split("|")]
    rows = {r["case"]: r for r in (dict(zip(header, (c.strip() for c in line.strip("|").split("|")))) for line in lines)}
    assert set(rows) == {"full, fails at 2", "fail-fast, fails at 2", "RK4 no cache", "RK4 cold cache", "RK4 warm cache"}
    assert rows["fail-fast, fails at 2"]["orders checked"] == "1"
    assert rows["full, fails at 2"]["orders checked"] == "7"  # energy orders 2 … 8
    rk4 = {rows[c]["failing"] for c in ("RK4 no cache", "RK4 cold cache", "RK4 warm cache")}
    assert len(rk4) == 1 and int(rk4.pop().replace(",", "")) > 0  # RK4 fails from 6 vertices on
    for r in rows.values():
        assert 0 <= float(r["check CPU s"]) <= float(r["process CPU s"])
        assert 10 < float(r["peak MB"]) < 2000
