"""The public Python API: what ``import rkcheck`` offers, and what the CLI calls.

Takes: tableaux (files, ``@name``, arrays of ints, Fractions, strings, floats, numpy or
sympy values) and check options.  Gives: :class:`Verification` results whose
``to_json()`` is the document of ``rkcheck verify --format json``, free trees and single
energy conditions, tableaux written in other formats, and one function per command
(scan, catalog, new, kernel, perturb, bench, simulate, workprec, conditions, explain)
whose result the CLI hands to :mod:`rkcheck.reports`.  Every refusal is an
:class:`~rkcheck.errors.RkcheckError` with the CLI's one-line message.

May import every stage of the flow (:mod:`rkcheck.options`, ``numbers``, ``trees``,
``methods``, ``io``, ``evaluation``, ``energy``, ``dynamics``, ``studies``, ``batch``,
``reports``) and :mod:`rkcheck.errors`; never :mod:`rkcheck.cli` (the CLI calls this).
"""

from rkcheck.api.batch import Catalog, ScanResult, ScanRow, catalog, scan
from rkcheck.api.dynamics import (
    EnergyOrderFit,
    Simulation,
    WorkPrecision,
    empirical_energy_order,
    hamiltonian,
    simulate,
    work_precision,
)
from rkcheck.api.interop import from_nodepy, to_nodepy
from rkcheck.api.methods import new, new_toml
from rkcheck.api.studies import Bench, Kernel, Perturbation, bench, kernel, perturb
from rkcheck.api.tableaux import from_arrays, library, load, loads, write
from rkcheck.api.trees import (
    ConditionList,
    EnergyCondition,
    FreeTree,
    RootingTerm,
    conditions,
    energy_condition,
    free_trees,
)
from rkcheck.api.verification import Condition, Verification, verify

__all__ = [
    "Bench",
    "Catalog",
    "Condition",
    "ConditionList",
    "EnergyCondition",
    "EnergyOrderFit",
    "FreeTree",
    "Kernel",
    "Perturbation",
    "RootingTerm",
    "ScanResult",
    "ScanRow",
    "Simulation",
    "Verification",
    "WorkPrecision",
    "bench",
    "catalog",
    "conditions",
    "empirical_energy_order",
    "energy_condition",
    "free_trees",
    "from_arrays",
    "from_nodepy",
    "hamiltonian",
    "kernel",
    "library",
    "load",
    "loads",
    "new",
    "new_toml",
    "perturb",
    "scan",
    "simulate",
    "to_nodepy",
    "verify",
    "work_precision",
    "write",
]
