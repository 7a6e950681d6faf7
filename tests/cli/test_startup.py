"""Start-up stays light (``--help`` and ``verify`` on a small file in
≤ 0.4 s): the modules each path loads, not its time (timing belongs in
benchmarks/bench_engine.py, ``--startup-runs``).

Each case runs in a fresh interpreter and lists ``sys.modules`` at exit, the way the
``rkcheck`` console script starts (``sys.argv[0] == "rkcheck"``, then
``rkcheck.cli.main``); ``-X importtime`` would miss the commands the CLI loads through
``importlib.import_module``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import pytest

import rkcheck

ROOT = Path(__file__).resolve().parents[2]
RK4 = str(ROOT / "tableaux" / "explicit" / "rk4.toml")

#: Never needed to check a small rational tableau (test-only, optional, or for other
#: number kinds: mpmath/FLINT/gmpy2 serve balls, decimals and number fields).
HEAVY = ("sympy", "matplotlib", "scipy", "networkx", "hypothesis", "pandas", "mpmath", "flint", "gmpy2")
#: Loaded only by what uses them: JSON input or output, suggestions for a misspelt key,
#: progress bars on a terminal, the version read from package metadata.
UNNEEDED = ("json", "difflib", "importlib.metadata", "email", "rich.progress", "rich.live", "rich.markdown",
            "rich.syntax", "rich.pretty", "rich.traceback")
#: numpy >= 2 imports these on first use only; rkcheck never needs them to verify
NUMPY_LAZY = ("numpy.ma", "numpy.random", "numpy.fft", "numpy.polynomial") if int(version("numpy").split(".")[0]) >= 2 else ()
#: the other commands' code
OTHER_COMMANDS = ("rkcheck.cli.library", "rkcheck.cli.scan", "rkcheck.cli.studies", "rkcheck.cli.dynamics",
                  "rkcheck.batch", "rkcheck.dynamics", "rkcheck.studies", "rkcheck.methods.families",
                  "rkcheck.reports.jsondoc", "rkcheck.reports.code", "rkcheck.reports.charts", "rkcheck.reports.scan")

PROGRAM = """
import atexit, sys
out, sys.argv = sys.argv[1], ["rkcheck", *sys.argv[2:]]
def dump():
    names = "\\n".join(sorted(sys.modules))
    with open(out, "w") as fh:
        fh.write(names)
atexit.register(dump)
from rkcheck.cli import main
main()
"""


def loaded(tmp_path: Path, *args: str) -> tuple[set[str], subprocess.CompletedProcess]:
    """The modules a fresh ``rkcheck ARGS`` has loaded when it exits, and the run."""
    out = tmp_path / "modules.json"
    env = {k: v for k, v in os.environ.items() if k not in ("RKCHECK_DEBUG",)}
    run = subprocess.run([sys.executable, "-c", PROGRAM, str(out), *args], capture_output=True, text=True,
                         cwd=tmp_path, env=env, timeout=120)
    return set(out.read_text().split()), run


def present(modules: set[str], names: tuple[str, ...]) -> list[str]:
    """The modules of ``names`` (packages with their submodules) that were loaded."""
    return sorted(m for m in modules for n in names if m == n or m.startswith(n + "."))


def test_verify_of_a_small_rational_tableau_loads_only_what_it_uses(tmp_path):
    modules, run = loaded(tmp_path, "verify", RK4)
    assert run.returncode == 0, run.stderr
    assert "OK: all 7 claims met" in run.stdout  # it did the whole check and the report
    assert {"numpy", "rich.console", "rich.table", "rkcheck.energy.check", "rkcheck.cli.check"} <= modules
    assert present(modules, HEAVY + UNNEEDED + NUMPY_LAZY + OTHER_COMMANDS) == []


def test_help_loads_neither_numpy_nor_rich_nor_the_engine(tmp_path):
    # the command modules themselves are loaded (their one-line help is listed)
    modules, run = loaded(tmp_path, "--help")
    assert run.returncode == 0, run.stderr
    assert "verify" in run.stdout and "Commands" in run.stdout
    assert present(modules, ("numpy", "rich", "rkcheck.api.verification", "rkcheck.energy", "rkcheck.evaluation",
                             "rkcheck.trees", "rkcheck.reports.text") + HEAVY + UNNEEDED) == []


def test_the_api_verify_loads_no_cli_and_nothing_heavy(tmp_path):
    code = ("import json, sys, rkcheck\n"
            f"r = rkcheck.verify({RK4!r})\n"
            "print(json.dumps([r.energy_order, sorted(sys.modules)]))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert run.returncode == 0, run.stderr
    energy_order, names = json.loads(run.stdout)
    assert energy_order == 4  # RK4: Σ b c⁴ = 1/5 fails (its quadrature order is 4)
    modules = set(names)
    assert present(modules, ("click", "rich", "rkcheck.cli", "rkcheck.reports") + HEAVY + NUMPY_LAZY) == []


@pytest.mark.parametrize("how", ["-c", "__main__.py"])
def test_a_library_import_leaves_the_process_settings_alone(tmp_path, how):
    # only the program tunes the collector and OpenBLAS (rkcheck/program.py): a library
    # user's process keeps its own settings, also when it is another package's
    # __main__.py (the program's own is rkcheck/__main__.py)
    code = "import gc, os, rkcheck; rkcheck.verify; print(gc.get_threshold()[0], 'OPENBLAS_THREAD_TIMEOUT' in os.environ)"
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_THREAD_TIMEOUT"}
    default = subprocess.run([sys.executable, "-c", "import gc; print(gc.get_threshold()[0])"], capture_output=True,
                             text=True, env=env).stdout.strip()
    if how == "-c":
        args = ["-c", code]
    else:
        (tmp_path / "tool").mkdir()
        (tmp_path / "tool" / "__main__.py").write_text(code)
        args = [str(tmp_path / "tool" / "__main__.py")]
    run = subprocess.run([sys.executable, *args], capture_output=True, text=True, cwd=tmp_path, env=env)
    assert run.stdout.split() == [default, "False"], run.stderr


def test_the_program_tunes_its_own_process():
    # the console script and `python -m rkcheck` both enter through rkcheck.program.main,
    # which tunes the process before the command runs (observed at exit, after the command)
    from importlib.metadata import entry_points

    (script,) = [e for e in entry_points(group="console_scripts") if e.name == "rkcheck"]
    assert script.value == "rkcheck.program:main"
    assert "from rkcheck.program import main" in (Path(rkcheck.__file__).parent / "__main__.py").read_text()
    code = ("import atexit, gc, os, sys; sys.argv = ['rkcheck', '--version']; "
            "atexit.register(lambda: print(gc.get_threshold()[0], os.environ.get('OPENBLAS_THREAD_TIMEOUT'))); "
            "from rkcheck.program import main; main()")
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_THREAD_TIMEOUT"}
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert run.stdout.split()[-2:] == ["100000", "4"], run.stderr


def test_a_ctrl_c_is_quiet_from_the_programs_first_import():
    # the package's own start-up (before main() runs) is covered too: importing the
    # program installs the quiet handler at once, and `import rkcheck` stays light
    # (typing, its slowest import, is not loaded)
    code = ("import signal, sys; before = 'typing' in sys.modules; import rkcheck.program; "
            "print(signal.getsignal(signal.SIGINT).__name__, before or 'typing' not in sys.modules)")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.stdout.split() == ["_early_interrupt", "True"], run.stderr

