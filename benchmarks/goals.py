"""The performance goals, measured: one command, one table (docs/performance.md quotes it).

    python benchmarks/goals.py                # every goal but order 22 and the cluster (5-10 minutes)
    python benchmarks/goals.py --repeat 5     # the median of five runs per case (default 3)
    python benchmarks/goals.py --order-22     # also RK4 at order 22 (long, and several GB)
    python benchmarks/goals.py --cluster      # also 2 000 files on a 2-worker LocalCluster (rkcheck[cluster])
    python benchmarks/goals.py --quick        # small orders, one run each: every case runs (no goal applies)

Every case is one ``rkcheck.verify`` (or one ``rkcheck scan`` process) in a fresh Python
process, as a user runs it: the listing cache on, in a private temporary
``RKCHECK_CACHE_DIR`` that one uncounted run per case fills, so "cached" is a check that
reads its condition listing from the cache.  A ``verify`` child imports every module of
rkcheck (``pkgutil.walk_packages``) and python-flint (the one dependency rkcheck imports
on first use) and loads its file, then times the check alone, in CPU seconds (user +
system: on a shared machine the steadier figure), its own and that of the children it
waits for (a number field is built in one, under its time limit), so that no arithmetic
pays for modules it imports lazily and another does not; the
parent reads each child's peak resident memory through ``os.wait4``.  The scan row is the
whole ``rkcheck scan`` process, start-up and children included.  Each figure is the
median of ``--repeat`` runs.

A goal is met when every figure of its row is within it.  Memory goals are read in
decimal units (1 GB = 10⁹ bytes); the table gives MiB as well.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

# the tableaux the other benchmarks measure these rows with (a script's folder is on its path)
from bench_arith import DENSE6, RK4_DECIMAL
from bench_stream import EULER, RK4

ROOT = Path(__file__).resolve().parent.parent

CHILD = r"""
import importlib, json, pkgutil, resource, sys, time
sys.path.insert(0, {root!r})
import rkcheck
from rkcheck.api.settings import use_listing_cache
use_listing_cache()
# every module of the package before the clock, and python-flint, the one dependency
# rkcheck imports on first use: a path that imports lazily (the decimal box, whose
# stability function is enclosed with FLINT's balls) pays no import inside the timed
# check, the same as the exact path
for module in pkgutil.walk_packages(rkcheck.__path__, "rkcheck."):
    importlib.import_module(module.name)
import flint
rkcheck.load({path!r})
def clock():  # this process and the children it waited for (a field is built in one)
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + r.ru_utime + r.ru_stime
c0 = clock()
v = rkcheck.verify({path!r}, **{kwargs!r})
cpu = clock() - c0
# the per-order counts, not the conditions: those would compute every failing value
counts = v.per_order
weakest = min((p.min_digits for p in counts if p.min_digits is not None), default=None)
print(json.dumps({{"cpu": cpu, "conditions": sum(p.conditions for p in counts), "failing": sum(p.failed for p in counts),
                  "undecided": sum(p.checked - p.held - p.failed for p in counts), "weakest": weakest}}))
"""

MB, MIB = 10**6, 2**20
#: a scan exits 1 when some file fails its gate: measured all the same
SCAN_EXITS = (0, 1)


def write_tableau(folder: Path, name: str, tableau: tuple) -> Path:
    """A tableau file without claims: its check is the conditions and the orders."""
    A, b = tableau
    quoted = lambda row: "[" + ", ".join(f'"{x}"' for x in row) + "]"  # noqa: E731
    path = folder / f"{name}.toml"
    path.write_text(f'[method]\nname = "{name}"\n\n[tableau]\nA = [{", ".join(map(quoted, A))}]\nb = {quoted(b)}\n',
                    encoding="utf-8")
    return path


def run_child(argv: list[str], env: dict, ok: tuple[int, ...] = (0,)) -> dict:
    """One child process: its last JSON line (if any), its CPU seconds with its own
    children (``process_cpu``) and its peak resident memory in bytes, through ``os.wait4``;
    an exit code outside ``ok`` stops the run with the child's error."""
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True, cwd=ROOT)
    _, status, usage = os.wait4(proc.pid, 0)
    out, err = proc.stdout.read(), proc.stderr.read()
    proc.stdout.close()
    proc.stderr.close()
    code = os.waitstatus_to_exitcode(status)
    if code not in ok:
        raise SystemExit(f"{' '.join(argv[-3:])} failed (exit {code}):\n{err.strip()}")
    lines = [line for line in out.splitlines() if line.startswith("{")]
    result = json.loads(lines[-1]) if lines else {}
    result["process_cpu"] = usage.ru_utime + usage.ru_stime
    result["peak"] = usage.ru_maxrss * (1 if sys.platform == "darwin" else 1024)  # KiB on Linux
    return result


@dataclass
class Runner:
    """Runs cases in fresh processes against one private listing cache."""

    cache: Path
    repeat: int
    env: dict = field(default_factory=dict)

    def __post_init__(self):
        # an installed rkcheck has its bytecode cached: a child that compiled every module
        # anew (PYTHONDONTWRITEBYTECODE, set in some sandboxes) would pay ~0.3 s per process
        self.env = {k: v for k, v in os.environ.items() if k not in ("RKCHECK_NO_CACHE", "PYTHONDONTWRITEBYTECODE")}
        self.env.update(RKCHECK_CACHE_DIR=str(self.cache), NO_COLOR="1")
        self._warm: set[tuple] = set()

    def verify(self, path: Path, cold: bool = False, **kwargs) -> dict:
        """``rkcheck.verify(path, **kwargs)``: the median CPU and peak over the runs, after
        one uncounted run that fills the listing cache (``cold``: no cache, every run
        builds its listing)."""
        argv = [sys.executable, "-c", CHILD.format(root=str(ROOT), path=str(path), kwargs=kwargs)]
        env = dict(self.env, RKCHECK_NO_CACHE="1") if cold else self.env
        key = (str(path), kwargs.get("order"), kwargs.get("degree"))
        if key not in self._warm and not cold:
            run_child(argv, env)
            self._warm.add(key)
        runs = [run_child(argv, env) for _ in range(self.repeat)]
        return dict(runs[0], cpu=statistics.median(r["cpu"] for r in runs),
                    peak=statistics.median(r["peak"] for r in runs))

    def scan(self, folder: Path) -> dict:
        """``rkcheck scan FOLDER --jobs 1``, the whole process: median CPU (children
        included) and peak, after one uncounted run."""
        argv = [sys.executable, "-m", "rkcheck", "scan", str(folder), "--jobs", "1", "--quiet"]
        run_child(argv, self.env, SCAN_EXITS)
        runs = [run_child(argv, self.env, SCAN_EXITS) for _ in range(self.repeat)]
        return {"cpu": statistics.median(r["process_cpu"] for r in runs),
                "peak": statistics.median(r["peak"] for r in runs)}


def _mem(peak: float) -> str:
    return f"{peak / MB:,.0f} MB ({peak / MIB:,.0f} MiB)".replace(",", "\u202f")


@dataclass
class Row:
    case: str
    measured: str
    goal: str
    met: bool | None  # None: no goal applies (--quick) or not run


def goal_rows(run: Runner, folder: Path, quick: bool, order_22: bool, cluster: bool) -> list[Row]:
    """Every goal row, in the order of the issue's table."""
    o20, o18, o16, o12 = (10, 10, 8, 6) if quick else (20, 18, 16, 12)
    judge = (lambda ok: None) if quick else (lambda ok: bool(ok))
    rk4, rk4_dec, euler, dense6 = (write_tableau(folder, n, t) for n, t in
                                   (("rk4", RK4), ("rk4-decimal", RK4_DECIMAL), ("euler", EULER), ("dense6", DENSE6)))
    gauss3 = ROOT / "tableaux" / "collocation" / "gauss-3.toml"
    # HBVM(6, 3) as its family, without the catalogue file's claims: the same one check
    # as the dense tableau's (the claims add a second check, at degree 5)
    hbvm63 = folder / "hbvm-6-3.toml"
    hbvm63.write_text('[method]\nname = "HBVM(6, 3)"\n\n[family]\nname = "hbvm"\nk = 6\ns = 3\n', encoding="utf-8")
    rows = []

    r = run.verify(rk4, order=o20, degree="none", arithmetic="exact")
    rows.append(Row(f"RK4 exact, order {o20}, cached", f"{r['cpu']:.2f} s, {_mem(r['peak'])}",
                    "≤ 10 s, ≤ 1 GB", judge(r["cpu"] <= 10 and r["peak"] <= 1000 * MB)))
    if order_22 and not quick:
        r = run.verify(rk4, order=22, degree="none", arithmetic="exact")
        rows.append(Row("RK4 exact, order 22", f"{r['cpu']:.1f} s, {_mem(r['peak'])}", "≤ 2 min, ≤ 2 GB",
                        r["cpu"] <= 120 and r["peak"] <= 2000 * MB))
    else:
        rows.append(Row("RK4 exact, order 22", "not run (--order-22)", "≤ 2 min, ≤ 2 GB", None))

    # the full run builds its listing, as the goal was set: fail-fast is to stop before
    # the orders beyond the failure are built (with a listing cached, both only read it)
    full = run.verify(euler, order=o18, degree="none", cold=True)
    fast = run.verify(euler, order=o18, degree="none", fail_fast=True, cold=True)
    ratio = fast["cpu"] / full["cpu"]
    rows.append(Row(f"`--fail-fast` at order {o18}, failing at order 2, listing built",
                    f"{fast['cpu']:.3f} s against {full['cpu']:.2f} s: {ratio:.3f} of full", "≤ 0.05 of full",
                    judge(ratio <= 0.05)))

    exact16 = run.verify(rk4, order=o16, degree="none", arithmetic="exact")
    dec16 = run.verify(rk4_dec, order=o16, degree="none")
    ratio = dec16["cpu"] / exact16["cpu"]
    rows.append(Row(f"decimal RK4 (16 digits), order {o16}", f"{dec16['cpu']:.2f} s against {exact16['cpu']:.2f} s "
                    f"exact: {ratio:.2f}×", "≤ 2× exact", judge(ratio <= 2)))

    parts, ok = [], True
    for name, path in (("RK4", rk4), ("Gauss-3", gauss3)):
        exact = run.verify(path, order=o18, degree="none", arithmetic="exact")
        ball = run.verify(path, order=o18, degree="none", arithmetic="ball")
        ratio = ball["cpu"] / exact["cpu"]
        ok = ok and ratio <= 1.5 and ball["peak"] <= 500 * MB
        parts.append(f"{name} {ball['cpu']:.2f} s against {exact['cpu']:.2f} s ({ratio:.2f}×), {_mem(ball['peak'])}")
    rows.append(Row(f"forced balls, order {o18}", "; ".join(parts), "≤ 1.5× exact, ≤ 0.5 GB", judge(ok)))

    dec18 = run.verify(rk4_dec, order=o18, degree="none")
    exact18 = run.verify(rk4, order=o18, degree="none", arithmetic="exact")
    # checked: RK4's failures all found on the box, every other condition holding to some digits
    checked = (dec18["failing"] == exact18["failing"] and dec18["undecided"] == 0
               and (dec18["weakest"] is None or dec18["weakest"] >= 1))
    rows.append(Row(f"decimal RK4, order {o18}", f"{dec18['failing']:,} of {exact18['failing']:,} failures found, "
                    f"{dec18['undecided']} undecided, the rest to ≥ {dec18['weakest']} digits; {dec18['cpu']:.1f} s, "
                    f"{_mem(dec18['peak'])}", "checked", judge(checked)))

    r = run.verify(gauss3, order=o18, degree="none", arithmetic="exact")
    rows.append(Row(f"Gauss-3 exact, order {o18}, cached", f"{r['cpu']:.2f} s, {_mem(r['peak'])}", "≤ 2 s",
                    judge(r["cpu"] <= 2)))

    scanned = "tableaux/collocation/" if quick else "tableaux/"
    r = run.scan(ROOT / scanned)
    rows.append(Row(f"`scan {scanned}` (`--jobs 1`), whole process", f"{r['cpu']:.2f} s CPU, {_mem(r['peak'])}",
                    "≤ 3 s", judge(r["cpu"] <= 3)))

    hbvm = run.verify(hbvm63, order=o12, degree=4)
    dense = run.verify(dense6, order=o12, degree=4)
    ratio = hbvm["cpu"] / dense["cpu"]
    rows.append(Row(f"HBVM(6, 3) against a dense rational 6-stage tableau, degree 4, order {o12}",
                    f"{hbvm['cpu']:.2f} s against {dense['cpu']:.2f} s: {ratio:.1f}×", "≤ 3×", judge(ratio <= 3)))

    rows.append(cluster_row() if cluster and not quick else
                Row("2 000 tableaux on a 2-worker LocalCluster", "not run (--cluster)", "≥ 1.8× `--jobs 1`", None))
    return rows


def cluster_row() -> Row:
    """benchmarks/report_cluster.py's speed-up of the LocalCluster over ``--jobs 1``."""
    proc = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "report_cluster.py")],
                          capture_output=True, text=True, cwd=ROOT)
    if proc.returncode:
        raise SystemExit(f"report_cluster.py failed:\n{proc.stderr.strip()}")
    found = {m.group(1): (float(m.group(2)), m.group(3)) for m in
             re.finditer(r"^\| (--\S+)[^|]*\| [\d.]+ \| ([\d.]+)× \| [\d.]+ \| ([\d.]*)×? \|", proc.stdout, re.M)}
    (cluster, top), (jobs2, _) = found["--scheduler"], found["--jobs"]  # "--jobs 2" comes after "--jobs 1"
    return Row("2 000 tableaux on a 2-worker LocalCluster",
               f"{cluster:.2f}× (`--jobs 2`: {jobs2:.2f}×; two copies of a pure-Python loop just before: {top}×)",
               "≥ 1.8× `--jobs 1`", cluster >= 1.8)


def markdown(rows: list[Row]) -> str:
    mark = {True: "met", False: "not met", None: "—"}
    lines = ["| case | measured | goal | |", "|---|---|---|---|"]
    lines += [f"| {r.case} | {r.measured} | {r.goal} | {mark[r.met]} |" for r in rows]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3, metavar="N", help="runs per case, the median kept (default 3)")
    parser.add_argument("--quick", action="store_true", help="small orders, one run each (no goal applies)")
    parser.add_argument("--order-22", action="store_true", help="also RK4 exact at order 22")
    parser.add_argument("--cluster", action="store_true", help="also the LocalCluster scan (rkcheck[cluster])")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="rkcheck-goals-") as tmp:
        folder, cache = Path(tmp) / "tableaux", Path(tmp) / "cache"
        folder.mkdir()
        run = Runner(cache, 1 if args.quick else max(1, args.repeat))
        load = os.getloadavg()[0]
        rows = goal_rows(run, folder, args.quick, args.order_22, args.cluster)
    shown = " ".join(argv if argv is not None else sys.argv[1:])
    print(f"`python benchmarks/goals.py{' ' + shown if shown else ''}`: median of {run.repeat} run(s), "
          f"{os.cpu_count()} cores, load average {load:.1f} before and {os.getloadavg()[0]:.1f} after\n")
    print(markdown(rows))


if __name__ == "__main__":
    main()
