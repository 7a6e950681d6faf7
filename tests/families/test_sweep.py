"""``rkcheck sweep``: the energy order over a grid of rational parameter values, each
point checked against rkcheck's exact engine on the tableau at that point."""

from __future__ import annotations

import json
import sys
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

import rkcheck
from rkcheck.energy.family_sweep import parse_grid, sweep
from rkcheck.errors import UserError

FAMILIES = TABLEAUX / "families"


def test_grid_values_are_exact_rationals_with_both_ends():
    assert parse_grid("beta=-1:1:5") == ("beta", [Fraction(-1), Fraction(-1, 2), Fraction(0), Fraction(1, 2),
                                                  Fraction(1)])
    assert parse_grid("gamma=1/3") == ("gamma", [Fraction(1, 3)])
    assert parse_grid("x=0:0.1:3") == ("x", [Fraction(0), Fraction(1, 20), Fraction(1, 10)])  # 0.1 is 1/10
    # the entries' grammar: scientific notation and powers, exact
    assert parse_grid("q=1e-3:1:3") == ("q", [Fraction(1, 1000), Fraction(1001, 2000), Fraction(1)])
    assert parse_grid("q=2^-4") == ("q", [Fraction(1, 16)])
    for bad, message in (("q=sqrt(2):2:3", "rational"), ("q=y:1:2", "rational"), ("q=1e5000:1:2", "out of range")):
        with pytest.raises(UserError, match=message):
            parse_grid(bad)


@pytest.mark.parametrize("name", ["sweep-s2-lobatto", "seed-kernel-zeta-0"])
def test_each_point_has_the_order_of_the_tableau_there(name):
    fam = rkcheck.load_family(FAMILIES / f"{name}.toml")
    grids = ["beta=-1:1:5"] + (["gamma=0:1:5"] if "gamma" in fam.parameters else [])
    sw = sweep(fam, grids, 3, 6)
    assert len(sw.orders) == (25 if len(grids) == 2 else 5)
    for point, order in zip(sw.points(), sw.orders):
        assert rkcheck.verify(fam.at(point), degree=3, order=6).energy_order == order, point


def test_the_api_sweep_is_the_command():
    sw = rkcheck.sweep(FAMILIES / "sweep-s2-lobatto.toml", ["beta=0:1:3", "gamma=0:1:3"], degree=3, order=4)
    assert sw.orders == [1, 2, 1] * 3 and sw.generic == 1


def test_the_kernel_family_is_avf_only_at_zero(capsys):
    r = run_cli(capsys, "sweep", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--grid", "beta=-1:1:9", "--json")
    assert r.code == 0, r.err
    doc = json.loads(r.out)
    orders = {p["values"]["beta"]: p["energy_order"] for p in doc["points"]}
    assert orders["0"] == 6 and all(o == 4 for b, o in orders.items() if b != "0")
    assert doc["energy_order_generic"] == 4 and len(doc["grid"]["beta"]) == 9


@pytest.mark.parametrize("degree", ["none", "2", "5"])
def test_the_degree_given_is_the_one_checked(capsys, degree):
    # the file's [check] says degree 3: a degree given on the command line, 'none' too, overrides it
    r = run_cli(capsys, "sweep", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--grid", "beta=-1:1:3", "--order", "8",
                "--degree", degree, "--json")
    assert r.code == 0, r.err
    doc = json.loads(r.out)
    fam = rkcheck.load_family(FAMILIES / "seed-kernel-zeta-0.toml")
    m = None if degree == "none" else int(degree)
    for point in doc["points"]:
        values = {k: Fraction(v) for k, v in point["values"].items()}
        assert point["energy_order"] == rkcheck.verify(fam.at(values), degree=m, order=8).energy_order, point


def test_plot_writes_a_png(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "order.png"
    r = run_cli(capsys, "sweep", str(FAMILIES / "sweep-s2-lobatto.toml"), "--grid", "beta=-1:1:5",
                "--grid", "gamma=0:1:5", "--plot", str(out))
    assert r.code == 0, r.err
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "energy order 2: 5 points" in r.out


def test_plot_without_matplotlib_is_a_one_line_error(capsys, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib now raises ImportError
    r = run_cli(capsys, "sweep", str(FAMILIES / "sweep-s2-lobatto.toml"), "--grid", "beta=0", "--grid",
                "gamma=0:1:3", "--plot", str(tmp_path / "x.png"))
    assert r.code == 2 and r.err.count("\n") == 1 and "rkcheck[plot]" in r.err, r.err


@pytest.mark.parametrize(("grids", "message"), [
    (["beta=-1:1:5"], "no grid or value for the parameter gamma"),
    (["beta=-1:1:5", "delta=0:1:3"], "unknown parameter 'delta'"),
    (["beta=1:-1:5", "gamma=0"], "upwards"),
    (["beta=0:1:x", "gamma=0"], "whole number"),
    (["beta=0:sqrt(2):3", "gamma=0"], "rational number"),
])
def test_bad_grids_are_one_line_errors(capsys, grids, message):
    args = [a for g in grids for a in ("--grid", g)]
    r = run_cli(capsys, "sweep", str(FAMILIES / "sweep-s2-lobatto.toml"), *args)
    assert r.code == 2 and r.err.count("\n") == 1 and message in r.err, r.err


def test_generic_orders_reached_at_the_order_checked_read_at_least(capsys):
    """The κ collocation kernels have B = 1 and C(τ) = τ for every κ: Σ b = 1 (classical
    order 1) and, at order 1, no energy condition — so both generic orders read "≥ 1",
    not an order that the check stopped at."""
    kappa = str(FAMILIES / "continuous-collocation-kappa.toml")
    r = run_cli(capsys, "verify", kappa, "--order", "1")
    assert "energy order for generic parameter values: ≥ 1" in r.out
    assert "classical order for generic parameter values: ≥ 1" in r.out
    r = run_cli(capsys, "sweep", kappa, "--grid", "kappa=0:1:3", "--order", "1")
    assert "energy order for generic parameter values: ≥ 1" in r.out


def test_a_point_that_reaches_the_order_checked_is_listed_as_a_lower_bound(capsys):
    # β = 0 is AVF over Gauss-2 (degree 3: every order); checked to 6, it reads "≥ 6"
    r = run_cli(capsys, "sweep", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--grid", "beta=-1:1:5", "--order", "6")
    assert r.code == 0 and "  beta = 0: ≥ 6" in r.out.splitlines(), r.out
