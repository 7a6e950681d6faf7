"""benchmarks/goals.py --quick runs every goal case against the current engine; the RK4
failures it reports at order 10 are the brute-force reference's count
(tests/support/reference.py), and each ratio is that of the figures printed beside it."""

from __future__ import annotations

import re
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest
from support import reference as ref

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "goals.py"

RK4_A = [[Fraction(0)] * 4, [Fraction(1, 2), 0, 0, 0], [0, Fraction(1, 2), 0, 0], [0, 0, Fraction(1), 0]]
RK4_B = [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)]


@pytest.mark.heavy
def test_quick_goals_report_every_case_with_the_reference_failures():
    proc = subprocess.run([sys.executable, str(SCRIPT), "--quick"], capture_output=True, text=True, cwd=ROOT,
                          timeout=900)
    assert proc.returncode == 0, proc.stderr
    rows = [[c.strip() for c in line.strip("|").split("|")] for line in proc.stdout.splitlines()
            if line.startswith("| ") and not line.startswith("| case")]
    cases = [r[0] for r in rows]
    assert [c.split(",")[0].split(" (")[0] for c in cases] == [
        "RK4 exact", "RK4 exact", "`--fail-fast` at order 10", "decimal RK4", "forced balls", "decimal RK4",
        "Gauss-3 exact", "`scan tableaux/collocation/`", "HBVM(6", "2 000 tableaux on a 2-worker LocalCluster"]
    assert all(r[3] == "—" for r in rows)  # no goal applies to the small orders of --quick

    A = [[Fraction(x) for x in row] for row in RK4_A]
    failing = sum(ref.energy_residual(c, A, RK4_B) != 0 for n in range(3, 12) for c in ref.energy_conditions(n))
    decimal = next(r for r in rows if r[0] == "decimal RK4, order 10")
    found, of = (int(x.replace("\u202f", "").replace(",", "")) for x in
                 re.match(r"([\d,\u202f]+) of ([\d,\u202f]+) failures found, 0 undecided", decimal[1]).groups())
    assert found == of == failing

    for r in rows:  # "x s against y s …: z×" (or "z of full"): z is x / y to the printed digits
        m = re.match(r"([\d.]+) s against ([\d.]+) s(?: exact)?: ([\d.]+)", r[1])
        if m:
            x, y, z = map(float, m.groups())
            assert abs(z - x / y) <= 0.01 * z + (0.006 + 0.0051 * z) / max(y, 0.01) + 0.001
