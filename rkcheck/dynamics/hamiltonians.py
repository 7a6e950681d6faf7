"""Polynomial Hamiltonians: the test problems of ``rkcheck simulate`` and ``workprec``.

A Hamiltonian is a polynomial in ``y = (q_1..q_d, p_1..p_d)`` with exact rational
coefficients; its gradient and Hessian are the exact derivative polynomials (no finite
differences).  The equations of motion follow the seed paper, ``y' = J⁻¹∇H`` with
``J = [[0, I], [−I, 0]]``, i.e. ``q' = −∂H/∂p``, ``p' = ∂H/∂q`` — the usual Hamilton
equations with time reversed, which changes no energy property.

Problems (``--problem``):

==========================  ======  ===  ==================================================
name                        degree  d    H
==========================  ======  ===  ==================================================
``harmonic``                2       1    (q² + p²)/2
``henon-heiles``            3       2    (p₁² + p₂² + q₁² + q₂²)/2 + q₁²q₂ − q₂³/3
``quartic``                 4       1    p²/2 + q⁴/4
``fpu``                     4       2    two-mass FPU-β chain, fixed ends: Σ p²/2 +
                                         Σ_{i=0..2} [(q_{i+1}−q_i)²/2 + (q_{i+1}−q_i)⁴/4]
``random:degree=m,dim=d,    m       d    every monomial of degree 1..m gets a coefficient
seed=S``                                 k/8 with k uniform in {−8..8}; a zero leading
                                         coefficient of degree m is redrawn, so the degree
                                         is exactly m (defaults: dim 2, seed 1)
==========================  ======  ===  ==================================================
"""

from __future__ import annotations

import math
import random
import re
from dataclasses import dataclass, field
from fractions import Fraction
from itertools import combinations_with_replacement
from typing import Any, Sequence

from rkcheck.errors import UserError
from rkcheck.numbers.formatting import count_text

Monomials = dict[tuple[int, ...], Fraction]  # exponents (len 2d) -> coefficient


def _derivative(poly: Monomials, k: int) -> Monomials:
    out: Monomials = {}
    for e, c in poly.items():
        if e[k]:
            e2 = e[:k] + (e[k] - 1,) + e[k + 1:]
            out[e2] = out.get(e2, Fraction(0)) + c * e[k]
    return {e: c for e, c in out.items() if c}


@dataclass
class Polynomial:
    """A polynomial in n variables, evaluated in any number type (float, mpf, Fraction)."""

    n: int
    terms: Monomials
    _compiled: Any = field(default=None, repr=False)

    @property
    def degree(self) -> int:
        return max((sum(e) for e in self.terms), default=0)

    def __call__(self, y: Sequence[Any]) -> Any:
        """Value at y: per variable a table of powers, then one product per monomial."""
        powers = _power_table(y, self.degree)
        total = 0
        for e, c in self._coeffs(y):
            v = c
            for k, ek in enumerate(e):
                if ek:
                    v = v * powers[k][ek]
            total = total + v
        return total

    def _coeffs(self, y):
        # coefficients converted once per number type
        kind = type(y[0])
        if self._compiled is None or self._compiled[0] is not kind:
            conv = _converter(y[0])
            self._compiled = (kind, [(e, conv(c)) for e, c in self.terms.items()])
        return self._compiled[1]

    def derivative(self, k: int) -> "Polynomial":
        return Polynomial(self.n, _derivative(self.terms, k))


def _power_table(y: Sequence[Any], m: int) -> list[list[Any]]:
    table = []
    for x in y:
        row = [1, x]
        for _ in range(2, m + 1):
            row.append(row[-1] * x)
        table.append(row)
    return table


def _converter(sample: Any):
    if isinstance(sample, float):
        return lambda c: c.numerator / c.denominator
    if isinstance(sample, Fraction):
        return lambda c: c
    try:
        import mpmath

        if isinstance(sample, mpmath.mpf):
            return lambda c: mpmath.mpf(c.numerator) / c.denominator
    except ImportError:  # pragma: no cover
        pass
    return lambda c: float(c)


@dataclass
class Hamiltonian:
    """H(q, p) with d degrees of freedom, its exact gradient and Hessian polynomials."""

    name: str
    d: int
    H: Polynomial
    grad: list[Polynomial] = field(default_factory=list)
    hess: list[list[Polynomial]] = field(default_factory=list)

    def __post_init__(self) -> None:
        n = 2 * self.d
        self.grad = [self.H.derivative(k) for k in range(n)]
        self.hess = [[g.derivative(k) for k in range(n)] for g in self.grad]

    @property
    def degree(self) -> int:
        return self.H.degree

    @property
    def dim(self) -> int:
        return 2 * self.d

    def energy(self, y: Sequence[Any]) -> Any:
        return self.H(y)

    def f(self, y: Sequence[Any]) -> list[Any]:
        """y' = J⁻¹∇H: q' = −∂H/∂p, p' = ∂H/∂q."""
        g = [gk(y) for gk in self.grad]
        d = self.d
        return [-g[d + i] for i in range(d)] + [g[i] for i in range(d)]

    def jacobian(self, y: Sequence[Any]) -> list[list[Any]]:
        """∂f/∂y = J⁻¹ ∇²H, from the exact Hessian polynomials."""
        d = self.d
        Hm = [[h(y) for h in row] for row in self.hess]
        return [[-x for x in Hm[d + i]] for i in range(d)] + [Hm[i] for i in range(d)]


def _poly(d: int, terms: dict[tuple[int, ...], Fraction | int]) -> Polynomial:
    return Polynomial(2 * d, {e: Fraction(c) for e, c in terms.items()})


def harmonic() -> Hamiltonian:
    return Hamiltonian("harmonic", 1, _poly(1, {(2, 0): Fraction(1, 2), (0, 2): Fraction(1, 2)}))


def henon_heiles() -> Hamiltonian:
    t: dict[tuple[int, ...], Fraction | int] = {
        (0, 0, 2, 0): Fraction(1, 2), (0, 0, 0, 2): Fraction(1, 2),
        (2, 0, 0, 0): Fraction(1, 2), (0, 2, 0, 0): Fraction(1, 2),
        (2, 1, 0, 0): 1, (0, 3, 0, 0): Fraction(-1, 3),
    }
    return Hamiltonian("henon-heiles", 2, _poly(2, t))


def quartic() -> Hamiltonian:
    return Hamiltonian("quartic", 1, _poly(1, {(0, 2): Fraction(1, 2), (4, 0): Fraction(1, 4)}))


def _add_power_of_difference(terms: Monomials, d: int, i: int, j: int | None, power: int, coeff: Fraction) -> None:
    """terms += coeff·(q_i − q_j)^power (q_j = 0 when j is None)."""
    from math import comb

    for k in range(power + 1):
        e = [0] * (2 * d)
        e[i] += power - k
        if j is not None:
            e[j] += k
        elif k:
            continue
        c = coeff * comb(power, k) * (-1) ** k
        key = tuple(e)
        terms[key] = terms.get(key, Fraction(0)) + c


def fpu() -> Hamiltonian:
    d = 2
    terms: Monomials = {(0, 0, 2, 0): Fraction(1, 2), (0, 0, 0, 2): Fraction(1, 2)}
    # springs q1 − q0, q2 − q1, q3 − q2 with q0 = q3 = 0
    for i, j in [(0, None), (1, 0), (1, None)]:
        _add_power_of_difference(terms, d, i, j, 2, Fraction(1, 2))
        _add_power_of_difference(terms, d, i, j, 4, Fraction(1, 4))
    return Hamiltonian("fpu", d, Polynomial(2 * d, {e: c for e, c in terms.items() if c}))


#: The most monomials a random Hamiltonian may have (docs/errors.md).
MAX_RANDOM_MONOMIALS = 20_000


def random_hamiltonian(degree: int, d: int = 2, seed: int = 1) -> Hamiltonian:
    """Every monomial of degree 1..m gets k/8, k uniform in {−8, ..., 8}; the degree-m
    part is redrawn until nonzero, so the degree is exactly m."""
    rng = random.Random(seed)
    n = 2 * d
    terms: Monomials = {}
    for total in range(1, degree + 1):
        for combo in combinations_with_replacement(range(n), total):
            e = [0] * n
            for k in combo:
                e[k] += 1
            terms[tuple(e)] = Fraction(rng.randint(-8, 8), 8)
    while not any(c for key, c in terms.items() if sum(key) == degree):
        for key in terms:
            if sum(key) == degree:
                terms[key] = Fraction(rng.randint(-8, 8), 8)
    name = f"random:degree={degree},dim={d},seed={seed}"
    return Hamiltonian(name, d, Polynomial(n, {e: c for e, c in terms.items() if c}))


PROBLEMS = {"harmonic": harmonic, "henon-heiles": henon_heiles, "quartic": quartic, "fpu": fpu}


def problem(spec: str) -> Hamiltonian:
    """``harmonic``, ``henon-heiles``, ``quartic``, ``fpu`` or ``random:degree=m[,dim=d][,seed=S]``."""
    if spec in PROBLEMS:
        return PROBLEMS[spec]()
    if spec.startswith("random"):
        params = {"dim": "2", "seed": "1"}  # degree: required
        rest = spec[len("random"):].lstrip(":")
        seen: set[str] = set()
        for part in filter(None, rest.split(",")):
            m = re.fullmatch(r"\s*(degree|dim|seed)\s*=\s*(-?\d+)\s*", part)
            if not m:
                raise UserError(f"cannot read {part!r} (expected degree=m, dim=d, seed=S)", "--problem")
            if m.group(1) in seen:
                raise UserError(f"{m.group(1)} is given twice in {spec!r}", "--problem")
            seen.add(m.group(1))
            params[m.group(1)] = m.group(2)
        if "degree" not in params:
            raise UserError("random needs degree=m, e.g. random:degree=4", "--problem")
        degree, dim, seed = int(params["degree"]), int(params["dim"]), int(params["seed"])
        if not 1 <= degree <= 12 or not 1 <= dim <= 6:
            raise UserError("random needs 1 <= degree <= 12 and 1 <= dim <= 6", "--problem")
        # H, its gradient and its Hessian hold (1 + 2d + 4d²) polynomials of up to this many
        # terms: degree 12 with dim 6 would be 2.7 million monomials and gigabytes
        monomials = math.comb(2 * dim + degree, degree) - 1
        if monomials > MAX_RANDOM_MONOMIALS:
            raise UserError(f"random:degree={degree},dim={dim} has {count_text(monomials)} monomials; the limit is "
                            f"{count_text(MAX_RANDOM_MONOMIALS)} (lower the degree or dim)", "--problem")
        return random_hamiltonian(degree, dim, seed)
    raise UserError(f"unknown problem {spec!r} ({', '.join(PROBLEMS)}, random:degree=m,dim=d,seed=S)", "--problem")
