"""The first two steps of the structured route of ``rkcheck solve``
(:mod:`rkcheck.energy.family_solve`), shared with the route over a curve of rules
(:mod:`rkcheck.energy.family_curve`): the quadrature system in the weights and nodes,
its solutions in Galois orbits when they are finitely many, and the conditions linear
in A (row sums and double bushes) as rows over any exact field.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

from rkcheck.energy.double_bush_rank import map_row
from rkcheck.energy.double_bush_rank import row_sum_rows as unit_row_sums
from rkcheck.numbers.groebner import (
    dimension,
    fmpq_of,
    groebner,
    integer_dicts,
    leading_monomial,
)
from rkcheck.numbers.parametric import THETA
from rkcheck.numbers.quotient import shape_position
from rkcheck.numbers.solving import _compose, _minpoly_in, eliminate_linear

# ------------------------------------------------------------------ step 1: b and c


@dataclass
class Orbit:
    """A Galois orbit of solutions of the quadrature system: K = Q[z]/φ and each
    variable of the family's ring (θ, the weights' parameters) and each node cᵢ as a
    polynomial in z modulo φ."""

    phi: Any  # fmpq_poly, irreducible
    coords: dict[str, Any]
    nodes: list[Any]


def quadrature_system(family: Any, layout: Any, degree: int | None, order: int,
                      extra: Sequence[Any]) -> tuple[list[Any], Any, list[str]]:
    """The star conditions and the extra equations over a context in (θ, weights'
    parameters, c₁ … c_s): ``(polys, ctx, node names)``."""
    from flint import fmpq_mpoly_ctx

    ring = family.ring
    s = family.stages
    b_params = [n for n in layout.b if n]
    nodes = [f"__c{i + 1}" for i in range(s)]
    head = (THETA,) if ring.field is not None else ()
    ctx = fmpq_mpoly_ctx.get(head + tuple(b_params) + tuple(nodes), "lex")
    gens = dict(zip(ctx.names(), ctx.gens()))
    images = [gens.get(n, ctx.constant(0)) for n in ring.variables]
    b = [gens[n] if n else layout.b_fixed[i].compose(*images) for i, n in enumerate(layout.b)]
    c = [gens[n] for n in nodes]
    total = sum(b[1:], b[0])
    top = order if degree is None else min(degree, order)
    polys = []
    for k in range(2, top + 1):
        star = sum((bi * ci ** (k - 1) for bi, ci in zip(b, c)), ctx.constant(0))
        polys.append(star - total ** k * ctx.constant(fmpq_of(Fraction(1, k))))
    polys += [q.compose(*images) for q in extra]
    return polys, ctx, nodes


def finite_orbits(polys: list[Any], ctx: Any, theta: str | None, field_: Any, deadline: float) -> list[Orbit] | None:
    """The orbits of the finitely many solutions (None when infinitely many; [] when
    none)."""
    from flint import fmpq_poly

    names = tuple(ctx.names())
    if theta is not None:
        polys = list(polys) + [_minpoly_in(ctx, theta, field_)]
    eqs, subs, inconsistent = eliminate_linear(polys, theta)
    if inconsistent:
        return []
    rest = tuple(n for n in names if n not in subs)
    keep = [names.index(n) for n in rest]
    dicts = [{tuple(m[i] for i in keep): c for m, c in d.items()} for d in integer_dicts(eqs)]
    basis = groebner(dicts, rest, "degrevlex", deadline)
    dim = dimension([leading_monomial(d, "degrevlex") for d in basis], len(rest)) if basis else len(rest)
    if dim < 0:
        return []
    if dim > 0:
        return None
    f, h = shape_position(basis, rest, deadline)
    fz = fmpq_poly([fmpq_of(x) for x in f])
    out = []
    for phi, _ in fz.factor()[1]:
        coords = {v: fmpq_poly([fmpq_of(x) for x in h[i]]) % phi for i, v in enumerate(rest)}
        for v, e in subs.items():
            coords[v] = _compose(e, names, coords, phi)
        out.append(rebased(Orbit(phi, coords, [coords[n] for n in names if n.startswith("__c")])))
    return out


def _size(P: Sequence[Fraction]) -> int:
    return sum(c.numerator.bit_length() + c.denominator.bit_length() for c in P)


def rebased(orbit: Orbit) -> Orbit:
    """The same orbit with a generator of small minimal polynomial: the separating form's
    polynomial often has coefficients of dozens of digits, while a node that generates
    the same field has a small one — and every later Gröbner basis in z runs on these
    coefficients."""
    from flint import fmpq_mat, fmpq_poly

    from rkcheck.numbers.minimal import minimal_polynomial

    D = orbit.phi.degree()
    if D <= 1:
        return orbit
    K = orbit_field(orbit)
    best = None
    for p in list(orbit.nodes) + list(orbit.coords.values()):
        if p.degree() <= 0:
            continue
        P = minimal_polynomial(element(K, p))
        if len(P) == D + 1 and (best is None or _size(P) < _size(best[1])):
            best = (p, P)
    if best is None or _size(best[1]) >= _size([Fraction(int(x.p), int(x.q)) for x in orbit.phi.coeffs()]):
        return orbit
    g, P = best
    M = fmpq_mat(D, D)  # column j: g^j in the powers of z
    power = fmpq_poly([1])
    for j in range(D):
        for i, c in enumerate(power.coeffs()):
            M[i, j] = c
        power = (power * g) % orbit.phi
    Minv = M.inv()

    def convert(p: Any) -> Any:
        X = fmpq_mat(D, 1)
        for i, c in enumerate(p.coeffs()):
            X[i, 0] = c
        Y = Minv * X
        return fmpq_poly([Y[i, 0] for i in range(D)])

    phi = fmpq_poly([fmpq_of(c) for c in P])
    coords = {v: convert(p) for v, p in orbit.coords.items()}
    return Orbit(phi, coords, [convert(p) for p in orbit.nodes])


def orbit_field(orbit: Orbit) -> Any:
    from rkcheck.numbers.algebraic import NumberField

    coeffs = [Fraction(int(x.p), int(x.q)) for x in orbit.phi.coeffs()]
    return NumberField(coeffs, 1, name="z")


def element(K: Any, p: Any) -> Any:
    return K([Fraction(int(x.p), int(x.q)) for x in p.coeffs()] or [Fraction(0)])



# ------------------------------------------------------------------ step 2: linear in A


def double_bush_rows(b: list[Any], c: list[Any], degree: int | None, order: int) -> list[list[Any]]:
    """The double-bush conditions ``t_{p,q}`` present up to ``order`` (p+q+2 vertices)
    within the degree bound (q+1 ≤ m), as rows ``[coefficient of a_ij …, constant]``:

        p bᵀC^(p−1)Ac^q − q bᵀC^(q−1)Ac^p − (Σb)^p bᵀc^q + (Σb)^q bᵀc^p

    (the residual times p!q!; the last two terms are the rootings at the centres)."""
    total = sum(b[1:], b[0])
    rows = []
    for q in range(2, order):
        if degree is not None and q + 1 > degree:
            break
        for p in range(1, q):
            if p + q + 2 > order + 1:
                break
            row = map_row(b, c, p, q)
            bq = sum((bi * ci ** q for bi, ci in zip(b, c)), b[0] * 0)
            bp = sum((bi * ci ** p for bi, ci in zip(b, c)), b[0] * 0)
            rows.append(row + [total ** q * bp - total ** p * bq])
    return rows


def row_sum_rows(c: list[Any]) -> list[list[Any]]:
    """The row sums ``Σ_j a_ij = c_i`` as rows ``[coefficients of a_ij …, −c_i]``, in c's type."""
    zero = c[0] * 0
    return [[zero + x for x in row] + [-ci] for row, ci in zip(unit_row_sums(len(c)), c)]
