"""Is the tableau the Averaged Vector Field method for degree-m Hamiltonians? (definitions §4)

AVF, ``y₁ = y₀ + h ∫₀¹ f((1−ξ)y₀ + ξy₁) dξ``, preserves every H.  For polynomial H of
degree ≤ m it *is* the Runge–Kutta method ``A = c bᵀ`` over any rule with
``Σ b_i c_i^(k−1) = 1/k``, k = 1..m.  A tableau is recognised after two reductions that
do not change the method:

1. drop stages that cannot influence the result: ``b_j = 0`` and no needed stage uses
   stage ``j`` (repeat until stable);
2. merge stages with identical rows of ``A`` (their stage values coincide): add their
   weights and their columns.

Then it equals AVF iff ``A = (A·1) bᵀ`` and the quadrature conditions hold for
k = 1..m.  This is a certificate: energy is preserved for every degree-≤m Hamiltonian
to every order, not only to the order checked.

Theorem 1 of the seed (m ≥ 3): a method with ``c = A·1`` preserving all degree-≤m
Hamiltonians has at least ``s_min = ⌊(m+1)/2⌋`` stages, and with exactly ``s_min`` it is
AVF.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from rkcheck.energy.orders import row_sums
from rkcheck.energy.verdicts import (
    FAILS,
    HOLDS,
    HOLDS_TO_DIGITS,
    Verdict,
    classify_interval,
    combine,
)
from rkcheck.methods.quadrature import quadrature_residual
from rkcheck.numbers.intervals import Interval


@dataclass(frozen=True)
class AvfVerdict:
    degree: int
    verdict: Verdict  # holds / holds_to_digits = equals AVF; fails = it does not
    reason: str
    reduced_stages: int
    stages: int
    kept: tuple[int, ...]  # 1-based original stages of the reduced method
    s_min: int | None  # Theorem 1 (m >= 3)
    notes: list[str] = field(default_factory=list)

    @property
    def equals_avf(self) -> bool:
        return self.verdict.state != FAILS


def reduce_stages(
    A: list[list[Interval]], b: list[Interval], exact: bool
) -> tuple[list[list[Interval]], list[Interval], list[int], list[Verdict]]:
    """Drop stages that cannot influence the result and merge stages with equal rows.

    Returns the reduced ``A``, ``b``, the 0-based original index of each kept stage, and
    the verdicts of every "is zero"/"rows equal" decision that was taken numerically
    (each of which holds only to some digits when the data is not exact).
    """
    s = len(b)
    used: list[Verdict] = []

    def counts_as_zero(x: Interval) -> bool:
        # zero unless certainly nonzero; the decision is recorded, since with inexact
        # data it holds only to some digits)
        v = classify_interval(x, exact)
        if v.state != FAILS:
            used.append(v)
            return True
        return False

    needed = {j for j in range(s) if not counts_as_zero(b[j])}
    frontier = list(needed)
    while frontier:
        i = frontier.pop()
        for j in range(s):
            if j not in needed and not counts_as_zero(A[i][j]):
                needed.add(j)
                frontier.append(j)
    keep = sorted(needed)
    A = [[A[i][j] for j in keep] for i in keep]
    b = [b[j] for j in keep]
    kept = list(keep)

    merged = True
    while merged:
        merged = False
        n = len(b)
        for i in range(n):
            for k in range(i + 1, n):
                if all(counts_as_zero(A[i][j] - A[k][j]) for j in range(n)):
                    for r in range(n):
                        A[r][i] = A[r][i] + A[r][k]
                    b[i] = b[i] + b[k]
                    for r in range(n):
                        del A[r][k]
                    del A[k]
                    del b[k]
                    del kept[k]
                    merged = True
                    break
            if merged:
                break
    return A, b, kept, used


def avf_verdict(A: list[list[Interval]], b: list[Interval], degree: int, exact: bool, reduced=None) -> AvfVerdict:
    """Decide whether ``(A, b)`` equals AVF for Hamiltonians of degree ≤ ``degree``
    (``reduced``: the result of :func:`reduce_stages`, if already computed)."""
    s = len(b)
    s_min = (degree + 1) // 2 if degree >= 3 else None
    rA, rb, kept, used = reduced or reduce_stages([row[:] for row in A], b[:], exact)
    n = len(rb)
    notes: list[str] = []
    if n < s:
        notes.append(f"reduced from {s} to {n} stages (kept stages {', '.join(str(k + 1) for k in kept)})")

    def result(verdict: Verdict, reason: str) -> AvfVerdict:
        return AvfVerdict(degree, verdict, reason, n, s, tuple(k + 1 for k in kept), s_min, notes)

    if n == 0:
        return result(Verdict(FAILS), "every weight b_j is zero: the method does not move")
    c = row_sums(rA)
    checks: list[Verdict] = list(used)
    for i in range(n):
        for j in range(n):
            diff = rA[i][j] - c[i] * rb[j]
            v = classify_interval(diff, exact)
            if v.state == FAILS:
                gi, gj = kept[i] + 1, kept[j] + 1
                return result(
                    Verdict(FAILS),
                    f"A − (A·1)bᵀ ≠ 0 at entry ({gi},{gj}) of the reduced tableau: {float(diff.mid):.6g}",
                )
            checks.append(v)
    for k in range(1, degree + 1):
        v = classify_interval(quadrature_residual(rb, c, k), exact)
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
            f"to {verdict.digits} digits"
        )
    return result(verdict, reason)


def theorem1_remark(avf: AvfVerdict, first_failure: str | None, order_checked: int) -> str | None:
    """The Theorem 1 sentence for the report (None when m < 3)."""
    if avf.s_min is None:
        return None
    s, m, smin = avf.reduced_stages, avf.degree, avf.s_min
    if s < smin:
        return (
            f"Theorem 1: preserving all degree-{m} Hamiltonians needs at least s_min = {smin} stages; "
            f"this method has {s} effective stages, so it cannot"
        )
    if s == smin:
        if avf.equals_avf:
            return f"Theorem 1: {s} = s_min stages and AVF — the minimal-stage energy-preserving method for degree {m}"
        if first_failure:
            return (
                f"Theorem 1: with s_min = {smin} stages only AVF preserves degree-{m} energy; "
                f"this method is not AVF, and {first_failure} fails"
            )
        return (
            f"Theorem 1: with s_min = {smin} stages only AVF preserves degree-{m} energy; this method is "
            f"not AVF, so a condition must fail beyond order {order_checked}"
        )
    return f"Theorem 1: s_min = {smin} for degree {m}; this method has {s} effective stages"

