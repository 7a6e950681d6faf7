"""Is the tableau the Averaged Vector Field method for degree-m Hamiltonians? (definitions §4)

AVF, ``y₁ = y₀ + h ∫₀¹ f((1−ξ)y₀ + ξy₁) dξ``, preserves every H.  For polynomial H of
degree ≤ m it *is* the Runge–Kutta method ``A = c bᵀ`` over any rule with
``Σ b_i c_i^(k−1) = 1/k``, k = 1..m.  A tableau is recognised on its irreducible form
(:mod:`rkcheck.properties.reduction`: dead stages and dead chains dropped, stages whose
values coincide merged, repeated to a fixpoint), since that form is unique up to a
permutation of the stages and defines the same method.

Then it equals AVF iff ``A = (A·1) bᵀ`` and the quadrature conditions hold for
k = 1..m.  This is a certificate: energy is preserved for every degree-≤m Hamiltonian
to every order, not only to the order checked.  The algebra is exact for exact
(rational or algebraic) tableaux and certified for enclosures
(:mod:`rkcheck.properties.scalars`).

Theorem 1 of the seed (m ≥ 3): a method with ``c = A·1`` preserving all degree-≤m
Hamiltonians has at least ``s_min = ⌊(m+1)/2⌋`` stages, and with exactly ``s_min`` it is
AVF.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable, Iterator

from rkcheck.numbers.formatting import counted, digits_text
from rkcheck.properties import scalars as sc
from rkcheck.properties.reduction import Reduction
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS, Verdict, combine


@dataclass(frozen=True)
class AvfVerdict:
    """Whether the reduced method equals the AVF method for Hamiltonians of degree ``degree``, and why."""

    degree: int
    verdict: Verdict  # holds / holds_to_digits = equals AVF; fails = it does not
    reason: str
    reduced_stages: int
    stages: int
    kept: tuple[int, ...]  # 1-based original stages of the reduced method
    s_min: int | None  # Theorem 1 (m >= 3)
    notes: list[str] = field(default_factory=list)
    exact_reduction: bool = True  # no zero test of the stage reduction was decided only to digits

    @property
    def equals_avf(self) -> bool:
        """Shown to be AVF: exactly or to digits (a verdict with no certain digit shows
        nothing)."""
        return self.verdict.shown


def avf_of_reduction(red: Reduction, degree: int) -> AvfVerdict:
    """The AVF verdict of definitions §4 on the irreducible form ``red``."""
    rA, rb = red.A, red.b
    n = len(rb)
    like = sc.sample(rA, rb)
    c = sc.row_sums(rA, like) if n else []
    entries = ((i, j, rA[i][j] - c[i] * rb[j]) for i in range(n) for j in range(n))
    return avf_verdict(red, degree, entries, sc.quadrature_residuals(rb, c) if n else iter(()))


def avf_verdict(red: Reduction, degree: int, entries: Iterable[tuple[int, int, sc.Scalar]],
                residuals: Iterator[sc.Scalar]) -> AvfVerdict:
    """The AVF verdict from the entries ``(i, j, (A − (A·1)bᵀ)_ij)`` of the reduced tableau
    (row by row; those left out are zero exactly) and its rule's quadrature residuals
    ``Σ b_i c_i^(k−1) − 1/k``, k = 1, 2, …"""
    s_min = (degree + 1) // 2 if degree >= 3 else None
    n, kept = red.reduced_stages, red.kept
    notes: list[str] = []
    described = red.describe()
    if described:
        notes.append(described)

    def result(verdict: Verdict, reason: str) -> AvfVerdict:
        return AvfVerdict(degree, verdict, reason, n, red.stages, tuple(k + 1 for k in kept), s_min, notes,
                          not red.decisions)

    if n == 0:
        return result(Verdict(FAILS), "every weight b_j is zero: the method does not move")
    checks: list[Verdict] = list(red.decisions)
    for i, j, diff in entries:
        v = sc.verdict(diff)
        if v.state == FAILS:
            gi, gj = kept[i] + 1, kept[j] + 1
            where = "reduced tableau" if red.reducible else "tableau"
            return result(
                Verdict(FAILS),
                f"A − (A·1)bᵀ ≠ 0 at entry ({gi},{gj}) of the {where}: {_value_text(diff)}",
            )
        checks.append(v)
    for k, residual in zip(range(1, degree + 1), residuals):
        v = sc.verdict(residual)
        if v.state == FAILS:
            return result(
                Verdict(FAILS),
                f"A = (A·1)bᵀ but the quadrature condition Σ b_i c_i^{k - 1} = 1/{k} fails "
                f"(the rule has exactness below degree {degree})",
            )
        checks.append(v)
    verdict = combine(checks)
    if verdict.state == HOLDS:
        reason = f"A = (A·1)bᵀ and Σ b_i c_i^(k−1) = 1/k for k = 1..{degree}, exactly"
    else:
        assert verdict.state == HOLDS_TO_DIGITS
        reason = (
            f"A = (A·1)bᵀ and Σ b_i c_i^(k−1) = 1/k for k = 1..{degree}, "
            f"to {digits_text(verdict.digits)}"
        )
    return result(verdict, reason)


def theorem1_remark(
    avf: AvfVerdict, first_failure: str | None, order_checked: int, conditions_exact: bool = True,
    min_digits: int | None = None,
) -> str | None:
    """The Theorem 1 sentence for the report (None when m < 3).

    "A condition must fail beyond order N" is concluded only when every condition up to
    N holds *exactly* (``conditions_exact``) and the AVF verdict is exact; when they
    only hold to D digits the failure Theorem 1 promises may be hidden below 10^−D at
    any order, and the sentence says so instead."""
    if avf.s_min is None:
        return None
    s, m, smin = avf.reduced_stages, avf.degree, avf.s_min
    if s < smin:
        if not avf.exact_reduction:  # stages merged on equalities shown only to digits: s may be too few
            return (
                f"Theorem 1: preserving all degree-{m} Hamiltonians needs at least s_min = {smin} stages; this "
                f"method has {counted(s, 'effective stage')} only if the stages merged to digits are equal, "
                "which is not a proof"
            )
        return (
            f"Theorem 1: preserving all degree-{m} Hamiltonians needs at least s_min = {smin} stages; "
            f"this method has {counted(s, 'effective stage')}, so it cannot"
        )
    if s == smin:
        if avf.equals_avf and avf.verdict.state == HOLDS_TO_DIGITS:  # AVF only to digits: no proof
            return (f"Theorem 1: {s} = s_min stages and AVF to {digits_text(avf.verdict.digits)} (not a proof) — the "
                    f"minimal-stage energy-preserving method for degree {m}")
        if avf.equals_avf:
            return f"Theorem 1: {s} = s_min stages and AVF — the minimal-stage energy-preserving method for degree {m}"
        if first_failure:
            return (
                f"Theorem 1: with s_min = {smin} stages only AVF preserves degree-{m} energy; "
                f"this method is not AVF, and {first_failure} fails"
            )
        if conditions_exact and avf.exact_reduction:
            return (
                f"Theorem 1: with s_min = {smin} stages only AVF preserves degree-{m} energy; this method is "
                f"not AVF, so a condition must fail beyond order {order_checked}"
            )
        held = f"hold only to {digits_text(min_digits)}" if min_digits is not None else "were not all decided exactly"
        return (
            f"Theorem 1: with s_min = {smin} stages only AVF preserves degree-{m} energy and this method is "
            f"not AVF, so some condition fails; the conditions up to order {order_checked} {held}, so the "
            f"failure may be one of them, too small to show at this precision (raise --dps), or lie beyond"
        )
    return f"Theorem 1: s_min = {smin} for degree {m}; this method has {counted(s, 'effective stage')}"



def _value_text(x: sc.Scalar) -> str:
    """A certainly nonzero entry: exact when exact, else its mid-point to 6 digits."""
    return sc.text(x, 6) if sc.is_exact(x) else sc.approx_text(x, 6)
