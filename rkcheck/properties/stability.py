"""The stability function R(z), and the certificate for quadratic Hamiltonians at every order.

Applied to ``y' = λy`` a Runge–Kutta method gives ``y₁ = R(hλ) y₀`` with

    R(z) = 1 + z bᵀ(I − zA)⁻¹1 = det(I − zA + z 1bᵀ) / det(I − zA) = P(z)/Q(z)

(matrix determinant lemma), a rational function with ``deg P, deg Q ≤ s``.  Its power
series is ``R(z) = Σ_k r_k z^k`` with ``r_0 = 1`` and ``r_k = bᵀA^(k−1)1`` — the
elementary weights of the tall trees.

**Quadratic Hamiltonians** (definitions §3: m = 2 leaves the odd paths, one condition per
even order).  The path with ``2k+1`` vertices rooted at its centre has residual

    R(path) = Σ_{j<k} (−1)^(k−j) r_j r_(2k−j) + r_k²/2 = (−1)^k e_(2k) / 2,

where ``e_n`` are the coefficients of ``R(z)R(−z) − 1 = Σ e_n z^n`` (odd ones vanish).  So
the m = 2 energy conditions up to order 2k are exactly ``e_2 = … = e_2k = 0``, and

    R(z)R(−z) − 1 = (P(z)P(−z) − Q(z)Q(−z)) / (Q(z)Q(−z)),

whose numerator has degree ≤ 2s and whose denominator is 1 at z = 0.  Hence
**R(z)R(−z) ≡ 1 iff e_2 = … = e_2s = 0**: finitely many exact tests prove energy
preservation for every quadratic H at every order (a certificate, like AVF).  Otherwise
the first nonzero ``e_2k z^2k`` is the leading term, and the m = 2 energy order is 2k − 1.

Everything is computed over the tableau's own scalars (:mod:`rkcheck.properties.scalars`):
exact over Q or the tableau's number field, certified for enclosures.  ``det(I − zA)``
comes from a Hessenberg reduction for exact scalars and from the Faddeev–LeVerrier
recursion (divisions by integers only) for enclosures; ``P = Q·R`` truncated to degree s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rkcheck.numbers import polynomials as poly
from rkcheck.numbers.algebraic import FieldElement
from rkcheck.numbers.centred import Centred
from rkcheck.numbers.deadline import Overrun, call_within
from rkcheck.numbers.formatting import decimal_string
from rkcheck.numbers.intervals import Interval
from rkcheck.properties import scalars as sc
from rkcheck.verdicts import FAILS, HOLDS, Verdict, combine

#: enclosures: above this many stages det(I − zA) is not expanded (the certificate,
#: which needs only the series, is still decided)
MAX_INTERVAL_DET_STAGES = 16

#: rational tableaux with at most this many stages, and entries of at most
#: MAX_FRACTION_BITS bits, stay in Python's Fractions (the generic exact path); the others go
#: to FLINT, whose import (~50 ms) would otherwise dominate a small check's start-up, while
#: Fraction growth hurts beyond ~15 stages, or already at 8 stages with 40-digit entries
#: (Euclid's algorithm on Fractions: 16 s, against milliseconds in FLINT)
MAX_FRACTION_STAGES = 8
MAX_FRACTION_BITS = 64

#: longest time spent cancelling the common factors of P/Q over a number field
STABILITY_SECONDS = 10.0

_SUP = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


# ---------------------------------------------------------------- polynomials
# lists of scalars, ascending powers (rkcheck.numbers.polynomials over the tableau's scalars)


def _is_zero(a: sc.Scalar) -> bool:
    return sc.verdict(a).state == HOLDS


def _trim(p: sc.Vector) -> sc.Vector:
    return poly.trim(p, _is_zero)


def _det_I_minus_zA(A: sc.Matrix, like: sc.Scalar) -> sc.Vector | None:
    """Coefficients of ``det(I − zA)`` (ascending), or None when not expanded."""
    n = len(A)
    exact = sc.is_exact(like)
    if not exact and n > MAX_INTERVAL_DET_STAGES:
        return None
    charpoly = _charpoly_hessenberg(A, like) if exact else _charpoly_faddeev(A, like)
    assert len(charpoly) == n + 1
    # det(xI − A) = Σ c_k x^k  ⇒  det(I − zA) = z^n det(z⁻¹I − A) = Σ c_(n−k) z^k
    return list(reversed(charpoly))


def _charpoly_faddeev(A: sc.Matrix, like: sc.Scalar) -> sc.Vector:
    """``det(xI − A)`` by Faddeev–LeVerrier: only divisions by integers."""
    n = len(A)
    zero, one = sc.const(0, like), sc.const(1, like)
    coeffs = [zero] * (n + 1)
    coeffs[n] = one
    M = [[zero] * n for _ in range(n)]
    for k in range(1, n + 1):
        AM = [[sc.total([A[i][l] * M[l][j] for l in range(n)], like) for j in range(n)] for i in range(n)]
        M = [[AM[i][j] + (coeffs[n - k + 1] if i == j else zero) for j in range(n)] for i in range(n)]
        trace = sc.total([sc.total([A[i][l] * M[l][i] for l in range(n)], like) for i in range(n)], like)
        coeffs[n - k] = -(trace * sc.const(Fraction(1, k), like))
    return coeffs


def _charpoly_hessenberg(A: sc.Matrix, like: sc.Scalar) -> sc.Vector:
    """``det(xI − A)`` of an exact matrix: similarity to upper Hessenberg form, then the
    recurrence on leading principal minors (H. Cohen, A Course in Computational Algebraic
    Number Theory, Algorithm 2.2.9)."""
    n = len(A)
    H = [list(row) for row in A]
    for m in range(1, n - 1):
        piv = next((i for i in range(m, n) if sc.certainly_nonzero(H[i][m - 1])), None)
        if piv is None:
            continue
        if piv != m:
            H[piv], H[m] = H[m], H[piv]
            for row in H:
                row[piv], row[m] = row[m], row[piv]
        t = H[m][m - 1]
        for i in range(m + 1, n):
            if not sc.certainly_nonzero(H[i][m - 1]):
                continue
            u = H[i][m - 1] / t
            for j in range(n):
                H[i][j] = H[i][j] - u * H[m][j]
            for j in range(n):
                H[j][m] = H[j][m] + u * H[j][i]
    zero, one = sc.const(0, like), sc.const(1, like)
    polys = [[one]]  # p_0 = 1; p_k = charpoly of the leading k×k block
    for k in range(1, n + 1):
        hkk = H[k - 1][k - 1]
        p = poly.sub([zero] + polys[k - 1], [hkk * a for a in polys[k - 1]] + [zero], zero)
        prod = one
        for i in range(k - 1, 0, -1):
            prod = prod * H[i][i - 1]
            coef = H[i - 1][k - 1] * prod
            term = [coef * a for a in polys[i - 1]]
            p = poly.sub(p, term + [zero] * (len(p) - len(term)), zero)
        polys.append(p)
    return polys[n]


# ---------------------------------------------------------- the stability function


@dataclass(frozen=True)
class StabilityFunction:
    """``R(z) = P(z)/Q(z)`` and ``R(z)R(−z) − 1`` of one tableau.

    ``series`` = ``r_0 … r_2s``; ``defect`` = ``e_0 … e_2s`` (``R(z)R(−z) − 1``);
    ``identity`` = the verdict of ``e_2 = … = e_2s = 0`` (``R(z)R(−z) ≡ 1``);
    ``leading_power`` / ``leading_coefficient`` = the first ``e_2k`` that certainly
    differs from 0 (None when the identity holds); ``numerator``/``denominator`` = P, Q
    in lowest terms with ``Q(0) = 1`` for exact tableaux (None when not expanded)."""

    stages: int
    exact: bool
    series: sc.Vector
    defect: sc.Vector
    identity: Verdict
    leading_power: int | None
    leading_coefficient: object | None
    numerator: sc.Vector | None
    denominator: sc.Vector | None

    @property
    def quadratic_energy_order(self) -> int | None:
        """The energy order for m = 2 (None: every order, R(z)R(−z) ≡ 1)."""
        return None if self.leading_power is None else self.leading_power - 1

    @property
    def defect_numerator(self) -> sc.Vector | None:
        """``P(z)P(−z) − Q(z)Q(−z)`` (so ``R(z)R(−z) − 1`` = it over ``Q(z)Q(−z)``)."""
        if self.numerator is None or self.denominator is None:
            return None
        zero = sc.const(0, self.series[0])
        P, Q = self.numerator, self.denominator
        return _trim(poly.sub(poly.mul(P, poly.reflect(P), zero), poly.mul(Q, poly.reflect(Q), zero), zero))

    def text(self) -> str:
        """``R(z) = …`` for people."""
        if self.numerator is None or self.denominator is None:
            return f"R(z) = {poly_text(self.series[: 6])} + …"
        num, den = poly_text(self.numerator), poly_text(self.denominator)
        eq = "=" if self.exact else "≈"
        if den == "1":
            return f"R(z) {eq} {num}"
        return f"R(z) {eq} ({num}) / ({den})"

    def defect_text(self) -> str:
        """``R(z)R(−z) − 1 = …``: the exact rational function when it is short, else its
        leading term."""
        if self.leading_power is None:
            if not self.identity.decided:
                return "R(z)R(−z) = 1 not decided (to 0 digits)"
            how = self.identity.how()
            return f"R(z)R(−z) = 1 ({how})"
        lead = monomial_text(self.leading_coefficient, self.leading_power)
        num = self.defect_numerator
        den = None
        if num is not None and self.denominator is not None:
            den = _trim(poly.mul(self.denominator, poly.reflect(self.denominator), sc.const(0, self.series[0])))
        if num is not None and den is not None and len(den) == 1 and self.exact:
            return f"R(z)R(−z) − 1 = {poly_text(num)}"
        return f"R(z)R(−z) − 1 = {lead} + O(z{str(self.leading_power + 2).translate(_SUP)})"


def _rational_parts(A: sc.Matrix, b: sc.Vector) -> tuple[sc.Vector, sc.Vector, sc.Vector] | None:
    """For a rational tableau of more than :data:`MAX_FRACTION_STAGES` stages or with an
    entry longer than :data:`MAX_FRACTION_BITS`: the series r_0 … r_2s, and P, Q in lowest
    terms with Q(0) = 1, computed with FLINT (exact rational matrices and polynomials:
    Fraction arithmetic and Euclid's algorithm on Fractions grow too fast)."""
    entries = [x for row in A for x in row] + list(b)
    if not all(isinstance(x, (Fraction, int)) for x in entries):
        return None
    if len(b) <= MAX_FRACTION_STAGES and all(_bits(x) <= MAX_FRACTION_BITS for x in entries):
        return None
    s = len(b)
    head, Q = _head_and_charpoly(A, b)
    P = (Q * poly.to_flint(head)).truncate(s + 1)
    numerator, denominator = poly.rational_lowest_terms(P, Q)
    return _series_of(P, Q, 2 * s + 1), numerator, denominator


def _head_and_charpoly(A: sc.Matrix, b: sc.Vector) -> tuple[list[Fraction], Any]:
    """r_0 … r_s and det(I − zA) (an ``fmpq_poly``) of a rational tableau, over the
    integers: with D the common denominator of A, r_(k+1) = bᵀ(DA)^k 1 / D^k, so the s
    products by the matrix are of integers (FLINT's rational matrices reduce every entry
    of every product to lowest terms), and det(I − zA) is that of DA at z/D."""
    from flint import fmpq_mat, fmpq_poly, fmpz_mat

    s = len(b)
    D = math.lcm(*(Fraction(x).denominator for row in A for x in row))
    M = fmpz_mat(s, s, [int(Fraction(x) * D) for row in A for x in row])
    B = fmpq_mat(1, s, [poly.to_fmpq(x) for x in b])
    v = fmpz_mat(s, 1, [1] * s)
    head, power = [Fraction(1)], 1  # power = D^k
    for _ in range(s):
        head.append(poly.to_fraction((B * fmpq_mat(v))[0, 0]) / power)
        v, power = M * v, power * D
    c = M.charpoly().coeffs()  # det(xI − DA) = Σ c_j x^j, so det(I − zA) = Σ c_(s−k) (z/D)^k
    return head, fmpq_poly([poly.to_fmpq(Fraction(int(c[s - k]), D**k)) for k in range(s + 1)])


def _series_of(P: Any, Q: Any, n: int) -> list[Fraction]:
    """The first ``n`` coefficients of the power series P/Q (Q(0) = 1), by FLINT's series
    division: past z^s they follow from P and Q alone, with no more products by A."""
    import flint

    saved = flint.ctx.cap
    flint.ctx.cap = n
    try:
        coeffs = (flint.fmpq_series(P.coeffs(), prec=n) / flint.fmpq_series(Q.coeffs(), prec=n)).coeffs()
    finally:
        flint.ctx.cap = saved
    return [poly.to_fraction(x) for x in coeffs] + [Fraction(0)] * (n - len(coeffs))


def _bits(x: Fraction | int) -> int:
    x = Fraction(x)
    return max(x.numerator.bit_length(), x.denominator.bit_length())


def _interval_parts(A: sc.Matrix, b: sc.Vector, with_series: bool = True) -> tuple[sc.Vector, sc.Vector] | None:
    """For enclosures: the series r_0 … r_2s and det(I − zA), enclosed with FLINT's ball
    matrices (rigorous: every input interval is enclosed by a ball, every result ball is
    returned as the interval it certifies); O(s³) instead of interval Faddeev–LeVerrier's
    O(s⁴) on rationals with long end points.  ``with_series`` False: the series is r_0
    alone (the caller computes it another way)."""
    if not all(isinstance(x, Interval) for row in A for x in row) or not all(isinstance(x, Interval) for x in b):
        return None
    import flint
    from flint import arb, arb_mat

    widths = [x.hi - x.lo for row in A for x in row if not x.is_point] + [x.hi - x.lo for x in b if not x.is_point]
    need = max((w.denominator.bit_length() - w.numerator.bit_length() for w in widths), default=64)
    bits = max(128, need + 64)

    ball, interval = poly.interval_arb, poly.arb_interval

    saved = flint.ctx.prec
    flint.ctx.prec = bits
    try:
        n = len(b)
        M = arb_mat(n, n, [ball(x) for row in A for x in row])
        B = arb_mat(1, n, [ball(x) for x in b])
        v = arb_mat(n, 1, [arb(1)] * n)
        series = [Interval.point(1)]
        for _ in range(2 * n if with_series else 0):
            series.append(interval((B * v)[0, 0]))
            v = M * v
        Q = [interval(c) for c in reversed(M.charpoly().coeffs())]
    finally:
        flint.ctx.prec = saved
    return [sc.tidy(x) for x in series], [sc.tidy(x) for x in Q]


def stability_function(A: sc.Matrix, b: sc.Vector, series: list[Fraction] | None = None) -> StabilityFunction:
    """``R(z)`` of the tableau ``(A, b)`` over its own scalars (see the module docstring);
    ``series``: ``r_0 … r_2s`` when they are known over Q beforehand (a family in node
    form), so that no product is taken in the entries' field."""
    s = len(b)
    if series is not None:
        return stability_of_series(series, s)
    like = sc.sample(A, b)
    rational = _rational_parts(A, b)
    if rational is not None:
        series, P, Q = rational
        return _from_parts(s, True, series, _trim(P), _trim(Q))
    # values in mean value form: the series, on which the identity R(z)R(−z) = 1 is
    # decided, in that form (FLINT's balls take every entry as independent), det(I − zA)
    # in balls
    centred = any(isinstance(x, Centred) for x in b)
    enclosed = _interval_parts(A, b, with_series=not centred)
    if enclosed is not None:
        series, Q = enclosed
        if centred:
            series = _series(A, b, like)
        P = [sc.total([Q[j] * series[k - j] for j in range(k + 1)], like) for k in range(s + 1)]
        return _from_parts(s, False, series, _trim(P), _trim(Q))
    series = _series(A, b, like)
    numerator: sc.Vector | None = None
    denominator: sc.Vector | None = None
    rational_series = _rational_series(series)
    if rational_series is not None:
        P, Q = _pade(rational_series, s)
        return _from_parts(s, True, series, _trim(P), _trim(Q))
    charpoly = _det_I_minus_zA(A, like)
    if charpoly is not None:
        Q = charpoly
        P = [sc.total([Q[j] * series[k - j] for j in range(k + 1)], like) for k in range(s + 1)]
        if sc.is_exact(like):
            P, Q = _cancelled(P, Q, like)
        numerator, denominator = _trim(P), _trim(Q)
    return _from_parts(s, sc.is_exact(like), series, numerator, denominator)


def _series(A: sc.Matrix, b: sc.Vector, like: sc.Scalar) -> sc.Vector:
    """``r_0 … r_2s``, ``r_k = bᵀA^(k−1)1``, over the tableau's scalars."""
    series = [sc.const(1, like)]
    v = [sc.const(1, like) for _ in b]  # A^(k−1) 1
    for _ in range(2 * len(b)):
        series.append(sc.dot(b, v, like))
        v = sc.matvec(A, v, like)
    return series


def _rational_series(series: sc.Vector) -> list[Fraction] | None:
    """The series as Fractions when the tableau's entries lie in a number field and every
    term r_k = bᵀA^(k−1)1 is rational anyway — as when the field's Galois group permutes
    the stages (Gauss, Radau, Lobatto, HBVM), which leaves each r_k fixed; else None
    (rational tableaux keep their own route, which never loads FLINT for a small one)."""
    if not isinstance(series[-1], FieldElement):
        return None
    out = [x if isinstance(x, (Fraction, int)) else x.rational() for x in series]
    return None if any(r is None for r in out) else [Fraction(r) for r in out]


def _pade(series: list[Fraction], s: int) -> tuple[list[Fraction], list[Fraction]]:
    """R = P/Q in lowest terms with Q(0) = 1 from its series r_0 … r_2s: R is a rational
    function with numerator and denominator of degree ≤ s, so it is the one such P/Q with
    ``P ≡ Q·Σ r_k z^k (mod z^(2s+1))`` — found by the extended Euclidean algorithm on
    ``z^(2s+1)`` and the series, stopped at the first remainder of degree ≤ s (over Q,
    where det(I − zA) by Hessenberg's reduction divides in a field of degree up to 48)."""
    from flint import fmpq_poly

    r0, r1 = fmpq_poly([0] * (2 * s + 1) + [1]), poly.to_flint(series[:2 * s + 1])
    t0, t1 = fmpq_poly([0]), fmpq_poly([1])
    while r1.degree() > s:
        q, r = divmod(r0, r1)
        r0, r1 = r1, r
        t0, t1 = t1, t0 - q * t1
    return poly.rational_lowest_terms(r1, t1)


def _cancelled(P: sc.Vector, Q: sc.Vector, like: sc.Scalar) -> tuple[sc.Vector, sc.Vector]:
    """P/Q in lowest terms with Q(0) = 1.  Over a number field Euclid's algorithm can take
    minutes (inverses in a field of degree 40 with long coefficients), so it runs under
    :data:`STABILITY_SECONDS` in a child process; past it R = P/Q is kept as it is, correct
    but not cancelled (Q(0) = det(I) = 1 already)."""
    if all(isinstance(x, (Fraction, int)) for x in P + Q):
        return poly.lowest_terms(P, Q, sc.const(0, like), _is_zero)
    rational = [x if isinstance(x, (Fraction, int)) else x.rational() for x in P + Q]
    if all(r is not None for r in rational):
        # a number field's tableau whose Galois group permutes its stages (Gauss, HBVM,
        # Lobatto, Radau) has a rational R(z): over Q the gcd is FLINT's (loaded for the
        # field already), with no child process and no time limit
        return poly.rational_lowest_terms(rational[:len(P)], rational[len(P):])
    try:
        parts: tuple[sc.Vector, sc.Vector] = call_within(STABILITY_SECONDS, poly.lowest_terms, P, Q,
                                                         sc.const(0, like), _is_zero)
        return parts
    except Overrun:
        return P, Q


def stability_of_series(series: list[Fraction], s: int) -> StabilityFunction:
    """``R(z)`` of an s-stage method from its series ``r_0 … r_2s`` over Q
    (:meth:`~rkcheck.methods.node_form.NodeForm.stability_series` for a family in node
    form), by Padé over Q."""
    P, Q = _pade(series, s)
    return _from_parts(s, True, list(series), _trim(P), _trim(Q))


def _from_parts(s: int, exact: bool, series: sc.Vector, numerator: sc.Vector | None,
                denominator: sc.Vector | None) -> StabilityFunction:
    """The defect coefficients e_n and the identity verdict from the series."""
    like = series[0]
    defect = _rational_defect(series, s)
    if defect is None:
        defect = [sc.const(0, like)]
        for n in range(1, 2 * s + 1):
            if n % 2:
                defect.append(sc.const(0, like))  # e_odd = 0 identically
                continue
            defect.append(sc.total([(series[j] if j % 2 == 0 else -series[j]) * series[n - j]
                                    for j in range(n + 1)], like))
    verdicts = []
    leading_power = leading = None
    for n in range(2, 2 * s + 1, 2):
        v_n = sc.verdict(defect[n])
        if v_n.state == FAILS:
            leading_power, leading = n, defect[n]
            break
        verdicts.append(v_n)
    identity = Verdict(FAILS) if leading_power is not None else combine(verdicts)
    return StabilityFunction(s, exact, series, defect, identity, leading_power, leading, numerator, denominator)


def _rational_defect(series: sc.Vector, s: int) -> sc.Vector | None:
    """The coefficients e_0 … e_2s of R(z)R(−z) − 1 as one FLINT product of the series
    and its reflection, for a rational series of more than MAX_FRACTION_STAGES stages
    (O(s²) products in Fractions of hundreds of digits would take minutes at 300
    stages); None otherwise."""
    if s <= MAX_FRACTION_STAGES or not all(isinstance(x, (Fraction, int)) for x in series):
        return None
    terms = list(series[:2 * s + 1])
    product = poly.to_flint(terms) * poly.to_flint([x if j % 2 == 0 else -x for j, x in enumerate(terms)])
    coeffs = product.coeffs()
    return [Fraction(0)] + [poly.to_fraction(coeffs[n]) if n % 2 == 0 and n < len(coeffs) else Fraction(0)
                            for n in range(1, 2 * s + 1)]


# ------------------------------------------------------------------------ text


def monomial_text(coef: sc.Scalar, k: int) -> str:
    """``c z^k`` for people: ``z⁶/72``, ``−3z²/4``, ``(1/2 + √3/6) z``, ``0.0833 z²``."""
    z = "" if k == 0 else ("z" if k == 1 else "z" + str(k).translate(_SUP))
    q = sc.rational(coef)
    if q is not None:
        sign = "−" if q < 0 else ""
        a, d = abs(q.numerator), q.denominator
        if not z:
            return sign + (str(a) if d == 1 else f"{a}/{d}")
        num = z if a == 1 else f"{a}{z}"
        return sign + (num if d == 1 else f"{num}/{d}")
    if sc.is_interval(coef):
        # an enclosure: its mid-point to 10 digits (the text says "≈"; JSON has the bounds)
        mid = coef.mid
        body = decimal_string(abs(mid), 10)
        sign = "−" if mid < 0 else ""
        if not z:
            return sign + body
        return sign + (z if body == "1" else f"{body}{z}")
    return f"({sc.exact_text(coef)}){' ' + z if z else ''}"


def poly_text(p: sc.Vector) -> str:
    """A polynomial (ascending coefficients) for people, zero terms left out."""
    # zero terms are left out; for an enclosure, one that may be zero (it is shown with ≈)
    terms = [(k, a) for k, a in enumerate(p) if sc.verdict(a).state == FAILS]
    if not terms:
        return "0"
    out = ""
    for i, (k, a) in enumerate(terms):
        t = monomial_text(a, k)
        if i == 0:
            out = t
        elif t.startswith("−"):
            out += " − " + t[1:]
        else:
            out += " + " + t
    return out