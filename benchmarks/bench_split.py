"""One exact check split over processes (``verify --jobs`` / ``--scheduler``), measured.

    python benchmarks/bench_split.py                       # RK4, order 18: --jobs 1 and 2
    python benchmarks/bench_split.py --order 20 --cluster  # and a 2-worker LocalCluster

Writes RK4 (rational, no claims) to a temporary file, fills a temporary listing cache
with one untimed check, then runs ``rkcheck.verify(FILE, order=N, degree="none", jobs=,
scheduler=)`` in a fresh process, three ways: ``jobs=1``, ``jobs=W`` (forked local
processes) and, with ``--cluster``, ``scheduler=`` a ``LocalCluster`` of W one-thread
workers started before the clock (they read the same listing cache; their CPU time is
not the checking process's and is not counted).  Timed inside the process, after its
imports: wall and CPU seconds of the check (its forked processes included) and the
largest peak resident memory among them.  Every run must give the same verdict for
every condition (compared through a digest of each order's verdict array: a JSON report
of millions of failing conditions would take longer to write than the check).  Prints
one Markdown table.  Needs ``rkcheck[cluster]`` for ``--cluster``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

RK4 = ('[tableau]\nA = [["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]]\n'
       'b = ["1/6", "1/3", "1/3", "1/6"]\n')


CHILD = r"""
import hashlib, json, resource, sys, time
sys.path.insert(0, {root!r})
import rkcheck
from rkcheck.api.settings import use_listing_cache
use_listing_cache()
w0, c0 = time.perf_counter(), time.process_time()
result = rkcheck.verify({path!r}, order={order}, degree="none", jobs={jobs}, scheduler={scheduler!r})
wall, cpu = time.perf_counter() - w0, time.process_time() - c0
kids = resource.getrusage(resource.RUSAGE_CHILDREN)
digest = hashlib.sha256()
for n, o in sorted(result.conditions.orders.items()):
    digest.update(bytes([n])); digest.update(o.state.tobytes())
print(json.dumps({{"wall": wall, "cpu": cpu + kids.ru_utime + kids.ru_stime,
                  "peak": max(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, kids.ru_maxrss) / 1024,
                  "digest": digest.hexdigest(), "order": result.energy_order}}))
"""


def timed_verify(path: Path, order: int, jobs: int = 1, scheduler: str | None = None) -> dict:
    """Wall s, CPU s and peak MB of one check in a fresh process, and its verdicts' digest."""
    code = CHILD.format(root=str(ROOT), path=str(path), order=order, jobs=jobs, scheduler=scheduler)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                          env=dict(os.environ, NO_COLOR="1"))
    if proc.returncode != 0:
        raise SystemExit(f"verify (jobs={jobs}, scheduler={scheduler}) failed: {proc.stderr.strip()[-500:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--order", type=int, default=18, help="energy order (default 18)")
    parser.add_argument("--workers", type=int, default=2, help="local processes and cluster workers (default 2)")
    parser.add_argument("--cluster", action="store_true", help="also on a LocalCluster (needs rkcheck[cluster])")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="rkcheck-split-") as tmp:
        path = Path(tmp) / "rk4.toml"
        path.write_text(RK4, encoding="utf-8")
        os.environ["RKCHECK_CACHE_DIR"] = str(Path(tmp) / "cache")  # the cluster's workers inherit it
        timed_verify(path, args.order)  # fills the listing cache
        results = {"--jobs 1": timed_verify(path, args.order),
                   f"--jobs {args.workers}": timed_verify(path, args.order, jobs=args.workers)}
        if args.cluster:
            try:
                from distributed import LocalCluster
            except ImportError:
                parser.error("--cluster needs Dask: pip install 'rkcheck[cluster]'")
            import logging

            logging.getLogger("distributed").setLevel(logging.CRITICAL)
            with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster:
                results[f"--scheduler (LocalCluster, {args.workers} workers)"] = timed_verify(
                    path, args.order, scheduler=cluster.scheduler_address)
    reference = results["--jobs 1"]["digest"]
    for name, got in results.items():
        if got["digest"] != reference:
            raise SystemExit(f"{name}: the verdicts differ from --jobs 1")
    base = results["--jobs 1"]["wall"]
    print(f"`python benchmarks/bench_split.py {' '.join(argv if argv is not None else sys.argv[1:])}`: RK4, "
          f"order {args.order}, listing cached, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}\n")
    print("| verify | wall s | speed-up | CPU s (process and children) | peak MB (largest process) |")
    print("|---|---|---|---|---|")
    for name, got in results.items():
        print(f"| {name} | {got['wall']:.2f} | {base / got['wall']:.2f}× | {got['cpu']:.2f} | {got['peak']:.0f} |")


if __name__ == "__main__":
    main()
