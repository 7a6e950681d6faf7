"""The benchmark report: one Markdown table and one PNG chart of time and peak memory
against energy order, for RK4 and Gauss-3 in every arithmetic, and rkcheck against the
direct Python implementation, all measured in the same run.

    python benchmarks/report.py --quick                      # orders 4 to 10 (a minute or two)
    python benchmarks/report.py --max-order 16 --chart docs/performance-report.png
    python benchmarks/report.py --max-order 14 --reference-max-order 12 -o report.md

Series (each tableau written to a temporary folder, without claims, so that a check is
the energy conditions and the orders only):

* ``exact``       — the exact entries (RK4 rational, Gauss-3 in Q(√15)): ``arithmetic="exact"``
  (residues modulo primes; rkcheck has no other exact route to compare with);
* ``ball``        — the same entries in certified balls at 50 digits (``arithmetic="ball"``);
* ``decimal box`` — the entries written with 16 significant digits: each stands for
  every number within half a unit of its last digit, and a condition is judged for the
  whole joint box (definitions §5);
* ``reference``   — RK4 only: the brute-force implementation of the definitions that
  the test-suite checks rkcheck against (``tests/support/reference.py``: networkx free
  trees, Fraction residuals), one residual per condition.  It cannot take Gauss-3
  (Fractions only).  pybs, the other implementation once compared with, is not
  measured: the registry reachable here holds only pybs 0.1, a Python 2 package.

Every measurement is ``rkcheck.verify(file, order=N, degree="none", ...)`` (or the
reference loop) in a fresh interpreter, timed inside it after the imports: wall time and
CPU time of the check (on a shared machine CPU time is the steadier of the two).  Its
peak memory is the whole child's maximum resident set, read by a small parent process
that runs just that child: ``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss``.
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

RK4 = {"A": [["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]],
       "b": ["1/6", "1/3", "1/3", "1/6"]}
RK4_DECIMAL = {"A": [["0", "0", "0", "0"], ["0.5", "0", "0", "0"], ["0", "0.5", "0", "0"], ["0", "0", "1", "0"]],
               "b": ["0.1666666666666667", "0.3333333333333333", "0.3333333333333333", "0.1666666666666667"]}
GAUSS3 = {"A": [["5/36", "2/9 - sqrt(15)/15", "5/36 - sqrt(15)/30"],
                ["5/36 + sqrt(15)/24", "2/9", "5/36 - sqrt(15)/24"],
                ["5/36 + sqrt(15)/30", "2/9 + sqrt(15)/15", "5/36"]],
          "b": ["5/18", "4/9", "5/18"]}

#: (label, tableau, file, arithmetic for verify, runner)
SERIES = [
    ("RK4", "exact", "rk4", "exact", "rkcheck"),
    ("RK4", "ball", "rk4", "ball", "rkcheck"),
    ("RK4", "decimal box", "rk4-decimal", "auto", "rkcheck"),
    ("RK4", "reference (direct Python)", "rk4", "exact", "reference"),
    ("Gauss-3", "exact", "gauss-3", "exact", "rkcheck"),
    ("Gauss-3", "ball", "gauss-3", "ball", "rkcheck"),
    ("Gauss-3", "decimal box", "gauss-3-decimal", "auto", "rkcheck"),
]

CHILD = r"""
import json, sys, time
sys.path.insert(0, {root!r}); sys.path.insert(0, {tests!r})
runner, path, order, arithmetic = {runner!r}, {path!r}, {order!r}, {arithmetic!r}
if runner == "rkcheck":
    import rkcheck
    rkcheck.load(path)  # modules loaded before the clock starts
else:
    import tomllib
    from fractions import Fraction
    from support import reference as ref
    data = tomllib.loads(open(path, encoding="utf-8").read())["tableau"]
    A = [[Fraction(x) for x in row] for row in data["A"]]
    b = [Fraction(x) for x in data["b"]]
t0, c0 = time.perf_counter(), time.process_time()
if runner == "rkcheck":
    v = rkcheck.verify(path, order=order, degree="none", arithmetic=arithmetic)
    out = {{"conditions": len(v.conditions), "failing": len(v.failures), "energy_order": v.energy_order}}
else:
    residuals = [ref.energy_residual(c, A, b) for n in range(3, order + 2) for c in ref.energy_conditions(n)]
    out = {{"conditions": len(residuals), "failing": sum(r != 0 for r in residuals)}}
out["seconds"], out["cpu"] = time.perf_counter() - t0, time.process_time() - c0
print(json.dumps(out))
"""

#: The parent of one measurement: its RUSAGE_CHILDREN is that one child's peak.
WRAPPER = r"""
import json, resource, subprocess, sys
proc = subprocess.run([sys.executable, "-c", sys.argv[1]], capture_output=True, text=True)
if proc.returncode:
    sys.exit(proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else f"exit {proc.returncode}")
out = json.loads(proc.stdout.strip().splitlines()[-1])
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
out["peak_mb"] = usage.ru_maxrss / 1024  # KiB on Linux
print(json.dumps(out))
"""


def write_tableaux(folder: Path) -> dict[str, str]:
    """The four tableau files, without claims (a check is the conditions and orders)."""
    def toml(name: str, tab: dict) -> str:
        rows = ",\n     ".join("[" + ", ".join(f'"{x}"' for x in row) + "]" for row in tab["A"])
        return (f'[method]\nname = "{name}"\n\n[tableau]\nA = [{rows}]\n'
                f'b = [{", ".join(chr(34) + x + chr(34) for x in tab["b"])}]\n')

    gauss_decimal = {"A": [[_decimal(x) for x in row] for row in GAUSS3["A"]], "b": [_decimal(x) for x in GAUSS3["b"]]}
    files = {"rk4": toml("RK4", RK4), "rk4-decimal": toml("RK4, 16 digits", RK4_DECIMAL),
             "gauss-3": toml("Gauss-3", GAUSS3), "gauss-3-decimal": toml("Gauss-3, 16 digits", gauss_decimal)}
    paths = {}
    for key, text in files.items():
        paths[key] = str(folder / f"{key}.toml")
        Path(paths[key]).write_text(text, encoding="utf-8")
    return paths


def _decimal(entry: str) -> str:
    """An entry of the form ``p/q [± sqrt(15)/r]`` to 16 significant digits."""
    import mpmath

    mpmath.mp.dps = 40
    rational, _, rest = entry.replace(" ", "").partition("sqrt(15)/")
    sign = -1 if rational.endswith("-") else 1
    value = mpmath.mpf(mpmath.fraction(*map(int, rational.rstrip("+-").split("/"))))
    if rest:
        value += sign * mpmath.sqrt(15) / int(rest)
    return mpmath.nstr(value, 16, min_fixed=-5, max_fixed=5, strip_zeros=False)


def measure(runner: str, path: str, order: int, arithmetic: str) -> dict:
    code = CHILD.format(root=str(ROOT), tests=str(ROOT / "tests"), runner=runner, path=path, order=order,
                        arithmetic=arithmetic)
    proc = subprocess.run([sys.executable, "-c", WRAPPER, code], capture_output=True, text=True, cwd=ROOT)
    if proc.returncode:
        raise SystemExit(f"{runner} {path} order {order} ({arithmetic}) failed: {proc.stderr.strip()}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


HEADER = ("| method | arithmetic | order | conditions | failing | wall s | CPU s | peak MB | CPU / exact |\n"
          "|---|---|---|---|---|---|---|---|---|")


def table_row(method: str, arithmetic: str, order: int, r: dict, exact_cpu: float | None) -> str:
    ratio = f"{r['cpu'] / exact_cpu:.1f}×" if exact_cpu else "—"
    return (f"| {method} | {arithmetic} | {order} | {r['conditions']:,} | {r['failing']:,} | {r['seconds']:.3f} "
            f"| {r['cpu']:.3f} | {r['peak_mb']:.0f} | {ratio} |").replace(",", "\u202f")


def run(orders: list[int], reference_max: int, progress) -> list[tuple[str, str, int, dict]]:
    results = []
    with tempfile.TemporaryDirectory(prefix="rkcheck-report-") as tmp:
        paths = write_tableaux(Path(tmp))
        for order in orders:
            for method, arithmetic, key, mode, runner in SERIES:
                if runner == "reference" and order > reference_max:
                    continue
                r = measure(runner, paths[key], order, mode)
                results.append((method, arithmetic, order, r))
                progress(f"{method:8s} {arithmetic:26s} order {order:2d}: {r['seconds']:8.3f} s wall, "
                         f"{r['cpu']:8.3f} s CPU, {r['peak_mb']:6.0f} MB")
    return results


def markdown(results: list[tuple[str, str, int, dict]]) -> str:
    exact = {(m, o): r["cpu"] for m, a, o, r in results if a == "exact"}
    lines = [HEADER]
    for method in dict.fromkeys(m for m, *_ in results):
        for method_, arithmetic, order, r in sorted((x for x in results if x[0] == method),
                                                    key=lambda x: (x[2], [s[1] for s in SERIES].index(x[1]))):
            lines.append(table_row(method_, arithmetic, order, r, exact.get((method_, order))))
    return "\n".join(lines) + "\n"


def chart(results: list[tuple[str, str, int, dict]], path: str, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_t, ax_m) = plt.subplots(1, 2, figsize=(12, 4.8))
    styles = {"RK4": "-", "Gauss-3": "--"}
    markers = {"exact": "o", "ball": "s", "decimal box": "^", "reference (direct Python)": "x"}
    for method, arithmetic, *_ in SERIES:
        pts = sorted((o, r) for m, a, o, r in results if (m, a) == (method, arithmetic))
        if not pts:
            continue
        orders = [o for o, _ in pts]
        label = f"{method}, {arithmetic}"
        ax_t.plot(orders, [r["cpu"] for _, r in pts], styles[method], marker=markers[arithmetic], label=label)
        ax_m.plot(orders, [r["peak_mb"] for _, r in pts], styles[method], marker=markers[arithmetic], label=label)
    ax_t.set(yscale="log", xlabel="energy order N (all Hamiltonians)", ylabel="CPU time of the check (s)",
             title="time")
    ax_m.set(yscale="log", xlabel="energy order N (all Hamiltonians)", ylabel="peak resident memory (MB)",
             title="peak memory (whole process)")
    from matplotlib.ticker import MaxNLocator, NullFormatter, ScalarFormatter

    for ax in (ax_t, ax_m):
        ax.grid(True, which="both", alpha=0.3)
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax_m.yaxis.set_major_formatter(ScalarFormatter())
    ax_m.yaxis.set_minor_formatter(NullFormatter())
    ax_t.legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="orders 4 to 10, the reference to 8 (a minute or two)")
    parser.add_argument("--max-order", type=int, default=16, metavar="N", help="highest energy order (default 16)")
    parser.add_argument("--min-order", type=int, default=6, metavar="N", help="lowest energy order (default 6)")
    parser.add_argument("--step", type=int, default=2, metavar="K", help="orders from min to max in steps of K")
    parser.add_argument("--reference-max-order", type=int, default=12, metavar="N",
                        help="highest order for the direct Python implementation (default 12; it is slow)")
    parser.add_argument("--chart", default=None, metavar="PNG", help="write the chart here (needs matplotlib)")
    parser.add_argument("-o", "--output", default=None, metavar="FILE", help="write the Markdown table here too")
    args = parser.parse_args(argv)
    if args.quick:
        args.min_order, args.max_order, args.reference_max_order = 4, min(args.max_order, 10), min(
            args.reference_max_order, 8)
    if not 2 <= args.min_order <= args.max_order <= 24 or args.step < 1:
        parser.error("orders: need 2 <= --min-order <= --max-order <= 24 and --step >= 1")
    orders = list(range(args.min_order, args.max_order + 1, args.step))
    if args.chart:
        try:
            import matplotlib  # noqa: F401  (before the measurements, not after them)
        except ImportError:
            parser.error("--chart needs matplotlib: pip install 'rkcheck[plot]'")
    results = run(orders, args.reference_max_order, lambda line: print(line, file=sys.stderr, flush=True))
    command = "python benchmarks/report.py " + " ".join(argv if argv is not None else sys.argv[1:])
    load = os.getloadavg()[0]
    text = (f"`{command.strip()}` — {os.cpu_count()} cores, load average {load:.1f} at the end\n\n"
            + markdown(results))
    print(text)
    if args.output:
        Path(args.output).write_text(text, encoding="utf-8")
    if args.chart:
        chart(results, args.chart, f"rkcheck verify, degree none: {command.strip()}")


if __name__ == "__main__":
    main()
