"""``check`` / ``rkcheck verify`` on methods whose energy behaviour is known in closed form."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX  # noqa: E402

from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load
from rkcheck.methods.tableau import Tableau
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS


def avf(nodes: list[str], weights: list[str]) -> Tableau:
    """A = c bᵀ over a quadrature rule given by entry strings (seed, eq. (avfmat))."""
    A = [[f"({ci})*({bj})" for bj in weights] for ci in nodes]
    return Tableau.from_values(A, weights, nodes)


# 2-point Gauss: nodes (3 ∓ √3)/6, weights 1/2 (exact to degree 3)
GAUSS2 = (["1/2 - sqrt(3)/6", "1/2 + sqrt(3)/6"], ["1/2", "1/2"])
# 3-point Gauss: nodes 1/2 ∓ √15/10, 1/2; weights 5/18, 8/18, 5/18 (exact to degree 5)
GAUSS3 = (["1/2 - sqrt(15)/10", "1/2", "1/2 + sqrt(15)/10"], ["5/18", "8/18", "5/18"])
# 2-point Radau IIA: nodes 1/3, 1; weights 3/4, 1/4 (exact to degree 2s-1 = 3), rational
RADAU2 = (["1/3", "1"], ["3/4", "1/4"])


@pytest.mark.parametrize("degree", [3, 4])
def test_avf_gauss2_holds_every_condition_and_is_recognised(degree):
    # sqrt(3) entries are decided exactly in Q(√3): every verdict is `holds`
    res = check(avf(*GAUSS2), CheckOptions(degree=degree, order=8))
    assert res.backend == "exact"
    assert res.failures == []
    assert {r.verdict.state for r in res.conditions} == {HOLDS}
    assert res.avf is not None and res.avf.equals_avf
    assert res.energy_order_all and res.energy_order == 8


def test_avf_gauss2_is_not_avf_for_degree_5():
    # a 2-point rule is exact only to degree 3 < 4 = m - 1: Σ b c^4 = 7/36 ≠ 1/5 (hand computation)
    res = check(avf(*GAUSS2), CheckOptions(degree=5, order=6))
    assert not res.avf.equals_avf and "Σ b_i c_i^4 = 1/5" in res.avf.reason
    assert res.first_failure is not None


def test_avf_gauss3_holds_for_degree_up_to_6_to_order_7():
    for degree in (5, 6):
        res = check(avf(*GAUSS3), CheckOptions(degree=degree, order=7))
        assert res.failures == [] and res.avf.equals_avf


def test_avf_over_a_rational_rule_holds_exactly():
    res = check(avf(*RADAU2), CheckOptions(degree=3, order=8))
    assert res.backend == "exact"
    assert {r.verdict.state for r in res.conditions} == {HOLDS}
    assert res.avf.verdict.state == HOLDS and res.energy_order_all


def test_implicit_midpoint_degree_2_holds_to_order_12():
    res = check(load(str(TABLEAUX / "collocation" / "implicit-midpoint.toml")), CheckOptions(degree=2, order=12))
    # m = 2 leaves the odd paths: one condition per even order 2, 4, ..., 12 (SPEC §3)
    assert [r.vertices for r in res.conditions] == [3, 5, 7, 9, 11, 13]
    assert all(r.verdict.state == HOLDS for r in res.conditions)
    assert res.avf.equals_avf


def test_implicit_midpoint_star_condition_value():
    # star [τ³] ~ [[τ²]]: R = -(Σ b c² - 1/3)/2! (tests/reference.py derivation);
    # midpoint c = 1/2, b = 1: R = -(1/4 - 1/3)/2 = 1/24
    res = check(load(str(TABLEAUX / "collocation" / "implicit-midpoint.toml")), CheckOptions(degree=None, order=3))
    star = next(r for r in res.conditions if r.id == "1,2,2,2")
    assert star.enclosure.mid == Fraction(1, 24) and star.verdict.state == FAILS
    assert res.energy_order == 2


def test_rk4_energy_order_is_4():
    # RK4 has classical order 4, so H(y1) - H(y0) = O(h^5); its local error term at h^5 is a
    # generic combination of elementary differentials, so some 6-vertex condition fails.
    res = check(load(str(TABLEAUX / "explicit" / "rk4.toml")), CheckOptions(degree=None, order=8))
    assert res.energy_order == 4
    assert res.classical.order == 4 and res.quadrature.order == 4
    assert res.first_failure.vertices == 6


def test_decimal_semantics_of_16_digit_avf():
    tab = load(str(TABLEAUX / "avf" / "avf-gauss-2-decimal16.toml"))
    rounded = check(tab, CheckOptions(degree=4, order=8, decimals="rounded"))
    assert rounded.failures == []
    digits = [r.verdict.digits for r in rounded.conditions]
    assert all(r.verdict.state == HOLDS_TO_DIGITS for r in rounded.conditions)
    assert 14 <= min(digits) <= 16  # "holds to ~15 digits": limited by the 16-digit input
    exact = check(tab, CheckOptions(degree=4, order=8, decimals="exact"))
    assert exact.backend == "exact" and exact.failures


def test_fifty_digit_input_limits_the_digits_not_the_precision():
    tab = load(str(TABLEAUX / "avf" / "avf-gauss-2-decimal50.toml"))
    res = check(tab, CheckOptions(degree=4, order=6, dps=80))
    assert res.failures == []
    assert 48 <= res.min_digits <= 50


def test_fail_fast_stops_after_the_first_failing_order():
    tab = load(str(TABLEAUX / "explicit" / "rk4.toml"))
    res = check(tab, CheckOptions(order=8, fail_fast=True))
    assert max(r.order for r in res.conditions) == 5
    assert res.energy_order == 4


# ---------------------------------------------------------------------- CLI


def test_verify_exit_codes_and_json_schema(capsys):
    good = run_cli(capsys, "verify", str(TABLEAUX / "avf" / "avf-gauss-2.toml"), "--format", "json")
    assert good.code == 0
    doc = json.loads(good.out)
    assert doc["schema"] == 1
    for key in ("energy_order", "order_checked", "degree", "equals_avf", "classical_order", "quadrature_order", "per_order"):
        assert key in doc["summary"]
    assert doc["summary"]["equals_avf"] is True and doc["summary"]["degree"] == 4
    cond = doc["conditions"][0]
    for key in ("id", "level_sequence", "bracket", "vertices", "max_degree", "state", "residual", "radius", "digits"):
        assert key in cond
    assert cond["state"] in ("holds", "holds_to_digits", "fails")
    assert len(doc["conditions"]) == doc["summary"]["conditions_total"]

    bad = run_cli(capsys, "verify", str(TABLEAUX / "explicit" / "rk4.toml"), "--format", "json", "--fail-on", "conditions")
    assert bad.code == 1
    doc = json.loads(bad.out)
    assert doc["summary"]["equals_avf"] is None and doc["summary"]["energy_order"] == 4
    fails = [c for c in doc["conditions"] if c["state"] == "fails"]
    assert fails and all(c["residual_exact"] not in (None, "0") for c in fails)


def test_verify_text_report(capsys):
    r = run_cli(capsys, "verify", str(TABLEAUX / "collocation" / "gauss-2.toml"), "--degree", "4", "--fail-on", "conditions")
    assert r.code == 1
    assert "energy order      4" in r.out and "Failing conditions" in r.out and "FAIL:" in r.out


def test_file_check_defaults_are_overridden_by_flags(capsys):
    # implicit-midpoint.toml says degree = 2 (all hold); --degree none brings the failing star
    path = str(TABLEAUX / "collocation" / "implicit-midpoint.toml")
    assert run_cli(capsys, "verify", path, "--fail-on", "conditions").code == 0
    assert run_cli(capsys, "verify", path, "--degree", "none", "--fail-on", "conditions").code == 1


def test_explain_writes_sigma_notation_and_evaluates(capsys):
    r = run_cli(capsys, "explain", "1,2,3,3,2")
    assert r.code == 0
    assert "Σ b_i c_i a_ij c_j" in r.out and "Σ b_i a_ij c_j²" in r.out
    r = run_cli(capsys, "explain", "1,2,2,2", "--tableau", str(TABLEAUX / "collocation" / "implicit-midpoint.toml"))
    assert "1/24" in r.out  # the star value derived above
    r = run_cli(capsys, "explain", "1,2,3,4")  # path of 4 vertices: u∘u with u = [τ]
    assert "superfluous" in r.out


def test_conditions_count_matches_spec(capsys):
    r = run_cli(capsys, "conditions", "--order", "11", "--count", "--format", "json")
    doc = json.loads(r.out)
    # SPEC §3: non-superfluous free trees with n = 3..12 vertices
    assert [c["conditions"] for c in doc["counts"]] == [1, 1, 3, 4, 11, 19, 47, 97, 235, 531]


def test_an_exact_algebraic_verify_never_mentions_digits(capsys):
    # AVF over Gauss-2 ends with an exact certificate and no
    # "digits" anywhere (the per-order table has no digits column for exact arithmetic)
    run = run_cli(capsys, "verify", str(TABLEAUX / "avf" / "avf-gauss-2.toml"))
    assert run.code == 0
    assert "digits" not in run.out.lower()
    assert run.out.rstrip().endswith("(AVF certificate); 66 conditions checked)")
    balls = run_cli(capsys, "verify", str(TABLEAUX / "avf" / "avf-gauss-2.toml"), "--arithmetic", "ball")
    assert "min digits" in balls.out


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_while_the_json_is_written_closes_the_document(sig):
    """The conditions go out as they are made: a signal once the list has begun (seen
    on the pipe, not guessed by a sleep) ends the rows, the document closes, and the
    exit code is 130 — valid JSON whose ``conditions_complete`` is false and whose
    rows are fewer than the conditions checked."""
    env = dict(os.environ, NO_COLOR="1")
    proc = subprocess.Popen([sys.executable, "-m", "rkcheck", "verify", str(TABLEAUX / "explicit" / "rk4.toml"),
                             "--order", "16", "--degree", "none", "--format", "json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    head = []
    while not head or not head[-1].startswith('  "conditions": ['):
        head.append(proc.stdout.readline())
        assert head[-1], "the document ended before its conditions"
    proc.send_signal(sig)
    rest = proc.stdout.read()  # the same buffered reader: nothing it read ahead is lost
    err = proc.stderr.read()
    proc.wait(timeout=120)
    doc = json.loads("".join(head) + rest)
    assert proc.returncode == 130 and "interrupted while writing" in err and "Traceback" not in err
    assert doc["conditions_complete"] is False
    assert len(doc["conditions"]) < doc["summary"]["conditions_checked"]


def test_an_interrupted_check_with_no_failure_is_no_ok(capsys, monkeypatch):
    import rkcheck.energy.check as check
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    def interrupted(*args, **kwargs):
        raise EvaluationInterrupted({})  # Ctrl-C before any order finished

    monkeypatch.setattr(check, "evaluate_orders", interrupted)
    r = run_cli(capsys, "verify", "@rk4", "--order", "6")
    assert r.code == 130 and "(none)" in r.err
    assert "INTERRUPTED: 0 conditions checked before Ctrl-C, none failing; no verdict" in r.out
    assert "OK" not in r.out.splitlines()[-1]


def _stopped_after_order(monkeypatch, last: int) -> None:
    """Ctrl-C with the orders up to ``last`` evaluated (keyed by vertices: order n has n + 1)."""
    import rkcheck.energy.check as check
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    real = check.evaluate_orders

    def interrupted(listing, values, fail_fast=False, progress=None):
        done = real(listing, values, fail_fast)
        raise EvaluationInterrupted({n: done[n].values for n in done if n <= last + 1})

    monkeypatch.setattr(check, "evaluate_orders", interrupted)


def test_an_interrupted_check_claims_no_order_it_did_not_finish(capsys, monkeypatch):
    # RK4's energy order is 4: a condition of order 5 fails.  Stopped with orders 2 and 3
    # finished, the report may claim order 3 and no more — not the 6 asked for
    _stopped_after_order(monkeypatch, 3)
    r = run_cli(capsys, "verify", "@rk4", "--order", "6", "--degree", "none", "--format", "json")
    s = json.loads(r.out)["summary"]
    assert r.code == 130 and s["verdict"] == "interrupted"
    assert (s["energy_order"], s["energy_order_to_digits"], s["energy_order_label"]) == (3, 3, "≥ 3")
    text = run_cli(capsys, "verify", "@rk4", "--order", "6", "--degree", "none")
    assert "≥ 3 (interrupted: every condition up to order 3 holds; order 4 was not finished)" in text.out
    monkeypatch.undo()
    whole = json.loads(run_cli(capsys, "verify", "@rk4", "--order", "6", "--degree", "none", "--format", "json").out)
    assert whole["summary"]["energy_order"] == 4  # the order the interrupted report did not claim beyond


def test_ctrl_c_while_the_conditions_are_listed_still_reports(capsys, monkeypatch):
    # the listing of a high order takes seconds before any condition is evaluated: a
    # Ctrl-C there is a report of nothing finished, valid JSON, not a bare "aborted"
    from rkcheck.trees.listing import ConditionListing

    def stopped(self, *args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(ConditionListing, "ensure", stopped)
    r = run_cli(capsys, "verify", "@rk4", "--order", "6", "--no-cache", "--format", "json")
    s = json.loads(r.out)["summary"]
    assert r.code == 130 and "(none)" in r.err
    assert s["verdict"] == "interrupted" and s["conditions_checked"] == 0
    assert (s["energy_order"], s["energy_order_label"]) == (1, "≥ 1")


def test_an_interrupted_check_with_no_failure_is_neither_passed_nor_proven_in_json(capsys, monkeypatch):
    # RK4 fails conditions at 5 vertices (its energy order is 4): a JSON document of a
    # check stopped before any order finished must not read as a pass or a proof
    import rkcheck.energy.check as check
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    def interrupted(*args, **kwargs):
        raise EvaluationInterrupted({})

    monkeypatch.setattr(check, "evaluate_orders", interrupted)
    r = run_cli(capsys, "verify", "@rk4", "--order", "6", "--format", "json")
    assert r.code == 130
    s = json.loads(r.out)["summary"]
    assert s["interrupted"] and s["verdict"] == "interrupted" and not s["passed"] and not s["proven"]
    monkeypatch.undo()
    finished = run_cli(capsys, "verify", "@rk4", "--order", "6", "--format", "json")
    assert not json.loads(finished.out)["summary"]["interrupted"]


@pytest.mark.parametrize("args", [["verify", "@avf-gauss-2-decimal16", "-q"],
                                  ["verify", "@gauss-2", "--require", "proof", "--arithmetic", "ball", "-q"]])
def test_the_verdict_is_one_line_when_piped_however_long(args):
    # a CI job reads the verdict with `| tail -1`: rich's fixed pipe width must not wrap it
    env = dict(os.environ, NO_COLOR="1", COLUMNS="60")
    proc = subprocess.run([sys.executable, "-m", "rkcheck", *args], capture_output=True, text=True, env=env)
    last = proc.stdout.rstrip("\n").splitlines()[-1]
    assert last.startswith(("OK", "FAIL")) and last.endswith(")") and len(last) > 128


def test_order_one_says_there_is_no_condition_not_all_zero_hold(capsys):
    # by hand: a free tree of one or two vertices carries no energy condition, so order 1
    # (trees of two vertices) has none
    r = run_cli(capsys, "verify", "@heun", "--order", "1", "--degree", "none")
    assert r.out.splitlines()[-1].endswith("OK: no energy condition up to order 1 (the first is of order 2))")


def test_an_interrupted_certified_check_counts_only_the_orders_it_verified(capsys, monkeypatch):
    # AVF over Gauss-2 is certified for degree 4 (every order); stopped with orders 2 and 3
    # done, the report says 3 verified, not the 6 asked for
    _stopped_after_order(monkeypatch, 3)
    r = run_cli(capsys, "verify", "@avf-gauss-2", "--degree", "4", "--order", "6")
    energy = next(line for line in r.out.splitlines() if line.startswith("energy order"))
    assert r.code == 130 and energy.rstrip().endswith("; 3 verified")


def test_ctrl_c_that_click_catches_says_interrupted(capsys, monkeypatch):
    # a command that leaves Ctrl-C to click (listing the conditions) ends as the others
    # do: "interrupted", exit 130
    import rkcheck.api.trees

    def stopped(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(rkcheck.api.trees, "conditions", stopped)
    r = run_cli(capsys, "conditions", "--order", "6")
    assert r.code == 130 and r.err.strip().splitlines()[-1] == "rkcheck: interrupted"
