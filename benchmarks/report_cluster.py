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
        results = {"--jobs 1": timed_scan(folder, args.order, "--jobs", "1"),
                   f"--jobs {args.workers}": timed_scan(folder, args.order, "--jobs", str(args.workers))}
        with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster:
            results[f"--scheduler (LocalCluster, {args.workers} workers)"] = timed_scan(
                folder, args.order, "--scheduler", cluster.scheduler_address)
    reference = rows(results["--jobs 1"][2])
    for name, (_, _, doc) in results.items():
        if rows(doc) != reference:
            raise SystemExit(f"{name}: the report differs from --jobs 1")
    base = results["--jobs 1"][0]
    print(f"`python benchmarks/report_cluster.py {' '.join(argv if argv is not None else sys.argv[1:])}`: "
          f"{args.files} files, order {args.order}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}\n")
    print("| scan | wall s | speed-up | CPU s (scan process and children) |\n|---|---|---|---|")
    for name, (wall, cpu, _) in results.items():
        print(f"| {name} | {wall:.2f} | {base / wall:.2f}× | {cpu:.2f} |")


if __name__ == "__main__":
    main()
