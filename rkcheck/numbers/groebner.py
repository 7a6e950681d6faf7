"""Gröbner bases of integer polynomial systems (FLINT, in a child process under a time
limit), the dimension of their solution set, and the shape basis of finitely many
solutions — the algebra behind :mod:`rkcheck.numbers.solving`."""

from __future__ import annotations

import itertools
import random
import time
from fractions import Fraction
from typing import Any, Sequence, TypeAlias

from rkcheck.errors import UserError

#: a polynomial as {exponents: coefficient}
Terms: TypeAlias = dict[tuple[int, ...], Any]

MAX_SOLVE_SECONDS = 60


class SolveLimitError(UserError):
    """The system is beyond what ``solve`` does within its limits (time, shape)."""




# ------------------------------------------------------------------ Gröbner bases


def integer_dicts(polys: Sequence[Any]) -> list[dict[tuple[int, ...], int]]:
    """Integer polynomials as plain dicts (denominators cleared: same ideal)."""
    import math

    out = []
    for p in polys:
        items = [(tuple(int(e) for e in m), int(c.p), int(c.q)) for m, c in p.to_dict().items()]
        lcm = math.lcm(*(q for _, _, q in items)) if items else 1
        out.append({m: num * (lcm // den) for m, num, den in items})
    return out


def _reduced_basis(names: tuple[str, ...], order: str, dicts: list[Terms]) -> list[dict[tuple[int, ...], int]]:
    from flint import fmpz_mpoly_ctx, fmpz_mpoly_vec

    ctx = fmpz_mpoly_ctx.get(names, order)
    vec = fmpz_mpoly_vec([ctx.from_dict(d) for d in dicts], ctx)
    G: Any = vec.buchberger_naive().autoreduction()
    return [{tuple(int(e) for e in m): int(c) for m, c in G[i].to_dict().items()} for i in range(len(G))]


def groebner(dicts: list[dict[tuple[int, ...], int]], names: tuple[str, ...], order: str,
             deadline: float) -> list[dict[tuple[int, ...], int]]:
    """The reduced Gröbner basis (integer, primitive) of the polynomials, computed in a
    child process stopped at ``deadline`` (time.monotonic) with a SolveLimitError: one
    call into FLINT cannot be interrupted from Python."""
    from rkcheck.numbers.deadline import Overrun, call_within

    if not dicts:
        return []
    try:
        basis: list[Terms] = call_within(max(0.0, deadline - time.monotonic()), _reduced_basis, names, order, dicts)
        return basis
    except Overrun:
        raise SolveLimitError("the Gröbner basis did not finish within the time limit (--max-seconds); "
                              "fix more parameters, lower --order or --degree, or raise the limit") from None
    except MemoryError:
        raise SolveLimitError("the Gröbner basis computation ended without a result (out of memory?); "
                              "lower --order or --degree") from None


def dimension(leading: list[tuple[int, ...]], n: int) -> int:
    """The dimension of the solution set from the leading monomials of a Gröbner basis
    (-1 when 1 is in the ideal): the largest set S of variables such that no leading
    monomial uses only variables of S."""
    if any(not any(m) for m in leading):
        return -1
    supports = [frozenset(i for i, e in enumerate(m) if e) for m in leading]
    for size in range(n, -1, -1):
        for S in itertools.combinations(range(n), size):
            chosen = set(S)
            if not any(sup <= chosen for sup in supports):
                return size
    return 0


def leading_monomial(d: dict[tuple[int, ...], int], order: str) -> tuple[int, ...]:
    """The leading monomial of a polynomial (as a dict) in ``degrevlex`` or ``lex``."""
    if order == "lex":
        return max(d)
    return max(d, key=lambda m: (sum(m), tuple(-e for e in reversed(m))))


# ------------------------------------------------------------------ finitely many solutions


def _univariate(d: dict[tuple[int, ...], int], i: int) -> list[Fraction]:
    """A polynomial in variable i only, as ascending coefficients."""
    deg = max(m[i] for m in d)
    coeffs = [Fraction(0)] * (deg + 1)
    for m, c in d.items():
        coeffs[m[i]] += c
    return coeffs


def _squarefree(coeffs: list[Fraction]) -> list[Fraction]:
    from flint import fmpq_poly

    p = fmpq_poly([fmpq_of(c) for c in coeffs])
    g = p.gcd(p.derivative())
    q = p / g if g.degree() > 0 else p
    return [Fraction(int(c.p), int(c.q)) for c in q.coeffs()]


def fmpq_of(c: Fraction) -> Any:
    from flint import fmpq

    return fmpq(c.numerator, c.denominator)


def _monom(n: int, i: int, e: int) -> tuple[int, ...]:
    return tuple(e if k == i else 0 for k in range(n))


def radical_additions(basis: list[Terms], names: tuple[str, ...], deadline: float) -> list[Terms]:
    """The square-free part of each variable's eliminant (Seidenberg's lemma: with these
    added, a zero-dimensional ideal becomes its radical)."""
    n = len(names)
    extra = []
    for i in range(n):
        order = names[:i] + names[i + 1:] + (names[i],)  # x_i last: its eliminant ends the basis
        perm = [names.index(x) for x in order]
        moved = [{tuple(m[j] for j in perm): c for m, c in d.items()} for d in basis]
        lex = groebner(moved, order, "lex", deadline)
        last = [d for d in lex if all(not any(m[:-1]) for m in d)]
        if not last:
            continue
        sf = _squarefree(_univariate(last[0], n - 1))
        extra.append(_integer_dict({_monom(n, i, k): c for k, c in enumerate(sf) if c}))
    return extra


def _integer_dict(d: dict[tuple[int, ...], Fraction]) -> dict[tuple[int, ...], int]:
    import math

    lcm = math.lcm(*(c.denominator for c in d.values())) if d else 1
    return {m: int(c * lcm) for m, c in d.items()}


def shape_basis(basis: list[Terms], names: tuple[str, ...], deadline: float,
                tries: int = 8) -> tuple[list[int], list[Fraction], list[list[Fraction]]]:
    """A separating form z = Σ rᵢxᵢ and the shape basis ``f(z)``, ``xᵢ = hᵢ(z)`` of a
    radical zero-dimensional ideal, as ``(r, f, [h_i])`` (ascending Fractions)."""
    n = len(names)
    rng = random.Random(20260)
    for attempt in range(tries):
        r = [1] * n if attempt == 0 else [rng.randint(-9, 9) or 1 for _ in range(n)]
        # z − Σ rᵢxᵢ with z last in a lex order
        zn = names + ("__z",)
        lifted = [{m + (0,): c for m, c in d.items()} for d in basis]
        form = {_monom(n + 1, n, 1): 1} | {_monom(n + 1, i, 1): -r[i] for i in range(n)}
        lex = groebner(lifted + [form], zn, "lex", deadline)
        found = _read_shape(lex, n)
        if found is not None:
            return r, found[0], found[1]
    raise SolveLimitError("no separating linear form found for the solutions (not in shape position)")


def _read_shape(lex: list[Terms], n: int) -> tuple[list[Fraction], list[list[Fraction]]] | None:
    f = None
    h: list[list[Fraction] | None] = [None] * n
    for d in lex:
        if all(not any(m[:n]) for m in d):
            f = _univariate(d, n)
            continue
        lead = max(d)
        i = next(k for k in range(n) if lead[k])
        if lead != _monom(n + 1, i, 1) or any(m[:n] != (0,) * n and m != lead for m in d):
            return None  # not x_i − h_i(z)
        c = d[lead]
        coeffs = [Fraction(0)] * (max((m[n] for m in d if m != lead), default=0) + 1)
        for m, v in d.items():
            if m != lead:
                coeffs[m[n]] -= Fraction(v, c)
        h[i] = coeffs
    if f is None or any(x is None for x in h):
        return None
    return f, [x for x in h if x is not None]


def solve_zero_dimensional(basis: list[Terms], names: tuple[str, ...],
                           deadline: float) -> tuple[list[Fraction], list[list[Fraction]]]:
    """``(f, [h_i])`` in shape position from a lexicographic basis (what the quotient ring
    of :mod:`rkcheck.numbers.quotient` does not read).  A shape basis with a square-free
    f generates a radical ideal, so the radical is computed only when the first try is
    not one."""
    try:
        _, f, h = shape_basis(basis, names, deadline, tries=1)
        if len(_squarefree(f)) == len(f):
            return f, h
    except SolveLimitError:
        pass
    radical = groebner(basis + radical_additions(basis, names, deadline), names, "degrevlex", deadline)
    _, f, h = shape_basis(radical, names, deadline)
    return f, h
