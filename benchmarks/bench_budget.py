"""The resource guard's estimates against what checks take: one command, one table.

    python benchmarks/bench_budget.py             # orders 16 and 18 (a few minutes)
    python benchmarks/bench_budget.py --order-20  # also order 20 (several GB, minutes each)
    python benchmarks/bench_budget.py --quick     # the tableaux at order 8, the kernels lower (a minute)

Before a check, rkcheck estimates its time and memory from the exact counts of its
listing (``rkcheck.energy.budget``), announces a long one and refuses one that would
not fit the available memory.  The memory model must stay on the high side — a check
it lets through must not run the machine out of memory — without refusing checks that
fit.  Each row is one ``rkcheck verify FILE --order N --degree none`` in a fresh
process (the listing cache off: every listing built), its CPU time and peak resident
memory read through ``os.wait4``, beside the estimate the check computes for itself.

The ball rows use methods whose conditions hold or nearly all hold, so the float screen
decides few of them and the certified balls evaluate every condition: the worst case
the model covers.  The last rows have many stages: the continuous methods with
Miyatake–Butcher matrix ``M = I_k`` (energy-preserving: every condition holds), checked
through surrogates of 100–270 stages, written to a temporary folder, and kernels of
degree 20 and 40 in rounded decimals, judged over the box of their decimals on
surrogates of thousands of entries.

Each estimate is computed in a process of its own: a forked child's peak memory counts
its parent's pages, so the measuring process stays small.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TABLEAUX = ROOT / "tableaux"

#: (label, file under tableaux/, arithmetic, orders, extra options)
CASES = [
    ("RK4", "explicit/rk4.toml", "exact", (16, 18, 20), ()),
    ("Gauss-3", "collocation/gauss-3.toml", "exact", (16, 18, 20), ()),
    ("AVF Gauss-2", "avf/avf-gauss-2.toml", "ball", (16, 18), ()),
    ("AVF Gauss-3", "avf/avf-gauss-3.toml", "ball", (16, 18, 20), ()),
    ("AVF Gauss-4", "avf/avf-gauss-4.toml", "ball", (16, 18), ()),
    ("AVF Gauss-3, 150 digits", "avf/avf-gauss-3.toml", "ball", (16,), ("--dps", "150")),
    ("AVF Gauss-2, 16-digit decimals", "avf/avf-gauss-2-decimal16.toml", "auto", (16, 18), ()),
    ("HBVM(6, 2), 60-digit decimals", "hbvm/hbvm-6-2-decimal60.toml", "auto", (16,), ()),
]


#: (label, k of M = I_k, arithmetic, orders, quick order): continuous methods of many stages
KERNELS = [
    ("M = I_10", 10, "exact", (10, 11), 9),
    ("M = I_20", 20, "exact", (8,), 6),
    ("M = I_10", 10, "ball", (9,), 7),
]


#: (label, degree p, orders, in --quick): the kernel τ + ¼τᵖσᵖ − ⅓τᵖ⁻¹σ² in 6-digit
#: decimals, judged over the box of its decimals on a surrogate of thousands of entries
DECIMAL_KERNELS = [
    ("degree-20 kernel, 6-digit decimals", 20, (3,), True),
    ("degree-40 kernel, 6-digit decimals", 40, (3,), False),
]


def decimal_kernel(folder: Path, p: int) -> Path:
    path = folder / f"decimal-{p}.toml"
    path.write_text(f'[method]\nname = "degree {p}"\n[continuous]\n'
                    f'A = "tau + 0.250000*tau^{p}*sigma^{p} - 0.333333*tau^{p - 1}*sigma^2"\n'
                    f'b = "1 + 0.142857*sigma^{p} - 0.142857*sigma^{p - 1}"\n')
    return path


def identity_kernel(folder: Path, k: int) -> Path:
    path = folder / f"identity-{k}.toml"
    rows = ",\n".join("[" + ", ".join('"1"' if i == j else '"0"' for j in range(k)) + "]" for i in range(k))
    path.write_text(f'[method]\nname = "M = I_{k}"\n[continuous]\nM = [\n{rows}\n]\n')
    return path


def estimated(path: Path, order: int, arithmetic: str, extra: tuple[str, ...]) -> tuple[float, int]:
    """The seconds and bytes the check's own estimate gives, in a fresh process."""
    argv = [sys.executable, __file__, "--estimate", str(path), str(order), arithmetic, *extra]
    seconds, size = subprocess.run(argv, capture_output=True, text=True, check=True, cwd=ROOT).stdout.split()
    return float(seconds), int(size)


def print_estimate(path: str, order: int, arithmetic: str, extra: list[str]) -> None:
    """As ``energy.check`` computes it (:func:`~rkcheck.energy.check.check_estimate`) on
    the surrogate of a continuous method on the rule the check takes."""
    from rkcheck.energy.check import check_estimate
    from rkcheck.evaluation.values import TableauValues
    from rkcheck.io.loader import load
    from rkcheck.numbers.reading import Reading
    from rkcheck.options import CheckOptions

    tableau = load(path)
    dps = int(extra[extra.index("--dps") + 1]) if "--dps" in extra else int(tableau.info.check.get("dps", 50))
    options = CheckOptions(order=order, degree=None, arithmetic=arithmetic, dps=dps)
    if getattr(tableau, "is_continuous", False):
        from rkcheck.energy.claims import in_intervals, vertices_needed

        tableau = tableau.surrogate(vertices_needed(options, []), in_intervals(tableau, options))
    est = check_estimate(TableauValues(tableau, Reading(dps=dps, arithmetic=arithmetic)), options)
    print(est.seconds, est.bytes)


def measured(path: Path, order: int, arithmetic: str, extra: tuple[str, ...]) -> tuple[float, int]:
    """CPU seconds and peak resident bytes of one ``rkcheck verify`` process."""
    argv = [sys.executable, "-m", "rkcheck", "verify", str(path), "--order", str(order), "--degree", "none",
            "--arithmetic", arithmetic, "--no-cache", "-q", *extra]
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=ROOT,
                            env=dict(os.environ, NO_COLOR="1"))
    _, status, usage = os.wait4(proc.pid, 0)
    err = proc.stderr.read().decode() if proc.stderr else ""
    if os.waitstatus_to_exitcode(status) not in (0, 1):
        raise SystemExit(f"{' '.join(argv[3:])}: {err.strip()}")
    return usage.ru_utime + usage.ru_stime, usage.ru_maxrss * 1024


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--order-20", action="store_true", help="also order 20 (several GB, minutes each)")
    parser.add_argument("--quick", action="store_true", help="every case at order 8 only")
    parser.add_argument("--estimate", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)  # PATH ORDER ARITHMETIC [EXTRA...]
    args = parser.parse_args(argv)
    if args.estimate:
        path, order, arithmetic, *extra = args.estimate
        return print_estimate(path, int(order), arithmetic, extra)
    print("| method | arithmetic | order | CPU s | estimated s | peak MB | estimated MB | estimate / peak |\n"
          "|---|---|---|---|---|---|---|---|")
    rows = [(label, TABLEAUX / name, arithmetic, (8,) if args.quick else orders, extra)
            for label, name, arithmetic, orders, extra in CASES]
    with tempfile.TemporaryDirectory() as folder:
        rows += [(label, identity_kernel(Path(folder), k), arithmetic, (quick,) if args.quick else orders, ())
                 for label, k, arithmetic, orders, quick in KERNELS]
        rows += [(label, decimal_kernel(Path(folder), p), "auto", orders, ())
                 for label, p, orders, quick in DECIMAL_KERNELS if quick or not args.quick]
        for label, path, arithmetic, orders, extra in rows:
            for order in orders:
                if order >= 20 and not args.order_20:
                    continue
                cpu, peak = measured(path, order, arithmetic, extra)
                seconds, size = estimated(path, order, arithmetic, extra)
                print(f"| {label} | {arithmetic} | {order} | {cpu:.1f} | {seconds:.0f} | {peak / 1e6:.0f} "
                      f"| {size / 1e6:.0f} | {size / peak:.2f} |", flush=True)


if __name__ == "__main__":
    main()
