"""rkcheck: energy-preservation conditions of Runge–Kutta methods, checked exactly.

The public API (docs/api.md)::

    import rkcheck
    tab = rkcheck.load("@gauss-2")                  # a file, or a shipped tableau by name
    tab = rkcheck.from_arrays([[0, 0], ["1/2", 0]], [0, 1])
    result = rkcheck.verify(tab, degree=4, order=8)
    result.verdict, result.energy_order, result.failures[:3], result.to_json()
    rkcheck.free_trees(6, max_degree=3)             # the conditions with 6 vertices
    rkcheck.energy_condition("1,2,3,2", tab)        # one condition, taken apart

Errors rkcheck raises on purpose are :class:`RkcheckError` subclasses whose ``str`` is
the CLI's one-line message.  The names are loaded on first use, so that ``import
rkcheck`` (and the CLI's start-up) stays fast.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

if TYPE_CHECKING:  # what type checkers and IDEs see; at run time __getattr__ loads it
    from rkcheck.api import (
        Condition,
        EnergyCondition,
        FreeTree,
        RootingTerm,
        Verification,
        energy_condition,
        free_trees,
        from_arrays,
        from_nodepy,
        library,
        load,
        loads,
        to_nodepy,
        verify,
        write,
    )
    from rkcheck.api.errors import (
        InputError,
        OptionError,
        RkcheckError,
        TableauError,
        UnknownMethodError,
        UserError,
    )
    from rkcheck.api.types import CheckOptions, Tableau

_API = ("Condition", "EnergyCondition", "FreeTree", "RootingTerm", "Verification", "energy_condition", "free_trees",
        "from_arrays", "from_nodepy", "library", "load", "loads", "to_nodepy", "verify", "write")
_ERRORS = ("InputError", "OptionError", "RkcheckError", "TableauError", "UnknownMethodError", "UserError")
_TYPES = ("CheckOptions", "Tableau")

__all__ = ["__version__", *_API, *_ERRORS, *_TYPES]


def __getattr__(name: str) -> Any:
    """Load a public name from :mod:`rkcheck.api` on first use (PEP 562)."""
    import importlib

    for module, names in (("rkcheck.api", _API), ("rkcheck.api.errors", _ERRORS), ("rkcheck.api.types", _TYPES)):
        if name in names:
            value = getattr(importlib.import_module(module), name)
            globals()[name] = value
            return value
    raise AttributeError(f"module 'rkcheck' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
