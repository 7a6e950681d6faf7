"""The resource guard's estimates against what checks take: one command, one table.

    python benchmarks/bench_budget.py             # orders 16 and 18 (a few minutes)
    python benchmarks/bench_budget.py --order-20  # also order 20 (several GB, minutes each)
    python benchmarks/bench_budget.py --quick     # every case at order 8 (half a minute)

Before a check, rkcheck estimates its time and memory from the exact counts of its
listing (``rkcheck.energy.budget``), announces a long one and refuses one that would
not fit the available memory.  The memory model must stay on the high side — a check
it lets through must not run the machine out of memory — without refusing checks that
fit.  Each row is one ``rkcheck verify FILE --order N --degree none`` in a fresh
process (the listing cache off: every listing built), its CPU time and peak resident
memory read through ``os.wait4``, beside the estimate the check computes for itself.

The ball rows use methods whose conditions hold or nearly all hold, so the float screen
decides few of them and the certified balls evaluate every condition: the worst case
the model covers.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
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


def estimated(path: Path, order: int, arithmetic: str, extra: tuple[str, ...]) -> tuple[float, int]:
    """The seconds and bytes the check's own estimate gives (as ``energy.check`` computes it)."""
    from rkcheck.energy.budget import estimate
    from rkcheck.energy.judging import box_directions
    from rkcheck.evaluation.backends import channels_for
    from rkcheck.evaluation.values import TableauValues
    from rkcheck.io.loader import load
    from rkcheck.numbers.reading import Reading

    tableau = load(str(path))
    dps = int(extra[extra.index("--dps") + 1]) if "--dps" in extra else int(tableau.info.check.get("dps", 50))
    values = TableauValues(tableau, Reading(dps=dps, arithmetic=arithmetic))
    est = estimate(order, None, values.backend, channels_for(values, order), values.stages, dps,
                   box_directions(values))
    return est.seconds, est.bytes


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
    args = parser.parse_args(argv)
    print("| method | arithmetic | order | CPU s | estimated s | peak MB | estimated MB | estimate / peak |\n"
          "|---|---|---|---|---|---|---|---|")
    for label, name, arithmetic, orders, extra in CASES:
        for order in (8,) if args.quick else orders:
            if order >= 20 and not args.order_20:
                continue
            path = TABLEAUX / name
            seconds, size = estimated(path, order, arithmetic, extra)
            cpu, peak = measured(path, order, arithmetic, extra)
            print(f"| {label} | {arithmetic} | {order} | {cpu:.1f} | {seconds:.0f} | {peak / 1e6:.0f} "
                  f"| {size / 1e6:.0f} | {size / peak:.2f} |", flush=True)


if __name__ == "__main__":
    main()
