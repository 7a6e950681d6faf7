"""The centroid route's evaluation alone, order by order: CPU seconds, nanoseconds per
condition and channel, and the conditions found nonzero (failing), for RK4 or a dense
6-stage rational tableau.

    python benchmarks/bench_centroid.py --vertices 23            # RK4 to order 22, five primes
    python benchmarks/bench_centroid.py --vertices 21 --dense    # a dense tableau to order 20

Exact checks from ``CENTROID_FROM_ORDER`` (rkcheck.trees.centroid) on enumerate their
conditions by centroid; this measures that walk and its arithmetic
(``rkcheck.evaluation.centroid``) in one process, every order from 3 vertices, at the
first ``--primes`` channel primes of the tableau (RK4 to order 22 needs five).  The
whole check as a user runs it is the order-22 row of ``benchmarks/goals.py``.
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

RK4 = ([[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]], ["1/6", "1/3", "1/3", "1/6"])


def main() -> None:
    from rkcheck.evaluation.scaled import scaled_rational
    from rkcheck.trees.centroid import CentroidListing

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vertices", type=int, default=23)
    ap.add_argument("--primes", type=int, default=5)
    ap.add_argument("--dense", action="store_true", help="a dense 6-stage rational tableau instead of RK4")
    args = ap.parse_args()
    if args.dense:
        from bench_arith import DENSE6 as tableau
    else:
        tableau = RK4
    A = [[Fraction(x) for x in row] for row in tableau[0]]
    b = [Fraction(x) for x in tableau[1]]
    scaled = scaled_rational(A, b)
    pairs = [(p, roots[0]) for p, roots in scaled.primes_for(31 * args.primes)][:args.primes]
    listing = CentroidListing(args.vertices - 1, None)
    print(f"{len(b)} stages, {len(pairs)} primes")
    print("| vertices | conditions | failing | CPU s | ns/condition·channel |")
    print("|---:|---:|---:|---:|---:|")
    conditions = failing = 0
    total = 0.0
    for n in range(3, args.vertices + 1):
        t0 = time.process_time()
        residues = scaled.residues_at(listing, pairs, [n])[n]
        took = time.process_time() - t0
        total += took
        nonzero = int(np.count_nonzero(np.any(residues != 0, axis=1)))
        conditions, failing = conditions + len(residues), failing + nonzero
        per = 1e9 * took / max(1, len(residues) * len(pairs))
        print(f"| {n} | {len(residues):,} | {nonzero:,} | {took:.2f} | {per:.0f} |")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"\n{conditions:,} conditions, {failing:,} failing; {total:.1f} s CPU, peak {peak:.0f} MiB")


if __name__ == "__main__":
    main()
