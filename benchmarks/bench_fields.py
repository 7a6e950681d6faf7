"""Exact checks in number fields against exact rational checks of the same size.

    python benchmarks/bench_fields.py            # Gauss-3 at orders 12, 14; Gauss-5 at 10
    python benchmarks/bench_fields.py --quick    # Gauss-3 at order 12 only

Each line times the evaluation of every energy condition (all degrees) by the exact
modular engine, given the condition listing (built once per order, shared, and timed
separately): a dense rational s-stage tableau against the s-stage Gauss tableau whose
entries lie in Q(√15) (s = 3, degree 2) or in the degree-8 field of Gauss-5's nodes.
Targets: Gauss-3 ≤ 3× the rational time, Gauss-5 ≤ 10×.  Best of
``--repeat`` runs; the field is found once per tableau (its time is shown too).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rkcheck.evaluation.modular import exact_condition_sums  # noqa: E402
from rkcheck.evaluation.scaled import scaled_field, scaled_rational  # noqa: E402
from rkcheck.io.loader import load  # noqa: E402
from rkcheck.methods.tableau import Tableau  # noqa: E402
from rkcheck.trees.listing import ConditionListing  # noqa: E402

RATIONAL = {
    3: ([["1/7", "-2/9", "3/11"], ["2/5", "1/8", "-1/6"], ["-1/12", "5/9", "1/4"]], ["1/5", "3/10", "1/2"]),
    5: ([["1/7", "-2/9", "3/11", "1/13", "1/6"], ["2/5", "1/8", "-1/6", "3/10", "-1/9"],
         ["-1/12", "5/9", "1/4", "2/15", "1/11"], ["3/8", "1/3", "-2/7", "1/5", "2/13"],
         ["1/9", "-1/10", "3/14", "1/12", "1/4"]],
        ["1/5", "3/10", "1/4", "1/8", "1/8"]),
}


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def measure(order: int, s: int, field_tableau: Tableau, repeat: int) -> dict:
    t0 = time.perf_counter()
    listing = ConditionListing(order, None)
    for n in listing.orders:  # build the term arrays now, outside the timed evaluation
        listing.orders[n].max_terms
    t_list = time.perf_counter() - t0
    A, b = RATIONAL[s]
    rat = Tableau.from_values(A, b)
    rat_scaled = scaled_rational(rat.exact_A(), rat.exact_b())
    t0 = time.perf_counter()
    values = field_tableau.exact_values()
    fld_scaled = scaled_field(values)
    t_field = time.perf_counter() - t0
    t_rat = best(lambda: exact_condition_sums(rat_scaled, listing), repeat)
    t_fld = best(lambda: exact_condition_sums(fld_scaled, listing), repeat)
    top = listing.orders[order]
    return {"order": order, "conditions": sum(len(o) for o in listing.orders.values()), "listing": t_list,
            "field": t_field, "degree": values.field.degree, "rational": t_rat, "algebraic": t_fld,
            "ratio": t_fld / t_rat, "primes_rat": len(rat_scaled.primes_for(rat_scaled.decision_bits(order, top.max_terms, top.coefficient_weight))),
            "primes_fld": len(fld_scaled.primes_for(fld_scaled.decision_bits(order, top.max_terms, top.coefficient_weight)))}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    gauss3 = load(str(ROOT / "tableaux" / "collocation" / "gauss-3.toml"))
    gauss5 = load(str(ROOT / "tableaux" / "collocation" / "gauss-5.toml"))
    cases = [("Gauss-3 (Q(√15))", 12, 3, gauss3, 3.0)]
    if not args.quick:
        cases += [("Gauss-3 (Q(√15))", 14, 3, gauss3, 3.0), ("Gauss-5 (degree 8)", 10, 5, gauss5, 10.0)]
    print(f"{'tableau':20s} {'order':>5s} {'conditions':>10s} {'listing':>8s} {'field':>7s} "
          f"{'rational':>9s} {'algebraic':>9s} {'ratio':>6s} {'target':>6s}  primes (rat/alg)")
    for label, order, s, tab, target in cases:
        r = measure(order, s, tab, args.repeat)
        print(f"{label:20s} {order:5d} {r['conditions']:10d} {r['listing']:7.2f}s {r['field']:6.2f}s "
              f"{r['rational']:8.3f}s {r['algebraic']:8.3f}s {r['ratio']:5.2f}× {target:5.0f}×  "
              f"{r['primes_rat']}/{r['primes_fld']} (×{r['degree']} roots)")


if __name__ == "__main__":
    main()
