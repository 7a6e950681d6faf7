"""Build hook: ship the curated tableaux as package data.

The repository keeps them in ``tableaux/`` (documented there by ``rkcheck catalog``);
a built wheel or sdist install carries a copy in ``rkcheck/library/`` so that
``rkcheck verify @gauss-3`` works anywhere (rkcheck.io.library).  Everything else is in
pyproject.toml.
"""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent


class BuildPyWithLibrary(build_py):
    """``build_py`` that also copies ``tableaux/**/*.{toml,json}`` into the package."""

    def run(self) -> None:
        super().run()
        source = HERE / "tableaux"
        if not source.is_dir():  # building from an sdist that already holds the copy
            return
        target = Path(self.build_lib) / "rkcheck" / "library"
        for f in sorted(source.rglob("*")):
            if f.is_file() and f.suffix in (".toml", ".json", ".md"):
                dest = target / f.relative_to(source)
                dest.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(f, dest)


setup(cmdclass={"build_py": BuildPyWithLibrary})
