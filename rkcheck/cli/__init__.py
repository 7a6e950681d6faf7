"""The ``rkcheck`` command line: one module per command group, each thin — parse the
options, call the core (or the public API), hand the result to a report, exit with the
documented code.

May import: every stage.  Nothing imports it.
"""

# The early Ctrl-C handler (a quiet exit 130 while the program is still starting) is
# installed by rkcheck/__init__.py, the first module any start-up imports.
from rkcheck.cli.main import cli, main

__all__ = ["cli", "main"]
