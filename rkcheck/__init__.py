"""rkcheck: energy-preservation conditions of Runge–Kutta methods, checked exactly.

The public API (the documentation's "Python API" page)::

    import rkcheck
    tab = rkcheck.load("@gauss-2")                  # a file, or a shipped tableau by name
    tab = rkcheck.from_arrays([[0, 0], ["1/2", 0]], [0, 1])
    result = rkcheck.verify(tab, degree=4, order=8)
    result.verdict, result.energy_order, result.failures[:3], result.to_json()
    rkcheck.free_trees(6, max_degree=3)             # the conditions with 6 vertices
    rkcheck.energy_condition("1,2,3,2", tab)        # one condition, taken apart
    rkcheck.new("gauss", stages=3), rkcheck.scan(["tableaux/"]), rkcheck.kernel(4, 2), ...
                                                    # one function per command of the CLI

Errors rkcheck raises on purpose are :class:`RkcheckError` subclasses whose ``str`` is
the CLI's one-line message.  The names are those of :mod:`rkcheck.api`, loaded on first
use, so that ``import rkcheck`` is fast and has no side effects.
"""

from __future__ import annotations

from rkcheck.version import __version__ as __version__

# not `from typing import TYPE_CHECKING`: importing typing is the slowest part of starting
# the program (a Ctrl-C in it would be a traceback); type checkers read this as True
TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from rkcheck.api import *  # noqa: F403


def __getattr__(name: str) -> Any:
    """A public name of :mod:`rkcheck.api`, loaded on first use (PEP 562)."""
    if name == "__all__":
        from rkcheck.api import public_names

        return ["__version__", *public_names()]
    import rkcheck.api

    if name == "api":  # rkcheck.api.settings with no import of rkcheck.api
        return rkcheck.api
    value = getattr(rkcheck.api, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    from rkcheck.api import public_names

    return ["__version__", *public_names()]
