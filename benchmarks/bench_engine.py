"""The performance table of the condition engine, one command.

    python benchmarks/bench_engine.py                       # orders 10 12 14 16, degrees none/3
    python benchmarks/bench_engine.py --orders 18 20        # up to order 20 (minutes, GBs)
    python benchmarks/bench_engine.py --orders 10 --degrees none --startup-runs 1

The tableau is a dense rational 4-stage implicit tableau (fixed entries, below).  Every
measurement runs in a fresh Python process, timed inside it (interpreter start-up and
module imports excluded) and with that process's own peak resident memory
(``resource.getrusage(RUSAGE_SELF).ru_maxrss``):

* listing  — ``condition_listing(order, degree)``: free trees, rootings, term arrays;
* exact    — ``evaluate(listing, TableauValues(tableau, Reading(arithmetic="exact")))``: residues modulo primes,
             given the listing (built first, not timed);
* balls    — the same with ``arithmetic="ball"`` at 50 digits: certified balls;
* float64  — the float screen (``float_context`` + ``condition_sums``);
* check    — ``energy.check.check`` from nothing (listing, evaluation, verdicts, orders):
             what a ``verify`` costs after start-up.

Columns: conditions and terms (rootings summed over the listing: the floor of the work),
seconds for each measurement (the best of ``--repeat`` processes below order 16),
balls/exact, ns per term of the exact evaluation, the peak memory of the ``check``
process (what a ``verify`` needs) and the largest peak of all five (the balls, as a rule).  The last lines time ``rkcheck verify
tableaux/explicit/rk4.toml`` and ``rkcheck --help`` (as ``python -m rkcheck`` from this
checkout) from process start to exit, best and median of ``--startup-runs`` (default 9),
interleaved with ``python -c pass`` and ``python -c "import numpy"`` for scale.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
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

MEASUREMENTS = ("listing", "exact", "balls", "float64", "check")

# One measurement per process: the listing is cached per (order, degree) inside a
# process, so two measurements in one process would share it and the second's memory.
CHILD = r"""
import gc, json, resource, sys, time
sys.path.insert(0, {root!r})
import numpy, mpmath  # start-up, not timed here
from rkcheck.methods.tableau import Tableau
from rkcheck.trees.listing import condition_listing
from rkcheck.evaluation.backends import evaluate, float_context
from rkcheck.evaluation.values import TableauValues
from rkcheck.numbers.reading import Reading
from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.energy.check import check
from rkcheck.options import CheckOptions
what, order, degree = {what!r}, {order!r}, {degree!r}
tableau = Tableau.from_values({A!r}, {B!r})
out = {{}}
gc.collect()
if what in ("listing", "check"):
    t0 = time.perf_counter()
    if what == "listing":
        listing = condition_listing(order, degree)
        out["conditions"], out["terms"] = len(listing), listing.terms()
    else:
        check(tableau, CheckOptions(degree=degree, order=order, dps=50))
    out["seconds"] = time.perf_counter() - t0
else:
    listing = condition_listing(order, degree)
    gc.collect()
    t0 = time.perf_counter()
    if what == "exact":
        evaluate(listing, TableauValues(tableau, Reading(arithmetic="exact")))
    elif what == "balls":
        evaluate(listing, TableauValues(tableau, Reading(arithmetic="ball")))
    else:
        condition_sums(listing, float_context(TableauValues(tableau, Reading())), tableau.stages)
    out["seconds"] = time.perf_counter() - t0
out["rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps(out))
"""


def measure(what: str, order: int, degree: int | None, repeat: int = 1) -> dict:
    """The best of ``repeat`` measurements, each in a fresh interpreter:
    ``{"seconds", "rss_mb", ...}`` (seconds the minimum, memory the maximum: on a shared
    machine the fastest run is the least disturbed one, memory does not depend on it)."""
    code = CHILD.format(root=str(ROOT), A=A_DENSE, B=B_DENSE, what=what, order=order, degree=degree)
    runs = []
    for _ in range(max(1, repeat)):
        proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        if proc.returncode != 0:
            raise SystemExit(f"{what} at order {order}, degree {degree} failed:\n{proc.stderr.strip()}")
        runs.append(json.loads(proc.stdout.strip().splitlines()[-1]))
    best = min(runs, key=lambda r: r["seconds"])
    return dict(best, rss_mb=max(r["rss_mb"] for r in runs))


#: What the start-up lines time, each from process start to exit: the two commands of
#: The target (≤ 0.4 s) and, for scale, bare Python and ``import numpy``.
STARTUP_COMMANDS = {
    "rkcheck verify tableaux/explicit/rk4.toml": ["-m", "rkcheck", "verify", "tableaux/explicit/rk4.toml"],
    "rkcheck --help": ["-m", "rkcheck", "--help"],
    'python -c "import numpy"': ["-c", "import numpy"],
    "python -c pass": ["-c", "pass"],
}


def start_to_exit(runs: int) -> dict[str, list[float]]:
    """Wall times of :data:`STARTUP_COMMANDS` (``python -m rkcheck`` from the checkout),
    from process start to exit, ``runs`` rounds with the commands interleaved so that all
    see the same load.  Byte code is cached as in an installed package (a first, untimed
    round writes it even when ``PYTHONDONTWRITEBYTECODE`` is set here)."""
    env = dict(os.environ, NO_COLOR="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    times: dict[str, list[float]] = {name: [] for name in STARTUP_COMMANDS}
    for round_ in range(runs + 1):
        for name, args in STARTUP_COMMANDS.items():
            t0 = time.perf_counter()
            subprocess.run([sys.executable, *args], cwd=ROOT, env=env, capture_output=True)
            if round_:
                times[name].append(time.perf_counter() - t0)
    return times


HEADER = ("| order | m | conditions | terms | listing s | exact s | balls50 s | balls/exact | float64 s "
          "| check s | ns/term | check peak MB | max peak MB |")


def row(order: int, degree: int | None, repeat: int) -> str:
    r = {what: measure(what, order, degree, repeat) for what in MEASUREMENTS}
    lst = r["listing"]
    exact, balls = r["exact"]["seconds"], r["balls"]["seconds"]
    peak = max(x["rss_mb"] for x in r.values())
    return (f"| {order} | {'none' if degree is None else degree} | {lst['conditions']:,} | {lst['terms']:,} "
            f"| {lst['seconds']:.3f} | {exact:.3f} | {balls:.3f} | {balls / exact:.2f} "
            f"| {r['float64']['seconds']:.3f} | {r['check']['seconds']:.3f} "
            f"| {exact / lst['terms'] * 1e9:.0f} | {r['check']['rss_mb']:.0f} | {peak:.0f} |").replace(",", "\u202f")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--orders", type=int, nargs="+", default=[10, 12, 14, 16], metavar="N",
                        help="energy orders (2 to 20; default 10 12 14 16)")
    parser.add_argument("--degrees", nargs="+", default=["none", "3"], metavar="M",
                        help="degree bounds, 'none' for no bound (default none 3)")
    parser.add_argument("--repeat", type=int, default=3, metavar="K",
                        help="best of K fresh processes per measurement below order 16 (default 3)")
    parser.add_argument("--startup-runs", type=int, default=9, metavar="K",
                        help="runs of each start-to-exit measurement, best and median (0: skip; default 9)")
    args = parser.parse_args(argv)
    if any(not 2 <= n <= 20 for n in args.orders):
        parser.error("--orders: each order must be between 2 and 20")
    degrees = [None if d.lower() == "none" else int(d) for d in args.degrees]
    print(HEADER)
    print("|" + "---|" * (HEADER.count("|") - 1))
    for order in args.orders:
        for degree in degrees:
            print(row(order, degree, args.repeat if order < 16 else 1), flush=True)
    if args.startup_runs > 0:
        load = os.getloadavg()[0]
        times = start_to_exit(args.startup_runs)
        print(f"\nprocess start to exit (python -m rkcheck, {args.startup_runs} interleaved runs, "
              f"load average {load:.1f} before): best / median")
        for name, runs in times.items():
            print(f"  {name:42s} {min(runs):.3f} s / {statistics.median(runs):.3f} s")


if __name__ == "__main__":
    main()
