"""Finitely many solutions read from a degree-reverse-lexicographic Gröbner basis by
linear algebra in the quotient ring, without a lexicographic basis.

For a zero-dimensional ideal I the standard monomials (those no leading monomial
divides) are a basis of Q[x]/I, of dimension D; multiplication by a variable is a D×D
matrix M_i, read from the normal forms of x_i·s.  For a linear form z = Σ rᵢxᵢ, when the
characteristic polynomial f of M_z = Σ rᵢM_i is square-free, its D roots are distinct, so
I is radical with D solutions and z separates them (Stickelberger: the eigenvalues of M_z
are the values of z at the solutions); the vectors 1, z, …, z^(D−1) are then a basis,
and writing each x_i in it gives x_i = h_i(z) mod f — the shape basis the lexicographic
route computes, at the cost of D normal forms and one D×D solve instead of a Gröbner basis
in lex order, which over a number field of degree 3 or more can take minutes.
"""

from __future__ import annotations

import random
import time
from fractions import Fraction

from rkcheck.numbers.groebner import (
    SolveLimitError,
    Terms,
    leading_monomial,
    solve_zero_dimensional,
)

#: The largest quotient ring read this way (standard monomials); beyond it the
#: lexicographic route is left to decide.
MAX_QUOTIENT_DIMENSION = 300


def _divides(a: tuple[int, ...], b: tuple[int, ...]) -> bool:
    return all(x <= y for x, y in zip(a, b))


def standard_monomials(leading: list[tuple[int, ...]], n: int) -> list[tuple[int, ...]] | None:
    """The monomials no leading monomial divides, when they are at most
    :data:`MAX_QUOTIENT_DIMENSION` (else None)."""
    seen = {(0,) * n}
    todo = [(0,) * n]
    while todo:
        m = todo.pop()
        for i in range(n):
            up = tuple(e + (k == i) for k, e in enumerate(m))
            if up in seen or any(_divides(lm, up) for lm in leading):
                continue
            seen.add(up)
            if len(seen) > MAX_QUOTIENT_DIMENSION:
                return None
            todo.append(up)
    return sorted(seen)


def _degrevlex(m: tuple[int, ...]) -> tuple[int, tuple[int, ...]]:
    return sum(m), tuple(-e for e in reversed(m))


class _Reducer:
    """Normal forms modulo a reduced degrevlex Gröbner basis, in exact rationals."""

    def __init__(self, basis: list[Terms]):
        self.rules = []
        for d in basis:
            lead = leading_monomial(d, "degrevlex")
            c = Fraction(d[lead])
            self.rules.append((lead, {m: -Fraction(v) / c for m, v in d.items() if m != lead}))

    def normal_form(self, f: dict[tuple[int, ...], Fraction], deadline: float) -> dict[tuple[int, ...], Fraction]:
        f = dict(f)
        out: dict[tuple[int, ...], Fraction] = {}
        while f:
            if time.monotonic() > deadline:
                raise SolveLimitError("the solutions were not read within the time limit (--max-seconds); "
                                      "fix more parameters, lower --order or --degree, or raise the limit")
            m = max(f, key=_degrevlex)
            c = f.pop(m)
            rule = next(((lead, tail) for lead, tail in self.rules if _divides(lead, m)), None)
            if rule is None:
                out[m] = out.get(m, Fraction(0)) + c
                continue
            lead, tail = rule
            shift = tuple(a - b for a, b in zip(m, lead))
            for t, v in tail.items():
                key = tuple(a + b for a, b in zip(t, shift))
                f[key] = f.get(key, Fraction(0)) + c * v
                if f[key] == 0:
                    del f[key]
        return {m: c for m, c in out.items() if c}


def shape_by_multiplication(basis: list[Terms], names: tuple[str, ...], deadline: float,
                            tries: int = 8) -> tuple[list[Fraction], list[list[Fraction]]] | None:
    """``(f, [h_i])`` of a radical zero-dimensional ideal from its reduced degrevlex basis
    (module docstring), or None when the ideal is not radical, no form tried separates its
    solutions, or its quotient ring is larger than :data:`MAX_QUOTIENT_DIMENSION`."""
    from flint import fmpq, fmpq_mat

    n = len(names)
    if n == 0:  # every variable eliminated already: nothing to separate
        return None
    standard = standard_monomials([leading_monomial(d, "degrevlex") for d in basis], n)
    if standard is None:
        return None
    index = {m: k for k, m in enumerate(standard)}
    D = len(standard)
    reducer = _Reducer(basis)

    def column(i: int, s: tuple[int, ...]) -> list[Fraction]:
        up = tuple(e + (k == i) for k, e in enumerate(s))
        out = [Fraction(0)] * D
        for m, c in reducer.normal_form({up: Fraction(1)}, deadline).items():
            out[index[m]] = c
        return out

    columns = [[column(i, s) for s in standard] for i in range(n)]  # columns[i][k]: x_i · standard[k]
    multiply = [fmpq_mat(D, D, [fmpq(c.numerator, c.denominator) for r in range(D) for c in
                                (columns[i][k][r] for k in range(D))]) for i in range(n)]
    one = fmpq_mat(D, 1, [fmpq(int(m == (0,) * n)) for m in standard])
    rng = random.Random(20260)
    for attempt in range(tries):
        r = [1] * n if attempt == 0 else [rng.randint(-9, 9) or 1 for _ in range(n)]
        Mz = multiply[0] * r[0]
        for i in range(1, n):
            Mz = Mz + multiply[i] * r[i]
        f = Mz.charpoly()
        if f.gcd(f.derivative()).degree() > 0:
            continue  # repeated roots: not radical, or z does not separate the solutions
        krylov = [one]
        for _ in range(D - 1):
            krylov.append(Mz * krylov[-1])
        K = fmpq_mat(D, D, [krylov[k][row, 0] for row in range(D) for k in range(D)])
        h = []
        for i in range(n):
            coords = K.solve(multiply[i] * one)
            h.append([Fraction(int(coords[k, 0].p), int(coords[k, 0].q)) for k in range(D)])
        return [Fraction(int(c.p), int(c.q)) for c in f.coeffs()], h
    return None


def shape_position(basis: list[Terms], names: tuple[str, ...], deadline: float) -> tuple[list[Fraction], list[list[Fraction]]]:
    """``(f, [h_i])`` of the finitely many solutions of a reduced degrevlex basis: read from
    its quotient ring when the ideal is radical, else through a lexicographic basis of its
    radical (:func:`~rkcheck.numbers.groebner.solve_zero_dimensional`)."""
    return shape_by_multiplication(basis, names, deadline) or solve_zero_dimensional(basis, names, deadline)
