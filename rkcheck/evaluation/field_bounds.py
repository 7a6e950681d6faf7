"""Certified size bounds of a number field's embeddings, for the scaled tableau
(:mod:`rkcheck.evaluation.scaled`): how large an entry's conjugates, the minimal
polynomial's derivative and the inverse Vandermonde matrix of its roots may be, and the
least denominator that makes every entry an algebraic integer.  Together they say how
many primes decide a condition exactly.  Every bound is an upper bound from Arb balls,
the working precision doubled until the balls are tight enough to give one.
"""

from __future__ import annotations

import math
from typing import Any, Sequence

from rkcheck.numbers.polynomials import complex_roots


def log2_upper(x: Any) -> float:
    """An upper bound of ``log₂ |x|`` for an arb (−1000 for 0): in the log domain, since
    the scaled entries of a field of high degree exceed a float (2^1236 for HBVM(6, 3))."""
    from flint import arb

    u = x.abs_upper()
    if u == 0:
        return -1000.0
    return float((u.log() / arb(2).log()).upper()) + 1e-9


def embedding_bounds(minpoly: list[int], Ai: list[Any], bi: list[Any]) -> tuple[float, list[float]]:
    """``log₂ M`` (``M = max_j M_j``) and ``log₂ max(α_j, β_j)`` per complex embedding
    (:mod:`rkcheck.evaluation.modular`), certified.  The working precision starts at 128 bits and doubles
    while a bound exceeds its ball's lower end by more than one bit: in fields of high
    degree (48 for the six Gauss-6 nodes) the entries' coefficients are large and cancel,
    and 128 bits leave balls too wide to bound anything."""
    from flint import acb_poly, arb, ctx

    prec = 128
    while True:
        with ctx.workprec(prec):
            roots = complex_roots(minpoly, prec)
            # each entry at every root at once (FLINT's multipoint evaluation)
            rows = [[acb_poly(v).evaluate(roots) for v in row] for row in Ai]
            rows.append([acb_poly(v).evaluate(roots) for v in bi])
            log2_M = 0.0
            per_embedding = []
            tight = True
            for j in range(len(roots)):
                sums = [sum((abs(values[j]) for values in row), arb(0)) for row in rows]
                for x in sums:
                    if not x.is_finite() or (x.abs_upper() > 0 and not x.abs_upper() <= 2 * x.abs_lower()):
                        tight = False
                top = max(log2_upper(x) for x in sums)
                log2_M = max(log2_M, top)
                per_embedding.append(top)
            if tight or prec >= 1 << 14:
                return log2_M, per_embedding
            prec *= 2


def log2_derivative_bound(minpoly: list[int]) -> float:
    """An upper bound of ``log₂ max_j |g'(σ_j θ)|`` over the roots of ``g = minpoly``."""
    from flint import acb, ctx, fmpz_poly

    dg = fmpz_poly(minpoly).derivative()
    prec = 128
    while True:
        with ctx.workprec(prec):
            values = [abs(dg(acb(r))) for r in complex_roots(minpoly, prec)]
            if all(v.is_finite() for v in values) or prec >= 1 << 14:
                return max(log2_upper(v) for v in values)
        prec *= 2


def vandermonde_inverse_norm(minpoly: list[int]) -> float:
    """``‖V⁻¹‖_∞`` for the Vandermonde matrix ``V`` of the roots of ``minpoly``, certified:
    Arb inverts ``V`` only when its balls prove it invertible, so the working precision is
    doubled until they do (128 bits suffice up to degree ~30; the degree-48 field of the
    six Gauss-6 nodes needs more, its conjugates lie close together)."""
    from flint import acb_mat, arb, ctx

    def upper(x: Any) -> float:  # an arb as a float upper bound
        return float(x.abs_upper()) * (1 + 2.0**-40)

    D = len(minpoly) - 1
    prec = 128
    while True:
        with ctx.workprec(prec):
            roots = complex_roots(minpoly, prec)
            V = acb_mat([[r**k for k in range(D)] for r in roots])
            try:
                W = V.inv()
            except ZeroDivisionError:
                if prec >= 1 << 14:
                    raise
                prec *= 2
                continue
            return max(upper(sum((abs(W[i, j]) for j in range(D)), arb(0))) for i in range(D))


def integrality_denominator(values: Sequence[Any], field: Any) -> int:
    """The least positive integer ``e`` with ``e·x`` an algebraic integer for every ``x``:
    the lcm over the entries of the least ``λ`` that makes ``λ^m P(X/λ)`` integral, with
    ``P`` the minimal polynomial of ``x`` (of degree m; by Gauss's lemma ``x`` is integral
    exactly when P has integer coefficients).  Conjugate entries share P, found once."""
    from rkcheck.numbers.minimal import MinimalPolynomials, integral_scale

    known = MinimalPolynomials()
    e = 1
    seen = set()
    for x in values:
        x = field(x)
        q = x.rational()
        if q is not None:
            e = math.lcm(e, q.denominator)
            continue
        key = tuple(x.coeffs)
        if key not in seen:
            seen.add(key)
            e = math.lcm(e, integral_scale(known.of(x)))
    return e
