"""The built wheel carries the curated tableaux and py.typed: ``@name`` works from an
installed rkcheck, away from any clone (the cwd and sys.path hold no tableaux/)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile

import pytest
from support.paths import REPO, TABLEAUX


def test_wheel_ships_the_library(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for name in ("pyproject.toml", "setup.py", "MANIFEST.in", "README.md"):
        shutil.copy(REPO / name, src / name)
    shutil.copytree(REPO / "rkcheck", src / "rkcheck", ignore=shutil.ignore_patterns("__pycache__", "library"))
    shutil.copytree(TABLEAUX, src / "tableaux")
    run = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path / "dist"),
                          str(src)], capture_output=True, text=True)
    if run.returncode != 0 and "Could not find a version" in run.stderr:
        pytest.skip("no build backend available offline")
    assert run.returncode == 0, run.stderr
    wheel = next((tmp_path / "dist").glob("rkcheck-*.whl"))
    names = zipfile.ZipFile(wheel).namelist()
    shipped = {n.removeprefix("rkcheck/library/") for n in names if n.startswith("rkcheck/library/")}
    want = {str(p.relative_to(TABLEAUX)) for p in TABLEAUX.rglob("*.toml")}
    assert want <= shipped and "rkcheck/py.typed" in names
    # installed elsewhere, it loads by name from its own package data
    target = tmp_path / "site"
    zipfile.ZipFile(wheel).extractall(target)
    code = ("import rkcheck, rkcheck.io.library as L; t = rkcheck.load('@gauss3'); "
            "print(rkcheck.__file__); print(L.library_root()); print(t.info.source, t.stages)")
    env = dict(os.environ, PYTHONPATH=str(target))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, env=env)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith(str(target)) and lines[1].startswith(str(target))
    assert lines[2] == "@collocation/gauss-3 3"
