"""Scan on a Dask cluster against a scan in one process, measured in the same run.

    python benchmarks/report_cluster.py                    # 2 000 tableaux, order 8, 2 workers
    python benchmarks/report_cluster.py --files 200 --workers 2 --order 6

Writes ``--files`` random rational 3-stage tableaux (fixed seed) to a temporary folder,
then times ``rkcheck scan FOLDER --order N --format json`` three ways, each a fresh
process from start to exit: ``--jobs 1``; ``--jobs W`` (the local process pool); and
``--scheduler`` on a ``LocalCluster`` of W worker processes with one thread each,
started before the clock (a cluster is started once and then serves many scans).  The
three reports must agree row for row (times aside).  Prints one Markdown table: wall
time, the speed-up against ``--jobs 1``, and the CPU time of the scan process and its
children (the cluster's workers are not its children: their CPU time is not counted).
Needs ``rkcheck[cluster]``.

Just before each parallel scan, the table's last column gives the machine's own
ceiling: W copies of a fixed pure-Python loop run side by side against one alone.  On a
shared or virtual machine the cores do not always give W times one core's work (a
neighbour's load, cores that share a physical one), and no scan can beat that ratio.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import resource
import subprocess
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def write_tableaux(folder: Path, count: int, seed: int = 1) -> None:
    rng = random.Random(seed)

    def entry() -> str:
        return str(Fraction(rng.randint(-9, 9), rng.randint(1, 12)))

    for i in range(count):
        rows = ", ".join("[" + ", ".join(f'"{entry()}"' for _ in range(3)) + "]" for _ in range(3))
        b = [Fraction(rng.randint(1, 9), rng.randint(1, 12)) for _ in range(2)]
        b.append(1 - sum(b))  # consistent: classical order >= 1
        (folder / f"t{i:05d}.toml").write_text(f'[tableau]\nA = [{rows}]\nb = [{", ".join(chr(34) + str(x) + chr(34) for x in b)}]\n',
                                               encoding="utf-8")


def timed_scan(folder: Path, order: int, *extra: str) -> tuple[float, float, dict]:
    """Wall time, CPU time of the scan process and its children, and the JSON report."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "rkcheck", "scan", str(folder), "--order", str(order), "--format",
                           "json", "-q", *extra], capture_output=True, text=True, cwd=ROOT,
                          env=dict(os.environ, NO_COLOR="1"))
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"scan {' '.join(extra)} failed: {proc.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, json.loads(proc.stdout)


#: The ceiling's loop: about a second of pure Python on one core.
SPIN = "s = 0\nfor i in range(12_000_000):\n    s += i * i % 7\n"


def ceiling(workers: int) -> float:
    """How many times one process's work ``workers`` processes do side by side here:
    ``workers`` × (one copy's wall time) / (the wall time of ``workers`` copies at once)."""

    def wall(copies: int) -> float:
        t0 = time.perf_counter()
        procs = [subprocess.Popen([sys.executable, "-c", SPIN]) for _ in range(copies)]
        if any(p.wait() for p in procs):
            raise SystemExit("the ceiling's loop failed")
        return time.perf_counter() - t0

    return workers * wall(1) / wall(workers)


def rows(doc: dict) -> list[tuple]:
    return [(f["file"], f["status"], f["error"], None if f["result"] is None else f["result"]["summary"])
            for f in doc["files"]]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--files", type=int, default=2000, help="number of tableaux (default 2000)")
    parser.add_argument("--order", type=int, default=8, help="energy order (default 8)")
    parser.add_argument("--workers", type=int, default=2, help="local processes and cluster workers (default 2)")
    args = parser.parse_args(argv)
    try:
        from distributed import LocalCluster
    except ImportError:
        parser.error("needs Dask: pip install 'rkcheck[cluster]'")
    import logging

    logging.getLogger("distributed").setLevel(logging.CRITICAL)  # the cluster's shutdown chatter
    with tempfile.TemporaryDirectory(prefix="rkcheck-cluster-") as tmp:
        folder = Path(tmp)
        write_tableaux(folder, args.files)
        results = {"--jobs 1": timed_scan(folder, args.order, "--jobs", "1")}
        ceilings = {"--jobs 1": None, f"--jobs {args.workers}": ceiling(args.workers)}
        results[f"--jobs {args.workers}"] = timed_scan(folder, args.order, "--jobs", str(args.workers))
        with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster:
            name = f"--scheduler (LocalCluster, {args.workers} workers)"
            ceilings[name] = ceiling(args.workers)
            results[name] = timed_scan(folder, args.order, "--scheduler", cluster.scheduler_address)
    reference = rows(results["--jobs 1"][2])
    for name, (_, _, doc) in results.items():
        if rows(doc) != reference:
            raise SystemExit(f"{name}: the report differs from --jobs 1")
    base = results["--jobs 1"][0]
    print(f"`python benchmarks/report_cluster.py {' '.join(argv if argv is not None else sys.argv[1:])}`: "
          f"{args.files} files, order {args.order}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}\n")
    print(f"| scan | wall s | speed-up | CPU s (scan process and children) | the machine's ceiling just before "
          f"({args.workers} processes) |\n|---|---|---|---|---|")
    for name, (wall, cpu, _) in results.items():
        top = "" if ceilings[name] is None else f"{ceilings[name]:.2f}×"
        print(f"| {name} | {wall:.2f} | {base / wall:.2f}× | {cpu:.2f} | {top} |")


if __name__ == "__main__":
    main()
