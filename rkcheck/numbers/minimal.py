"""Minimal polynomials of number-field elements (:mod:`rkcheck.numbers.algebraic`), and
what is read off them: whether an element is an algebraic integer, and the least
integer that makes it one (the exact engine's *integrality denominator*).

Minimal polynomials are found numerically and proven exactly (:func:`minimal_polynomial`).
Conjugate elements share theirs, and a tableau whose stages the Galois group permutes (the
Gauss and HBVM families: the group permutes the nodes) has few entries up to conjugacy —
HBVM(6, s), in the field of degree 48 of the six Gauss-6 nodes, has 42 irrational entries
in a few classes; :class:`MinimalPolynomials` finds each class's polynomial once, and an
entry of a known class costs one exact evaluation of it.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Sequence

from rkcheck.numbers.algebraic import FieldElement, largest_term_bits
from rkcheck.numbers.polynomials import evaluate, from_flint, to_fmpq, to_fraction


def minimal_polynomial(x: FieldElement) -> list[Fraction]:
    """The minimal polynomial of the element over Q: monic, ascending Fractions.

    Found numerically and proven exactly: the conjugates ``σ_j(x)`` (``x`` at the
    complex roots of ``g``, Arb balls) fall into clusters of equal values; the product
    of ``X − σ`` over one value per cluster has real rational coefficients, read off
    their balls as the only fraction of small enough denominator inside (continued
    fractions), and the candidate ``P`` is kept only if ``P(x) = 0`` in the field,
    exactly.  A monic ``P`` with ``P(x) = 0`` and no more roots than ``x`` has distinct
    conjugates is the minimal polynomial, so the numerics never decide the result;
    they only find it.  Where they cannot (precision exhausted), the characteristic
    polynomial of multiplication by ``x`` is factored exactly instead: in fields of
    degree 48 its rational 48×48 characteristic polynomial costs 0.6 s per entry,
    the numerical route 10 ms."""
    r = x.rational()
    if r is not None:
        return [-r, Fraction(1)]
    # the terms c_k·θ^k cancel to values of size about 1, so the conjugates need as many
    # bits more than the answer as the largest term has; powers of two share the root cache
    prec = 1 << max(8, (largest_term_bits(x) + 256).bit_length())
    while prec <= 1 << 16:
        found = candidate(x, prec)
        if found is not None and is_root(found, x):
            return found
        prec *= 2
    P = charpoly_mul(x)
    factor = next(from_flint(fac) for fac, _ in P.factor()[1] if is_root(from_flint(fac), x))
    return [c / factor[-1] for c in factor]


def candidate(x: FieldElement, prec: int) -> list[Fraction] | None:
    """The candidate of :func:`minimal_polynomial` at ``prec`` bits, or None when the
    conjugates or the coefficients are not yet resolved at that precision."""
    from flint import acb_poly, ctx, fmpq

    D = x.field.degree
    with ctx.workprec(prec):
        conj = acb_poly([fmpq(c.numerator, c.denominator) for c in x.coeffs]).evaluate(
            x.field.conjugates(prec))
        clusters: list[list[Any]] = []
        for z in conj:
            home = [c for c in clusters if any(z.overlaps(w) for w in c)]
            if len(home) > 1:
                return None  # a ball touching two clusters: not resolved yet
            if home:
                home[0].append(z)
            else:
                clusters.append([z])
        if D % len(clusters) or any(len(c) != D // len(clusters) for c in clusters):
            return None  # charpoly = minpoly^(D/m): every value occurs D/m times
        product = acb_poly.from_roots([c[0] for c in clusters])
        out = []
        for c in product.coeffs():
            if not c.imag.contains(0):
                return None
            mid, rad = to_fraction(c.real.mid()), to_fraction(c.real.rad())
            if rad == 0:
                out.append(mid)
                continue
            # the fraction nearest mid with denominator ≤ Q is the only one in the ball
            # when the ball is narrower than 1/(2Q²); any other q' ≤ Q differs by ≥ 1/Q²
            q_max = math.isqrt(int(1 / (4 * rad)))
            if q_max < 1:
                return None
            guess = mid.limit_denominator(q_max)
            if abs(guess - mid) > rad:
                return None
            out.append(guess)
    return out


def integral_scale(monic: Sequence[Fraction]) -> int:
    """The least positive integer λ with ``λ^n f(x/λ)`` integral, for the monic rational
    ``f`` (ascending coefficients): λθ is then an algebraic integer."""
    from flint import fmpz

    n = len(monic) - 1
    need: dict[int, int] = {}
    for k, c in enumerate(monic[:-1]):
        den = Fraction(c).denominator
        if den > 1:
            for fq, fe in fmpz(den).factor():
                need[int(fq)] = max(need.get(int(fq), 0), -(-int(fe) // (n - k)))
    lam = 1
    for q, e in need.items():
        lam *= q**e
    return lam


def charpoly_mul(alpha: FieldElement) -> Any:
    """The characteristic polynomial of multiplication by α on its field (its roots are the
    conjugates of α)."""
    from flint import fmpq_mat

    K = alpha.field
    D = K.degree
    M = fmpq_mat(D, D)
    x = alpha
    theta = K.gen
    for j in range(D):  # column j: α·θ^j
        for i, c in enumerate(x.coeffs):
            M[i, j] = to_fmpq(c)
        x = x * theta
    return M.charpoly()


def is_root(P: Sequence[Fraction], x: FieldElement) -> bool:
    """``P(x) = 0`` exactly, by baby steps and giant steps (Paterson–Stockmeyer): with
    ``k ≈ √m`` for P of degree m, ``P(x) = Σ_j B_j(x)·(x^k)^j`` where each ``B_j`` has
    degree < k and rational coefficients, so its value is a rational combination of
    ``1, x, …, x^(k−1)`` — about ``2√m`` products of field elements where Horner's scheme
    takes m (in a field of degree 48 a product costs about a millisecond)."""
    m = len(P) - 1
    if m < 4:
        return bool(evaluate(P, x, x.field(0)).is_zero())
    k = math.isqrt(m)
    powers = [x.field(1), x]
    while len(powers) <= k:
        powers.append(powers[-1] * x)
    giant = powers.pop()  # x^k
    acc = x.field(0)
    for j in reversed(range(0, m + 1, k)):
        block = x.field(0)
        for i, c in enumerate(P[j:j + k]):
            if c:
                block = block + powers[i] * c
        acc = acc * giant + block if j + k <= m else block
    return acc.is_zero()


#: The prime of :class:`MinimalPolynomials`' quick test (2^61 − 1, FLINT's nmod).
TEST_PRIME = (1 << 61) - 1


def _mod_p(coeffs: Sequence[Fraction], p: int) -> list[int] | None:
    """Rational coefficients modulo ``p`` (None when a denominator is divisible by p)."""
    out = []
    for c in coeffs:
        if c.denominator % p == 0:
            return None
        out.append(c.numerator * pow(c.denominator, -1, p) % p)
    return out


def may_be_root(P: Sequence[Fraction], x: FieldElement, p: int = TEST_PRIME) -> bool:
    """False only when ``P(x) ≠ 0`` for certain: ``P(x)`` reduced modulo ``p`` (in
    ``F_p[y]/(g)``, g the field's minimal polynomial) is nonzero, and reduction modulo p
    is a ring homomorphism on the elements whose denominators p does not divide.  Costs
    microseconds where :func:`is_root` multiplies elements of 1000-bit coefficients."""
    from flint import nmod_poly

    g, xs, Ps = _mod_p(x.field.minpoly, p), _mod_p(x.coeffs, p), _mod_p(P, p)
    if g is None or xs is None or Ps is None:
        return True
    gp, xp = nmod_poly(g, p), nmod_poly(xs, p)
    acc = nmod_poly([0], p)
    for c in reversed(Ps):
        acc = (acc * xp + c) % gp
    return acc.is_zero()


class MinimalPolynomials:
    """Minimal polynomials of the elements of one field, each class of conjugates found
    once (module docstring): a known polynomial that passes :func:`may_be_root` is proven
    by :func:`is_root` (an irreducible monic P with ``P(x) = 0`` is x's minimal
    polynomial), so the quick test only saves time, it never decides."""

    def __init__(self) -> None:
        self._known: list[list[Fraction]] = []

    def of(self, x: FieldElement) -> list[Fraction]:
        r = x.rational()
        if r is not None:
            return [-r, Fraction(1)]
        for P in self._known:
            if may_be_root(P, x) and is_root(P, x):
                return P
        P = minimal_polynomial(x)
        self._known.append(P)
        return P
