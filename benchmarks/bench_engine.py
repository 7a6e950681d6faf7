"""The performance table: energy checks to order 16, one command.

    python benchmarks/bench_engine.py                 # orders 10 12 14 16, degrees none/3/4
    python benchmarks/bench_engine.py --orders 10 12  # a quicker subset

Every measurement runs in a fresh Python process (so that tables are really built and
the peak memory is that order's own), timed inside the process: interpreter start-up is
excluded.  Tableaux (fixed entries):

* exact   — a dense rational 4-stage implicit tableau;
* balls   — the same entries written ``x + sqrt(2) - sqrt(2)``: algebraic, so checked in
            certified ball arithmetic at dps 50 (identical values, comparable work);
* float64 — the float64 screen on the algebraic tableau.

Columns: ``tables`` = rooted trees, free trees, rootings and the flattened term arrays
(built once per (order, degree) and shared by every file of a scan); the backend columns
are the evaluation of every condition given those tables; ``total exact`` is what
``check()`` costs from nothing once the modules are imported.  Module imports (numpy,
mpmath) are start-up cost: the last line times ``rkcheck verify`` from process start to
exit, imports included.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

A_DENSE = [
    ["1/7", "-2/9", "3/11", "1/13"],
    ["2/5", "1/8", "-1/6", "3/10"],
    ["-1/12", "5/9", "1/4", "2/15"],
    ["3/8", "1/3", "-2/7", "1/5"],
]
B_DENSE = ["1/5", "3/10", "1/4", "1/4"]

CHILD = r"""
import gc, json, resource, sys, time
sys.path.insert(0, {root!r})
import numpy, mpmath  # imports are start-up, timed separately (last line of the table)
from rkcheck.methods.tableau import Tableau
from rkcheck.trees.conditions import ConditionTable
from rkcheck.energy.check import evaluate_conditions
from rkcheck.studies.accuracy import backend_for
A, B = {A!r}, {B!r}
order, degree, repeat = {order!r}, {degree!r}, {repeat!r}
rational = Tableau.from_values(A, B)
algebraic = Tableau.from_values([[x + " + sqrt(2) - sqrt(2)" for x in row] for row in A], B)
t0 = time.perf_counter()
table = ConditionTable(order, degree)
table.term_arrays
t_tables = time.perf_counter() - t0
out = {{"conditions": len(table), "tables": t_tables}}
for name, tab, key in [("exact", rational, "exact"), ("dps:50", algebraic, "balls"), ("float64", algebraic, "float64")]:
    best = 1e9
    for _ in range(repeat):
        gc.collect()
        backend = backend_for(tab, name)
        t1 = time.perf_counter()
        evaluate_conditions(table, backend)
        best = min(best, time.perf_counter() - t1)
    out[key] = best
out["rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps(out))
"""


def measure(order: int, degree: int | None, repeat: int) -> dict:
    code = CHILD.format(root=str(ROOT), A=A_DENSE, B=B_DENSE, order=order, degree=degree, repeat=repeat)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def startup() -> float:
    env = dict(os.environ, NO_COLOR="1")
    best = 1e9
    for _ in range(5):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "rkcheck", "verify", "tableaux/explicit/rk4.toml", "-q"],
                       cwd=ROOT, env=env, capture_output=True)
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--orders", type=int, nargs="+", default=[10, 12, 14, 16])
    parser.add_argument("--degrees", nargs="+", default=["none", "3", "4"])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"{'order':>5} {'m':>4} {'conditions':>10} {'tables s':>9} {'exact s':>8} {'balls50 s':>9} "
          f"{'float64 s':>9} {'total exact s':>13} {'balls/exact':>11} {'dps50/float':>11} {'peak MB':>8}")
    for order in args.orders:
        for deg_text in args.degrees:
            degree = None if deg_text == "none" else int(deg_text)
            repeat = 1 if order >= 16 else args.repeat
            r = measure(order, degree, repeat)
            print(f"{order:>5} {deg_text:>4} {r['conditions']:>10} {r['tables']:>9.3f} {r['exact']:>8.3f} "
                  f"{r['balls']:>9.3f} {r['float64']:>9.3f} {r['tables'] + r['exact']:>13.3f} "
                  f"{r['balls'] / r['exact']:>11.2f} {r['balls'] / r['float64']:>11.1f} {r['rss_mb']:>8.0f}",
                  flush=True)
    print(f"rkcheck verify tableaux/explicit/rk4.toml, process start to exit: {startup():.3f} s")


if __name__ == "__main__":
    main()
