"""Fuzzing the front door: entries, whole files (shipped tableaux mutated, random TOML/JSON
documents, random bytes), option sets of every command and the importers (nodepy text,
CSV) never give a traceback, an internal error or an exit code other than 0, 1 or 2;
stderr is at most 3 lines; each run ends within its time limit (a SIGALRM guard).

The generators are tests/fuzz/generators.py, shared with ``benchmarks/fuzz.py``, which
runs them by the thousand in separate processes.  Here a few dozen examples per family,
derandomized (the same examples on every run), run in-process through the CLI's
``main()``: an escaping exception would be an exit 3.  ``RKCHECK_FUZZ_EXAMPLES=500``
runs more of them, with fresh random examples.
"""

from __future__ import annotations

import io
import os
import sys

import pytest
from fuzz.generators import FAMILIES, Case
from hypothesis import HealthCheck, given, settings
from support.clirun import run_cli
from support.guards import hang_guard
from support.limits import run_limited

EXAMPLES = int(os.environ.get("RKCHECK_FUZZ_EXAMPLES", "40"))
FUZZ = settings(max_examples=EXAMPLES, deadline=None, derandomize=not os.environ.get("RKCHECK_FUZZ_EXAMPLES"),
                database=None, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
#: the per-run limit: a guard against a hang, not a timing target (runs take well under 1 s)
SECONDS_PER_RUN = 20


def run_case(case: Case, folder, capsys):
    """``rkcheck ARGS`` in this process, in ``folder`` holding the case's files, with the
    case's standard input; the exit code, stdout and stderr."""
    for name, data in case.files.items():
        (folder / name).write_bytes(data)
    cwd, stdin = os.getcwd(), sys.stdin
    os.chdir(folder)
    sys.stdin = io.TextIOWrapper(io.BytesIO(case.stdin or b""), encoding="utf-8", errors="surrogateescape")
    try:
        with hang_guard(SECONDS_PER_RUN):
            return run_cli(capsys, *case.args)
    finally:
        os.chdir(cwd)
        sys.stdin = stdin


def check(case: Case, r) -> None:
    where = case.describe()
    assert r.code in (0, 1, 2), (where, r.code, r.err)
    assert "Traceback" not in r.err and "internal error" not in r.err, (where, r.err)
    assert len(r.err.splitlines()) <= 3, (where, r.err)
    if r.code == 0 and case.args[:1] == ["show"] and "python" in case.args:
        compile(r.out, "written.py", "exec")  # the written code is Python


@FUZZ
@given(case=FAMILIES["entries"])
def test_entries(tmp_path_factory, capsys, case):
    check(case, run_case(case, tmp_path_factory.mktemp("e"), capsys))


@FUZZ
@given(case=FAMILIES["files"])
def test_files(tmp_path_factory, capsys, case):
    check(case, run_case(case, tmp_path_factory.mktemp("f"), capsys))


@FUZZ
@given(case=FAMILIES["options"])
def test_options(tmp_path_factory, capsys, case):
    check(case, run_case(case, tmp_path_factory.mktemp("o"), capsys))


@FUZZ
@given(case=FAMILIES["importers"])
def test_importers(tmp_path_factory, capsys, case):
    check(case, run_case(case, tmp_path_factory.mktemp("i"), capsys))


# the costliest option sets the fuzz can draw, in a child process under memory and CPU
# limits the kernel enforces: validated options never start a check that does not fit
CPU_SECONDS_PER_RUN = 5
MEMORY_MB_PER_RUN = 500
COSTLIEST = [
    ["verify", "--order", "10", "--arithmetic", "ball", "--dps", "5000", "--max-conditions", "99999999999999999999"],
    ["scan", "--order", "10", "--arithmetic", "ball", "--dps", "5000", "--jobs", "1"],
    ["show", "--format", "json"],
    ["conditions", "-N", "10", "-m", "none", "--format", "json"],
    ["verify", "--order", "31", "--max-conditions", "99999999999999999999"],
]


@pytest.mark.parametrize("args", COSTLIEST, ids=[" ".join(a[:3]) for a in COSTLIEST])
def test_costliest_option_sets_run_within_500_mb_and_5_cpu_seconds(tmp_path, args):
    path = tmp_path / "t.toml"
    path.write_text('[tableau]\nA = [["1/2"]]\nb = [1]\n', encoding="utf-8")
    argv = args[:1] + ([] if args[0] == "conditions" else [str(path)]) + args[1:]
    run = run_limited(["-m", "rkcheck", *argv], memory_mb=MEMORY_MB_PER_RUN, cpu_seconds=CPU_SECONDS_PER_RUN)
    assert not run.killed, f"over {CPU_SECONDS_PER_RUN} CPU seconds: {run.code}"
    assert run.code in (0, 1, 2) and "Traceback" not in run.err and "internal error" not in run.err, run.err
    assert "out of memory" not in run.err, run.err
    assert args[2] != "31" or (run.code == 2 and "31" in run.err), run.err
