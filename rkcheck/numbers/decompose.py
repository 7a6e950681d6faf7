"""Pieces of a positive-dimensional solution set, split along factors.

When an element g of a Gröbner basis factors over Q, g = f₁^e₁ ⋯ f_r^e_r, the solution
set is the union of the sets where one fᵢ vanishes: V(I) = ∪ V(I + ⟨fᵢ⟩).  Each piece
gets its own reduced Gröbner basis (FLINT's factorisation of ``fmpz_mpoly`` and its
Buchberger, :mod:`rkcheck.numbers.groebner`) and is split again, until no basis element
factors.  What this gives, and what it does not: every solution lies in some piece; a
piece is not proven irreducible (a prime ideal need not show a factor in its basis), and
one piece may lie inside another.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rkcheck.numbers.groebner import Terms, dimension, groebner, leading_monomial

#: At most this many pieces: a split that would make more is not made, and the piece it
#: would have split is reported whole (``Piece.whole``), possibly a union of several.
MAX_PIECES = 32


@dataclass
class Piece:
    """A reduced Gröbner basis (integer dicts over ``names``) and its dimension."""

    basis: list[dict[tuple[int, ...], int]]
    dimension: int
    whole: bool = False  # left unsplit at MAX_PIECES: it may be a union of several


def _key(basis: list[Terms]) -> tuple[Any, ...]:
    return tuple(sorted(tuple(sorted(d.items())) for d in basis))


def _factors(d: dict[tuple[int, ...], int], names: tuple[str, ...]) -> list[Terms] | None:
    """The distinct irreducible factors of a polynomial when it has more than one (or
    a repeated one), else None."""
    from flint import fmpz_mpoly_ctx

    ctx = fmpz_mpoly_ctx.get(names, "degrevlex")
    _, factors = ctx.from_dict(d).factor()
    if len(factors) == 1 and factors[0][1] == 1:
        return None
    return [{tuple(int(e) for e in m): int(c) for m, c in f.to_dict().items()} for f, _ in factors]


def split(basis: list[Terms], names: tuple[str, ...], deadline: float) -> list[Piece]:
    """The pieces of V(basis) (a reduced degrevlex Gröbner basis), split along factors."""
    todo = [basis]
    done: dict[tuple[Any, ...], Piece] = {}
    while todo:
        G = todo.pop()
        for g in G:
            found = _factors(g, names)
            if found is not None:
                break
        else:
            done.setdefault(_key(G), Piece(G, _dimension(G, names)))
            continue
        if len(done) + len(todo) + len(found) > MAX_PIECES:  # splitting G would pass the limit
            done.setdefault(_key(G), Piece(G, _dimension(G, names), whole=True))
            continue
        for f in found:
            H = groebner(G + [f], names, "degrevlex", deadline)
            if _dimension(H, names) >= 0 and _key(H) not in done:
                todo.append(H)
    return sorted(done.values(), key=lambda p: (-p.dimension, len(p.basis)))


def _dimension(G: list[Terms], names: tuple[str, ...]) -> int:
    return dimension([leading_monomial(d, "degrevlex") for d in G], len(names)) if G else len(names)


def contains(piece: Piece, p: Terms, names: tuple[str, ...], deadline: float) -> bool:
    """Whether p lies in the piece's ideal (then it vanishes on the piece)."""
    if not p:
        return True
    more = groebner(piece.basis + [p], names, "degrevlex", deadline)
    return _key(more) == _key(piece.basis)


def as_polynomials(piece: Piece, ctx: Any, names: tuple[str, ...]) -> list[Any]:
    """The piece's basis as polynomials of ``ctx`` (whose variables include ``names``)."""
    all_names = tuple(ctx.names())
    out = []
    for d in piece.basis:
        full = {}
        for m, c in d.items():
            e = [0] * len(all_names)
            for j, n in enumerate(names):
                e[all_names.index(n)] = m[j]
            full[tuple(e)] = c
        p = ctx.from_dict(full)
        out.append(p / p.leading_coefficient())
    return out
