"""Scan against separate verify runs, measured in one run.

    python benchmarks/bench_scan.py [--order 8] [--jobs 2] [PATH]

Runs ``rkcheck verify FILE --order N`` once per tableau file under PATH (default
``tableaux/``), one process each, and sums their wall times; then runs
``rkcheck scan PATH --order N --jobs J`` once.  The target is a ratio of at most 0.6:
process start-up and tree tables are paid once per worker, not once per file.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rkcheck.io.discovery import find_tableau_files  # noqa: E402


def wall(cmd: list[str]) -> float:
    env = dict(os.environ, NO_COLOR="1")
    t0 = time.perf_counter()
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, cwd=ROOT)
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("path", nargs="?", default="tableaux")
    parser.add_argument("--order", type=int, default=8)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    files = find_tableau_files([str(ROOT / args.path)], exclude=["README*"])
    exe = [sys.executable, "-m", "rkcheck"]
    separate = sum(wall(exe + ["verify", f, "--order", str(args.order), "-q"]) for f in files)
    scanned = wall(exe + ["scan", args.path, "--order", str(args.order), "--jobs", str(args.jobs), "-q"])
    print(f"files: {len(files)}; order {args.order}; jobs {args.jobs}")
    print(f"separate verify runs (sum): {separate:7.2f} s")
    print(f"one scan:                   {scanned:7.2f} s")
    print(f"ratio scan / separate:      {scanned / separate:7.2f}  (target <= 0.6)")


if __name__ == "__main__":
    main()
