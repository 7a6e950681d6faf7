"""Degree 1: the brute-force reference finds no energy condition at any order (no free
tree with more than two vertices has maximum degree 1), and by hand every method
preserves linear energy (f = Jg is constant, ΔH = h (Σb) gᵀJg = 0); so a check at
degree 1 proves every order — for tableaux, decimal boxes, kernels and families."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support import reference as ref
from support.clirun import run_subprocess

import rkcheck
from rkcheck.methods.continuous import ContinuousMethod


def test_the_reference_has_no_condition_of_degree_one():
    assert all(ref.energy_conditions(n, 1) == [] for n in range(3, 11))


@pytest.mark.parametrize("method", ["@rk4", "@gauss-2", "@explicit/heun"])
def test_every_order_is_proven_at_degree_one(method):
    run = run_subprocess("verify", method, "--degree", "1", "--format", "json", "--require", "proof")
    assert run.code == 0, run.err
    s = json.loads(run.out)["summary"]
    assert s["energy_order_all"] and s["energy_order_label"] == "all"
    assert s["certificate"]["kind"] == "linear" and s["certificate"]["state"] == "holds"


def test_a_decimal_box_and_a_kernel_are_proven_at_degree_one():
    tab = rkcheck.loads('[tableau]\nA = [["0.5000001"]]\nb = ["0.9999999"]\n', name="box.toml")
    for method in (tab, ContinuousMethod.from_kernel("tau + tau*(sigma - 1/2)")):  # neither AVF nor certified
        summary = rkcheck.verify(method, degree=1, order=6).to_dict()["summary"]
        assert summary["energy_order_all"] and summary["certificate"]["kind"] == "linear"


def test_a_family_has_every_order_for_every_parameter_value_at_degree_one():
    path = Path(__file__).parents[2] / "tableaux" / "families" / "design-s2-m3.toml"
    run = run_subprocess("verify", str(path), "--degree", "1", "--format", "json")
    assert run.code == 0, run.err
    doc = json.loads(run.out)
    assert doc["energy_order_all"] and doc["energy_order_everywhere"]
    assert not [c for c in doc["conditions"] if c["kind"] == "energy"]
