"""benchmarks/bench_centroid.py: its route agrees with the engine condition by condition
(the script's ``--check`` asserts every residue), and the conditions it enumerates by
centroid are as many as SPEC §3 counts (non-superfluous free trees with 3…12 vertices:
1, 1, 3, 4, 11, 19, 47, 97, 235, 531)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "bench_centroid.py"


def run(*args: str) -> str:
    proc = subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def test_every_condition_agrees_with_the_engine_rk4_and_a_dense_tableau():
    assert "11 vertices:    235 conditions agree" in run("--check", "11")
    assert "10 vertices:     97 conditions agree" in run("--check", "10", "--dense")


def test_the_centroid_enumeration_counts_the_non_superfluous_free_trees():
    out = run("--vertices", "12", "--primes", "2")
    counts = [int(x) for x in re.findall(r"vertices: .*?, (\d+) conditions", out)]
    assert counts == [1, 1, 3, 4, 11, 19, 47, 97, 235, 531]
    # RK4 has energy order 4: the conditions with 3, 4, 5 vertices hold, one with 6 fails
    nonzero = [int(x) for x in re.findall(r"(\d+) nonzero at some prime", out)]
    assert nonzero[:3] == [0, 0, 0] and nonzero[3] > 0
