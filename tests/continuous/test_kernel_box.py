"""Kernel identities over the box of a kernel's decimals: each verdict against the
identity worked out independently in sympy, as a polynomial in τ, σ and one symbol per
literal, at the corners and random points of the box."""

import itertools
import json
import random
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

sympy = pytest.importorskip("sympy")

import rkcheck  # noqa: E402
from rkcheck.energy import kernel_forms  # noqa: E402
from rkcheck.energy.kernel_box import box_verdicts  # noqa: E402
from rkcheck.methods.continuous import ContinuousMethod  # noqa: E402

tau, sigma = sympy.symbols("tau sigma")


def test_an_identity_the_decimals_cancel_in_holds_for_every_kernel_of_the_box():
    """A = τ + κ(τ² − τ)(2σ − 1), B = 1, with κ = 0.250000 ± 5·10⁻⁷: ∂τA = 1 + κ(2τ − 1)(2σ − 1)
    is symmetric, A(0, σ) = 0 and A(1, σ) = 1 for every κ, and A(τ,σ) + A(1−τ,1−σ) = 1:
    the certificate and symmetry hold for every kernel of the box, a proof whatever κ is."""
    m = ContinuousMethod.from_kernel("tau + 0.250000*(tau^2 - tau)*(2*sigma - 1)")
    v = box_verdicts(m, "auto", 4)
    assert v["certificate"].state == "holds" and v["symmetric"].state == "holds"
    res = rkcheck.verify(m, degree=4, order=6)
    assert res.energy_order_all and res.certificate.verdict.state == "holds"
    assert "for every kernel of the box of its decimals" in res.certificate.reason
    # κ multiplies τ·σ terms: AVF's form A = C(τ)B(σ) fails for every κ ≠ 0 of the box
    assert v["avf"].state == "fails"


def test_a_constant_is_one_number_and_a_literal_written_twice_two():
    """M = [[4, m], [m, 12]]: ∂τA = 4 + mσ + mτ + 12τσ is symmetric for every m, and B(σ) =
    A(1, σ) by its definition: the certificate holds.  Written twice, −6.00000 is two
    numbers x, y: ∂τA − its swap = (x − y)(σ − τ), |x − y| ≤ 10⁻⁵, and each of its two
    coefficients is bounded by 10⁻⁵: 2·10⁻⁵ in all, 4 digits."""
    shared = rkcheck.loads('[constants]\nm = "-6.00000"\n[continuous]\nM = [["4", "m"], ["m", "12"]]\n')
    assert box_verdicts(shared, "auto")["certificate"].state == "holds"
    twice = ContinuousMethod.from_matrix([["4", "-6.00000"], ["-6.00000", "12"]])
    v = box_verdicts(twice, "auto")["certificate"]
    assert v.state == "holds_to_digits" and v.digits == 4


def test_identities_too_large_for_forms_are_judged_on_intervals(monkeypatch):
    """Past FORM_TERMS the identity is judged on interval coefficients, each use of κ on
    its own: no longer a proof, but never a failure of what holds on the box."""
    monkeypatch.setattr(kernel_forms, "FORM_TERMS", 1)
    m = ContinuousMethod.from_kernel("tau + 0.250000*(tau^2 - tau)*(2*sigma - 1)")
    v = box_verdicts(m, "auto", 4)
    assert v["certificate"].state == "holds_to_digits" and v["symmetric"].state == "holds_to_digits"


# ------------------------------------------------------------------ against sympy


class _Literals:
    """Decimal literals written with 6 to 8 significant digits, one sympy symbol and one
    box (half a unit of the last digit) each."""

    def __init__(self, rng: random.Random):
        self.rng, self.symbols, self.boxes = rng, [], []

    def new(self, name: str | None = None, one: bool = False) -> tuple[str, object]:
        """A new literal; ``one``: 1 written with its digits (1.00000…)."""
        digits = self.rng.randint(6, 8)
        q = self.rng.randint(10 ** (digits - 1), 10**digits - 1) * self.rng.choice([1, -1])
        exponent = -(digits - 1) + self.rng.randint(-1, 0)
        if one:
            q, exponent = 10 ** (digits - 1), -(digits - 1)
        value, half = Fraction(q) * Fraction(10) ** exponent, Fraction(1, 2) * Fraction(10) ** exponent
        symbol = sympy.Symbol(name or f"l{len(self.symbols)}")
        self.symbols.append(symbol)
        self.boxes.append((value - half, value + half))
        return f"({q}e{exponent})", symbol


def _random_kernel(rng: random.Random):
    """Texts of A and B and their constants, the sympy kernel in one symbol per literal,
    and the literals."""
    lits = _Literals(rng)
    constants, shared = {}, None
    if rng.random() < 0.5:  # a constant: one number wherever it is used
        text, shared = lits.new("k")
        constants["k"] = text

    def coefficient() -> tuple[str, object]:
        roll = rng.random()
        if roll < 0.3:
            q = Fraction(rng.randint(-6, 6), rng.randint(1, 4))
            return f"({q})", sympy.Rational(q.numerator, q.denominator)
        if roll < 0.5 and shared is not None:
            return "k", shared
        return lits.new()

    if rng.random() < 0.4:  # A = τ + κ(τ² − τ)(2σ − 1): certificate and symmetry for every κ
        text, kappa = coefficient()
        one, c = lits.new(one=True) if rng.random() < 0.5 else ("1", 1)
        A_text = f"{one}*tau + {text}*(tau^2 - tau)*(2*sigma - 1)"
        A_sym = c * tau + kappa * (tau**2 - tau) * (2 * sigma - 1)
    else:
        terms, A_sym = [], sympy.Integer(0)
        for i, j in [(1, 0), (1, 1), (2, 0), (2, 1), (1, 2)]:
            if rng.random() < 0.7:
                text, c = coefficient()
                terms.append(f"{text}*tau^{i}*sigma^{j}")
                A_sym += c * tau**i * sigma**j
        A_text = " + ".join(terms) or "tau"
        A_sym = A_sym if terms else tau
    B_text, B_sym = "1", sympy.Integer(1)
    if rng.random() < 0.4:
        B_text, B_sym = lits.new(one=True) if rng.random() < 0.7 else coefficient()
    return A_text, B_text, A_sym, B_sym, lits, constants


def _identities(A, B, degree):
    """The defects, in sympy, as definitions §6 states each identity."""
    B_s = B.subs(tau, sigma)
    dA = sympy.diff(A, tau)
    C = sympy.integrate(A, (sigma, 0, 1))
    out = {
        "certificate": [A.subs(tau, 0), A.subs(tau, 1) - B_s, dA - dA.subs({tau: sigma, sigma: tau}, simultaneous=True)],
        "symmetric": [B - B.subs(tau, 1 - tau), A + A.subs({tau: 1 - tau, sigma: 1 - sigma}, simultaneous=True) - B_s],
        "symplectic": [B * A + B_s * A.subs({tau: sigma, sigma: tau}, simultaneous=True) - B * B_s],
        "avf": [A - C * B_s] + [sympy.integrate(B * C ** (k - 1), (tau, 0, 1)) - sympy.Rational(1, k)
                               for k in range(1, degree + 1)],
    }
    return out


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10**9))
def test_box_verdicts_agree_with_the_identities_at_every_point_of_the_box(seed):
    rng = random.Random(seed)
    A_text, B_text, A_sym, B_sym, lits, constants = _random_kernel(rng)
    symbols, boxes = lits.symbols, lits.boxes
    m = ContinuousMethod.from_kernel(A_text, B_text, constants=constants)
    if not m.is_box("rounded"):
        return
    degree = 3
    verdicts = box_verdicts(m, "rounded", degree)
    defects = _identities(A_sym, B_sym, degree)
    points = [dict(zip(symbols, corner)) for corner in itertools.islice(itertools.product(*boxes), 16)]
    points += [{s: lo + (hi - lo) * Fraction(rng.randint(0, 100), 100) for s, (lo, hi) in zip(symbols, boxes)}
               for _ in range(4)]
    grid = [(Fraction(i, 4), Fraction(j, 4)) for i in range(5) for j in range(5)]
    for name, parts in defects.items():
        v = verdicts[name]
        at = [[sympy.expand(p.subs({s: sympy.Rational(x.numerator, x.denominator) for s, x in pt.items()}))
               for p in parts] for pt in points]
        if v.state == "holds":
            assert all(p == 0 for ps in at for p in ps), name
        elif v.state == "fails":  # some part is nonzero for every kernel of the box
            assert all(any(p != 0 for p in ps) for ps in at), name
        else:
            bound = Fraction(1, 10**v.digits)
            for ps in at:
                for p in ps:
                    for x, y in grid:
                        value = p.subs({tau: sympy.Rational(x.numerator, x.denominator),
                                        sigma: sympy.Rational(y.numerator, y.denominator)})
                        assert abs(Fraction(str(value))) <= bound, (name, p)


def test_a_decimal_zero_at_face_value_still_counts_in_the_surrogates_degree():
    """A = τ + d·τσ(σ − ½)²(σ − 1), B = 1, d = 1.000000 − 1 ∈ [−5·10⁻⁷, 5·10⁻⁷]: at face value
    A = τ (degree 0 in σ), but every other kernel of the box has σ-degree 4.  Here
    R([τ²]) = a([τ]) − a(τ)²/2 = d·∫₀¹σ(σ − ½)²(σ − 1)dσ·∫₀¹τ dτ — worked out by sympy —, so
    |R| reaches 5·10⁻⁷/240 on the box: it holds to digits (never exactly), within that."""
    d = sympy.Symbol("d")
    A = tau + d * tau * sigma * (sigma - sympy.Rational(1, 2)) ** 2 * (sigma - 1)
    a_bracket = sympy.integrate(sympy.integrate(A, (sigma, 0, 1)), (tau, 0, 1))
    R = sympy.expand(a_bracket - sympy.Rational(1, 2))
    worst = abs(Fraction(str(R.coeff(d)))) * Fraction(5, 10**7)
    assert worst > 0
    m = ContinuousMethod.from_kernel("tau + (1.000000 - 1)*tau*sigma*(sigma - 1/2)^2*(sigma - 1)")
    res = rkcheck.verify(m, order=3)
    (c,) = [c for c in res.conditions if c.id == "1,2,2"]
    assert c.state == "holds_to_digits" and Fraction(1, 10**c.digits) >= worst and c.digits >= 7
    assert res.classical.order == 1 and res.classical.verdict.state == "holds_to_digits"  # a([τ]) = ½ to digits


@pytest.mark.parametrize("kernel, digits", [
    # A(1, σ) − B = x + 10⁻⁷ − 1, x ∈ [1 − 5·10⁻⁷, 1 + 5·10⁻⁷]: from −4·10⁻⁷ to 6·10⁻⁷, 0 inside
    ({"A": "(1.000000 + 1/10000000)*tau"}, 6),
    # ∂τA − its swap = (M₁₂ − M₂₁)(σ − τ), M₁₂ − M₂₁ from −6.5·10⁻⁸ to 4.5·10⁻⁸: two coefficients
    # of at most 6.5·10⁻⁸ each, 1.3·10⁻⁷ in all
    ({"M": [["1", "0.1234567"], ["0.12345671", "1"]]}, 6),
])
def test_a_certificate_missed_at_face_value_but_not_on_the_whole_box_does_not_fail(tmp_path, kernel, digits):
    path = tmp_path / "k.json"
    path.write_text(json.dumps({"continuous": kernel}), encoding="utf-8")
    res = rkcheck.verify(path, order=3)
    assert res.certificate.verdict.state == "holds_to_digits" and res.certificate.verdict.digits == digits
    assert "at face value, which the box of its decimals does not exclude" in res.certificate.reason
    exact = rkcheck.verify(path, order=3, decimals="exact")
    assert exact.certificate.verdict.state == "fails"
