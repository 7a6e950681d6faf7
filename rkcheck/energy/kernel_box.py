"""A kernel whose decimals stand for intervals (definitions §5.2) judged rigorously: its
``A(τ, σ)`` and ``B(τ)`` as polynomials with interval coefficients, and each kernel
identity of :mod:`rkcheck.energy.continuous` as a defect polynomial ``D`` enclosed over
the whole box of kernels.

Every literal occurrence is enclosed on its own (a decimal written twice may take two
values), which only widens the enclosure: a bound on ``|D|`` stays a bound.  On [0, 1]²
``|τ^i σ^j| ≤ 1``, so ``max |D| ≤ Σ max|coefficient|``.  Verdicts: ``fails`` when some
coefficient of D excludes 0 (D ≠ 0 for every kernel of the box), ``holds`` when every
coefficient is exactly 0, otherwise ``holds to D digits`` with ``max|D| ≤ 10^−D``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode
from rkcheck.verdicts import (
    FAILS,
    HOLDS,
    HOLDS_TO_DIGITS,
    Verdict,
    certified_digits,
)

Poly = dict[tuple[int, int], Interval]
ONE = Interval.point(1)


def _add(p: Poly, q: Poly, sign: int = 1) -> Poly:
    out = dict(p)
    for k, c in q.items():
        c = c if sign > 0 else -c
        out[k] = out[k] + c if k in out else c
    return out


def _mul(p: Poly, q: Poly) -> Poly:
    out: Poly = {}
    for (i, j), a in p.items():
        for (k, l), b in q.items():
            key = (i + k, j + l)
            out[key] = out[key] + a * b if key in out else a * b
    return out


def _power(p: Poly, n: int) -> Poly:
    out: Poly = {(0, 0): ONE}
    for _ in range(n):
        out = _mul(out, p)
    return out


def interval_poly(node: ex.Expr, decimals: DecimalsMode, constants: dict[str, Interval], bits: int) -> Poly:
    """``node`` (a polynomial in tau and sigma) with every literal enclosed."""
    def combine(n: ex.Expr, vals: list[Any]) -> Poly:
        if isinstance(n, ex.Name):
            if n.name == "tau":
                return {(1, 0): ONE}
            if n.name == "sigma":
                return {(0, 1): ONE}
            return {(0, 0): constants[n.name]}
        if isinstance(n, (ex.Num, ex.Call)):  # a number (roots take no tau or sigma: the kernel is polynomial)
            return {(0, 0): xp.enclose(n, bits, decimals, constants)}
        if isinstance(n, ex.Unary):
            return {k: -c for k, c in vals[0].items()}
        if isinstance(n, ex.Power):
            k = xp.evaluate_exact(n.exponent, {})
            assert k is not None and k.denominator == 1 and k >= 0  # checked when the kernel was read
            return _power(vals[0], int(k))
        left, right = vals
        if n.op in "+-":
            return _add(left, right, 1 if n.op == "+" else -1)
        if n.op == "*":
            return _mul(left, right)
        (divisor,) = right.values()  # a number: checked when the kernel was read
        return {k: c / divisor for k, c in left.items()}

    poly: Poly = xp.fold(node, combine, xp.polynomial_operands)
    return poly


def _affine(p: Poly, which: int) -> Poly:
    """``p`` with the variable ``which`` (0: τ, 1: σ) replaced by 1 − it."""
    out: Poly = {}
    for (i, j), c in p.items():
        e = (i, j)[which]
        term = _power({(0, 0): ONE, ((1, 0) if which == 0 else (0, 1)): -ONE}, e)
        rest = {((0, j) if which == 0 else (i, 0)): c}
        out = _add(out, _mul(term, rest))
    return out


def _at(p: Poly, value: int) -> Poly:
    """``p(value, σ)`` as a polynomial in σ (value 0 or 1)."""
    out: Poly = {}
    for (i, j), c in p.items():
        if value == 1 or i == 0:
            out = _add(out, {(0, j): c})
    return out


def verdict_of(defect: Poly) -> Verdict:
    if any(not c.contains_zero() for c in defect.values()):
        return Verdict(FAILS)
    bound = sum((max(abs(c.lo), abs(c.hi)) for c in defect.values()), Fraction(0))
    return Verdict(HOLDS) if bound == 0 else Verdict(HOLDS_TO_DIGITS, certified_digits(bound))


def box_verdicts(method: Any, decimals: DecimalsMode, degree: int | None = None, bits: int = 256) -> dict[str, Verdict]:
    """The kernel identities over the box: ``certificate`` (its three parts together),
    ``avf`` (AVF's form for Hamiltonians of ``degree``), ``symmetric``, ``symplectic``."""
    consts = method.info.constants.enclosures(bits, decimals)
    A = interval_poly(method.nodes[0], decimals, consts, bits)
    B = interval_poly(method.nodes[1], decimals, consts, bits)
    B_sigma = {(0, i): c for (i, _), c in B.items()}

    def swap(p: Poly) -> Poly:
        return {(j, i): c for (i, j), c in p.items()}

    dA = {(i - 1, j): c * Interval.point(i) for (i, j), c in A.items() if i > 0}
    parts = [verdict_of(_at(A, 0)), verdict_of(_add(_at(A, 1), B_sigma, -1)), verdict_of(_add(dA, swap(dA), -1))]
    return {
        "certificate": _weakest(parts),
        "avf": _avf_form(A, B, B_sigma, degree),
        "symmetric": _weakest([verdict_of(_add(B, _affine(B, 0), -1)),
                               verdict_of(_add(_add(A, _affine(_affine(A, 0), 1)), B_sigma, -1))]),
        "symplectic": verdict_of(_add(_add(_mul(B, A), _mul(B_sigma, swap(A))), _mul(B, B_sigma), -1)),
    }


def _avf_form(A: Poly, B: Poly, B_sigma: Poly, degree: int | None) -> Verdict:
    """AVF's form over the box (:mod:`rkcheck.energy.continuous`): ``A = C(τ)B(σ)`` and
    ``∫B C^(k−1) = 1/k`` for k = 1…m, or for every degree ``B = ±C'`` with C from one
    end of [0, 1] to the other."""
    C: Poly = {}
    for (i, j), c in A.items():  # ∫₀¹ A dσ
        C = _add(C, {(i, 0): c / Interval.point(j + 1)})
    parts = [verdict_of(_add(A, _mul(C, B_sigma), -1))]
    if degree is None:
        dC = {(i - 1, 0): c * Interval.point(i) for (i, _), c in C.items() if i > 0}
        at0, at1 = _at(C, 0), _at(C, 1)
        rising = [verdict_of(at0), verdict_of(_add(at1, {(0, 0): ONE}, -1)), verdict_of(_add(B, dC, -1))]
        falling = [verdict_of(_add(at0, {(0, 0): ONE}, -1)), verdict_of(at1), verdict_of(_add(B, dC))]
        ends = max((_weakest(rising), _weakest(falling)), key=_strength)
        return _weakest(parts + [ends])
    power: Poly = {(0, 0): ONE}
    for j in range(1, degree + 1):
        moment = sum((c / Interval.point(i + 1) for (i, _), c in _mul(B, power).items()), Interval.point(0))
        parts.append(verdict_of({(0, 0): moment - Interval.point(Fraction(1, j))}))
        power = _mul(power, C)
    return _weakest(parts)


def _strength(v: Verdict) -> tuple[int, int]:
    """Order of verdicts from fails to holds (more digits is stronger)."""
    return {FAILS: (0, 0), HOLDS_TO_DIGITS: (1, v.digits or 0), HOLDS: (2, 0)}[v.state]


def _weakest(verdicts: list[Verdict]) -> Verdict:
    if any(v.state == FAILS for v in verdicts):
        return Verdict(FAILS)
    digits = [v.digits for v in verdicts if v.state == HOLDS_TO_DIGITS and v.digits is not None]
    return Verdict(HOLDS_TO_DIGITS, min(digits)) if digits else Verdict(HOLDS)
