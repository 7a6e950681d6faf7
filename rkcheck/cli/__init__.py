"""The ``rkcheck`` command line: one module per command group, each thin — parse the
options, call the core (or the public API), hand the result to a report, exit with the
documented code.

May import: every stage.  Nothing imports it.
"""

import os as _os
import signal as _signal
import sys as _sys


def _early_interrupt(signum, frame) -> None:  # pragma: no cover - timing-dependent by nature
    """Ctrl-C or SIGTERM while the program is still starting (importing click, rich, ...):
    nothing has begun, so end quietly with exit 130 instead of an import traceback."""
    _os.write(2, b"rkcheck: interrupted\n")
    _os._exit(130)


# Only when running as the rkcheck program (the console script or python -m rkcheck), never
# on a library import: main() replaces these handlers as soon as it starts (issue 16).
if _os.path.basename(_sys.argv[0] if _sys.argv else "") in ("rkcheck", "__main__.py"):
    _signal.signal(_signal.SIGINT, _early_interrupt)
    _signal.signal(_signal.SIGTERM, _early_interrupt)

from rkcheck.cli.main import cli, main  # noqa: E402  (after the handlers: they cover this import)

__all__ = ["cli", "main"]
