"""Families of methods with free parameters: their conditions as exact polynomials, and
the exact solution set of those conditions — ``rkcheck verify``/``conditions`` on a file
with ``[parameters]``, and ``rkcheck solve``."""

from __future__ import annotations

import os
from typing import Any, Sequence

from rkcheck.api.settings import watching_memory
from rkcheck.api.verification import UNSET, _option
from rkcheck.energy.family_conditions import FamilyConditions, PolynomialCondition
from rkcheck.errors import OptionError
from rkcheck.methods.parametric import Family, family_from_arrays
from rkcheck.numbers.coordinates import AlgebraicValue
from rkcheck.numbers.solving import Solution, SolutionSet
from rkcheck.options import (
    DEFAULT_FAMILY_ORDER,
    DEFAULT_MAX_STAGES,
    MAX_ORDER,
    parse_degree,
    parse_int_in,
)

#: The largest order ``solve`` and the polynomial conditions go to (their size grows
#: quickly with it: order 9 has 1 842 rooted trees, each a polynomial of degree 9).
MAX_FAMILY_ORDER = 12
#: How ``solve`` may go (see :func:`solve`).
ROUTES = ("auto", "structured", "plain")
#: The time limit of ``solve`` (seconds), and the range the option accepts.
MAX_SECONDS_RANGE = (1, 86_400)


def load_family(path: str | os.PathLike[str], *, max_stages: int = DEFAULT_MAX_STAGES) -> Family:
    """A family file (a tableau file with a ``[parameters]`` table), or ``"@name"``."""
    from rkcheck.io.loader import load_family as load
    from rkcheck.options import MAX_STAGES_RANGE, parse_int_in

    if not isinstance(path, (str, os.PathLike)):
        raise OptionError(f"expected a path (str or os.PathLike) or '@name', got {type(path).__name__}", "path")
    max_stages = _option(lambda: parse_int_in(max_stages, MAX_STAGES_RANGE, "max_stages"))  # as load() refuses it
    return load(os.fsdecode(path), max_stages)


def _texts(value: Any, name: str) -> list[str]:
    """One text or a list of texts (``where``, ``grids``), as a list."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, (list, tuple)):
        bad = [v for v in value if not isinstance(v, str)]
        if not bad:
            return list(value)
        raise OptionError(f"expected texts, but the list holds a value of type {type(bad[0]).__name__}", name)
    raise OptionError(f"expected a text or a list of texts, got {type(value).__name__}", name)


def _seconds(value: Any) -> float:
    """A time limit in seconds, within :data:`MAX_SECONDS_RANGE`."""
    lo, hi = MAX_SECONDS_RANGE
    if isinstance(value, (int, float)) and not isinstance(value, bool) and lo <= value <= hi:
        return float(value)
    raise OptionError(f"expected a number of seconds from {lo} to {hi:,}, got {value!r}", "max_seconds")


def is_family_file(path: str | os.PathLike[str]) -> bool:
    """Whether the file (or ``"@name"``) declares free ``[parameters]``."""
    from rkcheck.io.loader import is_family_file as check

    if not isinstance(path, (str, os.PathLike)):
        raise OptionError(f"expected a path (str or os.PathLike), got {type(path).__name__}", "path")
    return check(os.fspath(path))


def _family(family: Family | str | os.PathLike[str]) -> Family:
    from rkcheck.methods.parametric import Family

    if isinstance(family, Family):
        return family
    if isinstance(family, (str, os.PathLike)):
        return load_family(family)
    raise OptionError(f"expected a family (rkcheck.load_family) or a path, got {type(family).__name__}", "family")


def _classical(classical_order: Any) -> int | None:
    if classical_order is None:
        return None
    return _option(lambda: parse_int_in(classical_order, (1, MAX_FAMILY_ORDER), "classical_order"))


def check_options(fam: Family, degree: Any = UNSET, order: Any = UNSET,
                  places: tuple[str, str] = ("degree", "order")) -> tuple[int | None, int]:
    """``degree`` and ``order`` read (None: no degree bound), each left out (:data:`UNSET`) taken from the family
    file's ``[check]`` table (order :data:`~rkcheck.options.DEFAULT_FAMILY_ORDER` where
    that has none): the one resolution for the API and the CLI.  Each is validated
    where it came from: an error names the file's ``check.order``, or ``places`` (the
    CLI's ``--order``)."""
    check = fam.info.check
    from_file = (degree is UNSET, order is UNSET)
    degree = check.get("degree") if from_file[0] else degree
    order = check.get("order", DEFAULT_FAMILY_ORDER) if from_file[1] else order
    where = [("check." + name, fam.info.source) if file else (place, None)
             for file, name, place in zip(from_file, ("degree", "order"), places)]
    deg = _option(lambda: parse_degree(degree, *where[0]))
    N = _option(lambda: parse_int_in(order, (1, min(MAX_ORDER, MAX_FAMILY_ORDER)), *where[1]))
    return deg, N


@watching_memory
def family_conditions(family: Family | str | os.PathLike[str], *, degree: int | str | None = UNSET,
                      order: int = UNSET, classical_order: int | None = None) -> FamilyConditions:
    """Every energy condition up to ``order`` for Hamiltonians of degree ≤ ``degree`` (and
    the classical conditions up to ``classical_order``) as exact polynomials in the
    family's parameters, with the generic orders and the conditions that carve out
    exceptional parameter values.  ``degree`` and ``order`` left out: the file's
    ``[check]`` (no degree bound and order 6 without one)."""
    from rkcheck.energy.family_conditions import family_conditions as compute

    fam = _family(family)
    deg, N = check_options(fam, degree, order)
    return compute(fam, deg, N, _classical(classical_order))


@watching_memory
def solve(family: Family | str | os.PathLike[str], *, degree: int | str | None = UNSET, order: int = UNSET,
          classical_order: int | None = None, where: Sequence[str] = (),
          max_seconds: float = 60, route: str = "auto") -> SolutionSet:
    """The exact solution set of every energy condition up to ``order`` (degree ≤
    ``degree``), the classical order conditions up to ``classical_order`` and the extra
    equations ``where`` (``"a11 = a22"``): a reduced Gröbner basis, the dimension, and
    for finitely many solutions each one exactly (:mod:`rkcheck.numbers.solving`).

    ``route``: ``"auto"`` takes the structured route (:mod:`rkcheck.energy.family_solve`:
    quadrature conditions, then the conditions linear in A) when it applies and the
    plain one otherwise; ``"plain"`` always one Gröbner basis of every condition;
    ``"structured"`` refuses a family it does not apply to.  ``degree`` and ``order``
    left out: the file's ``[check]``, as in :func:`family_conditions`."""
    from rkcheck.energy.family_conditions import family_conditions as compute
    from rkcheck.energy.family_solve import layout_of, solve_structured
    from rkcheck.numbers.groebner import SolveLimitError
    from rkcheck.numbers.parametric import THETA
    from rkcheck.numbers.solving import solve_system

    fam = _family(family)
    deg, N = check_options(fam, degree, order)
    q = _classical(classical_order)
    fam = fam.covering(max(N + 1, q or 0))
    seconds = _seconds(max_seconds)
    extra = [fam.equation(w) for w in _texts(() if where is None else where, "where")]
    theta = THETA if fam.ring.field is not None else None
    if route not in ROUTES:
        raise OptionError(f"expected one of {', '.join(ROUTES)}, got {route!r}", "route")
    # the structured route reads A and b as a tableau's own entries, never a kernel's surrogate
    layout = layout_of(fam, extra) if route != "plain" and not fam.kernel else None
    if layout is not None:
        found = solve_structured(fam, layout, deg, N, q, extra, seconds, _count(deg, N, q) + len(extra))
        if found is not None:
            return found
        fix = ("fix more weights with --where (each equation in the weights takes away one freedom)" if extra
               else "fix a weight with --where (e.g. \"b1 = 1/4\") to solve that slice")
        hint = ("; the quadrature conditions leave infinitely many weights and nodes, so the structured route "
                f"does not apply: {fix}")
    else:
        hint = ""
    if route == "structured":
        raise OptionError("the structured route needs A free (each entry its own parameter), weights that are "
                          "numbers or their own parameters, no other parameter, --where equations in the weights only, "
                          "and finitely many solutions of the quadrature conditions", "route")
    conditions = compute(fam, deg, N, q)
    polys = [c.polynomial for c in conditions.energy] + [c.polynomial for c in conditions.classical or []] + extra
    polys = polys or [fam.ring.constant(0)]  # order 1 has no condition: every parameter value solves it
    try:
        result = solve_system(polys, theta, fam.ring.field, seconds)
    except SolveLimitError as err:
        if not hint:
            raise
        raise SolveLimitError(err.message + hint) from None
    if result.pieces:
        _avf_on_pieces(fam, result, seconds)
    return result


def _avf_on_pieces(fam: Family, result: SolutionSet, seconds: float) -> None:
    """Whether A − (A·1) bᵀ lies in the ideal of each piece (True), else not decided
    (None: it may still vanish on the piece without lying in its ideal)."""
    import time

    from rkcheck.numbers.decompose import contains
    from rkcheck.numbers.groebner import integer_dicts

    deadline = time.monotonic() + seconds
    ctx = fam.ring.ctx
    names = tuple(ctx.names())
    images = [ctx.gens()[i] if n not in result.eliminated else result.eliminated[n] for i, n in enumerate(names)]
    keep = [names.index(n) for n in result.rest]
    s = fam.stages
    if fam.kernel:
        gaps = _gaps_to_avf_kernel(fam)
    else:
        gaps = [fam.ring.reduce(fam.A[i][j] - sum(fam.A[i][1:], fam.A[i][0]) * fam.b[j])
                for i in range(s) for j in range(s)]
    gaps = [g.compose(*images) for g in gaps]
    dicts = [{tuple(m[i] for i in keep): c for m, c in d.items()} for d in integer_dicts([g for g in gaps if not g.is_zero()])]
    for piece, comp in zip(result.pieces or [], result.components or []):
        comp.avf = True if all(contains(piece, d, result.rest, deadline) for d in dicts) else None


def _gaps_to_avf_kernel(fam: Family) -> list[Any]:
    """What vanishes exactly where a kernel family's member is AVF's kernel A = τ, B = 1,
    whose surrogate is ``A_ij = w_j x_i``, ``b_i = w_i``: the coefficients of
    ``A(τ, σ) − τ`` when A is read through its factors ``V C Wᵀ`` (V and W, the powers
    of more nodes than the kernel's degrees, have independent columns, so ``V D Wᵀ = 0``
    only for ``D = 0``), else every entry of ``A − (w_j x_i)``; and ``b − w``."""
    from rkcheck.methods.quadrature import rational_rule

    s, ring = fam.stages, fam.ring
    x, w = rational_rule(s)
    if fam.factors is not None:
        C = fam.factors[1]
        monomials = [(a, c) for a in range(C.shape[0]) for c in range(C.shape[1])]  # τᵃσᶜ
        gaps = [C[a, c] - ring.constant(1 if (a, c) == (1, 0) else 0) for a, c in monomials]
        gaps += [] if (1, 0) in monomials else [ring.constant(-1)]  # no τ in A: never τ
    else:
        gaps = [ring.reduce(fam.A[i][j] - ring.constant(w[j] * x[i])) for i in range(s) for j in range(s)]
    return gaps + [ring.reduce(fam.b[i] - ring.constant(w[i])) for i in range(s)]


@watching_memory
def sweep(family: Family | str | os.PathLike[str], grids: Sequence[str], *, degree: int | str | None = UNSET,
          order: int = UNSET) -> Any:
    """The energy order of the family at every point of a grid of rational parameter
    values (``"beta=-1:1:41"``: 41 equally spaced rationals from −1 to 1; ``"gamma=1/2"``:
    one value; every parameter needs one), each evaluated exactly from the conditions as
    polynomials: a :class:`~rkcheck.energy.family_sweep.Sweep` (``points()``,
    ``orders``, ``generic``); ``degree`` and ``order`` left out: the file's ``[check]``."""
    from rkcheck.energy.family_sweep import sweep as run

    fam = _family(family)
    deg, N = check_options(fam, degree, order)
    return run(fam, _texts(grids, "grids"), deg, N)


def _count(degree: int | None, order: int, classical: int | None) -> int:
    """How many conditions: energy conditions up to ``order`` and rooted trees up to
    ``classical``."""
    from rkcheck.trees.listing import condition_listing
    from rkcheck.trees.table import TreeTable

    total = len(condition_listing(order, degree))
    if classical is not None:
        table = TreeTable(1)
        table.grow_to(classical)
        total += int(table.first[classical + 1] - table.first[1])
    return total


__all__ = ["AlgebraicValue", "Family", "FamilyConditions", "PolynomialCondition", "Solution", "SolutionSet",
           "family_conditions", "family_from_arrays", "is_family_file", "load_family", "solve", "sweep"]
