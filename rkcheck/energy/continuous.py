"""What a continuous-stage method's kernel says by itself (definitions §6): the
energy-preservation certificate of every order, equals-AVF, symmetry and
symplecticity — judged on the polynomials ``A(τ, σ)``, ``B(τ)`` exactly, never on the
surrogate tableau that carries the B-series (:mod:`rkcheck.methods.continuous`).

* **Certificate** (a theorem: Tang & Sun 2012, Miyatake 2014, Miyatake & Butcher 2016;
  docs/continuous.md gives the proof): if ``A(0, σ) = 0``, ``A(1, σ) = B(σ)`` and
  ``∂A/∂τ(τ, σ)`` is symmetric in (τ, σ), then for every ``f = J∇H`` (J constant and
  skew) ``H(y₁) − H(y₀) = h∫∫ ∂τA(τ,σ) ∇H(Y_τ)ᵀ J ∇H(Y_σ) dσ dτ = 0`` — the integrand
  is antisymmetric under τ ↔ σ.  So every energy condition holds, for every degree.
  For the Miyatake–Butcher form it says: M symmetric.
* **Equals AVF**: the kernel is AVF's, ``A ≡ τ`` and ``B ≡ 1`` (then every elementary
  weight is AVF's; the converse is not claimed).
* **Symmetric**: the adjoint kernel ``(B(σ) − A(1−τ, 1−σ), B(1−τ))`` is the kernel:
  ``B(τ) = B(1−τ)`` and ``A(τ,σ) + A(1−τ,1−σ) = B(σ)``.
* **Symplectic**: ``B(τ)A(τ,σ) + B(σ)A(σ,τ) = B(τ)B(σ)`` (Tang & Sun 2012), the
  continuous form of ``BA + AᵀB = bbᵀ``.

A kernel whose decimals stand for intervals (a box, definitions §5.2) is judged over the
whole box (:mod:`rkcheck.energy.kernel_box`): "fails" only when every kernel of the box
fails, otherwise "holds to D digits" — never a proof.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from rkcheck.methods.continuous import ContinuousMethod
from rkcheck.properties.symplectic import PropertyVerdict
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS, Verdict


@dataclass(frozen=True)
class ContinuousCertificate:
    """The kernel certificate of every order (module docstring); the check's
    :class:`~rkcheck.properties.lineintegral.Certificate` protocol."""

    degree: int | None
    verdict: Verdict
    reason: str
    sigma: int | None = None

    @property
    def certified(self) -> bool:
        return self.verdict.state != FAILS

    @property
    def kind(self) -> str | None:
        return "continuous_kernel" if self.certified else None

    @property
    def name(self) -> str:
        return "kernel certificate"

    @property
    def claim_note(self) -> str:
        return "kernel certificate (∂A/∂τ symmetric, A(0,σ) = 0, A(1,σ) = B(σ)): every order, every degree"

    def refuted(self, condition_id: str) -> "ContinuousCertificate":
        return ContinuousCertificate(self.degree, Verdict(FAILS),
                                     f"{self.reason}; refuted: condition {condition_id} certainly fails")


@dataclass(frozen=True)
class ContinuousAvf:
    """Equals-AVF of a kernel; read like :class:`~rkcheck.properties.avf.AvfVerdict`."""

    degree: int | None
    verdict: Verdict
    reason: str
    stages: int | None = None
    reduced_stages: int | None = None
    kept: tuple[int, ...] = ()
    s_min: int | None = None
    notes: list[str] = field(default_factory=list)
    exact_reduction: bool = True

    @property
    def equals_avf(self) -> bool:
        return self.verdict.state != FAILS


@dataclass(frozen=True)
class ContinuousProperties:
    """The kernel's own properties, in place of a tableau's (no stage reduction and no
    stability function: a continuous method has neither as a finite object)."""

    exact: bool
    symplectic: PropertyVerdict
    symmetric: PropertyVerdict
    reduction: None = None
    stability: None = None
    continuous: bool = True

    def certificates(self, degree: int | None) -> Any:  # the tableau interface; the kernel's come from kernel_facts
        raise NotImplementedError


@dataclass(frozen=True)
class KernelFacts:
    avf: ContinuousAvf
    certificate: ContinuousCertificate
    properties: ContinuousProperties


def _holds(ok: bool, digits: int | None) -> Verdict:
    if not ok:
        return Verdict(FAILS)
    return Verdict(HOLDS) if digits is None else Verdict(HOLDS_TO_DIGITS, digits)


def kernel_facts(method: ContinuousMethod, degree: int | None, box: Any = None) -> KernelFacts:
    """Certificate, AVF, symmetry and symplecticity of ``method``'s kernel; ``box``: the
    decimals mode under which its decimals stand for intervals (None: the kernel at face
    value), judged over the whole box (:mod:`rkcheck.energy.kernel_box`)."""
    facts = _exact_facts(method, degree)
    if box is None:
        return facts
    from rkcheck.energy.kernel_box import box_verdicts

    v = box_verdicts(method, box)
    cert = facts.certificate
    if v["certificate"].state == FAILS and cert.certified:
        cert = ContinuousCertificate(degree, v["certificate"], "no kernel certificate over the box of its decimals")
    elif cert.certified:
        cert = ContinuousCertificate(degree, v["certificate"], cert.reason)
    props = facts.properties
    return KernelFacts(
        ContinuousAvf(degree, v["avf"], facts.avf.reason),
        cert,
        ContinuousProperties(False, PropertyVerdict("symplectic", v["symplectic"], props.symplectic.reason),
                             PropertyVerdict("symmetric", v["symmetric"], props.symmetric.reason)),
    )


def _exact_facts(method: ContinuousMethod, degree: int | None) -> KernelFacts:
    k = method.kernel
    ring = k.ring
    tau, sigma = k.gens()
    one, zero = ring.constant(1), ring.constant(0)
    A, B = k.A_poly, k.B_poly
    digits = None
    B_sigma = k.substitute(B, sigma, tau)

    starts = k.is_zero(k.substitute(A, zero, sigma))
    ends = k.is_zero(k.substitute(A, one, sigma) - B_sigma)
    dA = ring.reduce(A.derivative("tau"))
    symmetric_dA = k.is_zero(dA - k.substitute(dA, sigma, tau))
    if starts and ends and symmetric_dA:
        what = "M is symmetric" if method.M is not None else "∂A/∂τ is symmetric in (τ, σ), A(0, σ) = 0, A(1, σ) = B(σ)"
        cert = ContinuousCertificate(degree, _holds(True, digits), f"{what}: energy is preserved to every order "
                                     "for every Hamiltonian (kernel certificate)")
    else:
        missing = [t for t, ok in (("A(0, σ) ≠ 0", starts), ("A(1, σ) ≠ B(σ)", ends),
                                   ("∂A/∂τ is not symmetric", symmetric_dA)) if not ok]
        cert = ContinuousCertificate(degree, Verdict(FAILS), "no kernel certificate: " + ", ".join(missing))

    is_avf = k.is_zero(A - tau) and k.is_zero(B - one)
    avf = ContinuousAvf(degree, _holds(is_avf, digits),
                        "A(τ, σ) = τ and B(τ) = 1: the AVF method itself" if is_avf
                        else "the kernel is not AVF's (A = τ, B = 1)")

    adj_B = k.substitute(B, one - tau, sigma)
    sym_ok = k.is_zero(B - adj_B) and k.is_zero(A + k.substitute(A, one - tau, one - sigma) - B_sigma)
    symmetric = PropertyVerdict(
        "symmetric", _holds(sym_ok, digits),
        "B(τ) = B(1−τ) and A(τ,σ) + A(1−τ,1−σ) = B(σ): the adjoint kernel is the kernel" if sym_ok
        else "the adjoint kernel (B(σ) − A(1−τ,1−σ), B(1−τ)) differs from the kernel")
    A_swapped = k.substitute(A, sigma, tau)
    sympl_ok = k.is_zero(ring.reduce(B * A + B_sigma * A_swapped - B * B_sigma))
    symplectic = PropertyVerdict(
        "symplectic", _holds(sympl_ok, digits),
        "B(τ)A(τ,σ) + B(σ)A(σ,τ) = B(τ)B(σ)" if sympl_ok else "B(τ)A(τ,σ) + B(σ)A(σ,τ) ≠ B(τ)B(σ)")
    return KernelFacts(avf, cert, ContinuousProperties(digits is None, symplectic, symmetric))
