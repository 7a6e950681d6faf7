"""Certificates of every order from the stability function: ``R(z)R(−z) ≡ 1`` proves
energy preservation for every quadratic Hamiltonian (definitions §3, m = 2), and
:func:`prefer` chooses between two certificates of one degree (this one and the
line-integral one, :mod:`rkcheck.properties.lineintegral`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, TypeVar

from rkcheck.numbers.formatting import digits_text
from rkcheck.properties.stability import StabilityFunction
from rkcheck.verdicts import FAILS, HOLDS, UNDECIDED_TEXT, Verdict


@dataclass(frozen=True)
class StabilityCertificate:
    """Energy preservation for every quadratic Hamiltonian at every order, proven by
    ``R(z)R(−z) ≡ 1`` (the same interface as the line-integral certificate)."""

    degree: int
    verdict: Verdict
    reason: str
    sigma: None = None
    kind: str = "stability"

    @property
    def certified(self) -> bool:
        """It proves every order, exactly or to digits (a verdict with no certain digit
        certifies nothing)."""
        return self.verdict.shown

    @property
    def name(self) -> str:
        return "stability-function certificate"

    @property
    def claim_note(self) -> str:
        return "stability-function certificate (R(z)R(−z) ≡ 1): every order"

    def refuted(self, condition_id: str) -> StabilityCertificate:
        return StabilityCertificate(
            self.degree, Verdict(FAILS),
            f"R(z)R(−z) = 1 only to {digits_text(self.verdict.digits)}, and condition {condition_id} certainly fails",
        )


def quadratic_certificate(stab: StabilityFunction, degree: int) -> StabilityCertificate:
    """The certificate for degree ≤ 2 from the stability function."""
    if stab.identity.state == FAILS:
        assert stab.leading_power is not None  # a failing identity has a leading term
        return StabilityCertificate(
            degree, Verdict(FAILS),
            f"{stab.defect_text()}: quadratic energy is preserved to order {stab.leading_power - 1} only",
        )
    how = stab.identity.how()
    return StabilityCertificate(
        degree, stab.identity,
        f"R(z)R(−z) = 1 {how} (e_2 = … = e_{2 * stab.stages} = 0 and deg(P(z)P(−z) − Q(z)Q(−z)) ≤ "
        f"{2 * stab.stages}): " + ("ΔH = 0 for every H of degree ≤ 2" if stab.identity.decided else UNDECIDED_TEXT),
    )


class _Ranked(Protocol):
    """What :func:`prefer` reads of a certificate."""

    @property
    def certified(self) -> bool: ...
    @property
    def verdict(self) -> Verdict: ...


_C = TypeVar("_C", bound=_Ranked)


def prefer(first: _C, second: _C | None) -> _C:
    """The better of two certificates for the same degree: an exact proof over one that
    holds to digits, a certified one over none, and one that decides nothing (held to 0
    digits) over one that fails; ``first`` on ties."""
    def rank(cert: _C | None) -> int:
        if cert is None or cert.verdict.state == FAILS:
            return 0
        if not cert.certified:
            return 1
        return 3 if cert.verdict.state == HOLDS else 2

    return second if second is not None and rank(second) > rank(first) else first
