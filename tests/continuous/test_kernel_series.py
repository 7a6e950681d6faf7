"""Symmetry, symplecticity and equality with AVF of kernels whose own form does not show
them: each verdict against the B-series worked out independently by exact symbolic
integration (sympy), tree by tree."""

import json
from fractions import Fraction

import pytest

sympy = pytest.importorskip("sympy")

from support.clirun import run_subprocess  # noqa: E402

import rkcheck  # noqa: E402
from rkcheck.methods.continuous import ContinuousMethod  # noqa: E402

from .test_weights import rooted_trees, sigma, tau, weight_sympy  # noqa: E402

UP_TO = 6  # vertices of the trees compared by sympy


def trees():
    return [t for n in range(1, UP_TO + 1) for t in rooted_trees(n)]


def kernel(A, B):
    return sympy.sympify(A, locals={"tau": tau, "sigma": sigma}), sympy.sympify(B, locals={"tau": tau})


def weights(A, B):
    A, B = kernel(A, B)
    return {t: weight_sympy(t, A, B) for t in trees()}


def avf_weight(t):
    w = Fraction(1, len(t) + 1)
    for child in t:
        w *= avf_weight(child)
    return w


def adjoint(A, B):
    """(B(σ) − A(τ, σ), B(τ)), as (1bᵀ − A, b) is a tableau's adjoint."""
    A, B = kernel(A, B)
    return B.subs(tau, sigma) - A, B


def verify(A, B, **options):
    return rkcheck.verify(ContinuousMethod.from_kernel(A, B), order=options.pop("order", 6), **options)


def test_avf_reparametrised_is_avf_and_symmetric():
    # σ ↦ σ² turns AVF (τ, 1) into (2τ²σ, 2τ); by sympy its weights are AVF's on every
    # tree up to 6 vertices, and AVF is symmetric and not symplectic
    A, B = "2*tau^2*sigma", "2*tau"
    assert all(w == avf_weight(t) for t, w in weights(A, B).items())
    res = verify(A, B, degree=None)
    assert res.avf.verdict.state == "holds" and res.properties.symmetric.verdict.state == "holds"
    assert res.properties.symplectic.verdict.state == "fails"
    # the witness rkcheck names: u = τ, v = [τ], so u∘v = [[τ]] and v∘u = [τ²]
    w = weights(A, B)
    defect = w[(((),),)] + w[((), ())] - w[()] * w[((),)]
    assert defect == Fraction(1, 12)
    assert "= 1/12 for u = τ, v = [τ]" in res.properties.symplectic.reason


@pytest.mark.parametrize("A, B", [("sigma", "1"), ("sigma", "2*tau"), ("3*sigma^2", "1")])
def test_a_kernel_free_of_tau_is_its_one_stage_method(A, B):
    # every stage is one: a = ∫A dσ, b = ∫B; sympy confirms the weights are the 1-stage
    # tableau's, a(t) = b·a^(|t|−1)·(its stage products) — here by comparing with [[a]], [b]
    a = sympy.integrate(kernel(A, B)[0], (sigma, 0, 1))
    b = sympy.integrate(kernel(A, B)[1], (tau, 0, 1))
    assert all(w == weight_sympy(t, a, b) for t, w in weights(A, B).items())
    res = verify(A, B, degree=None)
    both = a * 2 == b  # symmetric and symplectic exactly then (1-stage tableau)
    for prop in (res.properties.symmetric, res.properties.symplectic):
        assert prop.verdict.state == ("holds" if both else "fails"), (A, B, prop.reason)


def test_avf_for_degree_four_in_product_form():
    # A = τ·B(σ), B = 1 + P₄(2σ − 1): ∫B σ^(k−1) = 1/k for k ≤ 4 but not 5
    A = "tau*(1 + 70*sigma^4 - 140*sigma^3 + 90*sigma^2 - 20*sigma + 1)"
    B = "1 + 70*tau^4 - 140*tau^3 + 90*tau^2 - 20*tau + 1"
    w = weights(A, B)

    def widest(t):
        return max([len(t), *(widest(c) for c in t)])

    assert all(w[t] == avf_weight(t) for t in w if widest(t) <= 3)  # what degree 4 sees
    bush = ((),) * 4
    assert w[bush] == Fraction(127, 630) != avf_weight(bush)
    assert verify(A, B, degree=4, order=8).avf.verdict.state == "holds"
    five = verify(A, B, degree=5, order=8).avf
    assert five.verdict.state == "fails" and "[τ⁴] is not AVF's (127/630" in five.reason


def test_a_symmetric_kernel_the_reflection_misses_is_undecided_not_no(tmp_path):
    # the s = 2 energy-preserving collocation kernel reparametrised by σ ↦ σ²: by sympy its
    # weights equal its adjoint's on every tree up to 6 vertices (and it is symmetric, as
    # the kernel it comes from), but the reflected kernel differs: "no" would be wrong
    A = "(tau^2 + 3*(tau^4 - tau^2)*(2*sigma^2 - 1))*2*sigma"
    B = "2*tau"
    own = weights(A, B)
    adj_A, adj_B = adjoint(A, B)
    assert all(weight_sympy(t, adj_A, adj_B) == w for t, w in own.items())
    path = tmp_path / "k.toml"
    path.write_text(f'[continuous]\nA = "{A}"\nb = "{B}"\n[expect]\nsymmetric = true\n', encoding="utf-8")
    run = run_subprocess("verify", str(path), "--order", "6", "--format", "json")
    doc = json.loads(run.out)
    assert doc["summary"]["symmetric"]["state"] == "undecided"
    claim = next(c for c in doc["claims"] if c["claim"] == "symmetric")
    assert claim["found"] == "undecided" and not claim["met"] and run.code == 1
    text = run_subprocess("verify", str(path), "--order", "6")
    assert text.code == 1 and text.out.splitlines()[-1].startswith("CLAIMS NOT SHOWN: 1 of 1")
    assert "BROKEN" not in text.out


def test_the_witness_of_two_tau_sigma_is_sympys():
    # 2τσ: reflected adjoint differs, and sympy finds the adjoint's weight of [[[τ]]] differs
    A, B = "2*tau*sigma", "1"
    t = ((((),),),)
    adj_A, adj_B = adjoint(A, B)
    mine, theirs = weight_sympy(t, *kernel(A, B)), weight_sympy(t, adj_A, adj_B)
    assert (mine, theirs) == (Fraction(2, 9), Fraction(7, 36))
    res = verify(A, B, degree=None, order=4)
    assert res.properties.symmetric.verdict.state == "fails"
    assert "[[[τ]]] is not its adjoint's (2/9 against 7/36)" in res.properties.symmetric.reason
    # and every smaller tree agrees, so no smaller witness was missed
    assert all(weight_sympy(s, adj_A, adj_B) == weight_sympy(s, *kernel(A, B)) for n in (1, 2, 3) for s in rooted_trees(n))


def test_a_box_kernel_is_refuted_only_by_a_tree_that_fails_on_the_whole_box():
    # AVF with a rounded decimal κ in A = κτ: a([τ]) = κ/2 differs from AVF's 1/2 on the
    # whole box of κ = 0.9999990 (± 5e-8), so AVF fails; at κ = 1.000000 the box holds κ = 1
    far = verify("0.9999990*tau", "1", degree=None)
    assert far.avf.verdict.state == "fails" and "[τ]" in far.avf.reason
    near = verify("1.000000*tau", "1", degree=None)
    assert near.avf.verdict.state != "fails"


@pytest.mark.parametrize("make", [
    lambda: ContinuousMethod.from_kernel("sqrt(tau)"),
    lambda: ContinuousMethod.from_kernel("tau", "1/0"),
    lambda: ContinuousMethod.from_matrix([["x"]]),
    lambda: ContinuousMethod.from_matrix([[1, 2], [3]]),
    lambda: rkcheck.loads('[continuous]\nA = "tau"\nM = [[1]]\n'),
    lambda: rkcheck.loads('[tableau]\nA = [["sqrt("]]\nb = [1]\n'),
])
def test_a_method_refused_for_its_content_raises_a_tableau_error(make):
    # docs/api.md and docs/continuous.md: what cannot be built from its content is a TableauError
    with pytest.raises(rkcheck.TableauError):
        make()


def test_a_kernels_quadrature_order_claim_reads_at_least_what_was_checked(tmp_path):
    # AVF's rule (B = 1, C(τ) = τ) integrates every polynomial: ∫ τ^(k−1) dτ = 1/k for all
    # k, so its quadrature order has no bound and the check can only say "≥"
    path = tmp_path / "avf.toml"
    path.write_text('[continuous]\nA = "tau"\n[expect]\nquadrature_order = 7\n', encoding="utf-8")
    doc = json.loads(run_subprocess("verify", str(path), "--order", "6", "--format", "json").out)
    claim = doc["claims"][0]
    assert claim["found"].startswith("≥ ") and int(claim["found"][2:]) > 7 and not claim["met"]


def test_an_irrational_kernel_is_searched_in_certified_balls():
    # A = √2·τ: a([τ]) = ∫√2·τ dτ = √2/2 (by hand), not AVF's 1/2 — found in Arb balls
    res = verify("sqrt(2)*tau", "1", degree=None, order=4)
    assert res.avf.verdict.state == "fails"
    shown = res.avf.reason.split("[τ] is not AVF's (≈ ")[1].split(" ")[0]
    assert abs(float(shown) - 2 ** 0.5 / 2) < 1e-5


def test_the_rooted_trees_searched_are_all_of_them():
    # OEIS A000081: rooted trees with n vertices
    from rkcheck.energy.kernel_series import trees_of

    assert [len(trees_of(n)) for n in range(1, 11)] == [1, 1, 2, 4, 9, 20, 48, 115, 286, 719]
    assert all(len(t) == n and len(set(trees_of(n))) == len(trees_of(n)) for n in range(1, 9) for t in trees_of(n))
