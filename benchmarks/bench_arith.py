"""Every arithmetic against exact: evaluation and judging given the listing.

    python benchmarks/bench_arith.py                 # orders 16 and 18, every case
    python benchmarks/bench_arith.py --orders 16 --cases rk4-exact rk4-decimal

Each case runs in a fresh Python process: the condition listing is built first (not
timed), then the conditions are evaluated and judged as ``rkcheck verify`` does
(``energy.check._judged_orders``: the evaluation, and for decimal tableaux the joint box
of inputs).  Columns: wall seconds, CPU seconds (user + system of the process over the
timed part: on a shared machine the CPU time is the steadier figure), the ratio of
CPU time to the exact case of the same tableau and order, ns per term and channel
(exact cases: CPU time / (terms × channels)) and the process's peak memory.

Cases: RK4 and Gauss-3 exact, RK4 with 16-digit decimals (a box of inputs), RK4 in
forced balls (``--arithmetic ball``, 50 digits), and HBVM(6, 3) (entries in a degree-48
number field, degree 4 as its file says) against a dense rational 6-stage tableau.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

RK4_DECIMAL = (
    [["0", "0", "0", "0"], ["0.5", "0", "0", "0"], ["0", "0.5", "0", "0"], ["0", "0", "1", "0"]],
    ["0.1666666666666667", "0.3333333333333333", "0.3333333333333333", "0.1666666666666667"],
)
DENSE6 = (
    [["1/7", "-2/9", "3/11", "1/13", "1/6", "2/17"], ["2/5", "1/8", "-1/6", "3/10", "-1/9", "1/19"],
     ["-1/12", "5/9", "1/4", "2/15", "1/11", "-3/23"], ["3/8", "1/3", "-2/7", "1/5", "2/13", "1/29"],
     ["1/9", "-1/10", "3/14", "1/12", "1/4", "2/31"], ["1/21", "2/27", "-1/33", "1/14", "3/37", "1/8"]],
    ["1/5", "3/10", "1/4", "1/8", "1/16", "1/16"],
)

#: name: (file or inline tableau, arithmetic, degree, reference exact case)
CASES = {
    "rk4-exact": ("tableaux/explicit/rk4.toml", "auto", None, None),
    "rk4-decimal": (RK4_DECIMAL, "auto", None, "rk4-exact"),
    "rk4-ball": ("tableaux/explicit/rk4.toml", "ball", None, "rk4-exact"),
    "gauss3-exact": ("tableaux/collocation/gauss-3.toml", "auto", None, None),
    "gauss3-ball": ("tableaux/collocation/gauss-3.toml", "ball", None, "gauss3-exact"),
    "dense6-exact-m4": (DENSE6, "auto", 4, None),
    "hbvm63-exact-m4": ("tableaux/hbvm/hbvm-6-3.toml", "auto", 4, "dense6-exact-m4"),
}

CHILD = r"""
import gc, json, os, resource, sys, time
sys.path.insert(0, {root!r})
from rkcheck.energy.check import _judged_orders, _listing
from rkcheck.evaluation.backends import channels_for
from rkcheck.evaluation.values import TableauValues
from rkcheck.io.loader import load
from rkcheck.methods.tableau import Tableau
from rkcheck.options import CheckOptions
source, arithmetic, degree, order = {source!r}, {arithmetic!r}, {degree!r}, {order!r}
tableau = load(os.path.join({root!r}, source)) if isinstance(source, str) else Tableau.from_values(*source)
tableau = getattr(tableau, "tableau", tableau)
options = CheckOptions(degree=degree, order=order, arithmetic=arithmetic)
values = TableauValues.of(tableau, options.reading)
listing = _listing(values, options, None)
for n in listing.orders:
    listing.orders[n].max_terms
terms = sum(listing.orders[n].rows for n in listing.orders)
gc.collect()
w0, c0 = time.perf_counter(), os.times()
orders, interrupted, note = _judged_orders(listing, values, options, None)
w1, c1 = time.perf_counter(), os.times()
cpu = (c1.user - c0.user) + (c1.system - c0.system)
states = {{int(n): o.state.tolist() for n, o in orders.items()}}
print(json.dumps(dict(wall=w1 - w0, cpu=cpu, terms=terms, channels=channels_for(values, order),
                      rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, note=note,
                      conditions=len(listing), digest=hash(json.dumps(states)) % 10**8)))
"""


def run(case: str, order: int) -> dict:
    source, arithmetic, degree, _ = CASES[case]
    code = CHILD.format(root=str(ROOT), source=source, arithmetic=arithmetic, degree=degree, order=order)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={"PYTHONHASHSEED": "0", **__import__("os").environ})
    if proc.returncode != 0:
        raise SystemExit(f"{case} at order {order} failed:\n{proc.stderr.strip()}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--orders", type=int, nargs="+", default=[16, 18], metavar="N")
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES), metavar="CASE")
    args = parser.parse_args(argv)
    print("| case | order | conditions | wall s | CPU s | CPU / exact | ns per term·channel | peak MB | note |")
    print("|---|---|---|---|---|---|---|---|---|")
    for order in args.orders:
        done: dict[str, dict] = {}
        for case in args.cases:
            r = done[case] = run(case, order)
            ref = CASES[case][3]
            ratio = f"{r['cpu'] / done[ref]['cpu']:.2f}" if ref in done and done[ref]['cpu'] else ""
            ns = f"{r['cpu'] / (r['terms'] * r['channels']) * 1e9:.1f}" if r["channels"] else ""
            note = (r["note"] or "")[:60]
            print(f"| {case} | {order} | {r['conditions']} | {r['wall']:.2f} | {r['cpu']:.2f} | {ratio} | {ns} "
                  f"| {r['rss_mb']:.0f} | {note} |", flush=True)


if __name__ == "__main__":
    main()
