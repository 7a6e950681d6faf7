"""The tableau's own properties in verify/show reports (text and JSON keys).

Expected values come from sympy (the defect matrix), the brute-force reference (the
residuals whose squares make the error constant) and by hand (R for RK4)."""

from __future__ import annotations

import json
from fractions import Fraction as F

import sympy
from support import reference as ref
from support.clirun import run_cli
from support.paths import TABLEAUX

RK4 = str(TABLEAUX / "explicit" / "rk4.toml")
RK4_A = [[0, 0, 0, 0], [F(1, 2), 0, 0, 0], [0, F(1, 2), 0, 0], [0, 0, 1, 0]]
RK4_b = [F(1, 6), F(1, 3), F(1, 3), F(1, 6)]


def test_verify_json_has_the_property_keys(capsys):
    r = run_cli(capsys, "verify", RK4, "--format", "json")
    s = json.loads(r.out)["summary"]
    # BA + AᵀB − bbᵀ by sympy; its largest |entry|
    A, b = sympy.Matrix(RK4_A), sympy.Matrix(RK4_b)
    M = sympy.diag(*b) * A + A.T * sympy.diag(*b) - b * b.T
    assert s["symplectic"]["state"] == "fails" and F(s["symplectic"]["defect"]) == F(str(max(abs(x) for x in M)))
    assert s["symmetric"]["state"] == "fails" and s["symmetric"]["permutation"] is None
    assert s["stability"]["defect"] == "R(z)R(−z) − 1 = z⁶/72 + z⁸/576"
    assert s["stability"]["numerator"] == ["1", "1", "1/2", "1/6", "1/24"] and s["stability"]["denominator"] == ["1"]
    assert s["reduction"] == {"stages": 4, "reduced_stages": 4, "classes": [[1], [2], [3], [4]], "dropped": [],
                              "cancelled": [], "exact": True}
    # RK4 (all H) first fails at 6 vertices: C² = Σ R² over those conditions, by brute force
    squares = sum(ref.energy_residual(c, RK4_A, RK4_b) ** 2 for c in ref.energy_conditions(6))
    ec = s["error_constant"]
    assert ec["norm"] == "euclidean" and ec["order"] == 5 and ec["energy_order"] == 4
    assert F(ec["squared"]) == squares and ec["conditions"] == len(ref.energy_conditions(6))


def test_verify_text_has_the_property_lines(capsys):
    out = run_cli(capsys, "verify", str(TABLEAUX / "collocation" / "lobatto-iiib-3.toml")).out
    lines = {line.split("  ")[0]: line for line in out.splitlines()}
    assert lines["symplectic"].split()[1] == "no" and "1/36" in lines["symplectic"]
    assert "with the stages in reversed order, exactly" in lines["symmetric"]
    assert "R(z) = (1 + z/2 + z²/12) / (1 − z/2 + z²/12)" in lines["stability"]
    assert "stability-function certificate" in out


def test_the_certificate_kind_is_stability_for_lobatto_iiib_3(capsys):
    doc = json.loads(run_cli(capsys, "verify", str(TABLEAUX / "collocation" / "lobatto-iiib-3.toml"),
                             "--format", "json").out)
    s = doc["summary"]
    assert s["certificate"]["kind"] == "stability" and s["energy_order_all"] is True
    assert s["stability"]["identity"] == {"state": "holds", "digits": None}


def test_show_prints_R(capsys):
    out = run_cli(capsys, "show", RK4).out
    assert "R(z) = 1 + z + z²/2 + z³/6 + z⁴/24;  R(z)R(−z) − 1 = z⁶/72 + z⁸/576" in out
    doc = json.loads(run_cli(capsys, "show", RK4, "--format", "json").out)
    assert doc["stability"]["leading_power"] == 6 and doc["stability"]["leading_coefficient"] == "1/72"
