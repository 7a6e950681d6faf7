"""The ``rkcheck`` command line: parse options, call the core, render a report.

May import: every stage.  Nothing imports it.
"""

from rkcheck.cli.main import cli, main

__all__ = ["cli", "main"]
