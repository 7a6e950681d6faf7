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

The test is made on the irreducible form of the tableau (:mod:`rkcheck.properties.reduction`),
exactly for exact tableaux and certified for enclosures (:mod:`rkcheck.properties.scalars`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Iterator, Protocol

from rkcheck.methods.quadrature import shifted_legendre
from rkcheck.numbers.formatting import digits_text
from rkcheck.numbers.polynomials import integral
from rkcheck.properties import scalars as sc
from rkcheck.properties.reduction import Reduction
from rkcheck.verdicts import FAILS, UNDECIDED_TEXT, Verdict, combine


class Certificate(Protocol):
    """What the check and the reports read of a certificate of every order: a
    :class:`LineIntegralCertificate` or a
    :class:`~rkcheck.properties.quadratic.StabilityCertificate`."""

    @property
    def degree(self) -> int: ...
    @property
    def verdict(self) -> Verdict: ...
    @property
    def reason(self) -> str: ...
    @property
    def sigma(self) -> int | None: ...
    @property
    def kind(self) -> str | None: ...
    @property
    def certified(self) -> bool: ...
    @property
    def name(self) -> str: ...
    @property
    def claim_note(self) -> str: ...
    def refuted(self, condition_id: str) -> Certificate: ...


@dataclass(frozen=True)
class LineIntegralCertificate:
    """The line-integral certificate for degree ``degree``: the stage path's degree σ, the verdict and why."""

    degree: int
    sigma: int | None  # the degree of the stage path; None when no σ works
    verdict: Verdict  # holds / holds_to_digits: certified; fails: not certified
    reason: str

    @property
    def certified(self) -> bool:
        """It proves every order, exactly or to digits (a verdict with no certain digit
        certifies nothing)."""
        return self.verdict.shown

    @property
    def kind(self) -> str | None:
        """``avf`` (σ = 1), ``line_integral`` (σ > 1) or None (not certified)."""
        if self.sigma is None:
            return None
        return "avf" if self.sigma == 1 else "line_integral"

    @property
    def name(self) -> str:
        """How reports name the certificate."""
        if self.sigma is None:
            return "certificate"
        return "AVF certificate" if self.sigma == 1 else f"line-integral certificate, σ = {self.sigma}"

    @property
    def claim_note(self) -> str:
        kind = "AVF" if self.sigma in (None, 1) else f"line-integral (σ = {self.sigma})"
        return f"{kind} certificate: every order"

    def refuted(self, condition_id: str) -> "LineIntegralCertificate":
        """The certificate after condition ``condition_id`` was found to fail for certain
        (possible only when it held to digits, never when exact)."""
        return LineIntegralCertificate(
            self.degree, None, Verdict(FAILS),
            f"(LI) holds only to {digits_text(self.verdict.digits)}, and condition {condition_id} certainly fails",
        )


def line_integral_matrix(c: sc.Vector, b: sc.Vector, sigma: int) -> sc.Matrix:
    """``Σ_(j<σ) (2j+1) G_j(c)(P_j(c) ⊙ b)ᵀ`` over any scalars (the right-hand side of (LI))."""
    matrices = line_integral_matrices(c, b)
    for _ in range(sigma - 1):
        next(matrices)
    return next(matrices)


def line_integral_matrices(c: sc.Vector, b: sc.Vector) -> Iterator[sc.Matrix]:
    """The right-hand sides of (LI) for σ = 1, 2, …, len(c), each from the previous one by
    its new term ``(2σ−1) G_(σ−1)(c)(P_(σ−1)(c) ⊙ b)ᵀ``: O(s²) per σ, not O(s²σ)."""
    n = len(c)
    like = sc.sample([], b)
    acc = [[sc.const(0, like) for _ in range(n)] for _ in range(n)]
    for j in range(n):
        P = shifted_legendre(j)
        Gc = [sc.poly_at(integral(P), ci) for ci in c]
        Pb = [sc.poly_at(P, cl) * bl for cl, bl in zip(c, b)]
        weight = sc.const(2 * j + 1, like)
        acc = [[sc.tidy(acc[i][l] + weight * Gc[i] * Pb[l]) for l in range(n)] for i in range(n)]
        yield acc


def _check_entries(A: sc.Matrix, rhs: sc.Matrix) -> list[Verdict] | None:
    """Verdicts of the entries of (LI) against the right-hand side ``rhs``, or None at the
    first certain mismatch."""
    out = []
    for row, rhs_row in zip(A, rhs):
        for a, r in zip(row, rhs_row):
            v = sc.verdict(a - r)
            if v.state == FAILS:
                return None
            out.append(v)
    return out


def certificate_of_reduction(red: Reduction, degree: int) -> LineIntegralCertificate:
    """(LI) on the irreducible form ``red``."""
    rA, rb = red.A, red.b
    if not rb:
        return line_integral_certificate(red, degree, iter(()), lambda sigma: None)
    c = sc.row_sums(rA, sc.sample(rA, rb))
    matrices = line_integral_matrices(c, rb)
    return line_integral_certificate(red, degree, sc.quadrature_residuals(rb, c),
                                     lambda sigma: _check_entries(rA, next(matrices)))


def line_integral_certificate(red: Reduction, degree: int, residuals: Iterator[sc.Scalar],
                              matches: Callable[[int], list[Verdict] | None]) -> LineIntegralCertificate:
    """(LI) from the rule's quadrature residuals ``Σ b_i c_i^(k−1) − 1/k`` (k = 1, 2, …)
    and ``matches(σ)``: the verdicts of (LI)'s entries for σ, or None when one certainly
    differs (asked for σ = 1, 2, … in turn)."""
    n = red.reduced_stages
    if n == 0:
        return LineIntegralCertificate(degree, None, Verdict(FAILS), "every weight is zero")
    quad: list[Verdict] = []
    quad_order = 0
    for k, residual in zip(range(1, 2 * n + 1), residuals):
        v = sc.verdict(residual)
        if v.state == FAILS:
            break
        quad.append(v)
        quad_order = k
    for sigma in range(1, n + 1):
        if degree * sigma > quad_order:
            break
        entries = matches(sigma)
        if entries is not None:
            verdict = combine(list(red.decisions) + entries + quad[: degree * sigma])
            how = verdict.how()
            return LineIntegralCertificate(
                degree, sigma, verdict,
                f"A = Σ_(j<{sigma}) (2j+1) G_j(c)(P_j(c)⊙b)ᵀ and the rule (b, A·1) has quadrature order "
                f"{quad_order} ≥ {degree}·{sigma}, {how}: " + (
                    f"the stages lie on a degree-{sigma} path and ΔH = 0 for every H of degree ≤ {degree}"
                    if verdict.decided else UNDECIDED_TEXT),
            )
    return LineIntegralCertificate(
        degree, None, Verdict(FAILS),
        f"no σ ≤ {n} with A = Σ_(j<σ) (2j+1) G_j(c)(P_j(c)⊙b)ᵀ and quadrature order ≥ {degree}σ "
        f"(quadrature order {quad_order})",
    )
