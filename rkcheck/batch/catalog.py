"""A catalogue of tableaux: one row per file with its orders per degree (``rkcheck catalog``).

Pure: it loads and checks the files it is given and returns rows; rendering (Markdown for
``tableaux/README.md``) is in :mod:`rkcheck.reports.markdown`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rkcheck.energy.check import CheckOptions
from rkcheck.energy.error_constants import error_constant
from rkcheck.errors import UserError, is_out_of_memory
from rkcheck.io.loader import load
from rkcheck.numbers.formatting import decimal_string, digits_text
from rkcheck.verdicts import State


@dataclass
class CatalogRow:
    path: str
    name: str = ""
    stages: int | str = 0  # "∞" for a continuous-stage method
    structure: str = ""
    classical: str = ""
    quadrature: str = ""
    energy: dict[str, str] = field(default_factory=dict)  # degree label -> "all" / "≥ N" / "n"
    avf_degrees: list[int] = field(default_factory=list)
    claims: str = ""  # "ok" / "BROKEN" / ""
    error: str | None = None
    symplectic: str = ""  # "yes" / "no" / "yes†" (held to the working precision only) / "?" (not decided)
    symmetric: str = ""
    energy_orders: dict[str, int | None] = field(default_factory=dict)  # label -> energy order (None: all / ≥ N)
    constants: dict[str, Fraction | None] = field(default_factory=dict)  # label -> C_m (None: no failure)


def _property_cell(pv) -> str:
    if not pv.verdict.decided:
        return "?"
    if pv.verdict.state is State.FAILS:
        return "no"
    return "yes" if pv.verdict.state is State.HOLDS else "yes†"


def catalog_row(path: str, degrees: list[int | None], order: int, dps: int = 50, budget: Any = None) -> CatalogRow:
    """One file's row; a file that cannot be read or checked is a row with its error
    (``budget``: refuse a check that would not fit, as :func:`rkcheck.energy.check.check`)."""
    row = CatalogRow(path)
    try:
        _fill_row(row, path, degrees, order, dps, budget)
    except UserError as err:  # one file's error is its row, the catalogue goes on
        row.error = str(err if err.source else err.located(source=path))
    except RecursionError:
        row.error = f"{path}: nesting too deep"
    except (MemoryError, ImportError, OSError) as err:  # a library that could not be mapped too
        if not is_out_of_memory(err):
            raise
        row.error = f"{path}: out of memory"
    return row


def _fill_row(row: CatalogRow, path: str, degrees: list[int | None], order: int, dps: int, budget: Any) -> None:
    from rkcheck.energy.check import CheckRunner
    from rkcheck.energy.claims import check_claims

    tab: Any = load(path)
    if getattr(tab, "is_continuous", False):  # its B-series through a surrogate exact as far as the checks read
        from rkcheck.energy.claims import surrogate_within

        row.name, row.stages, row.structure = tab.name, "∞", "continuous"
        tab = surrogate_within(tab, CheckOptions(order=order), list(tab.info.claims), budget)
    else:
        row.name, row.stages, row.structure = tab.name, tab.stages, tab.structure
    runner = CheckRunner(budget)
    for deg in degrees:
        res = runner(tab, CheckOptions(degree=deg, order=order, dps=dps))
        label = "all H" if deg is None else f"m={deg}"
        row.energy[label] = res.energy_order_label
        ec = error_constant(res)
        row.energy_orders[label] = ec.energy_order if ec is not None else None
        # 15 significant digits, as the catalogue compares them ("=" when they agree there)
        row.constants[label] = Fraction(decimal_string(ec.value, 15)) if ec is not None else None
        if res.properties is not None and not row.symplectic:
            row.symplectic = _property_cell(res.properties.symplectic)
            row.symmetric = _property_cell(res.properties.symmetric)
        if res.avf is not None and res.avf.equals_avf and deg is not None:
            row.avf_degrees.append(deg)
        if deg is None or not row.classical:
            cls, quad = res.classical, res.quadrature
            row.classical = _order_cell(cls.to_digits if cls.first_failure else f"≥ {cls.to_digits}", cls)
            open_ended = row.structure == "continuous" and not quad.first_failure  # checked as far as the B-series
            row.quadrature = _order_cell(f"≥ {quad.to_digits}" if open_ended else quad.to_digits, quad)
    if tab.info.claims:
        results = check_claims(tab, list(tab.info.claims), CheckOptions(order=order, dps=dps), runner)
        row.claims = "ok" if all(r.met for r in results) else "BROKEN"


def _order_cell(reach, r) -> str:
    """``4``, or ``0; 4 to 15 digits`` when the order is reached only to digits."""
    return str(reach) if r.digits is None else f"{r.order}; {reach} to {digits_text(r.digits)}"
