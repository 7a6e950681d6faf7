"""Methods of equal energy order compared by their energy error constant (``scan --sort energy``).

The order of rows: files that were checked first, by degree m; within a degree by
energy order, best first (``all`` = proven for every order, then ``≥ N``, then the exact
order n from high to low); within an energy order by the constant C_m of
:mod:`rkcheck.energy.error_constants`, smallest first; ties by path.  Files that could not
be checked or were skipped come last, in path order.
"""

from __future__ import annotations

import math

from rkcheck.energy.error_constants import error_constant


def energy_key(outcome) -> tuple:
    try:
        return _energy_key(outcome)
    except Exception:  # noqa: BLE001 - a row that cannot be ranked goes last; the report says why
        return (1, "", 0.0, 0.0, outcome.path)


def _energy_key(outcome) -> tuple:
    res = outcome.result
    if res is None:
        return (1, "", 0.0, 0.0, outcome.path)
    degree = res.options.degree
    deg_key = "~" if degree is None else f"{degree:06d}"  # all Hamiltonians after every m
    if res.certified_all:
        order_key = -math.inf
    elif res.first_failure is None:
        order_key = -(res.options.order + 0.5)  # ≥ N ranks above an exact N
    else:
        order_key = -float(res.energy_order_to_digits)
    ec = error_constant(res)
    return (0, deg_key, order_key, ec.value if ec is not None else 0.0, outcome.path)


def rank_outcomes(outcomes: list) -> list:
    """The outcomes sorted as the module docstring says (a new list)."""
    return sorted(outcomes, key=energy_key)
