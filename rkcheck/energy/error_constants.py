"""The leading energy error term and its size: the energy error constant.

For a Hamiltonian of degree ≤ m the energy error of one step is a B-series over free trees
(Chartier, Faou, Murua 2006; definitions §3):

    H(y₁) − H(y₀) = Σ_{t̄} h^(|t̄|−1) R(t̄) F_t̄(H)(y₀),

with ``R(t̄)`` the residual of the energy condition (for the designated rooting t of t̄)
and ``F_t̄(H) = H^(k)(F(t₁), …, F(t_k))`` the elementary Hamiltonian of that rooting
(``t = [t₁ … t_k]``, ``F`` the elementary differentials of ``f = J⁻¹∇H``): rooting t̄
elsewhere changes ``F`` and ``R`` by the same sign.  The elementary Hamiltonians of
different free trees are linearly independent, so with energy order q the leading term is

    H(y₁) − H(y₀) = h^(q+1) Σ_{|t̄| = q+2, deg ≤ m} R(t̄) F_t̄(H)(y₀) + O(h^(q+2)).

Its size for a "typical" H is a norm of the residual vector of the first failing order.
rkcheck reports the **Euclidean norm** ``C_m = (Σ R(t̄)²)^(1/2)`` over the conditions of
order q+1 with maximum degree ≤ m (docs/decisions.md: it is the root-mean-square of the
leading coefficient when the elementary Hamiltonians are uncorrelated with equal spread,
it does not depend on the sign convention of the designated rooting, and ``C_m²`` is an
exact rational for a rational tableau).  For m = 2 there is one condition per order and
``C_2 = |e_(q+1)|/2`` with ``R(z)R(−z) − 1 = e_(q+1) z^(q+1) + …``.

Methods of equal energy order are compared by ``C_m``: smaller is better.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rkcheck.numbers.formatting import decimal_string
from rkcheck.numbers.intervals import Interval
from rkcheck.verdicts import FAILS


@dataclass(frozen=True)
class ErrorConstant:
    """``C_m`` of one check: the Euclidean norm of the residuals at the first failing order."""

    degree: int | None
    energy_order: int  # q: the energy error is O(h^(q+1))
    order: int  # q + 1: the order of the conditions that form the leading term
    conditions: int  # how many conditions of that order (degree ≤ m)
    failing: int  # how many of them certainly fail
    squared: Fraction | Interval  # C_m², exact or enclosed
    exact: bool

    @property
    def value(self) -> Fraction:
        """``C_m`` to about 60 significant digits (the mid-point of the enclosure when not
        exact), in exact rational arithmetic: a float overflows past C ≈ 1e154."""
        sq = self.squared if isinstance(self.squared, Fraction) else self.squared.mid
        return sqrt_fraction(Fraction(sq))

    @property
    def bounds(self) -> tuple[Fraction, Fraction]:
        """Lower and upper bound of ``C_m`` (a square root apart when exact)."""
        lo, hi = (self.squared, self.squared) if isinstance(self.squared, Fraction) else (self.squared.lo,
                                                                                           self.squared.hi)
        return sqrt_fraction(max(Fraction(lo), Fraction(0)), up=False), sqrt_fraction(Fraction(hi), up=True)

    def text(self, sig: int = 4) -> str:
        """``0.006944 (C² = 1/20736)``: the exact square when rational and short."""
        value = decimal_string(self.value, sig)
        if self.exact:
            sq = str(self.squared)
            return f"{value} (C² = {sq})" if len(sq) <= 24 else value
        return value

    def short(self, sig: int = 3) -> str:
        return decimal_string(self.value, sig)


#: bits of the square roots of :func:`sqrt_fraction` (about 60 decimal digits)
SQRT_BITS = 200


def sqrt_fraction(x: Fraction, up: bool | None = None) -> Fraction:
    """√x for a rational x ≥ 0, to SQRT_BITS bits, in integers (no float, so no overflow
    at any magnitude): rounded down (``up=False``), up (``up=True``) or either way."""
    if x <= 0:
        return Fraction(0)
    p, q = x.numerator, x.denominator
    # √(p/q) = √(p·q·4^k) / (q·2^k): k makes the integer square root SQRT_BITS long
    k = max(0, (2 * SQRT_BITS - (p * q).bit_length()) // 2 + 1)
    n = p * q << (2 * k)
    r = math.isqrt(n)
    if up and r * r != n:
        r += 1
    return Fraction(r, q << k)


def error_constant(result: Any) -> ErrorConstant | None:
    """``C_m`` of a :class:`~rkcheck.energy.check.CheckResult` (None when no condition
    fails up to the checked order, or a certificate proves every order)."""
    if result.energy_order_all:
        return None
    first = result.first_failure
    if first is None:
        return None
    order = first.order
    # only the first failing order is read (the results are columnar and lazy)
    n, res = first.vertices, result.conditions
    at_order = [res.result(n, k) for k in range(len(res.orders[n]))]
    exact = all(r.enclosure.exact for r in at_order)
    if exact:
        squared: Fraction | Interval = sum((Fraction(r.enclosure.mid) ** 2 for r in at_order), Fraction(0))
    else:
        lo = hi = Fraction(0)
        for r in at_order:
            mid, rad = Fraction(r.enclosure.mid), Fraction(r.enclosure.rad)
            a, b = abs(mid) - rad, abs(mid) + rad
            lo += max(a, Fraction(0)) ** 2
            hi += b * b
        squared = Interval(lo, hi)
    failing = sum(1 for r in at_order if r.verdict.state == FAILS)
    return ErrorConstant(result.options.degree, order - 1, order, len(at_order), failing, squared, exact)
