"""The streamed listing and the listing cache, measured: one command.

    python benchmarks/bench_stream.py                      # orders 16 18
    python benchmarks/bench_stream.py --orders 16 18 20    # order 20: a minute, 1-2 GB
    python benchmarks/bench_stream.py --root ../other      # another checkout (before/after)

Every measurement is one ``check`` (the engine behind ``rkcheck verify``, without the
claims of a file's [expect] table) in a fresh Python process; the child times itself
(imports excluded) and the parent reads the child's own resource usage
(``os.wait4``): CPU seconds (user + system) and peak resident memory.  On a shared
machine wall time follows the load; CPU time much less so — both are printed.

Cases, per order N:

* ``fail-fast, fails at 2`` — ``--fail-fast`` on explicit Euler (energy order 1: a
  condition with 3 vertices fails), against ``full, fails at 2``: the same tableau
  checked to order N (no cache);
* ``RK4 no cache`` — classical RK4 (every condition up to order 4 holds, then some
  fail), listing built in the process, nothing read or saved;
* ``RK4 cold cache`` — the same with an empty listing cache (the listing is built and
  saved);
* ``RK4 warm cache`` — the same again: the listing is read from the cache.

``--tableau FILE`` checks that file instead of RK4 (``--tableau
tableaux/collocation/gauss-3.toml``); ``--cases`` picks cases (``warm`` brings ``cold``,
which fills the cache).

The cache is a temporary directory (``RKCHECK_CACHE_DIR``), removed at the end.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

EULER = ([["0"]], ["1"])
RK4 = ([["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]],
       ["1/6", "1/3", "1/3", "1/6"])

CHILD = r"""
import json, sys, time
sys.path.insert(0, {root!r})
from rkcheck.energy.check import check
from rkcheck.methods.tableau import Tableau
from rkcheck.options import CheckOptions
try:
    from rkcheck.api.settings import use_listing_cache
    use_listing_cache({cache!r})
except ImportError:  # a checkout from before the cache (--root): always built
    pass
if {path!r} is None:
    tableau = Tableau.from_values({A!r}, {b!r})
else:
    from rkcheck.api.tableaux import load
    tableau = load({path!r})
t0, c0 = time.perf_counter(), time.process_time()
result = check(tableau, CheckOptions(order={order!r}, degree=None, fail_fast={fail_fast!r}))
seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
print(json.dumps({{"seconds": seconds, "check_cpu": cpu, "orders": len(result.conditions.orders), "energy_order": result.energy_order,
                  "failed": sum(p.failed for p in result.per_order), "listing_s": result.timings.get("trees", 0.0)}}))
"""


def measure(tableau, order: int, fail_fast: bool, cache: bool, cache_dir: Path, root: Path = ROOT) -> dict:
    """One check in a fresh process: its own timing and the process's CPU and memory."""
    A, b = (None, None) if isinstance(tableau, Path) else tableau
    path = str(tableau) if isinstance(tableau, Path) else None
    code = CHILD.format(root=str(root), cache=cache, A=A, b=b, path=path, order=order, fail_fast=fail_fast)
    env = dict(os.environ, RKCHECK_CACHE_DIR=str(cache_dir))
    env.pop("RKCHECK_NO_CACHE", None)
    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                            text=True)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    out, err = proc.stdout.read(), proc.stderr.read()  # small: one JSON line
    proc.stdout.close()
    proc.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"order {order} failed:\n{err.strip()}")
    result = json.loads(out.strip().splitlines()[-1])
    # ru_maxrss: kilobytes on Linux, bytes on macOS
    rss = usage.ru_maxrss / (1024 * 1024 if sys.platform == "darwin" else 1024)
    return dict(result, cpu=usage.ru_utime + usage.ru_stime, process_wall=wall, rss_mb=rss)


HEADER = "| order | case | check s | check CPU s | process CPU s | peak MB | orders checked | failing |"


CASES = {  # name: (tableau, fail-fast, cache); in this order (the warm cache follows the cold one)
    "full, fails at 2": (EULER, False, False),
    "fail-fast, fails at 2": (EULER, True, False),
    "RK4 no cache": (RK4, False, False),
    "RK4 cold cache": (RK4, False, True),
    "RK4 warm cache": (RK4, False, True),
}
SHORT = {"full": "full, fails at 2", "fail-fast": "fail-fast, fails at 2", "no-cache": "RK4 no cache",
         "cold": "RK4 cold cache", "warm": "RK4 warm cache"}


def rows(order: int, cache_dir: Path, root: Path = ROOT, cases: list[str] | None = None,
         tableau: Path | None = None) -> list[str]:
    shutil.rmtree(cache_dir, ignore_errors=True)
    wanted = [SHORT[c] for c in cases] if cases else list(CASES)
    if "RK4 warm cache" in wanted and "RK4 cold cache" not in wanted:
        wanted.insert(wanted.index("RK4 warm cache"), "RK4 cold cache")  # it fills the cache
    out = []
    for name in [n for n in CASES if n in wanted]:
        data, fail_fast, cache = CASES[name]
        if tableau is not None and data is RK4:  # --tableau: checked instead of RK4
            data, name = tableau, name.replace("RK4", tableau.stem)
        r = measure(data, order, fail_fast, cache, cache_dir, root)
        out.append(f"| {order} | {name} | {r['seconds']:.2f} | {r['check_cpu']:.2f} | {r['cpu']:.2f} | {r['rss_mb']:.0f} "
                   f"| {r['orders']} | {r['failed']:,} |")
        print(out[-1], flush=True)
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--orders", type=int, nargs="+", default=[16, 18], metavar="N",
                        help="energy orders (2 to 20; default 16 18)")
    parser.add_argument("--root", type=Path, default=ROOT, metavar="DIR",
                        help="measure the rkcheck of another checkout (before/after; default this one)")
    parser.add_argument("--cases", nargs="+", choices=list(SHORT), default=None, metavar="CASE",
                        help=f"only these cases ({', '.join(SHORT)}; default all)")
    parser.add_argument("--tableau", type=Path, default=None, metavar="FILE",
                        help="check this tableau file instead of RK4 in the cache cases")
    args = parser.parse_args(argv)
    if any(not 2 <= n <= 20 for n in args.orders):
        parser.error("--orders: each order must be between 2 and 20")
    print(f"load average {os.getloadavg()[0]:.1f}, {os.cpu_count()} CPUs")
    print(HEADER)
    print("|" + "---|" * (HEADER.count("|") - 1), flush=True)
    scratch = Path(tempfile.mkdtemp(prefix="rkcheck-bench-cache-"))
    try:
        for order in args.orders:
            rows(order, scratch / "cache", args.root.resolve(), args.cases,
                 None if args.tableau is None else args.tableau.resolve())
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
