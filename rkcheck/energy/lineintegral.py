"""The line-integral certificate: energy preservation proven for every order.

This generalises the AVF certificate of definitions §4 (it is its case σ = 1) to the Hamiltonian
Boundary Value Methods of Brugnano, Iavernaro and Trigiante.  Let ``(b, c)``, ``c = A·1``,
be the tableau's own quadrature rule, ``P_j`` the shifted Legendre polynomials
(``P_j(1) = 1``) and ``G_j(x) = ∫₀^x P_j``.  If for some σ

    A = Σ_{j<σ} (2j+1) G_j(c) (P_j(c) ⊙ b)ᵀ                                  (LI)

then with ``γ_j = Σ_l b_l √(2j+1) P_j(c_l) f(Y_l)`` the stages lie on the polynomial path
``u(τ) = y₀ + h Σ_{j<σ} √(2j+1) G_j(τ) γ_j`` (``Y_i = u(c_i)``, ``y₁ = u(1)``), so

    H(y₁) − H(y₀) = h Σ_{j<σ} (∫₀¹ √(2j+1) P_j(τ) ∇H(u(τ)) dτ)ᵀ γ_j .

For H of degree ≤ m the integrand has degree ≤ mσ − 1; when the rule has quadrature
order ≥ mσ the integral equals ``Σ_l b_l √(2j+1) P_j(c_l) ∇H(Y_l) = J γ_j`` and
``ΔH = h Σ_j γ_jᵀ Jᵀ γ_j = 0`` because J is skew.  Hence (LI) plus quadrature order ≥ mσ
proves energy preservation for all degree-≤m Hamiltonians to every order.  σ = 1 is
``A = c bᵀ`` (AVF); HBVM(k, s) satisfies (LI) with σ = s over k Gauss nodes (order 2k), so
it is certified for m ≤ 2k/s; s-stage Gauss collocation (HBVM(s, s)) for m ≤ 2.

The test is made on the tableau after the stage reduction of :mod:`rkcheck.energy.avf`.
"""

from __future__ import annotations

from dataclasses import dataclass

from rkcheck.energy.avf import reduce_stages
from rkcheck.energy.orders import row_sums
from rkcheck.energy.verdicts import FAILS, HOLDS, Verdict, classify_interval, combine
from rkcheck.methods.quadrature import line_integral_matrix, quadrature_residual
from rkcheck.numbers.intervals import Interval


@dataclass(frozen=True)
class LineIntegralCertificate:
    degree: int
    sigma: int | None  # the degree of the stage path; None when no σ works
    verdict: Verdict  # holds / holds_to_digits: certified; fails: not certified
    reason: str

    @property
    def certified(self) -> bool:
        return self.verdict.state != FAILS


def _check_sigma(A, b, c, sigma: int, exact: bool) -> list[Verdict] | None:
    """Verdicts of the entries of (LI) for this σ, or None at the first certain mismatch."""
    rhs = line_integral_matrix(c, b, sigma)
    out = []
    for row, rhs_row in zip(A, rhs):
        for a, r in zip(row, rhs_row):
            v = classify_interval(a - r, exact)
            if v.state == FAILS:
                return None
            out.append(v)
    return out


def line_integral_certificate(
    A: list[list[Interval]], b: list[Interval], degree: int, exact: bool, reduced=None
) -> LineIntegralCertificate:
    """Search the smallest σ for which (LI) holds and the rule has order ≥ degree·σ
    (``reduced``: the result of :func:`~rkcheck.energy.avf.reduce_stages`, if already computed)."""
    rA, rb, kept, used = reduced or reduce_stages([row[:] for row in A], b[:], exact)
    n = len(rb)
    if n == 0:
        return LineIntegralCertificate(degree, None, Verdict(FAILS), "every weight is zero")
    c = row_sums(rA)
    quad: list[Verdict] = []
    quad_order = 0
    for k in range(1, 2 * n + 1):
        r = quadrature_residual(rb, c, k)
        v = classify_interval(r, exact)
        if v.state == FAILS:
            break
        quad.append(v)
        quad_order = k
    for sigma in range(1, n + 1):
        if degree * sigma > quad_order:
            break
        entries = _check_sigma(rA, rb, c, sigma, exact)
        if entries is not None:
            verdict = combine(list(used) + entries + quad[: degree * sigma])
            how = "exactly" if verdict.state == HOLDS else f"to {verdict.digits} digits"
            return LineIntegralCertificate(
                degree, sigma, verdict,
                f"A = Σ_(j<{sigma}) (2j+1) G_j(c)(P_j(c)⊙b)ᵀ and the rule (b, A·1) has quadrature order "
                f"{quad_order} ≥ {degree}·{sigma}, {how}: the stages lie on a degree-{sigma} path and "
                f"ΔH = 0 for every H of degree ≤ {degree}",
            )
    return LineIntegralCertificate(
        degree, None, Verdict(FAILS),
        f"no σ ≤ {n} with A = Σ_(j<σ) (2j+1) G_j(c)(P_j(c)⊙b)ᵀ and quadrature order ≥ {degree}σ "
        f"(quadrature order {quad_order})",
    )
