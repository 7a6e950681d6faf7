"""Time the energy check: tree/condition tables, exact evaluation, certified balls.

    python benchmarks/bench_engine.py [--orders 10 12 14] [--degree none] [--repeat 3]

A dense rational 4-stage implicit tableau (fixed entries) is checked without a degree
bound; the "balls" column checks the same tableau with an irrational perturbation
(``+ sqrt(2) - sqrt(2)`` on every entry, so the values are identical but the entries are
algebraic) at dps 50.  Times are best-of-``repeat`` wall-clock seconds in one process,
interpreter start-up excluded; the condition table is rebuilt for every measurement.
"""

from __future__ import annotations

import argparse
import gc
import time
from fractions import Fraction

from rkcheck.check import CheckOptions, check
from rkcheck.conditions import ConditionTable
from rkcheck import conditions as conditions_module
from rkcheck.tableau import Tableau

A_DENSE = [
    ["1/7", "-2/9", "3/11", "1/13"],
    ["2/5", "1/8", "-1/6", "3/10"],
    ["-1/12", "5/9", "1/4", "2/15"],
    ["3/8", "1/3", "-2/7", "1/5"],
]
B_DENSE = ["1/5", "3/10", "1/4", "1/4"]


def dense_rational() -> Tableau:
    return Tableau.from_values(A_DENSE, B_DENSE, name="dense rational 4-stage")


def dense_algebraic() -> Tableau:
    A = [[f"{x} + sqrt(2) - sqrt(2)" for x in row] for row in A_DENSE]
    return Tableau.from_values(A, B_DENSE, name="dense algebraic 4-stage")


def best(f, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        gc.collect()
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def run(orders: list[int], degree: int | None, repeat: int) -> None:
    rational, algebraic = dense_rational(), dense_algebraic()
    print(f"degree bound: {degree if degree is not None else 'none'}; best of {repeat}")
    print(f"{'order':>5} {'conditions':>10} {'tables s':>9} {'exact s':>9} {'balls50 s':>10} {'ratio':>6}")
    for order in orders:
        def build():
            return ConditionTable(order, degree)

        t_tables = best(build, repeat)
        table = build()
        n = len(table)

        def checked(tab, dps=50):
            # a fresh table per run, so that every run pays for its trees
            conditions_module.condition_table.cache_clear()
            return check(tab, CheckOptions(degree=degree, order=order, dps=dps))

        t_exact = best(lambda: checked(rational), repeat)
        t_ball = best(lambda: checked(algebraic), repeat)
        print(f"{order:>5} {n:>10} {t_tables:>9.3f} {t_exact:>9.3f} {t_ball:>10.3f} {t_ball / t_exact:>6.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--orders", type=int, nargs="+", default=[8, 10, 12, 14])
    parser.add_argument("--degree", default="none")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    degree = None if args.degree == "none" else int(args.degree)
    run(args.orders, degree, args.repeat)


if __name__ == "__main__":
    main()
