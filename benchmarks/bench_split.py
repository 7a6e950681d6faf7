"""One exact check split over processes (``verify --jobs`` / ``--scheduler``), measured.

    python benchmarks/bench_split.py                       # RK4, order 18: --jobs 1 and 2
    python benchmarks/bench_split.py --order 20 --cluster  # and a 2-worker LocalCluster

Writes RK4 (rational, no claims) to a temporary file, fills a temporary listing cache
with one untimed check, then times ``rkcheck verify FILE --order N --degree none
--format json`` as a fresh process from start to exit, three ways: ``--jobs 1``,
``--jobs W`` (forked local processes) and, with ``--cluster``, ``--scheduler`` on a
``LocalCluster`` of W one-thread workers started before the clock (they read the same
listing cache; their CPU time is not the verify process's and is not counted).  The
reports must agree (times aside).  Prints one Markdown table: wall seconds, speed-up
against ``--jobs 1``, CPU seconds of the verify process and its children, and the
largest peak resident memory among them.  Needs ``rkcheck[cluster]`` for ``--cluster``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

RK4 = ('[tableau]\nA = [["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]]\n'
       'b = ["1/6", "1/3", "1/3", "1/6"]\n')


def timed_verify(path: Path, order: int, env: dict[str, str], *extra: str) -> tuple[float, float, float, dict]:
    """Wall s, CPU s and largest peak MB of the verify process and its children, and its JSON."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "rkcheck", "verify", str(path), "--order", str(order), "--degree",
                           "none", "--format", "json", *extra], capture_output=True, text=True, cwd=ROOT, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"verify {' '.join(extra)} failed: {proc.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, after.ru_maxrss / 1024, json.loads(proc.stdout)


def comparable(doc: dict) -> tuple:
    """The report without its times: summary and every condition's verdict and residual."""
    summary = {k: v for k, v in doc["summary"].items() if "time" not in k}
    return summary, [(c["id"], c["state"], c.get("residual_exact")) for c in doc.get("conditions", [])]


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
        env = dict(os.environ, NO_COLOR="1")
        timed_verify(path, args.order, env)  # fills the listing cache
        results = {"--jobs 1": timed_verify(path, args.order, env, "--jobs", "1"),
                   f"--jobs {args.workers}": timed_verify(path, args.order, env, "--jobs", str(args.workers))}
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
                    path, args.order, env, "--scheduler", cluster.scheduler_address)
    reference = comparable(results["--jobs 1"][3])
    for name, (*_, doc) in results.items():
        if comparable(doc) != reference:
            raise SystemExit(f"{name}: the report differs from --jobs 1")
    base = results["--jobs 1"][0]
    print(f"`python benchmarks/bench_split.py {' '.join(argv if argv is not None else sys.argv[1:])}`: RK4, "
          f"order {args.order}, listing cached, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}\n")
    print("| verify | wall s | speed-up | CPU s (process and children) | peak MB (largest process) |")
    print("|---|---|---|---|---|")
    for name, (wall, cpu, peak, _) in results.items():
        print(f"| {name} | {wall:.2f} | {base / wall:.2f}× | {cpu:.2f} | {peak:.0f} |")


if __name__ == "__main__":
    main()
