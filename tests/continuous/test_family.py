"""A continuous kernel with a free parameter is a family: its energy conditions vanish
identically when ∂A/∂τ is symmetric for every value, and `solve` finds the parameter of
a classical order (κ = 3: Hairer's energy-preserving collocation, order 4)."""

from fractions import Fraction
from pathlib import Path

import rkcheck

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "tableaux" / "families" / "continuous-collocation-kappa.toml"


def test_solve_finds_the_collocation_parameter():
    res = rkcheck.solve(FILE, degree=None, order=2, classical_order=4)
    assert res.dimension == 0 and [s.values["kappa"].text for s in res.solutions] == ["3"]
    # the member it names has classical order 4 by the non-family route
    member = rkcheck.ContinuousMethod.from_kernel("tau + 3*(tau^2 - tau)*(2*sigma - 1)")
    assert rkcheck.verify(member, order=5).classical_order == 4


def test_every_energy_condition_vanishes_identically():
    fc = rkcheck.family_conditions(FILE, degree=None, order=6)
    assert fc.energy_order is None or fc.energy_order >= 6
    assert not fc.exceptional


def test_a_kernel_family_without_the_symmetry_has_exceptional_values(tmp_path):
    """A = τ + κτσ − κτ/2 (C(τ) = τ for every κ): ∂A/∂τ = 1 + κ(σ − 1/2) is symmetric only
    at κ = 0 (AVF), so the energy conditions are polynomials in κ vanishing at 0."""
    f = tmp_path / "k.toml"
    f.write_text('[parameters]\nkappa = "free"\n[continuous]\nA = "tau + kappa*tau*sigma - kappa*tau/2"\n')
    res = rkcheck.solve(f, degree=None, order=4)
    assert [s.values["kappa"].text for s in res.solutions] == ["0"]


KERNEL = "tau + kappa*tau*sigma - kappa*tau/2"


def _kernel_family(tmp_path, A=KERNEL, b="1"):
    f = tmp_path / "k.toml"
    f.write_text(f'[parameters]\nkappa = "free"\n[continuous]\nA = "{A}"\nb = "{b}"\n')
    return f


def test_family_conditions_at_a_value_are_the_kernels_own_residuals(tmp_path):
    """Each energy condition up to order 6, its polynomial evaluated at κ = 1/3, is the
    residual the single-kernel route (its own surrogate, built for its own order) finds
    for the method A = τ + τσ/3 − τ/6: the family's surrogate, built for the trees of
    order 6 only, reads them exactly."""
    from fractions import Fraction

    from flint import fmpq

    fc = rkcheck.family_conditions(_kernel_family(tmp_path), degree=None, order=6)
    assert fc.family.reach == 7
    member = rkcheck.verify(rkcheck.ContinuousMethod.from_kernel("tau + 1/3*tau*sigma - 1/6*tau"), degree=None,
                            order=6, arithmetic="exact")
    residuals = {c.id: Fraction(c.residual) for c in member.conditions}
    assert len(fc.energy) == len(residuals) == 20
    for c in fc.energy:
        value = c.polynomial(fmpq(1, 3))
        assert Fraction(int(value.p), int(value.q)) == residuals[c.id], c.id


def test_a_kernels_quadrature_order_is_its_own(tmp_path):
    """B(τ) = 1 + κ(τ² − τ + 1/6) is orthogonal to 1 and τ, and ∫ B τ² = 1/3 + κ/180 (by
    hand): quadrature order 2 with the third condition κ/180.  With B = 1 and C(τ) = τ
    every ∫ τ^(k−1) = 1/k: the order is at least every k the surrogate reads."""
    from flint import fmpq

    fc = rkcheck.family_conditions(_kernel_family(tmp_path, b="1 + kappa*(tau^2 - tau + 1/6)"), degree=None, order=4)
    assert fc.quadrature_order == 2
    third = fc.quadrature[2].polynomial
    assert third(fmpq(1)) == fmpq(1, 180) and third(fmpq(0)) == 0
    fc = rkcheck.family_conditions(_kernel_family(tmp_path), degree=None, order=4)
    assert fc.quadrature_order == fc.quadrature_checked == 5


def test_a_kernel_family_costs_the_surrogate_of_the_order_asked(tmp_path):
    """τ⁴⁰ in A: trees of n vertices need (n − 1)·40 + 1 nodes — 481 for 13 (over
    MAX_SURROGATE_NODES = 400), 41 for order 1, which runs; order 10 (401) is refused
    naming the limit and the file, before any work."""
    import pytest

    from rkcheck.errors import UserError

    f = _kernel_family(tmp_path, A="tau + kappa*tau^40*(sigma - 1/2)")
    fc = rkcheck.family_conditions(f, degree=None, order=1)
    assert fc.family.stages == 41 and fc.quadrature_order == fc.quadrature_checked == 2
    with pytest.raises(UserError, match="MAX_SURROGATE_NODES") as err:
        rkcheck.family_conditions(f, degree=None, order=10)
    assert str(f) in str(err.value)


def test_a_kernel_family_at_a_value_is_the_continuous_method(tmp_path):
    """At κ = 0 the kernel is τ: the AVF method, energy-preserving for every degree."""
    member = rkcheck.load_family(_kernel_family(tmp_path)).at({"kappa": 0})
    assert isinstance(member, rkcheck.ContinuousMethod)
    assert rkcheck.verify(member, degree=None, order=6, arithmetic="exact").energy_order == 6


def test_b_in_both_variables_is_refused_and_unknown_keys_are_warned(tmp_path):
    import pytest

    from rkcheck.errors import UserError

    with pytest.raises(UserError, match="continuous.b: B is a polynomial in one variable"):
        rkcheck.load_family(_kernel_family(tmp_path, b="tau + sigma + kappa"))
    f = tmp_path / "B.toml"
    f.write_text('[parameters]\nkappa = "free"\n[continuous]\nA = "tau + kappa"\nweight = "2"\n')
    assert "unknown key continuous.weight ignored (known: A, b)" in rkcheck.load_family(f).info.warnings
    # B for b would be ignored, and another family (B = 1) checked without a word but a warning
    f.write_text('[parameters]\nkappa = "free"\n[continuous]\nA = "tau + kappa"\nB = "2"\n')
    with pytest.raises(UserError, match="continuous.B: unknown key: keys are case-sensitive.*write b"):
        rkcheck.load_family(f)


def test_avf_of_a_kernel_family_is_a_equal_to_tau_and_b_to_1(tmp_path):
    """A = k (a constant kernel, B = 1): its surrogate on one node is the 1-stage tableau
    (k, 1), which the tableau families' route would call AVF (A = (A·1) bᵀ) at k = 1/2;
    as a kernel it is A = 1/2 ≠ τ, not AVF.  A = τ + k(τ² − τ) + j(τ³ − τ) is AVF's kernel
    only at k = j = 0: on the line k + 3j/2 = 0 where its conditions to order 2 vanish
    for cubic H, A = C(τ)·1 (a tableau's A = (A·1) bᵀ) but not AVF.  A = τ + k·j·τ(σ − 1/2)
    is AVF's kernel on both pieces k = 0 and j = 0."""
    f = tmp_path / "k.toml"
    f.write_text('[parameters]\nk = "free"\n[continuous]\nA = "k"\n')
    res = rkcheck.solve(f, degree=2, order=4)
    assert res.route == "plain" and [s.values["k"].text for s in res.solutions] == ["1/2"]
    assert not (res.components and any(c.avf for c in res.components))
    f.write_text('[parameters]\nk = "free"\nj = "free"\n[continuous]\nA = "tau + k*(tau^2 - tau) + j*(tau^3 - tau)"\n')
    res = rkcheck.solve(f, degree=2, order=2)
    assert res.dimension == 1 and res.components and res.components[0].avf is not True
    f.write_text('[parameters]\nk = "free"\nj = "free"\n[continuous]\nA = "tau + k*j*tau*(sigma - 1/2)"\n')
    res = rkcheck.solve(f, degree=None, order=5)
    assert len(res.components) == 2 and all(c.avf is True for c in res.components)


def test_a_kernel_family_over_a_number_field_is_its_surrogate_tableau_family(tmp_path):
    """With √3 among the kernel's constants, the family read through the factors
    V C Wᵀ over Q(√3) has the conditions of the family whose entries are the surrogate's,
    written out one by one as texts: A_ij = w_j K(x_i, x_j), b_i = w_i."""
    from rkcheck.methods.quadrature import rational_rule

    f = tmp_path / "k.toml"
    f.write_text('[parameters]\nk = "free"\n[constants]\nr = "sqrt(3)"\n'
                 '[continuous]\nA = "tau + k*tau^3*(sigma - r/6)"\nb = "1"\n')
    fc = rkcheck.family_conditions(f, degree=None, order=5)
    n = fc.family.stages
    x, w = rational_rule(n)
    A = [[f"({w[j]})*(({x[i]}) + k*({x[i]})^3*(({x[j]}) - r/6))" for j in range(n)] for i in range(n)]
    written = rkcheck.family_from_arrays(A, [str(v) for v in w], ["k"], constants={"r": "sqrt(3)"})
    ref = rkcheck.family_conditions(written, degree=None, order=5)
    assert fc.family.ring.field.name == ref.family.ring.field.name == "sqrt(3)"
    got = {c.id: str(c.polynomial) for c in fc.energy}
    assert got == {c.id: str(c.polynomial) for c in ref.energy}
    assert any("__theta" in p for p in got.values())  # √3 is in them, not only rationals


def test_at_takes_exact_real_values_of_the_parameters(tmp_path):
    import mpmath
    import pytest

    from rkcheck.errors import UserError

    fam = rkcheck.load_family(_kernel_family(tmp_path))
    assert fam.at({"kappa": "1/3"}).A == fam.at({"kappa": Fraction(1, 3)}).A
    # at κ = √2 the member fails exactly the conditions whose polynomials do not vanish there
    fc = rkcheck.family_conditions(_kernel_family(tmp_path), degree=None, order=4)
    with mpmath.workdps(50):
        root2 = mpmath.sqrt(2)
        nonzero = {c.id for c in fc.energy if abs(sum(mpmath.mpf(int(q.p)) / int(q.q) * root2 ** int(e[0])
                                                      for e, q in c.polynomial.terms())) > 1e-30}
    member = rkcheck.verify(fam.at({"kappa": "sqrt(2)"}), degree=None, order=4, arithmetic="exact")
    assert nonzero and {c.id for c in member.conditions if c.verdict.state == "fails"} == nonzero
    assert {c.verdict.state for c in member.conditions if c.id not in nonzero} <= {"holds"}
    for values, message in (({"kappa": float("nan")}, "finite rational"), ({"kappa": 1, "zz": 2}, "not a parameter"),
                            ({"kappa": "sqrt(-2)"}, "negative number"), ({"kappa": None}, "expected a number")):
        with pytest.raises(UserError, match=message):
            fam.at(values)


def test_a_kernel_familys_errors_call_tau_a_variable_not_a_parameter(tmp_path):
    import pytest

    from rkcheck.errors import UserError

    with pytest.raises(UserError, match="tau, sigma or a parameter in a denominator") as err:
        rkcheck.load_family(_kernel_family(tmp_path, A="1/tau + kappa"))
    assert err.value.place == "continuous.A"


def test_a_kernel_familys_surrogate_entries_are_the_kernel_at_the_nodes(tmp_path):
    """The surrogate built from the kernel's coefficients (A = V C Wᵀ) has, at κ = 2/7,
    the entries w_j·K(x_i, x_j) and b_i = w_i·B(x_i), K and B evaluated here in
    Fractions on the same nodes, for a kernel of τ-degree 5 with a σ² term and a b in τ."""
    from flint import fmpq

    from rkcheck.methods.quadrature import rational_rule

    fam = rkcheck.load_family(_kernel_family(tmp_path, A="tau + kappa*tau^5*(sigma^2 - 1/3) - kappa^2*tau*sigma/7",
                                      b="1 + kappa*(tau - 1/2)")).covering(4)
    kappa = Fraction(2, 7)

    def K(t, s):
        return t + kappa * t**5 * (s**2 - Fraction(1, 3)) - kappa**2 * t * s / 7

    def B(t):
        return 1 + kappa * (t - Fraction(1, 2))

    x, w = rational_rule(fam.stages)
    at = (fmpq(kappa.numerator, kappa.denominator),)

    def value(p):
        v = p(*at)
        return Fraction(int(v.p), int(v.q))

    assert [[value(a) for a in row] for row in fam.A] == [[w[j] * K(x[i], x[j]) for j in range(len(x))]
                                                          for i in range(len(x))]
    assert [value(bi) for bi in fam.b] == [w[i] * B(x[i]) for i in range(len(x))]
    assert [value(ci) for ci in fam.A.row_sums()] == [sum(w[j] * K(x[i], x[j]) for j in range(len(x)))
                                                      for i in range(len(x))]


def test_the_factored_product_is_the_product_by_the_entries(tmp_path):
    """x·Aᵀ through A = V C Wᵀ equals x·Aᵀ through the n² entries, polynomial for
    polynomial, on vectors of random polynomials in κ."""
    import random

    import numpy as np

    from rkcheck.evaluation.polynomial import PolynomialContext

    fam = rkcheck.load_family(_kernel_family(tmp_path, A="tau + kappa*tau^3*(sigma - 1/2)")).covering(5)
    ring, A = fam.ring, fam.A
    assert getattr(A, "factors", None) is not None
    rng = random.Random(3)
    kappa = ring.parameter("kappa")
    x = np.empty((4, fam.stages), dtype=object)
    for i in range(4):
        for j in range(fam.stages):
            x[i, j] = ring.constant(Fraction(rng.randint(-9, 9), rng.randint(1, 9))) + \
                ring.constant(Fraction(rng.randint(-9, 9), 7)) * kappa ** rng.randint(0, 3)
    factored = PolynomialContext(ring, A, fam.b).matvec(x)
    plain = PolynomialContext(ring, [list(row) for row in A], fam.b).matvec(x)
    assert all(u == v for u, v in zip(factored.reshape(-1), plain.reshape(-1)))
