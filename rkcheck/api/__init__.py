"""The public Python API: what ``import rkcheck`` offers, and what the CLI calls.

Takes: tableaux (files, ``@name``, arrays of ints, Fractions, strings, floats, numpy or
sympy values) and check options.  Gives: :class:`Verification` results whose
``to_json()`` is the document of ``rkcheck verify --format json``, free trees and single
energy conditions, tableaux written in other formats.  Every refusal is an
:class:`~rkcheck.errors.RkcheckError` with the CLI's one-line message.

May import every stage of the flow (:mod:`rkcheck.options`, ``numbers``, ``trees``,
``methods``, ``io``, ``evaluation``, ``energy``, ``dynamics``, ``studies``, ``batch``,
``reports``) and :mod:`rkcheck.errors`; never :mod:`rkcheck.cli` (the CLI calls this).
"""

from rkcheck.api.interop import from_nodepy, to_nodepy
from rkcheck.api.tableaux import from_arrays, library, load, loads, write
from rkcheck.api.trees import EnergyCondition, FreeTree, RootingTerm, energy_condition, free_trees
from rkcheck.api.verification import Condition, Verification, verify

__all__ = [
    "Condition",
    "EnergyCondition",
    "FreeTree",
    "RootingTerm",
    "Verification",
    "energy_condition",
    "free_trees",
    "from_arrays",
    "from_nodepy",
    "library",
    "load",
    "loads",
    "to_nodepy",
    "verify",
    "write",
]
