"""The reduced Gröbner basis of finitely many algebraic points (Buchberger–Möller).

The points come in Galois orbits, each an irreducible ψ(w) over Q and every coordinate
a polynomial in w modulo ψ (:mod:`rkcheck.energy.family_solve`).  A polynomial p with
rational coefficients vanishes on the whole orbit exactly when p(coordinates) is zero
modulo ψ, so "evaluate at every point" is a Q-linear map to the concatenated remainders
(Q^N, N the number of points).  Buchberger–Möller walks the monomials in increasing
graded reverse lexicographic order: a monomial whose evaluation is a combination of the
standard monomials' gives a basis element ``t − Σ cₛ s``; otherwise it becomes standard.
The result is the reduced basis of the ideal of the points, in exact rational
arithmetic.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

#: At most this many points (the linear algebra is N × N).
MAX_POINTS = 400


def _order_key(m: tuple[int, ...]) -> tuple[int, tuple[int, ...]]:
    """Graded reverse lexicographic: total degree, then the reversed exponents negated."""
    return (sum(m), tuple(-e for e in reversed(m)))


def points_basis(orbits: Sequence[tuple[Any, Sequence[Any]]], n: int) -> list[dict[tuple[int, ...], Fraction]]:
    """The reduced degrevlex basis of the ideal of the points (``orbits``: ψ and the n
    coordinates as fmpq_poly in w), as dicts monomial → coefficient (leading
    coefficient 1); empty beyond MAX_POINTS points."""
    from flint import fmpq_poly

    sizes = [psi.degree() for psi, _ in orbits]
    if sum(sizes) > MAX_POINTS:
        return []

    def vector(values: list[Any]) -> list[Fraction]:
        out: list[Fraction] = []
        for v, d in zip(values, sizes):
            coeffs = [Fraction(int(c.p), int(c.q)) for c in v.coeffs()]
            out += coeffs + [Fraction(0)] * (d - len(coeffs))
        return out

    one = tuple(0 for _ in range(n))
    evals = {one: [fmpq_poly([1]) for _ in orbits]}
    echelon: list[tuple[int, list[Fraction], dict[Any, Fraction]]] = []  # (pivot, row, combination of standard monomials)
    basis: list[dict[Any, Any]] = []
    leads: list[tuple[int, ...]] = []
    todo = {one}
    done: set[tuple[int, ...]] = set()
    while todo:
        t = min(todo, key=_order_key)
        todo.discard(t)
        done.add(t)
        if any(all(a >= b for a, b in zip(t, lead)) for lead in leads):
            continue
        row, combo = _reduce(vector(evals[t]), {t: Fraction(1)}, echelon)
        pivot = next((i for i, x in enumerate(row) if x), None)
        if pivot is None:
            basis.append(combo)
            leads.append(t)
            continue
        echelon.append((pivot, row, combo))
        for i in range(n):
            u = tuple(e + (1 if k == i else 0) for k, e in enumerate(t))
            if u not in done and u not in evals:
                evals[u] = [(v * coords[i]) % psi for v, (psi, coords) in zip(evals[t], orbits)]
            if u not in done:
                todo.add(u)
    return basis


def _reduce(row: list[Fraction], combo: dict[Any, Fraction],
            echelon: list[tuple[int, list[Fraction], dict[Any, Fraction]]]) -> tuple[list[Fraction], dict[Any, Fraction]]:
    """Row minus multiples of the echelon rows (each with its pivot normalised to 1),
    tracking the combination of monomials."""
    row = list(row)
    combo = dict(combo)
    for pivot, r, c in echelon:
        f = row[pivot]
        if f:
            row = [x - f * y for x, y in zip(row, r)]
            for m, v in c.items():
                combo[m] = combo.get(m, Fraction(0)) - f * v
    lead = next((i for i, x in enumerate(row) if x), None)
    if lead is not None:
        inv = 1 / row[lead]
        row = [x * inv for x in row]
        combo = {m: v * inv for m, v in combo.items()}
    return row, {m: v for m, v in combo.items() if v}
