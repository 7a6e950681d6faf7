"""rkcheck: energy-preservation conditions of Runge–Kutta methods, checked exactly.

The public API (docs/api.md)::

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
the CLI's one-line message.  The names are loaded on first use, so that ``import
rkcheck`` (and the CLI's start-up) stays fast.
"""

from __future__ import annotations

import gc as _gc
import os as _os
import signal as _signal
import sys as _sys


def _running_as_program() -> bool:
    """The ``rkcheck`` console script or ``python -m rkcheck`` — never a library import."""
    argv0 = _sys.argv[0] if _sys.argv else ""
    name = _os.path.basename(argv0)
    if name == "rkcheck" or (name == "__main__.py" and _os.path.basename(_os.path.dirname(argv0)) == "rkcheck"):
        return True  # (not another package's __main__.py that imports rkcheck as a library)
    argv = getattr(_sys, "orig_argv", [])
    return "-m" in argv and argv.index("-m") + 1 < len(argv) and argv[argv.index("-m") + 1] == "rkcheck"


def _early_interrupt(signum, frame) -> None:  # pragma: no cover - timing-dependent by nature
    """Ctrl-C or SIGTERM while the program is still starting (importing click, rich, ...):
    nothing has begun, so end quietly with exit 130 instead of an import traceback."""
    _os.write(2, b"rkcheck: interrupted\n")
    _os._exit(130)


#: True in the ``rkcheck`` program (the process ends when its command does), False when
#: rkcheck is imported as a library: only the program tunes process-wide settings.
_PROGRAM = _running_as_program()

# As early as possible (this is the first module any start-up imports); the CLI's main()
# replaces these handlers as soon as it starts (issue 16).
if _PROGRAM:
    _signal.signal(_signal.SIGINT, _early_interrupt)
    _signal.signal(_signal.SIGTERM, _early_interrupt)
    # numpy's bundled OpenBLAS starts a worker thread per core when numpy is imported, and
    # each idle worker spins for 2^28 cycles (~0.1 s) before it sleeps: on a 2-core machine
    # that takes a core from every command's start-up (~60 ms of rkcheck verify's ~0.4 s,
    # issue 15).  2^4 cycles: idle workers sleep at once and are woken (microseconds) when
    # a large matrix product needs them; BLAS still uses every core.  Set before numpy is
    # loaded (OpenBLAS reads it then); a value the user set wins.
    _os.environ.setdefault("OPENBLAS_THREAD_TIMEOUT", "4")
    # Start-up allocates ~50 000 containers (modules, classes, functions) that live until
    # exit; with the default first threshold (700) the cyclic collector runs ~70 times
    # over them (12-22 ms of verify's start-up on RK4).  Young cyclic garbage is rare
    # here (refcounting frees the rest at once), so a later first collection costs
    # nothing in memory (same peak at order 16) and collections still run.
    _gc.set_threshold(100_000, *_gc.get_threshold()[1:])

from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

if TYPE_CHECKING:  # what type checkers and IDEs see; at run time __getattr__ loads it
    from rkcheck.api import (
        Bench,
        Catalog,
        Condition,
        ConditionList,
        EnergyCondition,
        EnergyOrderFit,
        FreeTree,
        Kernel,
        Perturbation,
        RootingTerm,
        ScanResult,
        ScanRow,
        Simulation,
        Verification,
        WorkPrecision,
        bench,
        catalog,
        conditions,
        empirical_energy_order,
        energy_condition,
        free_trees,
        from_arrays,
        from_nodepy,
        hamiltonian,
        kernel,
        library,
        load,
        loads,
        new,
        new_toml,
        perturb,
        scan,
        simulate,
        to_nodepy,
        verify,
        work_precision,
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

# the names rkcheck.api exports (that module imports nothing heavy: each name loads on use)
from rkcheck.api import __all__ as _API  # noqa: E402

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
