"""The compositum of a number field ``Q(θ)`` and a new generator ``γ``
(:mod:`rkcheck.numbers.field_builder`): a separating multiplier t, the characteristic
polynomial of ``θ + tγ`` (whose irreducible factor at the primitive element is the new
field's minimal polynomial), and the old generator θ in the new field.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from rkcheck.numbers.algebraic import FieldElement, NotAlgebraic, NumberField
from rkcheck.numbers.minimal import is_root
from rkcheck.numbers.polynomials import add, divide, from_flint, mul


def separating_multipliers(g: Any, f: Any, candidates: Sequence[int] = (1, -1, 2, -2, 3, -3, 5, 7, 11, 13),
                           check_time: Callable[[], None] = lambda: None) -> Iterator[int]:
    """The integers t (from ``candidates``) for which the sums ``θ_i + t·γ_j`` over all
    conjugates are pairwise distinct — proven with certified complex balls (FLINT acb):
    two balls whose difference excludes 0 are distinct numbers.  Then the characteristic
    polynomial of ``θ + tγ`` is square-free without computing a gcd.

    The roots are enclosed at 256 bits beyond the coefficients' own size, then at four and
    sixteen times that: conjugates of size 10^77 (``sqrt(sqrt(1e155))``) leave balls of
    fixed precision too wide to tell apart, while a t that truly makes two sums equal is
    never certified at any precision."""
    from flint import ctx

    size = max(abs(int(c)).bit_length() for p in (g, f) for c in p.numer().coeffs())
    tried: set[int] = set()
    for bits in (256 + 2 * size, 1024 + 8 * size, 4096 + 32 * size):
        check_time()
        with ctx.workprec(bits):
            thetas = [r for r, _ in g.numer().complex_roots()]
            gammas = [r for r, _ in f.numer().complex_roots()]
            for t in candidates:
                if t in tried:
                    continue
                sums = [a + t * b for a in thetas for b in gammas]
                if all(not (sums[i] - sums[j]).contains(0) for i in range(len(sums)) for j in range(i)):
                    tried.add(t)
                    yield t


def _power_sums(poly: Any, count: int) -> list[Any]:
    """``p_1 … p_count``, the power sums of the roots of ``poly`` (fmpq_poly), by
    Newton's identities on its monic coefficients."""
    n = poly.degree()
    lead = poly[n]
    a = [poly[i] / lead for i in range(n + 1)]  # monic: a[n] = 1
    p: list[Any] = [None] * (count + 1)  # p[0] unused
    for k in range(1, count + 1):
        total = -k * a[n - k] if k <= n else 0 * lead
        for i in range(1, min(k, n + 1)):
            total -= a[n - i] * p[k - i]
        p[k] = total
    return p


def charpoly_sum(g: Any, f: Any, t: int) -> Any:
    """The characteristic polynomial ``Π (x − θ_i − t·γ_j)`` of ``y + t·z`` on
    ``Q[y, z]/(g(y), f(z))``, over all conjugates θ_i of g and γ_j of f.

    Its power sums are ``P_k = Σ_l C(k, l) tˡ G_(k−l) F_l`` from those of g and f (``G_0 =
    deg g``), and Newton's identities turn them into its coefficients: O(N²) products of
    rationals for degree N = deg g · deg f, where the characteristic polynomial of the
    N×N Kronecker sum would cost O(N³), a quarter of a second at N = 144."""
    from flint import fmpq, fmpq_poly

    m, n = g.degree(), f.degree()
    N = m * n
    G, F = _power_sums(g, N), _power_sums(f, N)
    G[0], F[0] = fmpq(m), fmpq(n)
    tl = [fmpq(1)]
    for _ in range(N):
        tl.append(tl[-1] * t)
    TF = [tl[l] * F[l] for l in range(N + 1)]
    P = [sum((math.comb(k, l) * G[k - l] * TF[l] for l in range(k + 1)), fmpq(0)) for k in range(N + 1)]
    e = [fmpq(1)]  # elementary symmetric functions of the roots θ_i + t·γ_j
    for k in range(1, N + 1):
        total = fmpq(0)
        for i in range(1, k + 1):
            term = e[k - i] * P[i]
            total = total + term if i % 2 else total - term
        e.append(total / k)
    return fmpq_poly([e[N - j] if (N - j) % 2 == 0 else -e[N - j] for j in range(N + 1)])


def theta_in(L: NumberField, g: Any, f: Any, t: int, check_time: Callable[[], None] = lambda: None) -> FieldElement:
    """θ (root of g) in L = Q(η), η = θ + tγ: ``η − tγ``, with γ the one common root of
    ``f(z)`` and ``r(z) = g(η − tz) mod f`` over L (t separates the conjugates).

    γ comes from linear algebra, not from Euclid's algorithm: the n − 1 rows
    ``z^k·r mod f`` (k < n − 1, n = deg f) span the multiples of ``gcd(f, r) = z − γ``
    modulo f, so their kernel is spanned by ``(1, γ, …, γ^(n−1))`` and γ is a ratio of two
    maximal minors, products only.  Euclid over L divides by elements of L at every step
    and swelled their coefficients to 40 000 bits (10 s of the 12 s build of the Gauss-6
    field of degree 48)."""
    fc = from_flint(f)
    monic = [c / fc[-1] for c in fc]
    n = len(monic) - 1
    line = [L.gen, L(-t)]  # η − t·z
    zero = L(0)
    r = [zero]
    for c in reversed(from_flint(g)):  # Horner's scheme modulo f: products by rationals only
        r = divide(add(mul(r, line, zero), [L(c)], zero), monic, zero)[1]
    rows = []
    for _ in range(n - 1):
        rows.append(r + [zero] * (n - len(r)))
        r = divide([zero] + r, monic, zero)[1]
    # minors[cols]: the determinant of the first len(cols) rows on those columns
    minors: dict[tuple[int, ...], FieldElement] = {(): L(1)}
    for i, row in enumerate(rows):
        nxt: dict[tuple[int, ...], FieldElement] = {}
        for cols, m in minors.items():
            check_time()  # the minors can number 2^n
            for j in range(n):
                if j in cols or row[j].is_zero():
                    continue
                key = tuple(sorted(cols + (j,)))
                sign = -1 if (i + key.index(j)) % 2 else 1  # Laplace along row i
                term = m * row[j]
                nxt[key] = nxt[key] + term * sign if key in nxt else term * sign
        minors = nxt
    full = tuple(range(n))
    v0 = minors.get(full[1:], zero)  # kernel vector: v_j = (−1)^j · minor without column j
    v1 = -minors.get(full[:1] + full[2:], zero)
    gamma = v1 / v0 if not v0.is_zero() else None
    # the answer is checked, not trusted: γ must be a root of f and η − tγ one of g
    if gamma is None or not is_root(monic, gamma) or not is_root(from_flint(g), L.gen - gamma * t):
        raise NotAlgebraic("the primitive element does not separate the conjugates (internal error)")
    return L.gen - gamma * t
