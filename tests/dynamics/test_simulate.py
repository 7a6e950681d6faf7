"""Energy in practice: empirical energy orders against verify, the integrator's orders on
the harmonic oscillator (exact solution), and Newton's failure as an error."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import pytest
from support.clirun import run_cli
from support.heavy import heavy
from support.paths import TABLEAUX, tableau_files

from rkcheck.dynamics.hamiltonians import problem
from rkcheck.dynamics.integrator import Float64, NewtonError, RKMethod, integrate, step
from rkcheck.dynamics.simulate import energy_order_agreement, fit_energy_order
from rkcheck.io.loader import load
from rkcheck.methods.families import FamilySpec, family_tableau


def test_rk4_energy_order_on_random_quartic():
    fit = fit_energy_order(load(str(TABLEAUX / "explicit" / "rk4.toml")), problem("random:degree=4"))
    assert abs(fit.empirical_order - 4) <= 0.2


def test_pseudo_energy_preserving_method_has_energy_order_4_for_all_h():
    # energy order 4 (conditions up to 5 vertices) with classical order 2; degree 6 > the
    # largest vertex degree of any 6-vertex tree, so this H is generic for that order
    tab = load(str(TABLEAUX / "pseudo-energy-preserving" / "cmmoqw-3stage.toml"))
    fit = fit_energy_order(tab, problem("random:degree=6"))
    assert abs(fit.empirical_order - 4) <= 0.2


def test_avf_stays_at_solver_precision():
    tab = load(str(TABLEAUX / "avf" / "avf-gauss-2.toml"))
    fit = fit_energy_order(tab, problem("random:degree=4"), dps=40)
    assert fit.at_solver_precision and fit.slope is None
    assert all(float(r.high) < 1e-30 for r in fit.rows)


def test_seed_kernel_family_has_the_order_verify_reports():
    tab = family_tableau(FamilySpec("kernel", 2, zeta=Fraction(1, 2), beta=Fraction(1, 10)))
    ham = problem("random:degree=3")
    fit, agreement = energy_order_agreement(tab, ham)
    assert agreement.algebraic == "3" and agreement.agree
    assert abs(fit.empirical_order - 3) <= 0.2


@pytest.mark.parametrize("name, order", [
    ("explicit/euler.toml", 1), ("explicit/rk4.toml", 4), ("collocation/implicit-midpoint.toml", 2),
    ("collocation/gauss-2.toml", 4), ("collocation/radau-iia-3.toml", 5), ("explicit/ssprk3.toml", 3),
])
def test_integrator_reproduces_the_harmonic_oscillator_to_the_methods_order(name, order):
    # y' = J⁻¹∇H (seed): q' = −p, p' = q, so from (1, 0): q = cos t, p = sin t
    ham, ctx = problem("harmonic"), Float64()
    method = RKMethod.from_tableau(load(str(TABLEAUX / name)), ctx)
    errors = []
    for n in (16, 32, 64):
        _, ys, _ = integrate(method, ham, [1.0, 0.0], 1.0 / n, n, ctx)
        q, p = ys[-1]
        errors.append(math.hypot(q - math.cos(1.0), p - math.sin(1.0)))
    observed = [math.log2(errors[i] / errors[i + 1]) for i in range(2)]
    assert all(abs(o - order) <= 0.15 for o in observed), observed


def test_newton_failure_is_an_error_not_a_wrong_number(capsys):
    # large steps on a random quartic H: the Newton iteration of 2-stage Gauss diverges
    # from the predictor (at h = 1 it converges)
    tab = load(str(TABLEAUX / "collocation" / "gauss-2.toml"))
    ham, ctx = problem("random:degree=4"), Float64()
    method = RKMethod.from_tableau(tab, ctx)
    y0 = [0.3, -0.2, 0.1, 0.4]
    step(method, ham, y0, 1.0, ctx)
    with pytest.raises(NewtonError):
        step(method, ham, y0, 3.0, ctx)
    r = run_cli(capsys, "simulate", str(TABLEAUX / "collocation" / "gauss-2.toml"),
                "--problem", "random:degree=4", "--h", "5", "--steps", "3")
    assert r.code == 2 and "Newton's method did not converge at step 1" in r.err


def test_simulate_and_workprec_commands(capsys, tmp_path):
    r = run_cli(capsys, "simulate", str(TABLEAUX / "explicit" / "rk4.toml"), "--problem", "random:degree=4",
                "--energy-order", "--points", "2")
    assert r.code == 0 and "agree: algebraic energy order 4" in r.out
    r = run_cli(capsys, "simulate", str(TABLEAUX / "avf" / "avf-gauss-2.toml"), "--problem", "henon-heiles",
                "--h", "1/5", "--steps", "50")
    assert r.code == 0 and "max |ΔH|" in r.out
    r = run_cli(capsys, "workprec", str(TABLEAUX / "explicit" / "rk4.toml"), "--problem", "harmonic",
                "--T", "1", "--steps", "8,16")
    assert r.code == 0 and "error at T" in r.out
    r = run_cli(capsys, "simulate", str(TABLEAUX / "explicit" / "rk4.toml"), "--problem", "random:dim=2")
    assert r.code == 2 and "random needs degree=m" in r.err


# ---------------------------------------- agreement with verify, shipped tableaux


def _energy_claims():
    out = []
    for path in tableau_files():
        for claim in load(path).info.claims:
            if claim.kind == "energy_order":
                out.append((path, claim.degree, claim.value))
    return out


def _claim_params():
    # HBVM(6, ·) (the 48-degree field, or 60 digits) and Hamiltonians of degree 7 or more
    # take seconds per claim: CI's heavy run
    return [pytest.param(path, degree, value, id=f"{Path(path).relative_to(TABLEAUX)}-m{degree}",
                         marks=[heavy] if "hbvm-6-" in path or (degree or 0) >= 7 else [])
            for path, degree, value in _energy_claims()]


@pytest.mark.parametrize("path, degree, value", _claim_params())
def test_one_step_energy_order_agrees_with_verify_on_every_shipped_claim(path, degree, value):
    tab = load(path)
    m = degree if degree is not None else 6  # degree 6 covers every tree with <= 6 vertices
    if degree is None and isinstance(value, int) and value > 4:
        pytest.skip("a claim beyond order 4 for all H needs a higher-degree H than this test uses")
    n = value if isinstance(value, int) else 0
    # a small step range (2^-6..2^-11) and three points keep CI fast
    fit, agreement = energy_order_agreement(tab, problem(f"random:degree={m}"), points=3,
                                            exponents=range(6, 12), order=max(10, n + 1))
    assert agreement.agree, agreement.message
