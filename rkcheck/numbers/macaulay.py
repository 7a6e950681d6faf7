"""Whether every coordinate vanishes on the zeros of a polynomial system over a number
field, by exact linear algebra on its Macaulay matrix — the last step of the structured
route of ``solve`` (:mod:`rkcheck.energy.family_solve`), where the system lives over the
field K of one orbit of nodes and its unknowns are the few kernel directions.

The Macaulay matrix of degree D holds the coefficients of every polynomial times every
monomial that keeps the total degree ≤ D; its row space is a part of the ideal, so a
monomial ``k^e`` in the row space lies in the ideal and k = 0 at every zero, and 1 in it
means there is no zero.  Elimination is exact, over K (:mod:`rkcheck.numbers.algebraic`).
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from typing import Any

#: The Macaulay matrices of the kernel system go this many degrees past its largest one.
MACAULAY_EXTRA_DEGREES = 3
#: ... and stop at this many columns (monomials): the linear algebra is over K.
MAX_MACAULAY_COLUMNS = 400


def forced_zero(R: Any, rest: list[Any]) -> bool | None:
    """True when, for every kernel coordinate k, some power k^e lies in the ideal of the
    remaining conditions over K (so k = 0 at every solution); False when 1 does (no
    solution); None when neither shows up to the degree limit (a Gröbner basis decides).

    Membership is decided by exact linear algebra over K on the Macaulay matrix: the
    conditions times every monomial, up to a total degree D in the kernel coordinates."""
    K = R.field
    n = len(R.ctx.names()) - 1
    polys = [_by_monomial(p, K) for p in rest]
    top = max((sum(m) for d in polys for m in d), default=0)
    for D in range(top, top + MACAULAY_EXTRA_DEGREES + 1):
        columns = _monomials(n, D)
        if len(columns) > MAX_MACAULAY_COLUMNS:
            return None
        index = {m: i for i, m in enumerate(columns)}
        rows = []
        for d in polys:
            deg = max(sum(m) for m in d)
            for u in _monomials(n, D - deg):
                row = [K(0)] * len(columns)
                for m, a in d.items():
                    row[index[tuple(x + y for x, y in zip(m, u))]] = a
                rows.append(row)
        pivots = _echelon(rows)
        if _member(pivots, index[(0,) * n], len(columns), K):
            return False
        if all(any(_member(pivots, index[tuple(e if j == i else 0 for j in range(n))], len(columns), K)
                   for e in range(1, D + 1)) for i in range(n)):
            return True
    return None


def _by_monomial(p: Any, K: Any) -> dict[tuple[int, ...], Any]:
    """A polynomial over K in the kernel coordinates: monomial → coefficient in K."""
    groups: dict[tuple[int, ...], list[Fraction]] = {}
    for m, c in p.to_dict().items():
        key = tuple(int(e) for e in m[1:])
        coeffs = groups.setdefault(key, [Fraction(0)] * K.degree)
        coeffs[int(m[0])] += Fraction(int(c.p), int(c.q))
    return {m: K(c) for m, c in groups.items()}


def _monomials(n: int, D: int) -> list[tuple[int, ...]]:
    """Every monomial of total degree ≤ D in n variables, highest degree first."""
    out = [m for m in itertools.product(range(D + 1), repeat=n) if sum(m) <= D]
    return sorted(out, key=lambda m: (-sum(m), m))


def _echelon(rows: list[list[Any]]) -> dict[int, list[Any]]:
    """Reduced pivot rows keyed by pivot column (Gaussian elimination over K)."""
    pivots: dict[int, list[Any]] = {}
    for row in rows:
        row = _reduce(row, pivots)
        col = next((j for j, x in enumerate(row) if not x.is_zero()), None)
        if col is None:
            continue
        inv = 1 / row[col]
        pivots[col] = [x * inv for x in row]
    return pivots


def _reduce(row: list[Any], pivots: dict[int, list[Any]]) -> list[Any]:
    for col in sorted(pivots):
        f = row[col]
        if not f.is_zero():
            row = [x - f * y for x, y in zip(row, pivots[col])]
    return row


def _member(pivots: dict[int, list[Any]], column: int, size: int, K: Any) -> bool:
    """Whether the monomial of ``column`` lies in the row space."""
    unit = [K(0)] * size
    unit[column] = K(1)
    return all(x.is_zero() for x in _reduce(unit, pivots))
