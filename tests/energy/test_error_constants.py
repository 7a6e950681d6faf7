"""The energy error constant C_m: its value by independent routes, and its meaning checked
against simulation (one step on random polynomial Hamiltonians)."""

from __future__ import annotations

import math
import random
from fractions import Fraction as F

import pytest
from support import reference as ref
from support.heavy import heavy
from support.paths import TABLEAUX

from rkcheck.energy.check import CheckOptions, check
from rkcheck.energy.error_constants import error_constant
from rkcheck.io.loader import load
from rkcheck.methods.tableau import Tableau


def random_tableau(rng, s):
    A = [[F(rng.randint(-6, 6), rng.randint(1, 6)) for _ in range(s)] for _ in range(s)]
    b = [F(rng.randint(-6, 6), rng.randint(1, 6)) for _ in range(s)]
    return A, b


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("degree", [2, 3, None])
def test_the_constant_is_the_norm_of_the_first_failing_residuals(seed, degree):
    # brute force: the first vertex count with a failing condition, the sum of squares there
    rng = random.Random(seed)
    A, b = random_tableau(rng, rng.randint(1, 3))
    res = check(Tableau.from_values(A, b), CheckOptions(degree=degree, order=6))
    ec = error_constant(res)
    for n in range(3, 8):
        residuals = [ref.energy_residual(c, A, b) for c in ref.energy_conditions(n, degree)]
        if any(residuals):
            assert ec is not None and ec.order == n - 1 and ec.energy_order == n - 2
            assert ec.exact and ec.squared == sum(r * r for r in residuals)
            assert ec.conditions == len(residuals) and ec.failing == sum(1 for r in residuals if r)
            return
    assert ec is None


def test_m2_constant_is_half_the_stability_defect():
    # one condition per order for m = 2: C_2 = |e_2k|/2 (RK4: e_6 = 1/72, so C_2 = 1/144)
    res = check(load(str(TABLEAUX / "explicit" / "rk4.toml")), CheckOptions(degree=2, order=8))
    ec = error_constant(res)
    assert ec.squared == F(1, 144) ** 2 and ec.order == 6


def test_no_constant_when_a_certificate_proves_every_order():
    res = check(load(str(TABLEAUX / "collocation" / "lobatto-iiib-3.toml")), CheckOptions(degree=2, order=8))
    assert error_constant(res) is None


def test_enclosed_constants_bound_the_exact_one():
    # a rational tableau written with + sqrt(2) − sqrt(2), checked in balls: same constant
    A = [["0", "0"], ["2/3 + sqrt(2) - sqrt(2)", "0"]]
    b = ["1/4", "3/4"]
    exact = error_constant(check(Tableau.from_values([["0", "0"], ["2/3", "0"]], b), CheckOptions(order=6)))
    balls = error_constant(check(Tableau.from_values(A, b), CheckOptions(order=6, arithmetic="ball")))
    lo, hi = balls.bounds
    assert not balls.exact and lo <= exact.value <= hi and hi - lo < 1e-40


# ------------------------------------------------------------------ simulation

# Explicit third-order methods (Hairer–Nørsett–Wanner I, Table II.1.1) built here, and
# shipped methods; all have energy order exactly 3 for degree-4 Hamiltonians, with
# constants C_4 spread over two decades.
KUTTA3 = ([[0, 0, 0], [F(1, 2), 0, 0], [-1, 2, 0]], [F(1, 6), F(2, 3), F(1, 6)])
SHIPPED = ["explicit/ralston.toml", "explicit/ssprk3.toml", "collocation/radau-iia-2.toml",
           "avf/avf-radau-i-2.toml", "counterexamples/kernel-zeta-third-beta-0.1.toml"]


@heavy
def test_measured_energy_errors_follow_the_constants():
    """One step from random points of 100 random degree-4 Hamiltonians in 3 degrees of
    freedom (rkcheck.dynamics, float64): the leading coefficient L of ΔH/h⁴ (Richardson
    extrapolation of h = 2⁻⁵, 2⁻⁶) must order six methods of energy order 3 exactly as
    C_4 does.  Each sample (H, y₀) is divided by the RMS of L over the six methods at
    that sample, so that every random Hamiltonian weighs the same (raw RMS is dominated
    by the few Hamiltonians with the largest derivatives); then the RMS over samples.

    (This is another norm of the same residual vector — it weights each condition by the
    spread of its elementary Hamiltonian over the random model — so the ratio to C
    differs between methods; the ordering is what C_4 promises.  It held on six
    independent sets of 100 Hamiltonians.)"""
    from rkcheck.dynamics.hamiltonians import random_hamiltonian
    from rkcheck.dynamics.integrator import Float64, RKMethod, step
    from rkcheck.dynamics.simulate import random_points

    tableaux = [load(str(TABLEAUX / p)) for p in SHIPPED] + [Tableau.from_values(*KUTTA3, name="Kutta3")]
    constants = []
    for tab in tableaux:
        ec = error_constant(check(tab, CheckOptions(degree=4, order=5)))
        assert ec is not None and ec.energy_order == 3, tab.name
        constants.append(ec.value)
    ctx = Float64()
    methods = [RKMethod.from_tableau(tab, ctx) for tab in tableaux]
    samples = []  # per (H, y0): L for every method
    for k in range(100):
        ham = random_hamiltonian(4, 3, 1 + k)
        for y in random_points(ham.dim, 2, 101 + k, ctx):
            H0 = ham.energy(y)
            row = []
            for method in methods:
                lead = [(ham.energy(step(method, ham, y, h, ctx)) - H0) / h**4 for h in (2.0**-5, 2.0**-6)]
                row.append(2 * lead[1] - lead[0])  # ΔH/h⁴ = L + O(h): extrapolated to h = 0
            samples.append(row)
    measured = []
    for i in range(len(methods)):
        total = 0.0
        for row in samples:
            scale = math.sqrt(sum(v * v for v in row) / len(row))
            total += (row[i] / scale) ** 2
        measured.append(math.sqrt(total / len(samples)))
    order = sorted(range(len(methods)), key=lambda i: constants[i])
    ranked = [(constants[i], measured[i], tableaux[i].name) for i in order]
    assert all(b[0] > 1.4 * a[0] for a, b in zip(ranked, ranked[1:])), ranked  # well separated
    assert [r[1] for r in ranked] == sorted(r[1] for r in ranked), ranked
