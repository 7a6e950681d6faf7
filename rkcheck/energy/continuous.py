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
* **Equals AVF** (degree m): ``A(τ, σ) = C(τ)B(σ)`` with ``C(τ) = ∫₀¹ A(τ, σ) dσ``, so
  that ``Y_τ = y₀ + C(τ)(y₁ − y₀)``, and ``∫₀¹ B C^(k−1) = 1/k`` for k = 1…m, so that
  the rule integrates AVF's integrand exactly (every degree: ``B = ±C'`` with C running
  from 0 to 1 or from 1 to 0) — the continuous form of a tableau's ``A = (A·1)bᵀ`` with
  the quadrature conditions; ``A ≡ τ``, ``B ≡ 1`` is AVF itself.
* **Symmetric**: the reflected adjoint kernel ``(B(1−σ) − A(1−τ, 1−σ), B(1−τ))`` is the
  kernel: ``B(τ) = B(1−τ)`` and ``A(τ,σ) + A(1−τ,1−σ) = B(σ)``.
* **Symplectic**: ``B(τ)A(τ,σ) + B(σ)A(σ,τ) = B(τ)B(σ)`` (Tang & Sun 2012), the
  continuous form of ``BA + AᵀB = bbᵀ``.

These three tests on the kernel are sufficient, not necessary (one method has many
kernels): where one fails, the B-series decides — a rooted tree refutes the property, or
it stays ``undecided`` (:mod:`rkcheck.energy.kernel_series`).

A kernel whose decimals stand for intervals (a box, definitions §5.2) is judged over the
whole box (:mod:`rkcheck.energy.kernel_box`): "fails" only when every kernel of the box
fails, "holds" when it holds for every kernel of the box (its decimals cancel in it),
otherwise "holds to D digits" — never a proof.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

from rkcheck.methods.continuous import ContinuousMethod
from rkcheck.properties.symplectic import PropertyVerdict
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS, UNDECIDED, Verdict


@dataclass(frozen=True)
class ContinuousCertificate:
    """The kernel certificate of every order (module docstring); the check's
    :class:`~rkcheck.properties.lineintegral.Certificate` protocol."""

    degree: int | None
    verdict: Verdict
    reason: str
    sigma: int | None = None
    #: the kernel is AVF for the degree (its stages lie on the segment from y₀ to y₁, and
    #: its rule integrates their polynomial exactly): AVF's certificate, not the kernel's
    via_avf: bool = False

    @property
    def certified(self) -> bool:
        """It proves every order, exactly or to digits (a verdict with no certain digit
        certifies nothing)."""
        return self.verdict.shown

    @property
    def kind(self) -> str | None:
        if not self.certified:
            return None
        return "avf" if self.via_avf else "continuous_kernel"

    @property
    def name(self) -> str:
        return "AVF certificate" if self.via_avf else "kernel certificate"

    @property
    def claim_note(self) -> str:
        if self.via_avf:
            return f"AVF certificate (A = C(τ)B(σ), ∫B C^(k−1) = 1/k): every order{_for(self.degree)}"
        return "kernel certificate (∂A/∂τ symmetric, A(0,σ) = 0, A(1,σ) = B(σ)): every order, every degree"

    def refuted(self, condition_id: str) -> "ContinuousCertificate":
        return replace(self, verdict=Verdict(FAILS), reason=f"{self.reason}; refuted: condition {condition_id} "
                       "certainly fails")


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
    form_reason: str = ""  # what the kernel's form says, when its B-series left it undecided

    @property
    def equals_avf(self) -> bool:
        return self.verdict.shown

    def refuted(self, condition_id: str) -> "ContinuousAvf":
        """Undecided by the kernel and its trees, refuted by an energy condition that
        certainly fails (AVF preserves every energy)."""
        return replace(self, verdict=Verdict(FAILS),
                       reason=f"{self.form_reason}, and condition {condition_id} certainly fails")


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


def kernel_facts(method: ContinuousMethod, degree: int | None, box: Any = None, vertices: int = 0) -> KernelFacts:
    """Certificate, AVF, symmetry and symplecticity of ``method``'s kernel; ``box``: the
    decimals mode under which its decimals stand for intervals (None: the kernel at face
    value), judged over the whole box (:mod:`rkcheck.energy.kernel_box`).  A property
    the kernel's form does not show is decided by its B-series on the rooted trees up to
    ``vertices`` (at least :data:`~rkcheck.energy.kernel_series.SERIES_VERTICES`), or
    stays undecided."""
    facts = _exact_facts(method, degree)
    if box is not None:
        facts = _over_the_box(facts, method, degree, box)
    return _by_the_series(facts, method, degree, box, vertices)


def _over_the_box(facts: KernelFacts, method: ContinuousMethod, degree: int | None, box: Any) -> KernelFacts:
    from rkcheck.energy.kernel_box import box_verdicts

    v = box_verdicts(method, box, degree)
    cert = facts.certificate
    boxed = v["avf"] if cert.via_avf else v["certificate"]
    if boxed.state == FAILS and cert.certified:
        cert = replace(cert, verdict=boxed, reason=f"no {cert.name} over the box of its decimals")
    elif cert.certified:
        cert = replace(cert, verdict=boxed, reason=_boxed(cert.verdict, boxed, cert.reason))
    elif v["certificate"].state != FAILS:  # missed at face value, not on every kernel of the box
        cert = replace(cert, verdict=v["certificate"], reason=_boxed(cert.verdict, v["certificate"], cert.reason))
    elif v["avf"].state != FAILS:  # AVF for the degree on some kernel of the box
        cert = _avf_certificate(degree, v["avf"], _boxed(facts.avf.verdict, v["avf"], facts.avf.reason))
    props = facts.properties
    sym, sym_box = props.symplectic, v["symplectic"]
    rev, rev_box = props.symmetric, v["symmetric"]
    return KernelFacts(
        ContinuousAvf(degree, v["avf"], _boxed(facts.avf.verdict, v["avf"], facts.avf.reason)),
        cert,
        ContinuousProperties(False, PropertyVerdict("symplectic", sym_box, _boxed(sym.verdict, sym_box, sym.reason)),
                             PropertyVerdict("symmetric", rev_box, _boxed(rev.verdict, rev_box, rev.reason))),
    )


def _avf_certificate(degree: int | None, verdict: Verdict, avf_reason: str) -> ContinuousCertificate:
    """AVF for the degree as the certificate of every order of it."""
    return ContinuousCertificate(degree, verdict, f"{avf_reason}: energy is preserved to every order for "
                                 f"{'every Hamiltonian' if degree is None else f'degree ≤ {degree}'} "
                                 "(AVF certificate)", via_avf=True)


def _boxed(face: Verdict, box: Verdict, reason: str) -> str:
    """The reason of a kernel identity at face value, as the verdict over the box of its
    decimals reads it: unchanged where both agree, else said of the face values."""
    if box.state == HOLDS:  # the decimals cancel in it
        return f"{reason}, for every kernel of the box of its decimals"
    if box.state == face.state or box.state == FAILS:
        return reason
    if face.state == FAILS:  # nonzero at face value; the box's enclosure does not exclude 0
        return f"{reason} at face value, which the box of its decimals does not exclude"
    return f"{reason} at face value; over the box of its decimals {box.label()}"


def _by_the_series(facts: KernelFacts, method: ContinuousMethod, degree: int | None, box: Any,
                   vertices: int) -> KernelFacts:
    """Each property whose kernel test failed: ``no`` where a rooted tree refutes it
    (over the whole box), else ``undecided`` (:mod:`rkcheck.energy.kernel_series`)."""
    from rkcheck.energy import kernel_series as ks
    from rkcheck.numbers.reading import DecimalsMode

    avf, props = facts.avf, facts.properties
    failed = [v.state == FAILS for v in (avf.verdict, props.symmetric.verdict, props.symplectic.verdict)]
    if not any(failed):
        return facts
    A, B = ks.kernel_polys(method, box or DecimalsMode.EXACT)
    vertices = max(vertices, ks.SERIES_VERTICES)
    # over a box the balls only fail to tell the two apart: no agreement is shown
    exact = all(c.is_point for c in [*A.values(), *B.values()])
    if failed[0]:
        answer = ks.avf_witness(A, B, degree, vertices)
        agrees = (f"its B-series agrees with AVF's{_for(degree)} on every rooted tree up to {answer.vertices} vertices"
                  if exact else f"no rooted tree up to {answer.vertices} vertices tells its B-series from AVF's"
                  f"{_for(degree)} over the box of its decimals")
        avf = ContinuousAvf(degree, *_decided(answer, avf.reason, agrees), form_reason=avf.reason)
    symmetric, symplectic = props.symmetric, props.symplectic
    if failed[1]:
        answer = ks.symmetric_witness(A, B, vertices)
        agrees = (f"its B-series agrees with its adjoint's on every rooted tree up to {answer.vertices} vertices"
                  if exact else f"no rooted tree up to {answer.vertices} vertices tells its B-series from its "
                  "adjoint's over the box of its decimals")
        symmetric = PropertyVerdict("symmetric", *_decided(answer, symmetric.reason, agrees))
    if failed[2]:
        answer = ks.symplectic_witness(A, B, vertices)
        agrees = (f"a(u∘v) + a(v∘u) = a(u)a(v) for every pair of rooted trees up to {answer.vertices} vertices "
                  "in all" if exact else f"no pair of rooted trees up to {answer.vertices} vertices in all shows "
                  "a(u∘v) + a(v∘u) ≠ a(u)a(v) over the box of its decimals")
        symplectic = PropertyVerdict("symplectic", *_decided(answer, symplectic.reason, agrees))
    return KernelFacts(avf, facts.certificate, ContinuousProperties(props.exact, symplectic, symmetric))


def _for(degree: int | None) -> str:
    return "" if degree is None else f" for degree {degree}"


def _decided(answer: Any, kernel_reason: str, agrees: str) -> tuple[Verdict, str]:
    if answer.witness is not None:
        return Verdict(FAILS), f"{kernel_reason}, and the B-series shows it: {answer.witness}"
    return Verdict(UNDECIDED), f"{kernel_reason}, yet {agrees}: neither shown nor refuted"


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

    avf = ContinuousAvf(degree, *_avf_form(k, A, B, B_sigma, degree))
    if not cert.certified and avf.verdict.state == HOLDS:  # AVF for the degree proves every order of it
        cert = _avf_certificate(degree, Verdict(HOLDS), avf.reason)

    adj_B = k.substitute(B, one - tau, sigma)
    sym_ok = k.is_zero(B - adj_B) and k.is_zero(A + k.substitute(A, one - tau, one - sigma) - B_sigma)
    symmetric = PropertyVerdict(
        "symmetric", _holds(sym_ok, digits),
        "B(τ) = B(1−τ) and A(τ,σ) + A(1−τ,1−σ) = B(σ): the reflected adjoint kernel is the kernel" if sym_ok
        else "the reflected adjoint kernel (B(1−σ) − A(1−τ,1−σ), B(1−τ)) differs from the kernel")
    A_swapped = k.substitute(A, sigma, tau)
    sympl_ok = k.is_zero(ring.reduce(B * A + B_sigma * A_swapped - B * B_sigma))
    symplectic = PropertyVerdict(
        "symplectic", _holds(sympl_ok, digits),
        "B(τ)A(τ,σ) + B(σ)A(σ,τ) = B(τ)B(σ)" if sympl_ok else "B(τ)A(τ,σ) + B(σ)A(σ,τ) ≠ B(τ)B(σ)")
    if k.deg_tau == 0:  # one stage: the tableau's tests decide, both ways
        symmetric, symplectic = _one_stage(k, A, B)
    elif not sym_ok and (avf.verdict if degree is None else _avf_form(k, A, B, B_sigma, None)[0]).state == HOLDS:
        symmetric = PropertyVerdict("symmetric", Verdict(HOLDS), "the method is AVF, reparametrised (A = C(τ)B(σ), "
                                    "B = ±C′), and AVF is symmetric")
    return KernelFacts(avf, cert, ContinuousProperties(digits is None, symplectic, symmetric))


def _one_stage(k: Any, A: Any, B: Any) -> tuple[PropertyVerdict, PropertyVerdict]:
    """Symmetry and symplecticity of a kernel whose A does not depend on τ: every stage
    Y_τ is one Y = y₀ + h·a·f(Y), y₁ = y₀ + h·b·f(Y), with a = ∫A dσ and b = ∫B — the
    1-stage tableau (a, b), symmetric (adjoint (b − a, b)) and symplectic (2ab = b²)
    exactly when b = 0 or 2a = b."""
    ring = k.ring
    a = k.integrate(A, "sigma")
    b = k.integrate(B, "tau")
    ok = k.is_zero(b) or k.is_zero(ring.reduce(2 * a - b))
    values = f"a = ∫A dσ = {_text(k, a)}, b = ∫B = {_text(k, b)}"
    why = (f"A does not depend on τ: every stage is one, the 1-stage method {values}, "
           + ("with 2a = b (or b = 0)" if ok else "with 2a ≠ b"))
    return PropertyVerdict("symmetric", _holds(ok, None), why), PropertyVerdict("symplectic", _holds(ok, None), why)


def _text(k: Any, p: Any) -> str:
    from rkcheck.numbers.formatting import exact_string

    value = k.number(p)
    return exact_string(value) if isinstance(value, Fraction) else str(value)


def _avf_form(k: Any, A: Any, B: Any, B_sigma: Any, degree: int | None) -> tuple[Verdict, str]:
    """Whether the kernel has AVF's form (module docstring), exactly, and why."""
    tau, _ = k.gens()
    ring = k.ring
    if k.is_zero(A - tau) and k.is_zero(B - ring.constant(1)):
        return Verdict(HOLDS), "A(τ, σ) = τ and B(τ) = 1: the AVF method itself"
    C = k.integrate(A, "sigma")
    if not k.is_zero(ring.reduce(A - C * B_sigma)):
        return Verdict(FAILS), "A(τ, σ) is not C(τ)B(σ) with C(τ) = ∫A dσ"
    if degree is None:
        zero, one = ring.constant(0), ring.constant(1)
        ends = (k.substitute(C, zero, zero), k.substitute(C, one, one))
        dC = ring.reduce(C.derivative("tau"))
        rising = k.is_zero(ends[0]) and k.is_zero(ends[1] - one) and k.is_zero(B - dC)
        falling = k.is_zero(ends[0] - one) and k.is_zero(ends[1]) and k.is_zero(B + dC)
        if rising or falling:
            return Verdict(HOLDS), ("A(τ, σ) = C(τ)B(σ) with B = ±C′ and C from one end of [0, 1] to the other: "
                                    "∫B Cᵏ = 1/(k+1) for every k, the AVF method reparametrised")
        return Verdict(FAILS), "A(τ, σ) = C(τ)B(σ), but B is not ±C′ with C running from 0 to 1"
    power = ring.constant(1)
    for j in range(1, degree + 1):
        if not k.is_zero(ring.reduce(k.integrate(ring.reduce(B * power), "tau") - ring.constant(Fraction(1, j)))):
            return Verdict(FAILS), f"A(τ, σ) = C(τ)B(σ), but ∫B C^{j - 1} ≠ 1/{j}"
        power = ring.reduce(power * C)
    return Verdict(HOLDS), (f"A(τ, σ) = C(τ)B(σ) and ∫B C^(k−1) = 1/k for k = 1…{degree}: the AVF method for "
                            f"Hamiltonians of degree ≤ {degree}")
