"""The exact evaluation of a rational tableau, per tree and channel: one command.

    python benchmarks/bench_exact.py                          # RK4, orders 16 and 18
    python benchmarks/bench_exact.py --orders 18 20           # order 20: a minute or two, ~2 GB
    python benchmarks/bench_exact.py --root ../old-checkout   # the same measured on another checkout

Each order runs in two fresh processes that share a temporary listing cache: the first
builds the listing (and fills the cache), the second reads it, so that its peak memory
is the evaluation's and not the listing build's.  In both, ``exact_condition_sums``
(every condition, every prime its bound needs) is timed alone, given the listing, in
CPU seconds (user + system: on a shared machine wall time follows the load); the table
shows the faster of the two.

Columns: *trees* — every rooted tree the listing holds, stored or only a term of the
top order (the items a pass over the listing visits); *channels* — the primes the top
order needs; *eval CPU s*; *ns/tree·ch* — evaluation CPU per tree and channel; *peak MB*
of the process that read the listing from the cache (the evaluation's peak, with the
listing's arrays) and of the one that built it.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

TABLEAUX = {  # name: (A, b), without claims
    "rk4": ([["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]],
            ["1/6", "1/3", "1/3", "1/6"]),
    "dense": ([["1/7", "-2/9", "3/11", "1/13"], ["2/5", "1/8", "-1/6", "3/10"], ["-1/12", "5/9", "1/4", "2/15"],
               ["3/8", "1/3", "-2/7", "1/5"]], ["1/5", "3/10", "1/4", "1/4"]),
}

CHILD = r"""
import json, resource, sys, time
sys.path.insert(0, {root!r})
from rkcheck.api.settings import use_listing_cache
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_rational
from rkcheck.methods.tableau import Tableau
from rkcheck.trees.listing import ConditionListing
use_listing_cache(True)
values = Tableau.from_values({A!r}, {b!r}).exact_values()
scaled = scaled_rational(values.A, values.b)
c0 = time.process_time()
listing = ConditionListing({order!r}, None).complete()
c1 = time.process_time()
sums = exact_condition_sums(scaled, listing)
c2 = time.process_time()
print(json.dumps({{"trees": listing.first[-1], "channels": max(len(o.primes) for o in sums.values()),
                  "listing_cpu": c1 - c0, "eval_cpu": c2 - c1, "cached": bool(listing.cache_hits),
                  "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}}))
"""


def measure(name: str, order: int, cache_dir: Path, root: Path) -> dict:
    """One process: the listing (built, or read from ``cache_dir``) and its exact evaluation."""
    A, b = TABLEAUX[name]
    code = CHILD.format(root=str(root), A=A, b=b, order=order)
    env = dict(os.environ, RKCHECK_CACHE_DIR=str(cache_dir))
    env.pop("RKCHECK_NO_CACHE", None)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise SystemExit(f"{name} at order {order} failed:\n{proc.stderr.strip()}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


HEADER = "| tableau | order | trees | channels | eval CPU s | ns/tree·ch | peak MB (cached listing) | peak MB (built) |"


def row(name: str, order: int, scratch: Path, root: Path) -> str:
    cache_dir = scratch / f"{name}-{order}"
    shutil.rmtree(cache_dir, ignore_errors=True)
    built = measure(name, order, cache_dir, root)
    cached = measure(name, order, cache_dir, root)
    shutil.rmtree(cache_dir, ignore_errors=True)
    cpu = min(built["eval_cpu"], cached["eval_cpu"])
    per = cpu / (built["trees"] * built["channels"]) * 1e9
    return (f"| {name} | {order} | {built['trees']:,} | {built['channels']} | {cpu:.2f} | {per:.1f} "
            f"| {cached['rss_mb']:.0f} | {built['rss_mb']:.0f} |").replace(",", "\u202f")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--orders", type=int, nargs="+", default=[16, 18], metavar="N",
                        help="energy orders (default 16 18)")
    parser.add_argument("--tableaux", nargs="+", default=["rk4"], choices=sorted(TABLEAUX),
                        help="rational tableaux to evaluate (default rk4)")
    parser.add_argument("--root", type=Path, default=ROOT, help="the checkout to measure (default this one)")
    args = parser.parse_args(argv)
    scratch = Path(tempfile.mkdtemp(prefix="rkcheck-bench-exact-"))
    try:
        print(HEADER)
        print("|" + "---|" * (HEADER.count("|") - 1))
        for name in args.tableaux:
            for order in args.orders:
                print(row(name, order, scratch, args.root.resolve()), flush=True)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
