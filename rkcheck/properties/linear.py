"""The certificate of every order for linear Hamiltonians (m = 1), which every method has.

For ``H(y) = gᵀy`` the vector field ``f = J∇H = Jg`` is constant, so every stage sees
the same ``f`` and ``y₁ = y₀ + h Σ_i b_i Jg``, whence ``H(y₁) − H(y₀) = h (Σ_i b_i) gᵀJg
= 0`` (J is skew).  No free tree with more than two vertices has maximum degree 1, so
definitions §3 has no condition to check for m = 1: the certificate says why nothing
was checked and every order still holds — exactly, whatever the entries (a box of
decimals included).
"""

from __future__ import annotations

from dataclasses import dataclass

from rkcheck.verdicts import HOLDS, Verdict


@dataclass(frozen=True)
class LinearCertificate:
    """Energy preservation for every linear Hamiltonian, at every order (the interface of
    :class:`~rkcheck.properties.lineintegral.Certificate`)."""

    degree: int = 1
    verdict: Verdict = Verdict(HOLDS)
    reason: str = ("f = J∇H is constant for H of degree 1, so ΔH = h (Σb) gᵀJg = 0 (J skew): every method "
                   "preserves it")
    sigma: None = None
    kind: str = "linear"

    @property
    def certified(self) -> bool:
        return True

    @property
    def name(self) -> str:
        return "linear-Hamiltonian certificate"

    @property
    def claim_note(self) -> str:
        return "linear Hamiltonians: ΔH = h (Σb) gᵀJg = 0, every order"

    def refuted(self, condition_id: str) -> "LinearCertificate":
        """Itself: an exact certificate is never refuted (and degree 1 has no condition)."""
        return self
