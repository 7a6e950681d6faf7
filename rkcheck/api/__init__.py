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

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # what type checkers see; at run time __getattr__ loads each name on first use
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

#: each public name and the module that defines it: importing one submodule (as the CLI
#: does for ``verify``) must not load the others (scan, simulation, studies: start-up)
_WHERE = {
    'Bench': 'rkcheck.api.studies',
    'Catalog': 'rkcheck.api.batch',
    'Condition': 'rkcheck.api.verification',
    'ConditionList': 'rkcheck.api.trees',
    'EnergyCondition': 'rkcheck.api.trees',
    'EnergyOrderFit': 'rkcheck.api.dynamics',
    'FreeTree': 'rkcheck.api.trees',
    'Kernel': 'rkcheck.api.studies',
    'Perturbation': 'rkcheck.api.studies',
    'RootingTerm': 'rkcheck.api.trees',
    'ScanResult': 'rkcheck.api.batch',
    'ScanRow': 'rkcheck.api.batch',
    'Simulation': 'rkcheck.api.dynamics',
    'Verification': 'rkcheck.api.verification',
    'WorkPrecision': 'rkcheck.api.dynamics',
    'bench': 'rkcheck.api.studies',
    'catalog': 'rkcheck.api.batch',
    'conditions': 'rkcheck.api.trees',
    'empirical_energy_order': 'rkcheck.api.dynamics',
    'energy_condition': 'rkcheck.api.trees',
    'free_trees': 'rkcheck.api.trees',
    'from_arrays': 'rkcheck.api.tableaux',
    'from_nodepy': 'rkcheck.api.interop',
    'hamiltonian': 'rkcheck.api.dynamics',
    'kernel': 'rkcheck.api.studies',
    'library': 'rkcheck.api.tableaux',
    'load': 'rkcheck.api.tableaux',
    'loads': 'rkcheck.api.tableaux',
    'new': 'rkcheck.api.methods',
    'new_toml': 'rkcheck.api.methods',
    'perturb': 'rkcheck.api.studies',
    'scan': 'rkcheck.api.batch',
    'simulate': 'rkcheck.api.dynamics',
    'to_nodepy': 'rkcheck.api.interop',
    'verify': 'rkcheck.api.verification',
    'work_precision': 'rkcheck.api.dynamics',
    'write': 'rkcheck.api.tableaux',
}


def __getattr__(name: str) -> Any:
    module = _WHERE.get(name)
    if module is None:
        raise AttributeError(f"module 'rkcheck.api' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value

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
