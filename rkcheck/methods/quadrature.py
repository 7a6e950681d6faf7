"""Quadrature rules on [0, 1] at any precision, with certified nodes (seed §2.4).

Rules:

* ``gauss`` (ζ = 0), ``radau-i`` (ζ = −1), ``radau-ii`` (ζ = 1), ``zeta:<value>``: the
  nodes are the zeros of ``P_s − ζ P_{s−1}`` (shifted Legendre on [0, 1], ``P_q(1) = 1``);
* ``lobatto``: 0, 1 and the zeros of ``P'_{s−1}`` (the zeros of ``x(x−1)P'_{s−1}``).

Weights satisfy ``Σ b_i c_i^(k−1) = 1/k`` for k = 1..s, i.e. ``b_i = ∫₀¹ ℓ_i``.

Nodes are **certified**: the node polynomial has exact rational coefficients, rational
zeros are found exactly (``1/3``, ``0``, ``1/2``), and every other zero is isolated by an
exact sign change of the polynomial on a dyadic interval, refined by bisection to any
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

from rkcheck.errors import UserError
from rkcheck.numbers.formatting import count_text
from rkcheck.numbers.intervals import Interval, poly_at

RULES = ("gauss", "radau-i", "radau-ii", "lobatto")


# ------------------------------------------------------------------ polynomials
# Polynomials are lists of Fractions, ascending powers.


def shifted_legendre(q: int) -> list[Fraction]:
    """``P_q`` on [0, 1] with ``P_q(1) = 1``: Σ_k (−1)^(q+k) C(q,k) C(q+k,k) x^k."""
    return [Fraction((-1) ** (q + k) * math.comb(q, k) * math.comb(q + k, k)) for k in range(q + 1)]


def poly_add(p: list[Fraction], q: list[Fraction]) -> list[Fraction]:
    n = max(len(p), len(q))
    return [(p[i] if i < len(p) else Fraction(0)) + (q[i] if i < len(q) else Fraction(0)) for i in range(n)]


def poly_scale(p: list[Fraction], a: Fraction) -> list[Fraction]:
    return [a * x for x in p]


def poly_mul(p: list[Fraction], q: list[Fraction]) -> list[Fraction]:
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def poly_deriv(p: list[Fraction]) -> list[Fraction]:
    return [k * p[k] for k in range(1, len(p))] or [Fraction(0)]


def poly_integral(p: list[Fraction]) -> list[Fraction]:
    """The antiderivative vanishing at 0."""
    return [Fraction(0)] + [c / (k + 1) for k, c in enumerate(p)]


def poly_eval(p: list[Fraction], x: Fraction) -> Fraction:
    acc = Fraction(0)
    for c in reversed(p):
        acc = acc * x + c
    return acc


def poly_trim(p: list[Fraction]) -> list[Fraction]:
    while len(p) > 1 and p[-1] == 0:
        p = p[:-1]
    return p


def poly_divide_root(p: list[Fraction], r: Fraction) -> list[Fraction]:
    """p(x)/(x − r) for an exact root r (synthetic division)."""
    n = len(p) - 1
    out = [Fraction(0)] * n
    acc = Fraction(0)
    for k in range(n, 0, -1):
        acc = acc * r + p[k]
        out[k - 1] = acc
    assert acc * r + p[0] == 0, "not a root"
    return out


def _sign_at_dyadic(p: list[Fraction], m: int, k: int) -> int:
    """sign of p(m / 2^k), exactly, in integers."""
    den = 1
    for c in p:
        den = math.lcm(den, c.denominator)
    coeffs = [int(c * den) for c in p]
    n = len(coeffs) - 1
    acc = 0
    for i in range(n, -1, -1):  # Σ c_i m^i 2^(k(n−i))
        acc = acc * m + coeffs[i] * (1 << (k * (n - i)))
    return (acc > 0) - (acc < 0)


# ------------------------------------------------------------------ nodes


@dataclass
class Node:
    """A simple real zero of a rational polynomial: exact, or an isolating dyadic interval."""

    poly: list[Fraction]
    exact: Fraction | None = None
    lo: tuple[int, int] = (0, 0)  # (m, k): the dyadic m / 2^k
    hi: tuple[int, int] = (0, 0)
    _refined: dict[int, Interval] = field(default_factory=dict)

    def enclosure(self, bits: int) -> Interval:
        """An interval of width <= 2^-bits containing the zero (bisection on exact signs)."""
        if self.exact is not None:
            return Interval.point(self.exact)
        if bits in self._refined:
            return self._refined[bits]
        (ml, kl), (mh, kh) = self.lo, self.hi
        k = max(kl, kh)
        ml <<= k - kl
        mh <<= k - kh
        s_lo = _sign_at_dyadic(self.poly, ml, k)
        while Fraction(mh - ml, 1 << k) > Fraction(1, 1 << bits):
            ml, mh, k = 2 * ml, 2 * mh, k + 1
            mid = (ml + mh) // 2
            s_mid = _sign_at_dyadic(self.poly, mid, k)
            if s_mid == 0:
                self.exact = Fraction(mid, 1 << k)
                return Interval.point(self.exact)
            if s_mid == s_lo:
                ml = mid
            else:
                mh = mid
        out = Interval(Fraction(ml, 1 << k), Fraction(mh, 1 << k))
        self._refined[bits] = out
        return out


def _approximate_roots(poly: list[Fraction]) -> list[float]:
    import mpmath

    with mpmath.workdps(40):
        coeffs = [mpmath.mpf(c.numerator) / c.denominator for c in reversed(poly)]
        roots = mpmath.polyroots(coeffs, maxsteps=200, extraprec=200)
    out = []
    for r in roots:
        if abs(mpmath.im(r)) > 1e-20:
            raise ValueError("complex zero")
        out.append(float(mpmath.re(r)))
    return sorted(out)


def isolate_zeros(poly: list[Fraction]) -> list[Node]:
    """All zeros of ``poly`` (assumed real and simple), each exact or isolated, sorted."""
    poly = poly_trim(poly)
    nodes: list[Node] = []
    rest = poly
    approx = _approximate_roots(poly)
    irrational: list[float] = []
    for r in approx:
        guess = Fraction(r).limit_denominator(10_000)
        if poly_eval(rest, guess) == 0 and len(rest) > 1:
            rest = poly_divide_root(rest, guess)
            nodes.append(Node(poly, exact=guess))
        else:
            irrational.append(r)
    k = 60
    for r in irrational:
        m = round(r * (1 << k))
        for width in (1 << 4, 1 << 12, 1 << 20):
            lo, hi = m - width, m + width
            if _sign_at_dyadic(poly, lo, k) * _sign_at_dyadic(poly, hi, k) < 0:
                nodes.append(Node(poly, lo=(lo, k), hi=(hi, k)))
                break
        else:
            raise ValueError(f"could not isolate the zero near {r}")
    nodes.sort(key=lambda n: n.exact if n.exact is not None else Fraction(n.lo[0], 1 << n.lo[1]))
    # disjoint isolating intervals + exact zeros: exactly deg(poly) distinct zeros
    for a, b in zip(nodes, nodes[1:]):
        if a.enclosure(60).hi >= b.enclosure(60).lo:
            raise ValueError("zeros are not separated")
    if len(nodes) != len(poly) - 1:
        raise ValueError("not all zeros are real and simple")
    return nodes


# ------------------------------------------------------------------ closed forms


def _squarefree(n: int) -> tuple[int, int]:
    """n = f² r with r as square-free as trial division up to 10^5 can make it."""
    f, r = 1, n
    d = 2
    while d * d <= r and d < 100_000:
        while r % (d * d) == 0:
            r //= d * d
            f *= d
        d += 1
    return f, r


def _sqrt_text(x: Fraction) -> tuple[Fraction, str]:
    """sqrt(x) for rational x >= 0 as (coefficient, "sqrt(r)") with integer r, or (root, "")."""
    p, q = x.numerator, x.denominator
    f, r = _squarefree(p * q)
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
        rest = poly_divide_root(rest, r)
    rest = poly_trim(rest)
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
        shifted = _shift(rest, Fraction(1, 2))
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
    from rkcheck.numbers.polynomials import poly_text

    text = poly_text(nodes[0].poly)
    return [str(n.exact) if n.exact is not None else f"root({text}, {k})" for k, n in enumerate(nodes, start=1)]


def _shift(p: list[Fraction], h: Fraction) -> list[Fraction]:
    """Coefficients of p(h + y) in y."""
    out = [Fraction(0)]
    for c in reversed(p):
        out = poly_add(poly_mul(out, [h, Fraction(1)]), [c])
    return out


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
    line-integral identity (LI) of :mod:`rkcheck.energy.lineintegral`."""
    P = [shifted_legendre(j) for j in range(sigma)]
    G = [poly_integral(p) for p in P]
    Gc = [[poly_at(G[j], ci) for j in range(sigma)] for ci in c]
    Pc = [[poly_at(P[j], cl) for j in range(sigma)] for cl in c]
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
    """``∫_lo^hi ℓ_i(x) dx`` for the Lagrange basis on the nodes ``c`` (interval arithmetic,
    end points rounded outwards to ``bits + 32`` bits to keep the rationals small)."""
    poly: list[Interval] = [Interval.point(1)]
    denom = Interval.point(1)
    for j, cj in enumerate(c):
        if j == i:
            continue
        # poly *= (x − c_j)
        new = [Interval.point(0)] * (len(poly) + 1)
        for k, a in enumerate(poly):
            new[k + 1] = new[k + 1] + a
            new[k] = new[k] - a * cj
        poly = new
        denom = denom * (c[i] - cj)
    total = Interval.point(0)
    for k, a in enumerate(poly):
        total = total + a * (hi.power(k + 1) - lo.power(k + 1)) / Interval.point(k + 1)
    return (total / denom).round_out(bits + 32)


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
        poly = poly_mul([Fraction(0), Fraction(-1), Fraction(1)], poly_deriv(shifted_legendre(s - 1)))
        return Rule(name, s, None, isolate_zeros(poly))
    zeta = {"gauss": Fraction(0), "radau-i": Fraction(-1), "radau-ii": Fraction(1)}.get(name)
    if zeta is None:
        if not name.startswith("zeta:"):
            raise UserError(f"unknown rule {name!r} ({', '.join(RULES)}, zeta:<value>)")
        zeta = _parse_zeta(name[5:])
    if abs(zeta) > MAX_ZETA:  # the root finder's domain (nodes beyond ~|ζ|); no use past it
        raise UserError(f"zeta must lie in [-{count_text(MAX_ZETA)}, {count_text(MAX_ZETA)}], got {float(zeta):.3g}")
    poly = poly_add(shifted_legendre(s), poly_scale(shifted_legendre(s - 1), -zeta))
    return Rule(name, s, zeta, isolate_zeros(poly))
