"""The exact solution set of a polynomial system (a family's order conditions).

The steps, each exact:

1. **Linear elimination.**  While an equation has total degree 1, solve it for one of its
   variables (the first in the ring's order, never the field generator θ) and substitute
   everywhere; a nonzero constant means no solution.  Order conditions are often linear
   in A (the double-bush conditions of the seed, row sums), so this removes most
   variables at the cost of substitutions.
2. **Gröbner basis** of the rest: FLINT's Buchberger (``fmpz_mpoly_vec.buchberger_naive``
   and ``autoreduction``, python-flint), graded reverse lexicographic, run in a child
   process so that a time limit can stop it (FLINT does not return to Python while it
   works).  Together with the eliminated variables it is a Gröbner basis of the whole
   system for the block order "eliminated variables first".
3. **Dimension** of the solution set over C from the leading monomials: the largest set
   of variables none of which's monomials leads a basis element (the dimension of the
   monomial ideal, which equals that of the ideal).
4. **Finitely many solutions** (dimension 0): the radical (square-free parts of each
   variable's eliminant added: Seidenberg's lemma), then a separating linear form
   ``z = Σ rᵢxᵢ`` and a lexicographic basis with z last, which for a radical ideal in
   general position has the *shape* ``xᵢ − hᵢ(z)``, ``f(z)`` (the shape lemma); the
   irreducible factors of f over Q give the solutions in Galois orbits, each exactly: a
   rational, a closed form over a quadratic field, or a minimal polynomial with an
   isolating interval.  Real solutions are those with z real.

When the parameters' field is K = Q(θ), θ is a variable with its minimal polynomial as one
more equation; of the solutions, those whose θ is the family's θ (not a conjugate) are
kept: certified by interval enclosures that separate θ from its conjugates.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Sequence

from rkcheck.numbers.coordinates import AlgebraicValue, coordinate_value
from rkcheck.numbers.groebner import (
    MAX_SOLVE_SECONDS,
    SolveLimitError,
    dimension,
    fmpq_of,
    groebner,
    integer_dicts,
    leading_monomial,
)


@dataclass
class Component:
    """One piece of the solution set: ``dimension``, the number of points when finite
    (complex, counted with the family's own field generator), the real ones, whether
    ``A = (A·1) bᵀ`` on all of it (None: not decided), and its defining equations
    (polynomials in the parameters, or texts) when it is positive-dimensional; ``node``:
    the name of the auxiliary variable they use beside the parameters (a node of the
    piece, a root of the first equation), if any."""

    dimension: int
    points: int | None = None
    real: int | None = None
    avf: bool | None = None
    equations: list[Any] = field(default_factory=list)
    node: str | None = None


@dataclass(frozen=True)
class Solution:
    values: dict[str, AlgebraicValue]
    real: bool


@dataclass
class SolutionSet:
    """What :func:`solve_system` found: the variables (the parameters), how many
    equations there were, the reduced Gröbner basis (as polynomial texts over the
    parameters; θ shown as such), the dimension (-1: no solution), and for dimension 0
    every solution; ``eliminated`` maps each variable removed by linear elimination to
    its expression in the others."""

    variables: tuple[str, ...]
    equations: int
    groebner: list[Any]
    dimension: int
    eliminated: dict[str, Any] = field(default_factory=dict)
    solutions: list[Solution] | None = None
    seconds: float = 0.0
    #: "plain" (one Gröbner basis of every condition) or "structured"
    #: (:mod:`rkcheck.energy.family_solve`: quadrature conditions first, no single basis)
    route: str = "plain"
    #: the pieces of the solution set: the orbits of the structured route, or the pieces
    #: of a positive-dimensional set split along factors (:mod:`rkcheck.numbers.decompose`)
    components: list[Any] | None = None
    pieces: list[Any] | None = None
    rest: tuple[str, ...] = ()
    #: the structured route: the dimension of the set of rules (b, c) the quadrature
    #: conditions leave (0: finitely many, solved orbit by orbit; 1: a curve, solved over
    #: all of it at once by :mod:`rkcheck.energy.family_curve`)
    rule_dimension: int = 0

    def __repr__(self) -> str:
        found = "" if self.solutions is None else f", {len(self.solutions)} solutions"
        return f"<SolutionSet in {', '.join(self.variables)}: dimension {self.dimension}{found}>"


# ------------------------------------------------------------------ linear elimination


def eliminate_linear(polys: list[Any], theta: str | None) -> tuple[list[Any], dict[str, Any], bool]:
    """Equations that remain, the substitutions made (variable → expression, fully
    substituted), and whether a nonzero constant showed the system inconsistent."""
    ctx = polys[0].context() if polys else None
    names = list(ctx.names()) if ctx is not None else []
    gens = ctx.gens() if ctx is not None else ()
    eqs = [p for p in polys if not p.is_zero()]
    subs: dict[str, Any] = {}
    while True:
        if any(p.is_constant() for p in eqs):
            return eqs, subs, True
        pick = _linear_pick(eqs, names, theta)
        if pick is None:
            return eqs, subs, False
        p, i = pick
        coeff = p.to_dict()[_unit_monom(len(names), i)]  # the coefficient of x_i (a number)
        value = -(p - coeff * gens[i]) / coeff
        images = list(gens)
        images[i] = value
        eqs = [q.compose(*images) for q in eqs if q is not p]
        eqs = [q for q in eqs if not q.is_zero()]
        subs = {k: v.compose(*images) for k, v in subs.items()}
        subs[names[i]] = value


def _unit_monom(n: int, i: int) -> tuple[int, ...]:
    return tuple(1 if k == i else 0 for k in range(n))


#: Linear equations with at most this many terms are solved and substituted; longer ones
#: would multiply the other equations' terms (a substitution into a degree-6 condition
#: expands it) and stay in the system, where Buchberger uses them as pivots at once.
MAX_SUBSTITUTION_TERMS = 3


def _linear_pick(eqs: list[Any], names: list[str], theta: str | None) -> tuple[Any, int] | None:
    best = None
    for p in eqs:
        if p.total_degree() != 1 or len(p.monoms()) > MAX_SUBSTITUTION_TERMS:
            continue
        for i, name in enumerate(names):
            if name != theta and any(m[i] for m in p.monoms()):
                candidate = (len(p.monoms()), p, i)  # the shortest equation first
                if best is None or candidate[0] < best[0]:
                    best = candidate
                break
    return None if best is None else (best[1], best[2])


# ------------------------------------------------------------------ the whole solve


def solve_system(polys: list[Any], theta: str | None, field: Any, max_seconds: float = MAX_SOLVE_SECONDS) -> SolutionSet:
    """The solution set of ``polys = 0`` (fmpq_mpoly over one context; ``theta``: the name
    of the field generator among its variables, with ``field`` its number field)."""
    t0 = time.monotonic()
    deadline = t0 + max_seconds
    ctx = polys[0].context()
    names = tuple(ctx.names())
    params = tuple(n for n in names if n != theta)
    equations = len([p for p in polys if not p.is_zero()])
    if theta is not None:
        polys = list(polys) + [_minpoly_in(ctx, theta, field)]
    eqs, subs, inconsistent = eliminate_linear(polys, theta)
    if inconsistent:
        return SolutionSet(params, equations, [ctx.constant(1)], -1, subs, [], time.monotonic() - t0)
    rest = tuple(n for n in names if n not in subs)
    keep = [names.index(n) for n in rest]
    dicts = [{tuple(m[i] for i in keep): c for m, c in d.items()} for d in integer_dicts(eqs)]
    basis = groebner(dicts, rest, "degrevlex", deadline)
    dim = dimension([leading_monomial(d, "degrevlex") for d in basis], len(rest)) if basis else len(rest)
    gb = [_from_dict(ctx, names, keep, d) for d in basis]
    if dim == -1:  # the unit ideal: its reduced basis is 1 alone, whatever was eliminated
        gb = [ctx.constant(1)]
    else:
        gb = [ctx.gens()[names.index(v)] - e for v, e in subs.items()] + gb
    out = SolutionSet(params, equations, gb, dim, subs)
    if dim > 0:
        from rkcheck.numbers.decompose import as_polynomials, split

        out.pieces = split(basis, rest, deadline)
        eliminated = [ctx.gens()[names.index(v)] - e for v, e in subs.items()]
        # θ's minimal polynomial defines the numbers, not the solutions: not an equation
        out.components = [Component(p.dimension, equations=eliminated + [
            g for g in as_polynomials(p, ctx, rest) if not _in_alone(g, theta)]) for p in out.pieces]
        out.rest = rest
    if dim == 0:
        from rkcheck.numbers.quotient import shape_position

        f, h = shape_position(basis, rest, deadline)
        out.solutions = _solutions(f, h, rest, subs, ctx, theta, field)
    elif dim == -1:
        out.solutions = []
    out.seconds = time.monotonic() - t0
    return out


def _in_alone(g: Any, name: str | None) -> bool:
    """Whether the polynomial ``g`` uses the variable ``name`` and no other."""
    names = g.context().names()
    return name is not None and {names[i] for m in g.monoms() for i, e in enumerate(m) if e} == {name}


def _minpoly_in(ctx: Any, theta: str, field: Any) -> Any:
    t = ctx.gens()[list(ctx.names()).index(theta)]
    out = ctx.constant(0)
    for k, c in enumerate(field.minpoly):
        if c:
            out = out + ctx.constant(fmpq_of(Fraction(c))) * t ** k
    return out


def _from_dict(ctx: Any, names: tuple[str, ...], keep: list[int], d: dict[tuple[int, ...], int]) -> Any:
    full = {}
    for m, c in d.items():
        e = [0] * len(names)
        for j, i in enumerate(keep):
            e[i] = m[j]
        full[tuple(e)] = c
    # monic in the order of the basis (degree reverse lexicographic), as a reduced basis is
    return ctx.from_dict(full) / d[leading_monomial(d, "degrevlex")]


# ------------------------------------------------------------------ solutions, exactly


def _solutions(f: list[Fraction], h: list[list[Fraction]], rest: tuple[str, ...], subs: dict[str, Any], ctx: Any,
               theta: str | None, field: Any) -> list[Solution]:
    """Every solution: per irreducible factor φ of f, each coordinate as a polynomial in
    z modulo φ, read through its own minimal polynomial (a rational, a quadratic closed
    form or a numbered root of it: :func:`~rkcheck.numbers.coordinates.coordinate_value`)."""
    from flint import fmpq_poly

    names = tuple(ctx.names())
    fz = fmpq_poly([fmpq_of(c) for c in f])
    hz = {v: fmpq_poly([fmpq_of(c) for c in h[i]]) for i, v in enumerate(rest)}
    out: list[Solution] = []
    for phi, _ in fz.factor()[1]:
        coords = {v: hz[v] % phi for v in rest}
        for v, e in subs.items():
            coords[v] = _compose(e, names, coords, phi)
        roots: Any = phi.complex_roots()  # (acb, multiplicity) pairs
        minimal: dict[str, list[Fraction] | None] = {}  # each coordinate's, shared by φ's roots
        for k, (root, _) in enumerate(roots):
            values = {v: coordinate_value(coords[v], phi, root, k, minimal, v) for v in names}
            if theta is not None and not _is_the_field_generator(values[theta], field):
                continue
            real = all(val.real for val in values.values())
            out.append(Solution({v: values[v] for v in names if v != theta}, real))
    return out


def _compose(e: Any, names: tuple[str, ...], coords: dict[str, Any], phi: Any) -> Any:
    from flint import fmpq_poly

    total = fmpq_poly([0])
    for m, c in e.to_dict().items():
        term = fmpq_poly([c])
        for i, k in enumerate(m):
            for _ in range(k):
                term = (term * coords[names[i]]) % phi
        total = total + term
    return total % phi


def _is_the_field_generator(value: AlgebraicValue, field: Any) -> bool:
    """Whether a solution's θ coordinate is the family's θ, not one of its conjugates.
    The coordinate is a root of θ's minimal polynomial, so it equals exactly one
    conjugate; certified by enclosures: it overlaps θ's and none of the others'."""
    from flint import acb, arb

    theta = field.theta_enclosure(128)
    mid, rad = (theta.lo + theta.hi) / 2, (theta.hi - theta.lo) / 2
    target = acb(arb(fmpq_of(mid), fmpq_of(rad)))
    ball = value.ball if value.ball is not None else acb(value.approx.real)
    others = [r for r in field.conjugates(128) if not r.overlaps(target)]
    if not ball.overlaps(target):
        return False
    if any(ball.overlaps(r) for r in others):
        raise SolveLimitError("cannot tell the field generator from its conjugates at this precision")
    return True


# ------------------------------------------------------------------ orbits of solutions


def orbit_solutions(pieces: list[tuple[Any, dict[str, Any]]], parameters: Sequence[str], theta: str | None,
                    field: Any) -> list[Solution]:
    """The solutions of each orbit piece (ψ, variable → polynomial in w): one per root of
    ψ whose θ is the family's (``theta``: the generator's name, ``field`` its field)."""
    out = []
    for psi, values in pieces:
        minimal: dict[str, list[Fraction] | None] = {}
        for k, (root, _) in enumerate(psi.complex_roots()):
            vals = {v: coordinate_value(p % psi, psi, root, k, minimal, v) for v, p in values.items()}
            if theta is not None and not _is_the_field_generator(vals[theta], field):
                continue
            real = all(x.real for x in vals.values())
            out.append(Solution({v: vals[v] for v in parameters}, real))
    return out
