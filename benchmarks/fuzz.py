"""Fuzz the command line at scale (on demand; the suite runs the same generators a few
dozen times, tests/fuzz/test_fuzz_cli.py).

    python benchmarks/fuzz.py --entries 20000 --files 3000 [--options N] [--importers N]
                              [--timeout 60] [--jobs 2] [--seed 0] [--show 5]

Draws the cases from tests/fuzz/generators.py (hypothesis, derandomized by --seed), then
runs each one as ``rkcheck ARGS`` in a process of its own, forked from this one after
rkcheck is imported and a few commands have run (start-up is paid once), in a fresh folder holding the case's
files, with NO_COLOR=1, a 4 GB address-space limit and a wall-clock timeout.  Reports,
per family, the count of each exit code, of timeouts, and of runs whose stderr shows a
traceback or an internal error; then the first --show failing cases of each kind.
The goal: no exit 3, no traceback, no timeout.
"""

from __future__ import annotations

import argparse
import os
import resource
import signal
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "tests" / "fuzz")]  # not "fuzz.": this script is "fuzz"

from generators import FAMILIES, Case  # noqa: E402
from hypothesis import HealthCheck, Phase, given, settings  # noqa: E402

from rkcheck.cli.main import main as cli_main  # noqa: E402

MEMORY_LIMIT = 4 * 2**30


def draw(strategy, count: int, seed: int) -> list[Case]:
    """``count`` cases from a strategy, reproducibly (hypothesis seeded by ``seed``)."""
    out: list[Case] = []
    if count <= 0:
        return out

    @settings(max_examples=count, database=None, phases=[Phase.generate], deadline=None,
              suppress_health_check=list(HealthCheck), derandomize=False)
    @given(strategy)
    def collect(case):
        out.append(case)

    from hypothesis import seed as hseed
    hseed(seed)(collect)()
    return out[:count]


def _child(case: Case, folder: str) -> None:
    """In the forked process: run the case and exit with its code (never returns)."""
    try:
        os.chdir(folder)
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
        for name, data in case.files.items():
            Path(name).write_bytes(data)
        fd = os.open("stdin", os.O_RDWR | os.O_CREAT)
        os.write(fd, case.stdin or b"")
        os.lseek(fd, 0, 0)
        os.dup2(fd, 0)
        os.dup2(os.open("stdout", os.O_WRONLY | os.O_CREAT), 1)
        os.dup2(os.open("stderr", os.O_WRONLY | os.O_CREAT), 2)
        sys.stdin = open(0, encoding="utf-8", errors="surrogateescape", closefd=False)
        sys.stdout = open(1, "w", encoding="utf-8", closefd=False)
        sys.stderr = open(2, "w", encoding="utf-8", closefd=False)
        os.environ["NO_COLOR"] = "1"
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        code = 0
        try:
            cli_main(list(case.args))
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    except BaseException:  # noqa: BLE001 - anything escaping main() is a traceback
        import traceback

        traceback.print_exc()
        sys.stderr.flush()
        os._exit(99)


def warm_up() -> None:
    """Run a few commands in this process, output discarded, so that the modules they load
    lazily (FLINT, mpmath, numpy, rich, every command's own) are loaded once here and
    inherited by each forked run instead of imported again in every child (a third of a
    second per run)."""
    import contextlib
    import io

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        for args in (["verify", "@gauss-2", "--order", "3"], ["verify", "@rk4", "--order", "3", "--format", "json"],
                     ["show", "@gauss-2"], ["conditions", "-N", "3"], ["explain", "1,2,2", "--tableau", "@rk4"]):
            try:
                cli_main(args)
            except SystemExit:
                pass


def run_all(cases: list[tuple[str, Case]], timeout: float, jobs: int, progress: bool):
    """Run the cases, ``jobs`` at a time; yields (family, case, code or "timeout", stderr, seconds)."""
    pending = list(enumerate(cases))
    running: dict[int, tuple[int, float, str]] = {}
    results = []
    done = bad = timeouts = 0
    while pending or running:
        while pending and len(running) < jobs:
            k, (family, case) = pending.pop(0)
            folder = tempfile.mkdtemp(prefix="rkfuzz-")
            pid = os.fork()
            if pid == 0:
                _child(case, folder)
            running[pid] = (k, time.monotonic(), folder)
        pid, status = os.waitpid(-1, os.WNOHANG)
        if pid == 0:
            now = time.monotonic()
            for p, (k, t0, folder) in list(running.items()):
                if now - t0 > timeout:
                    os.kill(p, signal.SIGKILL)
                    os.waitpid(p, 0)
                    del running[p]
                    results.append((k, "timeout", "", now - t0, folder))
                    timeouts += 1
                    if progress:
                        print(f"  timeout: {cases[k][1].describe()[:300]}", file=sys.stderr, flush=True)
            time.sleep(0.005)
            continue
        k, t0, folder = running.pop(pid)
        code = os.waitstatus_to_exitcode(status)
        err = Path(folder, "stderr").read_text(encoding="utf-8", errors="replace")
        results.append((k, code, err, time.monotonic() - t0, folder))
        done += 1
        if code not in (0, 1, 2) or "Traceback" in err or "internal error" in err:
            bad += 1
            if progress:  # at once: a long run shows its problems as they come
                print(f"  problem (exit {code}): {cases[k][1].describe()[:300]}\n    -> {err.strip()[-300:]}",
                      file=sys.stderr, flush=True)
        if progress and done % 200 == 0:
            print(f"  {done}/{len(cases)}, {bad} problems, {timeouts} timeouts", file=sys.stderr, flush=True)
    for k, code, err, seconds, folder in sorted(results, key=lambda r: r[0]):
        for name in os.listdir(folder):
            p = Path(folder, name)
            if p.is_file() or p.is_symlink():
                p.unlink()
        try:
            os.rmdir(folder)
        except OSError:
            pass
        yield cases[k][0], cases[k][1], code, err, seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--entries", type=int, default=2000)
    parser.add_argument("--files", type=int, default=300)
    parser.add_argument("--options", type=int, default=None, help="default: a tenth of --entries")
    parser.add_argument("--importers", type=int, default=None, help="default: a tenth of --entries")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per run")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--show", type=int, default=5, help="failing cases shown per kind")
    args = parser.parse_args()
    counts = {"entries": args.entries, "files": args.files,
              "options": args.entries // 10 if args.options is None else args.options,
              "importers": args.entries // 10 if args.importers is None else args.importers}
    cases = [(family, case) for family, n in counts.items() for case in draw(FAMILIES[family], n, args.seed)]
    print(f"{len(cases)} cases: " + ", ".join(f"{n} {f}" for f, n in counts.items()) +
          f"; timeout {args.timeout:g} s; seed {args.seed}", flush=True)
    warm_up()
    table: dict[str, Counter] = {f: Counter() for f in counts}
    bad: dict[str, list[str]] = {}
    slowest = (0.0, "")
    t0 = time.monotonic()
    for family, case, code, err, seconds in run_all(cases, args.timeout, args.jobs, progress=True):
        kind = "timeout" if code == "timeout" else f"exit {code}"
        table[family][kind] += 1
        if seconds > slowest[0]:
            slowest = (seconds, case.describe())
        problem = None
        if code == "timeout":
            problem = "timeout"
        elif code not in (0, 1, 2):
            problem = f"exit {code}"
        elif "Traceback" in err or "internal error" in err:
            problem = "traceback"
        if problem:
            if problem == "traceback":
                table[family]["traceback"] += 1
            bad.setdefault(problem, []).append(f"{case.describe()}\n    -> {err.strip()[-400:]}")
    print(f"\n{'family':10} " + " ".join(f"{k:>9}" for k in ("exit 0", "exit 1", "exit 2", "exit 3", "other",
                                                                "timeout", "traceback")))
    for family, c in table.items():
        other = sum(v for k, v in c.items() if k.startswith("exit") and k not in ("exit 0", "exit 1", "exit 2", "exit 3"))
        print(f"{family:10} " + " ".join(f"{v:>9}" for v in (c["exit 0"], c["exit 1"], c["exit 2"], c["exit 3"],
                                                              other, c["timeout"], c["traceback"])))
    print(f"\nwall time {time.monotonic() - t0:.0f} s; slowest run {slowest[0]:.1f} s: {slowest[1][:200]}")
    for problem, items in bad.items():
        print(f"\n== {problem}: {len(items)}")
        for item in items[:args.show]:
            print(" ", item)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
