"""benchmarks/report.py runs against the current engine and its table says what the
independent reference says: the number of conditions and of failing ones per order."""

from __future__ import annotations

import subprocess
import sys
from fractions import Fraction
from pathlib import Path

from support import reference as ref

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "report.py"

RK4_A = [[Fraction(0)] * 4, [Fraction(1, 2), 0, 0, 0], [0, Fraction(1, 2), 0, 0], [0, 0, Fraction(1), 0]]
RK4_B = [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)]


def table(stdout: str) -> list[dict[str, str]]:
    lines = [line for line in stdout.splitlines() if line.startswith("|")]
    header = [h.strip() for h in lines[0].strip("|").split("|")]
    return [dict(zip(header, (c.strip().replace("\u202f", "") for c in line.strip("|").split("|")))) for line in lines[2:]]


def test_orders_4_and_6_agree_with_the_reference(tmp_path):
    out = tmp_path / "report.md"
    proc = subprocess.run([sys.executable, str(SCRIPT), "--min-order", "4", "--max-order", "6", "--reference-max-order",
                           "6", "-o", str(out)], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    rows = table(proc.stdout)
    assert out.read_text(encoding="utf-8").strip() in proc.stdout  # -o writes what is printed
    series = {(r["method"], r["arithmetic"]) for r in rows}
    assert series == {("RK4", a) for a in ("exact", "ball", "decimal box", "reference (direct Python)")} | {
        ("Gauss-3", a) for a in ("exact", "ball", "decimal box")}
    for order in (4, 6):
        conditions = [c for n in range(3, order + 2) for c in ref.energy_conditions(n)]
        failing = sum(ref.energy_residual(c, RK4_A, RK4_B) != 0 for c in conditions)
        at = [r for r in rows if r["order"] == str(order)]
        assert {int(r["conditions"]) for r in at} == {len(conditions)}
        # RK4 has energy order 4 (the conditions at 6 vertices fail); Gauss-3 has 6
        assert {int(r["failing"]) for r in at if r["method"] == "RK4"} == {failing}
        assert {int(r["failing"]) for r in at if r["method"] == "Gauss-3"} == {0}
        assert all(float(r["CPU s"]) >= 0 and 10 < float(r["peak MB"]) < 4000 for r in at)
    assert failing > 0
