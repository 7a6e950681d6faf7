"""Quadrature rules on [0, 1] at any precision, with certified nodes (seed §2.4).

Rules:

* ``gauss`` (ζ = 0), ``radau-i`` (ζ = −1), ``radau-ii`` (ζ = 1), ``zeta:<value>``: the
  nodes are the zeros of ``P_s − ζ P_{s−1}`` (shifted Legendre on [0, 1], ``P_q(1) = 1``);
* ``lobatto``: 0, 1 and the zeros of ``P'_{s−1}`` (the zeros of ``x(x−1)P'_{s−1}``).

Weights satisfy ``Σ b_i c_i^(k−1) = 1/k`` for k = 1..s, i.e. ``b_i = ∫₀¹ ℓ_i``.

Nodes are **certified**: the node polynomial has exact rational coefficients, rational
zeros are found exactly (``1/3``, ``0``, ``1/2``), and every other zero is enclosed by
FLINT's certified root isolation (:class:`rkcheck.numbers.polynomials.RealRoots`) to any
number of bits — no floating-point rounding is trusted.  Where the zeros have a closed
form in square roots (linear, quadratic and biquadratic factors over Q), it is given as
an entry expression for ``rkcheck new``.

Quadrature **order** q means ``Σ b_i c_i^(k−1) = 1/k`` for k = 1..q (exact for
polynomials of degree ≤ q−1): 2s for Gauss, 2s−1 for any other ζ, 2s−2 for Lobatto.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache
from typing import Any

from rkcheck.errors import UserError
from rkcheck.numbers.formatting import count_text, exact_string
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.polynomials import (
    RealRoots,
    add,
    arb_interval,
    derivative,
    divide,
    evaluate_at_interval,
    integral,
    interval_arb,
    mul,
    poly_text,
    real_roots,
    scale,
    shift,
    squarefree_split,
    to_fmpq,
    to_fraction,
    trim,
)

RULES = ("gauss", "radau-i", "radau-ii", "lobatto")


# ------------------------------------------------------------------ nodes


def shifted_legendre(q: int) -> list[Fraction]:
    """``P_q`` on [0, 1] with ``P_q(1) = 1``: Σ_k (−1)^(q+k) C(q,k) C(q+k,k) x^k."""
    return [Fraction((-1) ** (q + k) * math.comb(q, k) * math.comb(q + k, k)) for k in range(q + 1)]


@dataclass(frozen=True)
class Node:
    """The ``index``-th smallest (0-based) of the real zeros ``roots`` of a rational
    polynomial: exact when rational, else enclosed to any width."""

    roots: RealRoots
    index: int

    @property
    def poly(self) -> list[Fraction]:
        return self.roots.poly

    @property
    def exact(self) -> Fraction | None:
        return self.roots.exact[self.index]

    def enclosure(self, bits: int) -> Interval:
        """An interval of width <= 2^-bits containing the zero (a point when rational),
        with dyadic end points of ``bits + 2`` bits: Arb's end points carry some 30 bits
        more, which every product of the weights' Lagrange integrals would pay for."""
        iv = self.roots.intervals(bits + 1)[self.index]
        return iv if iv.is_point else iv.round_out(bits + 2)


def isolate_zeros(poly: list[Fraction]) -> list[Node]:
    """All zeros of ``poly`` (which must be real and simple), increasing."""
    roots = real_roots(poly)
    if roots.count != len(roots.poly) - 1:
        raise ValueError("not all zeros are real and simple")
    return [Node(roots, k) for k in range(roots.count)]


# ------------------------------------------------------------------ closed forms


def _sqrt_text(x: Fraction) -> tuple[Fraction, str]:
    """sqrt(x) for rational x >= 0 as (coefficient, "sqrt(r)") with integer r, or (root, "")."""
    p, q = x.numerator, x.denominator
    f, r = squarefree_split(p * q, 100_000)
    coeff = Fraction(f, q)
    if r == 1:
        return coeff, ""
    return coeff, f"sqrt({r})"


def _term(coeff: Fraction, radical: str) -> str:
    """coeff * radical as text (coeff > 0)."""
    if not radical:
        return str(coeff)
    num, den = coeff.numerator, coeff.denominator
    text = radical if num == 1 else f"{num}*{radical}"
    return text if den == 1 else f"{text}/{den}"


def _affine(u: Fraction, v: Fraction, radical: str) -> str:
    """u + v·radical as entry text."""
    if not radical or v == 0:
        return str(u + (v if not radical else 0))
    term = _term(abs(v), radical)
    if u == 0:
        return term if v > 0 else f"-{term}"
    return f"{u} {'+' if v > 0 else '-'} {term}"


def _quadratic_roots(a: Fraction, b: Fraction, c: Fraction) -> list[str] | None:
    disc = b * b - 4 * a * c
    if disc <= 0:
        return None
    coeff, radical = _sqrt_text(disc)
    u = -b / (2 * a)
    v = coeff / (2 * abs(a))
    return [_affine(u, -v, radical), _affine(u, v, radical)]


def closed_forms(nodes: list[Node]) -> list[str] | None:
    """Square-root expressions of the zeros, in increasing order, or None if there are none.

    Handles what the rules need: rational zeros, one remaining quadratic factor, or a
    remaining quartic that is even about x = 1/2 (biquadratic).
    """
    poly = nodes[0].poly
    exact = [n.exact for n in nodes if n.exact is not None]
    rest = poly
    for r in exact:
        rest, remainder = divide(rest, [-r, Fraction(1)])
        assert remainder == [0], "not a root"
    rest = trim(rest)
    deg = len(rest) - 1
    texts: list[tuple[float, str]] = [(float(r), str(r)) for r in exact]
    if deg == 0:
        pass
    elif deg == 2:
        roots = _quadratic_roots(rest[2], rest[1], rest[0])
        if roots is None:
            return None
        texts += [(_approx(t), t) for t in roots]
    elif deg == 4:
        # substitute x = 1/2 + y; biquadratic iff the odd coefficients vanish
        shifted = shift(rest, Fraction(1, 2))
        if shifted[1] != 0 or shifted[3] != 0:
            return None
        a, b, c = shifted[4], shifted[2], shifted[0]
        disc = b * b - 4 * a * c
        if disc <= 0:
            return None
        coeff, radical = _sqrt_text(disc)
        for sign in (1, -1):
            w = _affine(-b / (2 * a), sign * coeff / (2 * a), radical)  # y² = w
            texts += [(_approx(f"1/2 - sqrt({w})"), f"1/2 - sqrt({w})"), (_approx(f"1/2 + sqrt({w})"), f"1/2 + sqrt({w})")]
    else:
        return None
    texts.sort()
    return [t for _, t in texts]


def root_forms(nodes: list[Node]) -> list[str]:
    """``root(P, k)`` for every irrational zero (k-th smallest real zero of the node
    polynomial P; the nodes are all of P's zeros, simple and increasing) and the exact
    value of a rational one."""
    text = poly_text(nodes[0].poly)
    return [str(n.exact) if n.exact is not None else f"root({text}, {k})" for k, n in enumerate(nodes, start=1)]


def _approx(text: str) -> float:
    from rkcheck.numbers.entries import Entry
    from rkcheck.numbers.reading import DecimalsMode

    return float(Entry.parse(text).enclosure(64, DecimalsMode.EXACT).mid)


# ------------------------------------------------------------------ rules


@dataclass
class Rule:
    """An s-node quadrature rule with certified nodes and weights at any precision."""

    name: str
    s: int
    zeta: Fraction | None
    nodes: list[Node]
    _cache: dict[int, tuple[list[Interval], list[Interval]]] = field(default_factory=dict)

    @property
    def is_rational(self) -> bool:
        return all(n.exact is not None for n in self.nodes)

    def enclosures(self, bits: int) -> tuple[list[Interval], list[Interval]]:
        """Nodes and weights ``b_i = ∫₀¹ ℓ_i`` enclosed at ``bits`` bits."""
        if bits not in self._cache:
            c = [n.enclosure(bits + 16) for n in self.nodes]
            b = [lagrange_integral(c, i, Interval.point(0), Interval.point(1), bits) for i in range(self.s)]
            self._cache[bits] = (c, b)
        return self._cache[bits]

    def exact_nodes_weights(self) -> tuple[list[Fraction], list[Fraction]]:
        assert self.is_rational
        c, b = self.enclosures(64)
        return [x.lo for x in c], [x.lo for x in b]

    def node_closed_forms(self) -> list[str] | None:
        """Exact entry texts of the nodes, increasing: square roots where they suffice,
        else ``root(P, k)`` (the k-th real zero of the node polynomial P)."""
        return closed_forms(self.nodes) or root_forms(self.nodes)

    def order(self, bits: int = 200) -> int:
        """Quadrature order: the largest q with Σ b c^(k−1) = 1/k for all k <= q (certified:
        a residual whose enclosure excludes 0 stops it)."""
        c, b = self.enclosures(bits)
        q = 0
        for k in range(1, 2 * self.s + 2):
            if not quadrature_residual(b, c, k).contains_zero():
                break
            q = k
        return q


def quadrature_residual(b: list[Interval], c: list[Interval], k: int) -> Interval:
    """``Σ b_i c_i^(k−1) − 1/k``: zero for every k <= q when the rule has order q."""
    total = Interval.point(0)
    for bi, ci in zip(b, c):
        total = total + bi * ci.power(k - 1)
    return total - Interval.point(Fraction(1, k))


def line_integral_matrix(c: list[Interval], b: list[Interval], sigma: int) -> list[list[Interval]]:
    """``Σ_(j<σ) (2j+1) G_j(c)(P_j(c) ⊙ b)ᵀ`` (``P_j`` shifted Legendre, ``G_j = ∫₀^x P_j``):
    the coefficients of HBVM(k, σ) over the rule (b, c), and the right-hand side of the
    line-integral identity (LI) of :mod:`rkcheck.properties.lineintegral`."""
    P = [shifted_legendre(j) for j in range(sigma)]
    G = [integral(p) for p in P]
    Gc = [[evaluate_at_interval(G[j], ci) for j in range(sigma)] for ci in c]
    Pc = [[evaluate_at_interval(P[j], cl) for j in range(sigma)] for cl in c]
    out = []
    for i in range(len(c)):
        row = []
        for l in range(len(c)):
            total = Interval.point(0)
            for j in range(sigma):
                total = total + Interval.point(2 * j + 1) * Gc[i][j] * Pc[l][j]
            row.append(total * b[l])
        out.append(row)
    return out


def lagrange_integral(c: list[Interval], i: int, lo: Interval, hi: Interval, bits: int) -> Interval:
    """``∫_lo^hi ℓ_i(x) dx`` for the Lagrange basis on the nodes ``c``, in Arb balls
    (certified: the result encloses the integral over every choice of nodes in their
    intervals), end points rounded outwards to ``bits + 32`` bits.  The working precision
    carries guard bits for the cancellation of the alternating sums and the small
    denominator; exact rationals would grow by the nodes' size at every factor (20 nodes:
    minutes)."""
    import flint

    if all(x.is_point for x in (*c, lo, hi)):  # rational nodes: the exact value
        return _lagrange_integral_exact([x.lo for x in c], i, lo.lo, hi.lo)
    saved = flint.ctx.prec
    flint.ctx.prec = bits + 64 + 8 * len(c)
    try:
        nodes = [interval_arb(x) for x in c]
        a, z = interval_arb(lo), interval_arb(hi)
        poly = [flint.arb(1)]
        denom = flint.arb(1)
        for j, cj in enumerate(nodes):
            if j == i:
                continue
            new = [flint.arb(0)] * (len(poly) + 1)  # poly *= (x − c_j)
            for k, coeff in enumerate(poly):
                new[k + 1] = new[k + 1] + coeff
                new[k] = new[k] - coeff * cj
            poly = new
            denom = denom * (nodes[i] - cj)
        total = flint.arb(0)
        for k, coeff in enumerate(poly):
            total = total + coeff * (z ** (k + 1) - a ** (k + 1)) / (k + 1)
        value = total / denom
        if not value.is_finite():
            raise ArithmeticError("a Lagrange weight's denominator is not bounded away from 0")
        return arb_interval(value).round_out(bits + 32)
    finally:
        flint.ctx.prec = saved


def _lagrange_integral_exact(c: list[Fraction], i: int, lo: Fraction, hi: Fraction) -> Interval:
    poly = [Fraction(1)]
    denom = Fraction(1)
    for j, cj in enumerate(c):
        if j != i:
            poly = mul(poly, [-cj, Fraction(1)])
            denom *= c[i] - cj
    return Interval.point(sum((a * (hi ** (k + 1) - lo ** (k + 1)) / (k + 1) for k, a in enumerate(poly)),
                              Fraction(0)) / denom)


#: largest |ζ| of a ``zeta:<value>`` rule (docs/errors.md)
MAX_ZETA = 10**6


def _parse_zeta(text: str) -> Fraction:
    from rkcheck.numbers.entries import Entry

    try:
        e = Entry.parse(text)
    except UserError as err:
        raise UserError(f"zeta: {err.message}") from None
    if e.exact is None:
        raise UserError(f"zeta must be rational, got {text!r}")
    return e.exact


@lru_cache(maxsize=64)
def rule(name: str, s: int) -> Rule:
    """The named rule with s nodes: gauss, radau-i, radau-ii, lobatto, zeta:<value>."""
    if s < 1:
        raise UserError(f"a rule needs at least 1 node, got {s}")
    if name == "lobatto":
        if s < 2:
            raise UserError("lobatto needs at least 2 nodes")
        poly = mul([Fraction(0), Fraction(-1), Fraction(1)], derivative(shifted_legendre(s - 1)))
        return Rule(name, s, None, isolate_zeros(poly))
    zeta = {"gauss": Fraction(0), "radau-i": Fraction(-1), "radau-ii": Fraction(1)}.get(name)
    if zeta is None:
        if not name.startswith("zeta:"):
            raise UserError(f"unknown rule {name!r} ({', '.join(RULES)}, zeta:<value>)")
        zeta = _parse_zeta(name[5:])
    if abs(zeta) > MAX_ZETA:  # nodes reach out to ~|ζ|; no rule of use lies past it
        raise UserError(f"zeta must lie in [-{count_text(MAX_ZETA)}, {count_text(MAX_ZETA)}], got {exact_string(zeta)}")
    poly = add(shifted_legendre(s), scale(shifted_legendre(s - 1), -zeta))
    return Rule(name, s, zeta, isolate_zeros(poly))


def rational_rule(n: int) -> tuple[list[Fraction], list[Fraction]]:
    """``n`` equispaced rational nodes on [0, 1] (the midpoint for n = 1) and the
    weights that integrate every polynomial of degree < n exactly (:func:`_weights`).
    Small denominators, for exact arithmetic; from 9 nodes on some weights are negative
    and Σ|w_i| grows like 2ⁿ/n² (175 at 19 nodes)."""
    if n == 1:
        return [Fraction(1, 2)], [Fraction(1)]
    nodes = [Fraction(i, n - 1) for i in range(n)]
    return nodes, _weights(nodes)


def positive_rule(n: int) -> tuple[list[Fraction], list[Fraction]]:
    """``n`` rational nodes on [0, 1], symmetric about 1/2, each the Chebyshev–Lobatto
    point ``(1 − cos(πi/(n−1)))/2`` rounded to a dyadic fraction, and the weights that
    integrate every polynomial of degree < n exactly: all positive (as Clenshaw–Curtis's
    are), so Σ|w_i| = 1 and an enclosure carried through the rule does not grow with n
    as through :func:`rational_rule`'s.  Its denominators are larger (a weight of 19
    nodes has about 180 bits against 44), worth it only where the entries are intervals."""
    if n <= 2:
        return rational_rule(n)
    bits = max(6, math.ceil(math.log2(n * n)) + 2)
    while True:
        scale = 1 << bits
        half = [Fraction(round((1 - math.cos(math.pi * i / (n - 1))) / 2 * scale), scale) for i in range((n + 1) // 2)]
        nodes = half + [1 - x for x in reversed(half[: n // 2])]
        if len(set(nodes)) == n:
            weights = _weights(nodes)
            if all(w > 0 for w in weights):
                return nodes, weights
        bits += 2  # a rounding too coarse for these n points: finer


def _weights(nodes: list[Fraction]) -> list[Fraction]:
    """``w_i = ∫₀¹ L_i`` for the Lagrange basis ``L_i = P/((x − x_i) P′(x_i))``, ``P = Π
    (x − x_j)``: O(n²) polynomial operations in FLINT, where solving the Vandermonde
    system is O(n³)."""
    from flint import fmpq_poly

    points = [to_fmpq(x) for x in nodes]
    X = fmpq_poly([0, 1])
    P = fmpq_poly([1])
    for xi in points:
        P *= X - xi
    dP = P.derivative()
    w = []
    for xi in points:
        integral = (P // (X - xi)).integral()  # exact: x_i is a root of P
        w.append((integral(1) - integral(0)) / dP(xi))
    return [to_fraction(q) for q in w]


def vandermonde(x: list[Fraction], columns: int) -> Any:
    """The matrix ``[x_i^k]`` of the nodes' powers below ``columns``, in FLINT."""
    from flint import fmpq_mat

    return fmpq_mat(len(x), columns, [to_fmpq(xi) ** k for xi in x for k in range(columns)])
