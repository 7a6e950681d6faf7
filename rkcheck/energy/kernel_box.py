"""A kernel whose decimals stand for intervals (definitions §5.2) judged rigorously: each
kernel identity of :mod:`rkcheck.energy.continuous` as a defect polynomial ``D`` in τ, σ
bounded over the whole box of kernels.

``A(τ, σ)`` and ``B(τ)`` are the kernel's forms (:mod:`rkcheck.energy.kernel_forms`):
exact polynomials in its literals as well, so that what cancels for every kernel of the
box cancels here, and an identity that holds for every kernel of the box holds — as a
classical condition whose weight involves no interval holds over a tableau's box.  Where
an identity's forms would be too large, its coefficients are intervals, every literal
occurrence enclosed on its own (:class:`IntervalForm`), which only widens the bound.  On
[0, 1]² ``|τ^i σ^j| ≤ 1``, so ``max |D| ≤ Σ max|coefficient|``.  Verdicts: ``fails``
when some coefficient of D is nonzero on the whole box (D ≠ 0 for every kernel of the
box), ``holds`` when every coefficient is 0 on it, otherwise ``holds to D digits`` with
``max|D| ≤ 10^−D``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Iterator

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


class IntervalForm:
    """A polynomial in τ, σ with interval coefficients, every literal occurrence enclosed
    on its own: the judge of an identity whose forms
    (:mod:`rkcheck.energy.kernel_forms`) would be too large."""

    __slots__ = ("p",)

    def __init__(self, p: Poly):
        self.p = p

    def __add__(self, other: "IntervalForm") -> "IntervalForm":
        return IntervalForm(_add(self.p, other.p))

    def __sub__(self, other: "IntervalForm") -> "IntervalForm":
        return IntervalForm(_add(self.p, other.p, -1))

    def __neg__(self) -> "IntervalForm":
        return IntervalForm({k: -c for k, c in self.p.items()})

    def __mul__(self, other: "IntervalForm") -> "IntervalForm":
        return IntervalForm(_mul(self.p, other.p))

    def scaled(self, q: Fraction) -> "IntervalForm":
        return IntervalForm({k: c * Interval.point(q) for k, c in self.p.items()})

    def constant(self, q: Fraction) -> "IntervalForm":
        return IntervalForm({(0, 0): Interval.point(q)})

    def at_tau(self, value: int) -> "IntervalForm":
        return IntervalForm(_at(self.p, value))

    def reflected(self, tau: bool, sigma: bool) -> "IntervalForm":
        p = _affine(self.p, 0) if tau else self.p
        return IntervalForm(_affine(p, 1) if sigma else p)

    def swapped(self) -> "IntervalForm":
        return IntervalForm({(j, i): c for (i, j), c in self.p.items()})

    def in_sigma(self) -> "IntervalForm":
        return IntervalForm({(0, i): c for (i, _), c in self.p.items()})

    def d_tau(self) -> "IntervalForm":
        return IntervalForm({(i - 1, j): c * Interval.point(i) for (i, j), c in self.p.items() if i > 0})

    def integral(self, var: str) -> "IntervalForm":
        out: Poly = {}
        for (i, j), c in self.p.items():
            key, e = ((i, 0), j) if var == "s" else ((0, j), i)
            out = _add(out, {key: c / Interval.point(e + 1)})
        return IntervalForm(out)

    def spans(self) -> Iterator[tuple[Fraction, Fraction]]:
        return ((c.mid, c.rad) for c in self.p.values())


def verdict_of(defect: Any) -> Verdict:
    """A defect polynomial's verdict on [0, 1]²: ``fails`` when some coefficient is
    nonzero on the whole box, ``holds`` when all are 0 on it, else the digits of
    ``Σ max |coefficient|``."""
    spans = list(defect.spans())
    if any(abs(centre) > spread for centre, spread in spans):
        return Verdict(FAILS)
    bound = sum((abs(centre) + spread for centre, spread in spans), Fraction(0))
    return Verdict(HOLDS) if bound == 0 else Verdict(HOLDS_TO_DIGITS, certified_digits(bound))


def box_verdicts(method: Any, decimals: DecimalsMode, degree: int | None = None, bits: int = 256) -> dict[str, Verdict]:
    """The kernel identities over the box: ``certificate`` (its three parts together),
    ``avf`` (AVF's form for Hamiltonians of ``degree``), ``symmetric``, ``symplectic``;
    each on the kernel's forms, or on interval coefficients where its forms would be
    too large."""
    from rkcheck.energy.kernel_forms import NoForm, kernel_forms

    def intervals() -> tuple[IntervalForm, IntervalForm]:
        consts = method.info.constants.enclosures(bits, decimals)
        return (IntervalForm(interval_poly(method.nodes[0], decimals, consts, bits)),
                IntervalForm(interval_poly(method.nodes[1], decimals, consts, bits)))

    try:
        forms: tuple[Any, Any] = kernel_forms(method, decimals, bits)
    except NoForm:
        forms = intervals()
    identities = {"certificate": _certificate, "avf": lambda A, B: _avf_form(A, B, degree),
                  "symmetric": _symmetric, "symplectic": _symplectic}
    out = {}
    for name, identity in identities.items():
        try:
            out[name] = identity(*forms)
        except NoForm:
            out[name] = identity(*intervals())
    return out


def _certificate(A: Any, B: Any) -> Verdict:
    """∂τA symmetric, A(0, σ) = 0, A(1, σ) = B(σ)."""
    dA = A.d_tau()
    return _weakest([verdict_of(A.at_tau(0)), verdict_of(A.at_tau(1) - B.in_sigma()), verdict_of(dA - dA.swapped())])


def _symmetric(A: Any, B: Any) -> Verdict:
    """B(τ) = B(1 − τ) and A(τ, σ) + A(1 − τ, 1 − σ) = B(σ)."""
    return _weakest([verdict_of(B - B.reflected(True, False)),
                     verdict_of(A + A.reflected(True, True) - B.in_sigma())])


def _symplectic(A: Any, B: Any) -> Verdict:
    """B(τ)A(τ, σ) + B(σ)A(σ, τ) = B(τ)B(σ)."""
    B_sigma = B.in_sigma()
    return verdict_of(B * A + B_sigma * A.swapped() - B * B_sigma)


def _avf_form(A: Any, B: Any, degree: int | None) -> Verdict:
    """AVF's form over the box (:mod:`rkcheck.energy.continuous`): ``A = C(τ)B(σ)`` and
    ``∫B C^(k−1) = 1/k`` for k = 1…m, or for every degree ``B = ±C'`` with C from one
    end of [0, 1] to the other."""
    C = A.integral("s")  # ∫₀¹ A dσ
    one = A.constant(Fraction(1))
    parts = [verdict_of(A - C * B.in_sigma())]
    if degree is None:
        dC = C.d_tau()
        at0, at1 = C.at_tau(0), C.at_tau(1)
        rising = [verdict_of(at0), verdict_of(at1 - one), verdict_of(B - dC)]
        falling = [verdict_of(at0 - one), verdict_of(at1), verdict_of(B + dC)]
        ends = max((_weakest(rising), _weakest(falling)), key=_strength)
        return _weakest(parts + [ends])
    power = one
    for j in range(1, degree + 1):
        parts.append(verdict_of((B * power).integral("t") - one.scaled(Fraction(1, j))))
        power = power * C
    return _weakest(parts)


def _strength(v: Verdict) -> tuple[int, int]:
    """Order of verdicts from fails to holds (more digits is stronger)."""
    return {FAILS: (0, 0), HOLDS_TO_DIGITS: (1, v.digits or 0), HOLDS: (2, 0)}[v.state]


def _weakest(verdicts: list[Verdict]) -> Verdict:
    if any(v.state == FAILS for v in verdicts):
        return Verdict(FAILS)
    digits = [v.digits for v in verdicts if v.state == HOLDS_TO_DIGITS and v.digits is not None]
    return Verdict(HOLDS_TO_DIGITS, min(digits)) if digits else Verdict(HOLDS)
