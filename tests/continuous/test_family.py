"""A continuous kernel with a free parameter is a family: its energy conditions vanish
identically when ∂A/∂τ is symmetric for every value, and `solve` finds the parameter of
a classical order (κ = 3: Hairer's energy-preserving collocation, order 4)."""

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
