"""benchmarks/bench_exact.py runs against the current engine: order 6, RK4.  The trees it
counts are the rooted trees with at most 7 vertices (OEIS A000081: 1, 1, 2, 4, 9, 20, 48),
and the channels are the primes the bound of the top order asks for, computed here from
the bound of modular.py's docstring with RK4's scaled entries."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "bench_exact.py"


def test_order_6_row_counts_the_trees_and_the_primes():
    proc = subprocess.run([sys.executable, str(SCRIPT), "--orders", "6"], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)
    assert proc.returncode == 0, proc.stderr
    lines = [line for line in proc.stdout.splitlines() if line.startswith("|")]
    header = [h.strip() for h in lines[0].strip("|").split("|")]
    cells = dict(zip(header, (c.strip().replace("\u202f", "") for c in lines[2].strip("|").split("|"))))
    assert int(cells["trees"]) == 1 + 1 + 2 + 4 + 9 + 20 + 48
    # RK4 scaled by d = 6: Â has row sums ≤ 6 and b̂ = (1, 2, 2, 1): M = 6, a 3-bit bound per
    # vertex; the top order has 7 vertices, and a condition's coefficients 6!/σ(u), divided
    # by their gcd, sum to at most 7 (the rootings of one free tree: 6!/|Aut| times the
    # sizes of its vertex orbits, which sum to 7)
    bits = math.ceil(6 * 3 + math.log2(7)) + 2
    primes, total = 0, 0.0
    while total <= bits:  # the primes are the largest below 2^30, each just under 30 bits
        primes += 1
        total += 30 - 1e-7
    assert int(cells["channels"]) == primes
    assert float(cells["eval CPU s"]) >= 0 and float(cells["ns/tree·ch"]) > 0
