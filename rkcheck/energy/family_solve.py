"""The structured route of ``rkcheck solve``: quadrature conditions first, then the
conditions linear in A, then a small system in the kernel directions.

It applies when every entry of A is its own free parameter (A free), each weight is
either a parameter-free number or its own parameter, there is no other parameter, and
the extra equations (``--where``) use only the weights.  Then, with ``c = A·1`` as new unknowns:

1. **Quadrature conditions.**  The energy condition of the star with k leaves is
   ``Σ bᵢcᵢ^(k−1) − (Σb)^k/k`` (times a constant), k = 2 … min(m, N): a system in b and c
   alone.  When its solutions are finitely many they are computed exactly
   (:mod:`rkcheck.numbers.groebner`) and grouped in Galois orbits: one irreducible φ(z)
   per orbit, every coordinate a polynomial in z modulo φ — a number field K = Q[z]/φ.
2. **Linear conditions.**  For one orbit, b and c are numbers of K and the double-bush
   conditions (definitions §3, with the star terms kept: they hold without assuming
   Σb = 1) and the row sums ``A·1 = c`` are linear in A: exact Gaussian elimination over
   K gives ``A = A₀ + Σ k_f N_f`` — with ``A₀ = c bᵀ`` (AVF) whenever it solves them, so
   the kernel coordinates k_f measure the distance from AVF.
3. **The rest.**  Every condition is evaluated on that A, over K, as a polynomial in the
   few k_f (:mod:`rkcheck.energy.family_conditions`).  Exact linear algebra over K on
   their Macaulay matrix (:mod:`rkcheck.numbers.macaulay`) shows a power of each k_f in
   the ideal (every k_f = 0: the orbit's one method) or 1 in it (none); failing that, a
   Gröbner basis with z as a variable and φ(z) among the equations decides.

Every step is exact and every solution of the full system lies in one orbit; nothing
is sampled.  The raw route (one Gröbner basis of every condition in every entry) is
:mod:`rkcheck.numbers.solving`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from fractions import Fraction
from math import factorial
from typing import Any, Sequence

from rkcheck.energy.family_rules import (
    Orbit,
    double_bush_rows,
    element,
    finite_orbits,
    orbit_field,
    quadrature_system,
    row_sum_rows,
)
from rkcheck.numbers.groebner import (
    SolveLimitError,
    Terms,
    dimension,
    fmpq_of,
    groebner,
    integer_dicts,
    leading_monomial,
)
from rkcheck.numbers.macaulay import forced_zero
from rkcheck.numbers.parametric import THETA, ParameterRing, fresh_name
from rkcheck.numbers.quotient import shape_position
from rkcheck.numbers.solving import (
    Component,
    Solution,
    SolutionSet,
    _compose,
    orbit_solutions,
)


@dataclass
class Layout:
    """Which parameter is which: ``A[i][j]`` the name of entry (i, j); ``b[i]`` a
    parameter name or None (then ``b_fixed[i]`` is its value, a polynomial in θ)."""

    A: list[list[str]]
    b: list[str | None]
    b_fixed: list[Any]


def layout_of(family: Any, extra: Sequence[Any]) -> Layout | None:
    """The layout when the structured route applies (module docstring), else None."""
    ring = family.ring
    gens = {name: ring.parameter(name) for name in ring.parameters}

    def bare(p: Any) -> str | None:
        return next((n for n, g in gens.items() if p == g), None)

    A = [[bare(p) for p in row] for row in family.A]
    flat = [n for row in A for n in row]
    if any(n is None for n in flat) or len(set(flat)) != len(flat):
        return None
    b: list[str | None] = []
    fixed: list[Any] = []
    names = ring.variables
    for p in family.b:
        name = bare(p)
        used = {names[i] for m in p.monoms() for i, e in enumerate(m) if e} - {THETA}
        if name is None and used:
            return None
        b.append(name)
        fixed.append(None if name else p)
    b_names = {n for n in b if n}
    if b_names & set(flat) or len(b_names) != len([n for n in b if n]):
        return None
    if set(ring.parameters) != set(flat) | b_names:  # a parameter no entry uses is free in every solution
        return None
    for q in extra:
        used = {names[i] for m in q.monoms() for i, e in enumerate(m) if e} - {THETA}
        if not used <= b_names:
            return None
    return Layout(A, b, fixed)  # type: ignore[arg-type]


# ------------------------------------------------------------------ step 2: linear in A


def affine_solution(rows: list[list[Any]], n: int) -> tuple[list[Any], dict[int, list[Any]]] | None:
    """``x = x₀ + Σ k_f v_f`` solving ``rows·(x, 1) = 0`` exactly, with the free columns
    f as keys (None: inconsistent)."""
    from rkcheck.energy.double_bush import nullspace_exact

    _, basis = nullspace_exact(rows, n + 1)
    particular = [v for v in basis if v[n] != 0]
    if not particular:
        return None
    x0 = particular[0]
    kernel = {next(j for j in range(n) if v[j] == 1 and all(w is v or w[j] == 0 for w in basis)): v
              for v in basis if v is not x0}
    return x0[:n], {f: v[:n] for f, v in kernel.items()}


# ------------------------------------------------------------------ the whole route


@dataclass
class OrbitResult:
    component: Component
    points: list[tuple[Any, dict[str, Any]]] = field(default_factory=list)  # (ψ, variable → poly in w)


def solve_structured(family: Any, layout: Layout, degree: int | None, order: int, classical: int | None,
                     extra: Sequence[Any], max_seconds: float, equations: int) -> SolutionSet | None:
    """The solution set by the structured route, or None when the quadrature system has
    infinitely many solutions (the raw route then applies)."""
    t0 = time.monotonic()
    deadline = t0 + max_seconds
    ring = family.ring
    theta = THETA if ring.field is not None else None
    polys, ctx, _ = quadrature_system(family, layout, degree, order, extra)
    orbits = finite_orbits(polys, ctx, theta, ring.field, deadline)
    ruled: list[Component] = []
    rule_dimension = 0
    if orbits is None:  # a curve of rules or more: the route over all of them at once
        from rkcheck.energy.family_curve import solve_on_rules

        on_rules = solve_on_rules(family, layout, degree, order, classical, extra, deadline)
        if on_rules is None:
            return None
        rule_dimension, ruled, exceptional = on_rules
        results = [solve_orbit(family, layout, o, ctx, degree, order, classical, deadline) for o in exceptional]
        if ruled:  # the AVF methods over the exceptional rules lie on the first component already
            results = [r for r in results if not (r.component.dimension == 0 and r.component.avf)]
    else:
        results = []
        for o in orbits:
            if time.monotonic() > deadline:  # the steps between Gröbner bases count against the limit too
                raise SolveLimitError("the structured route did not finish within the time limit (--max-seconds); "
                                      "fix more parameters, lower --order or --degree, or raise the limit")
            results.append(solve_orbit(family, layout, o, ctx, degree, order, classical, deadline))
    solutions: list[Solution] = []
    for r in results:
        found = orbit_solutions(r.points, ring.parameters, theta, ring.field)
        solutions += found
        if r.component.dimension == 0:
            r.component.points, r.component.real = len(found), sum(s.real for s in found)
    components = ruled + [r.component for r in results if r.component.dimension >= 0 and r.component.points != 0]
    dim = max((c.dimension for c in components), default=-1)
    # with a positive-dimensional component, these are the points of the finite ones
    out = SolutionSet(tuple(ring.parameters), equations, _points_basis(results, ring) if dim == 0 else [], dim, {},
                      solutions)
    out.route = "structured"
    out.rule_dimension = rule_dimension
    out.components = components
    out.seconds = time.monotonic() - t0
    return out


def _points_basis(results: list[OrbitResult], ring: ParameterRing) -> list[Any]:
    """The reduced degrevlex Gröbner basis of all the solutions (θ among the variables,
    its conjugates' solutions included, as in the plain route), from their orbits."""
    from rkcheck.numbers.points import points_basis

    names = ring.variables
    orbits = [(psi, [values[v] % psi for v in names]) for r in results for psi, values in r.points]
    out = []
    for d in points_basis(orbits, len(names)):
        out.append(ring.ctx.from_dict({m: fmpq_of(c) for m, c in d.items()}))
    return out


def solve_orbit(family: Any, layout: Layout, orbit: Orbit, ctx: Any, degree: int | None, order: int,
                 classical: int | None, deadline: float) -> OrbitResult:
    from rkcheck.energy.family_conditions import classical_conditions, energy_conditions

    s = family.stages
    K = orbit_field(orbit)
    b = [element(K, orbit.coords[n]) if n else element(K, _at_orbit(layout.b_fixed[i], family, ctx, orbit))
         for i, n in enumerate(layout.b)]
    c = [element(K, x) for x in orbit.nodes]
    rows = row_sum_rows(c) + double_bush_rows(b, c, degree, order)
    solved = affine_solution(rows, s * s)
    if solved is None:
        return OrbitResult(Component(-1))
    x0, kernel = solved
    avf_point = [c[i] * b[j] for i in range(s) for j in range(s)]
    if all(sum((r[k] * avf_point[k] for k in range(s * s)), r[-1]).is_zero() for r in rows):
        x0 = avf_point  # the kernel coordinates then measure the distance from AVF (0 there)
    free = [f"__k{f + 1}" for f in sorted(kernel)]
    R = ParameterRing(free, K)
    A_flat = [R.element(x0[k]) for k in range(s * s)]
    for name, v in zip(free, (kernel[f] for f in sorted(kernel))):
        for k in range(s * s):
            if not v[k].is_zero():
                A_flat[k] = A_flat[k] + R.element(v[k]) * R.parameter(name)
    A = [A_flat[i * s:(i + 1) * s] for i in range(s)]
    bR = [R.element(x) for x in b]
    conds = [cd.polynomial for cd in energy_conditions(R, A, bR, order, degree)]
    if classical is not None:
        conds += [cd.polynomial for cd in classical_conditions(R, A, bR, classical)]
    rest = [p for p in conds if not p.is_zero()]
    values = _values(family, layout, orbit, R, A_flat, ctx)
    avf_polys = [R.reduce(A[i][j] - sum(A[i][1:], A[i][0]) * bR[j]) for i in range(s) for j in range(s)]
    if not free:
        if rest:
            return OrbitResult(Component(-1))
        avf = all(p.is_zero() for p in avf_polys)
        return OrbitResult(Component(0, avf=avf), [(orbit.phi, {v: _as_z(p) for v, p in values.items()})])
    flat = [n for row in layout.A for n in row]
    named = dict(zip(free, (flat[f] for f in sorted(kernel))))
    return _kernel_system(R, rest, values, avf_polys, deadline, orbit.phi, named)


def _at_orbit(p: Any, family: Any, ctx: Any, orbit: Orbit) -> Any:
    """A polynomial of the family's ring in θ (and weights' parameters) at the orbit."""
    names = tuple(ctx.names())
    images = [ctx.gens()[names.index(v)] if v in names else ctx.constant(0) for v in family.ring.variables]
    return _compose(p.compose(*images), names, orbit.coords, orbit.phi)


def _as_z(p: Any) -> Any:
    """A polynomial in z alone (an fmpq_mpoly over (z,)) as an fmpq_poly."""
    from flint import fmpq_poly

    coeffs = [Fraction(0)] * (max((int(m[0]) for m in p.monoms()), default=0) + 1)
    for m, x in p.to_dict().items():
        coeffs[int(m[0])] += Fraction(int(x.p), int(x.q))
    return fmpq_poly([fmpq_of(x) for x in coeffs])


def _values(family: Any, layout: Layout, orbit: Orbit, R: ParameterRing, A_flat: list[Any], ctx: Any) -> dict[str, Any]:
    """Every variable of the family's ring (θ and the parameters) over R."""
    from flint import fmpq_poly

    def of(p: Any) -> Any:
        return R.element(element(R.field, p))

    out = {}
    flat = [n for row in layout.A for n in row]
    for n, p in zip(flat, A_flat):
        out[n] = p
    for n in family.ring.variables:
        if n in orbit.coords:
            out[n] = of(orbit.coords[n])
    for n in family.ring.parameters:
        if n not in out:  # a parameter no entry uses: free
            out[n] = R.parameter(n) if n in R.parameters else of(fmpq_poly([0]))
    return out


def _kernel_system(R: ParameterRing, rest: list[Any], values: dict[str, Any], avf_polys: list[Any],
                   deadline: float, phi: Any, named: dict[str, str]) -> OrbitResult:
    """The conditions left in the kernel directions (with φ(z)): their solutions.
    ``named``: each kernel coordinate's entry of A (its free column)."""
    from flint import fmpq_poly

    names = tuple(R.ctx.names())
    forced = forced_zero(R, rest)
    if forced is not None:  # every kernel coordinate is 0 on the solutions, or there are none
        origin = [R.ctx.constant(0)] * len(names)
        origin[0] = R.ctx.gens()[0]
        if not forced or any(not R.reduce(p.compose(*origin)).is_zero() for p in rest):
            return OrbitResult(Component(-1))
        at = {v: _as_z(R.reduce(p.compose(*origin))) for v, p in values.items()}
        avf = all(R.reduce(p.compose(*origin)).is_zero() for p in avf_polys)
        return OrbitResult(Component(0, avf=avf), [(phi, at)])
    polys = rest + [R.minpoly]
    basis = groebner(integer_dicts(polys), names, "degrevlex", deadline)
    dim = dimension([leading_monomial(d, "degrevlex") for d in basis], len(names))
    if dim < 0:
        return OrbitResult(Component(-1))
    if dim > 0:
        gens = [R.ctx.from_dict(d) for d in basis]
        flag: bool | None = all(_in_ideal(p, basis, names, deadline) for p in avf_polys)
        if not flag:  # certain only when the kernel coordinates are free (the basis is φ alone)
            flag = False if all(not any(m[1:]) for g in gens for m in g.monoms()) else None
        equations = _in_parameters(R, values, gens, named)
        return OrbitResult(Component(dim, avf=flag, equations=equations, node=_node_used(equations)))
    f, h = shape_position(basis, names, deadline)
    fz = fmpq_poly([fmpq_of(x) for x in f])
    points = []
    avf = True
    for psi, _ in fz.factor()[1]:
        coords = {v: fmpq_poly([fmpq_of(x) for x in h[i]]) % psi for i, v in enumerate(names)}
        points.append((psi, {v: _compose(p, names, coords, psi) for v, p in values.items()}))
        avf = avf and all(_compose(p, names, coords, psi).is_zero() for p in avf_polys)
    return OrbitResult(Component(0, avf=avf), points)


def _in_parameters(R: ParameterRing, values: dict[str, Any], gens: list[Any], named: dict[str, str]) -> list[Any]:
    """A positive-dimensional orbit piece as equations in z (a root of φ, the first
    equation) and the parameters: the kernel system's basis with each kernel coordinate
    written as its entry of A minus that entry's value at k = 0, and every other
    parameter equal to its value."""
    from flint import fmpq_mpoly_ctx

    params = [v for v in values if v != THETA]
    z = fresh_name("z", params)
    E = fmpq_mpoly_ctx.get((z,) + tuple(params), "lex")
    g = dict(zip(E.names(), E.gens()))
    at_z = [g[z]] + [E.constant(0)] * (len(R.ctx.names()) - 1)
    images = [g[z]] + [g[named[k]] - (values[named[k]] - R.parameter(k)).compose(*at_z) for k in R.ctx.names()[1:]]
    out = [p.compose(*images) for p in gens]
    out += [g[v] - values[v].compose(*images) for v in params if v not in named.values()]
    return _rational_orbit_substituted(out, E)


def _node_used(equations: list[Any]) -> str | None:
    """The name of z (the first variable of the equations' ring) when they still use it."""
    used = [e for e in equations if e.degrees()[0] > 0]
    return str(used[0].context().names()[0]) if used else None


def _rational_orbit_substituted(equations: list[Any], E: Any) -> list[Any]:
    """The equations with z replaced by its value where φ is linear (a rational orbit of
    nodes): z then stands for one number, and shown it would read as a parameter."""
    linear = next((p for p in equations if p.total_degree() == 1 and all(not any(m[1:]) for m in p.monoms())), None)
    if linear is None:
        return equations
    terms = {int(m[0]): c for m, c in zip(linear.monoms(), linear.coeffs())}
    value = E.constant(-terms.get(0, 0) / terms[1])
    at = [value] + list(E.gens()[1:])
    return [q for q in (p.compose(*at) for p in equations) if not q.is_zero()]


def _in_ideal(p: Any, basis: list[Terms], names: tuple[str, ...], deadline: float) -> bool:
    """Whether p lies in the ideal of a reduced Gröbner basis: adding it leaves the
    (unique) reduced basis unchanged."""
    if p.is_zero():
        return True
    more = groebner(basis + integer_dicts([p]), names, "degrevlex", deadline)
    return sorted(map(sorted_items, more)) == sorted(map(sorted_items, basis))


def sorted_items(d: dict[Any, Any]) -> list[tuple[Any, Any]]:
    return sorted(d.items())


def star_constant(k: int) -> Fraction:
    """The residual of the star with k leaves is this times ``Σbc^(k−1) − (Σb)^k/k``
    (rooted at the centre: (Σb)^k/k!, at a leaf: −Σbc^(k−1)/(k−1)!)."""
    return Fraction(-1, factorial(k - 1))
