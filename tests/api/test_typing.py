"""The public surface is typed (py.typed, PEP 561) and mypy accepts it: a typed user
script passes, misuse is caught, and every module of the package checks cleanly — the
core also under ``--strict`` (mypy settings: [tool.mypy] in pyproject.toml)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from support.paths import REPO

pytest.importorskip("mypy")
HERE = Path(__file__).parent


def mypy(*paths: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "mypy", "--no-incremental", "--follow-imports=silent",
                           "--config-file", str(REPO / "pyproject.toml"), *paths],
                          capture_output=True, text=True, cwd=REPO)


# every module is checked; add a prefix here only while a module is being rewritten
NOT_CHECKED: tuple[str, ...] = ()


def checked_modules() -> list[str]:
    modules = sorted(p.relative_to(REPO).as_posix() for p in (REPO / "rkcheck").rglob("*.py"))
    return [m for m in modules if not m.startswith(NOT_CHECKED)]


def test_package_and_typed_usage_pass_mypy_and_misuse_is_caught():
    """One run over every module, a typed user script and a misusing one (a run costs
    half a minute, most of it the package's own analysis, which the three share): the
    misuse's two errors, and nothing else, are reported."""
    modules = checked_modules()
    assert len(modules) > 50 and "rkcheck/energy/check.py" in modules  # a real list, not an empty one
    misuse = HERE / "typed_misuse.py"
    run = mypy(*modules, str(HERE / "typed_usage.py"), str(misuse))
    errors = [line for line in run.stdout.splitlines() if ": error:" in line]
    assert run.returncode == 1, run.stdout + run.stderr
    assert all(line.startswith(misuse.relative_to(REPO).as_posix() + ":") for line in errors), run.stdout
    assert any('Argument "order" to "verify" has incompatible type "str"' in line for line in errors)
    assert any('Incompatible types in assignment (expression has type "int", variable has type "str")' in line
               for line in errors)
    assert len(errors) == 2, run.stdout


#: the core (the stages that compute: no I/O) also passes ``mypy --strict``: no implicit
#: Any, every function annotated (a number context's values are ``Any`` on purpose, as
#: evaluation/protocols.py declares)
STRICT: tuple[str, ...] = ("rkcheck/verdicts.py", "rkcheck/numbers", "rkcheck/trees", "rkcheck/methods",
                          "rkcheck/evaluation", "rkcheck/properties", "rkcheck/energy")


def test_strict_core_packages_pass_mypy_strict():
    run = mypy("--strict", *STRICT)
    assert run.returncode == 0, run.stdout + run.stderr


def test_strict_mode_is_not_vacuous(tmp_path):
    """The strict run rejects what the default settings let through."""
    sample = tmp_path / "loose.py"
    sample.write_text("def f(x):\n    return x\n")
    assert mypy(str(sample)).returncode == 0
    run = mypy("--strict", str(sample))
    assert run.returncode == 1 and "missing a type annotation" in run.stdout


def test_py_typed_is_shipped():
    assert (REPO / "rkcheck" / "py.typed").is_file()
    assert "py.typed" in (REPO / "pyproject.toml").read_text()
