"""One coordinate of a solution, exactly (:class:`AlgebraicValue`): read through its own
minimal polynomial as a rational, a closed form ``p ± q*sqrt(d)``, or a numbered root of
it (FLINT's order: the real roots first, increasing), with a certified enclosure; and
the same value in the entries' grammar, for a member of the family to be built from it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rkcheck.numbers.groebner import fmpq_of


@dataclass(frozen=True)
class AlgebraicValue:
    """One coordinate of a solution, exactly: ``text`` is a rational, a closed form
    ``p + q*sqrt(d)`` or a polynomial in z at a root of
    z's minimal polynomial (numbered as FLINT isolates them: real roots first); ``ball``
    encloses it (None for rationals)."""

    text: str
    real: bool
    approx: complex
    minpoly: tuple[Fraction, ...] = ()
    ball: Any = None  # a certified complex enclosure (flint acb)
    #: its place among the roots of ``minpoly`` as FLINT orders them (the real ones
    #: first, increasing), when it is named as one (a minimal polynomial of degree ≥ 3)
    index: int | None = None

    def expression(self) -> str | None:
        """The value in the entries' grammar (a rational, ``p ± q*sqrt(d)``, or
        ``root(P, k)``: the k-th smallest real root of its minimal polynomial P), for a
        member of the family to be built from it; None when it is not real."""
        if not self.real or not self.minpoly:
            return None
        if len(self.minpoly) <= 3:  # a rational or a real quadratic: its text is a closed form
            return self.text
        if self.index is None:
            return None
        # a real root's place among all roots is its place among the real ones
        return f"root({_poly_text(list(self.minpoly), 'x')}, {self.index + 1})"


def _float(x: Any) -> float:
    """``x`` (a Fraction or an exact arb) as a float, ±inf past the range (a solution
    such as ``kappa = 10^400`` is exact; only its floating-point view saturates)."""
    try:
        return float(x)
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def _coordinate(p: Any, phi: Any, root: Any, k: int) -> AlgebraicValue:
    """The value of ``p(z)`` at the root ``root`` (the k-th complex root of φ)."""
    value = _horner([Fraction(int(c.p), int(c.q)) for c in p.coeffs()], root)
    real = root.imag == 0
    approx = complex(_float(value.real.mid()), _float(value.imag.mid()))
    coeffs = [Fraction(int(c.p), int(c.q)) for c in p.coeffs()] or [Fraction(0)]
    if p.degree() <= 0:
        q = coeffs[0]
        return AlgebraicValue(_frac_text(q), True, complex(_float(q)), (-q, Fraction(1)), value)
    if phi.degree() == 2:
        return _quadratic(coeffs, phi, root, real, approx)
    poly = _poly_text(coeffs, "z")
    phi_text = _poly_text([Fraction(int(c.p), int(c.q)) for c in phi.coeffs()], "z")
    kind = "" if real else "complex "
    return AlgebraicValue(f"{poly} at z = {kind}root {k + 1} of {phi_text}", real, approx, (), value)


def _quadratic(coeffs: list[Fraction], phi: Any, root: Any, real: bool, approx: complex) -> AlgebraicValue:
    """``c0 + c1·z`` with ``z = (−b ± √D)/2a`` as ``P ± Q·√d`` (d square-free)."""
    a, b, c = (Fraction(int(x.p), int(x.q)) for x in reversed(phi.coeffs()))
    D = b * b - 4 * a * c
    d, square = _squarefree_part(D)  # √D = square·√d
    from flint import arb

    centre = arb(fmpq_of(-b / (2 * a)))
    sign = 1 if (real and root.real > centre) or (not real and root.imag > 0) else -1
    c0, c1 = coeffs[0], coeffs[1] if len(coeffs) > 1 else Fraction(0)
    P = c0 + c1 * (-b / (2 * a))
    Q = sign * c1 * square / (2 * a)
    text = _closed_form(P, Q, d)
    minpoly = (P * P - Q * Q * d, -2 * P, Fraction(1))
    return AlgebraicValue(text, real, approx, minpoly, root_value(coeffs, root))


#: square factors of a discriminant are divided out up to this prime (trial division:
#: past it, a full factorisation could take any time); a square cofactor is found whole
SQUARE_TRIAL_LIMIT = 1 << 12


def _squarefree_part(D: Fraction) -> tuple[int, Fraction]:
    """``D = square²·d`` with d an integer (√D = square·√d): every integer up to
    :data:`SQUARE_TRIAL_LIMIT` divided out (its square into ``square``, an odd power's
    last factor kept in d), then the rest whole if it is a square.  d is square-free but
    where the square of a larger prime sits in a larger cofactor (√d is then exact,
    merely not reduced)."""
    num = D.numerator * D.denominator
    sign = -1 if num < 0 else 1
    num = abs(num)
    square, small = 1, 1
    k = 2
    while k <= SQUARE_TRIAL_LIMIT and k <= num:
        e = 0
        while num % k == 0:
            num //= k
            e += 1
        square *= k ** (e // 2)
        small *= k ** (e % 2)
        k += 1
    root = math.isqrt(num)
    if root * root == num:
        num, square = 1, square * root
    return sign * small * num, Fraction(square, D.denominator)


#: Bits of the roots an approximate value (``≈``, ten digits) is read from.
APPROX_BITS = 128


def _closed_form(P: Fraction, Q: Fraction, d: int) -> str:
    if Q == 0 or d == 1:
        return _frac_text(P + (Q if d == 1 else 0))
    root = f"sqrt({d})" if d > 0 else ("i" if d == -1 else f"sqrt({-d})*i")
    q = "" if abs(Q) == 1 else f"{_frac_text(abs(Q))}*"
    if P == 0:
        return f"{'-' if Q < 0 else ''}{q}{root}"
    return f"{_frac_text(P)} {'-' if Q < 0 else '+'} {q}{root}"


def _frac_text(q: Fraction) -> str:
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def _poly_text(coeffs: list[Fraction], x: str) -> str:
    terms = []
    for j in range(len(coeffs) - 1, -1, -1):
        c = coeffs[j]
        if c:
            mono = "" if j == 0 else (x if j == 1 else f"{x}^{j}")
            if mono and abs(c) == 1:  # x, not 1*x
                terms.append(mono if c > 0 else f"-{mono}")
            else:
                terms.append(f"{_frac_text(c)}{'*' if mono else ''}{mono}")
    return " + ".join(terms).replace("+ -", "- ") or "0"


def root_value(coeffs: list[Fraction], root: Any) -> Any:
    return _horner(coeffs, root)


def _horner(coeffs: list[Fraction], x: Any) -> Any:
    """A rational polynomial at a complex ball (flint acb), certified."""
    from flint import acb, arb

    out = acb(0)
    for c in reversed(coeffs):
        out = out * x + acb(arb(fmpq_of(c)))
    return out


def coordinate_value(p: Any, psi: Any, root: Any, k: int, minimal: dict[Any, Any], name: str) -> AlgebraicValue:
    """A coordinate ``p(z)`` at a root of ψ, shown through its own minimal polynomial
    (rational, a square-root closed form, or a numbered root of it) rather than as a
    polynomial in z: in a field of degree 8 the coordinates of A = c bᵀ have degree 4."""
    if p.degree() <= 0 or psi.degree() <= 2:
        return _coordinate(p, psi, root, k)
    if name not in minimal:
        from rkcheck.numbers.algebraic import NumberField
        from rkcheck.numbers.minimal import minimal_polynomial

        K = NumberField([Fraction(int(x.p), int(x.q)) for x in psi.coeffs()], 1, name="z")
        minimal[name] = minimal_polynomial(K([Fraction(int(x.p), int(x.q)) for x in p.coeffs()]))
    P = minimal[name]
    from flint import fmpq_poly

    if len(P) < 3:
        return _coordinate(fmpq_poly([fmpq_of(-P[0])]), psi, root, k)
    # which root of P the coordinate is, by enclosures: its value at a complex root of ψ
    # is a ball whose imaginary part straddles 0 even when it is real, so P's own root
    # (real exactly where it is real) is what the closed form is read from
    j, roots, value = _which_root(P, [Fraction(int(x.p), int(x.q)) for x in p.coeffs()], psi, root, k)
    if len(P) == 3:
        return _coordinate(fmpq_poly([0, 1]), fmpq_poly([fmpq_of(x) for x in P]), roots[j], j)
    real = roots[j].imag == 0
    # from P's own root, not from the coordinate's value at ψ's root: that ball is as wide
    # as ψ's root isolation (±1e-5 in a field of degree 12), and its midpoint's tenth
    # digit would be shown as if it were known
    approx = complex(_float(roots[j].real.mid()), _float(roots[j].imag.mid()))
    kind = "" if real else "complex "
    imag = "" if real else f" {'+' if approx.imag >= 0 else '-'} {abs(approx.imag):.10g}i"
    # the polynomial in the coordinate's own name: with several parameters, an x would
    # read as another of them
    return AlgebraicValue(f"{kind}root {j + 1} of {_poly_text(P, name)} (≈ {approx.real:.10g}{imag})", real, approx,
                          tuple(P), value, j)


#: the working precision at which two roots of a minimal polynomial are taken to be
#: told apart for certain (they are distinct: it is square-free)
MAX_ROOT_BITS = 1 << 16


def _which_root(P: list[Fraction], coeffs: list[Fraction], psi: Any, root: Any, k: int) -> tuple[int, list[Any], Any]:
    """The place of ``p(z)`` (``coeffs``) at ψ's k-th root among the roots of its
    minimal polynomial P, P's roots, and the value: the precision doubles until one root
    of P alone overlaps the value (two can lie closer than a first enclosure tells)."""
    from flint import ctx, fmpq_poly

    bits = APPROX_BITS  # P's roots, tight enough that every digit shown is right
    while True:
        with ctx.workprec(bits):
            found: Any = fmpq_poly([fmpq_of(x) for x in P]).complex_roots()  # (acb, multiplicity) pairs
            if bits > APPROX_BITS:
                root = psi.complex_roots()[k][0]
            value = root_value(coeffs, root)
        roots = [r for r, _ in found]
        hits = [i for i, r in enumerate(roots) if r.overlaps(value)]
        if len(hits) == 1:
            return hits[0], roots, value
        if bits >= MAX_ROOT_BITS:
            raise ArithmeticError(f"the roots of a minimal polynomial of degree {len(P) - 1} were not told apart "
                                  f"at {bits} bits")
        bits *= 2
