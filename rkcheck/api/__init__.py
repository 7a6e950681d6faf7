"""The public Python API: what ``import rkcheck`` offers, and what the CLI calls.

Takes: tableaux (files, ``@name``, arrays of ints, Fractions, strings, floats, numpy or
sympy values) and check options.  Gives: :class:`Verification` results whose
``to_json()`` is the document of ``rkcheck verify --format json``, free trees and single
energy conditions, tableaux written in other formats, and one function per command
(scan, catalog, new, kernel, perturb, bench, simulate, workprec, conditions, explain)
whose result the CLI hands to :mod:`rkcheck.reports`.  Every refusal is an
:class:`~rkcheck.errors.RkcheckError` with the CLI's one-line message.

Each public name is declared once, in the ``__all__`` of the submodule that defines or
re-exports it (:data:`MODULES`); a name is loaded on first use, so that importing one
submodule (as the CLI does for ``verify``) does not load the others.

May import every stage of the flow (:mod:`rkcheck.options`, ``numbers``, ``trees``,
``methods``, ``io``, ``evaluation``, ``energy``, ``dynamics``, ``studies``, ``batch``,
``reports``) and :mod:`rkcheck.errors`; never :mod:`rkcheck.cli` (the CLI calls this).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # what type checkers see; at run time __getattr__ loads each name
    from rkcheck.api.batch import *  # noqa: F403
    from rkcheck.api.dynamics import *  # noqa: F403
    from rkcheck.api.errors import *  # noqa: F403
    from rkcheck.api.families import *  # noqa: F403
    from rkcheck.api.interop import *  # noqa: F403
    from rkcheck.api.methods import *  # noqa: F403
    from rkcheck.api.studies import *  # noqa: F403
    from rkcheck.api.tableaux import *  # noqa: F403
    from rkcheck.api.trees import *  # noqa: F403
    from rkcheck.api.types import *  # noqa: F403
    from rkcheck.api.verification import *  # noqa: F403

#: The submodules whose ``__all__`` make the public API, cheapest to import first.
MODULES = ("errors", "types", "tableaux", "verification", "trees", "methods", "families", "interop", "batch", "studies",
           "dynamics")


#: Every submodule, reachable as an attribute (``rkcheck.api.settings``) without an import.
SUBMODULES = (*MODULES, "settings")


def _module(name: str) -> Any:
    return importlib.import_module(f"rkcheck.api.{name}")


def public_names() -> list[str]:
    """Every public name (imports every submodule)."""
    return sorted(n for m in MODULES for n in _module(m).__all__)


def __getattr__(name: str) -> Any:
    """Load a public name from its submodule on first use (PEP 562); ``__all__`` too."""
    if name == "__all__":
        return public_names()
    for m in MODULES:
        module = _module(m)
        if name in module.__all__:
            value = getattr(module, name)
            if type(value).__name__ == "function":  # a command's: the user's numbers may pass Python's limits
                from rkcheck.api.verification import numbers_as_errors

                value = numbers_as_errors(value)
            globals()[name] = value
            return value
    if name in SUBMODULES:  # rkcheck.api.settings after a bare ``import rkcheck``
        return _module(name)
    raise AttributeError(f"module 'rkcheck.api' has no attribute {name!r}")


def __dir__() -> list[str]:
    return public_names()
