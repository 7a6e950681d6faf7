"""The joint box of decimal inputs (definitions §5.2) judged in one pass, against routes
derived independently:

* the centre ``R(x̃)`` (balls at the face values) against the brute-force reference
  (``reference.energy_residual``: exact Fractions of SPEC §3) at the face values: the
  ball contains it and is far narrower than the variation; where it would not be, the
  order's centre comes from the residues modulo primes, equal to the reference;
* the decisions ``|R(x̃)| > V`` and the bounds ``|R(x̃)| + V`` against the same formulas
  in Fractions, for balls and for exact centres;
* the derivatives computed one direction per pass (what a box too large for one pass
  gets, instead of being skipped) against all directions in one pass;
* whole ``verify`` reports with the ball centre against the exact centre: the same
  verdicts and digits.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
from support import reference as ref

import rkcheck.evaluation.box as box
import rkcheck.evaluation.slopes as slopes
from rkcheck.energy.check import check
from rkcheck.evaluation.balls import ETA, INFLATE, U, BallSums
from rkcheck.methods.tableau import Tableau
from rkcheck.options import CheckOptions
from rkcheck.trees.listing import ConditionListing

RK4_DECIMAL = (
    [["0", "0", "0", "0"], ["0.5", "0", "0", "0"], ["0", "0.5", "0", "0"], ["0", "0", "1", "0"]],
    ["0.1666666666666667", "0.3333333333333333", "0.3333333333333333", "0.1666666666666667"],
)
#: a dense decimal tableau: every entry an interval (the gradient has 12 directions)
DENSE_DECIMAL = (
    [["0.1428571428571", "-0.2222222222222", "0.2727272727273"],
     ["0.4", "0.125", "-0.1666666666667"],
     ["-0.0833333333333", "0.5555555555556", "0.25"]],
    ["0.2", "0.3", "0.5"],
)
#: Gauss-2 in 16 digits (symmetric nodes 1/2 ± √3/6)
GAUSS2_DECIMAL = (
    [["0.25", "-0.03867513459481288"], ["0.5386751345948129", "0.25"]],
    ["0.5", "0.5"],
)


def _exact(A, b):
    return [[Fraction(x) for x in row] for row in A], [Fraction(x) for x in b]


def _box(A, b):
    from rkcheck.evaluation.values import TableauValues

    values = TableauValues.of(Tableau.from_values(A, b), CheckOptions().reading)
    return values.A, values.b


def _judged(data, listing, orders=None):
    A, b = _box(*data)
    cA, cb = _exact(*data)
    return box.judge_box(listing, A, b, cA, cb, sorted(listing.orders if orders is None else orders))


def _reference(listing, n, A, b):
    by_id = {d["id"]: d for d in ref.energy_conditions(n)}
    return [ref.energy_residual(by_id[listing.record(n, k).level_sequence], A, b) * listing.flip(n, k)
            for k in range(len(listing.orders[n]))]


@pytest.mark.parametrize("data", [RK4_DECIMAL, DENSE_DECIMAL, GAUSS2_DECIMAL])
def test_centre_ball_contains_the_reference_residual_at_the_face_values(data):
    A, b = _exact(*data)
    listing = ConditionListing(7, None)
    judged = _judged(data, listing)
    for n in sorted(listing.orders):
        centre = judged[n].centre
        assert isinstance(centre, box.BallCentre)  # narrow enough: no order needed residues
        for k, expected in enumerate(_reference(listing, n, A, b)):
            e = centre.sums.enclosure(k)
            assert abs(e.mid - expected) <= e.rad
            assert e.rad <= box.CENTRE_SPREAD * Fraction(float(judged[n].variation[k]))


@pytest.mark.parametrize("data", [RK4_DECIMAL, DENSE_DECIMAL])
def test_a_centre_ball_too_wide_takes_the_residues(monkeypatch, data):
    monkeypatch.setattr(box, "CENTRE_SPREAD", 0.0)  # no ball is narrow enough
    A, b = _exact(*data)
    listing = ConditionListing(7, None)
    judged = _judged(data, listing)
    for n in sorted(listing.orders):
        centre = judged[n].centre
        assert isinstance(centre, box.ExactCentre)
        assert [Fraction(x, centre.scale) * listing.flip(n, k) for k, x in enumerate(centre.integers)] == \
            _reference(listing, n, A, b)


def test_exact_decisions_and_bounds_match_the_fraction_formulas():
    rng = np.random.default_rng(7)
    scale = 3**40 * 10**20
    ints = [0, 1, -1, scale, -scale] + [int(x) * 10**int(e) for x, e in zip(rng.integers(-10**9, 10**9, 60),
                                                                             rng.integers(0, 40, 60))]
    variation = np.array([float(Fraction(abs(x) + int(d), scale)) for x, d in
                          zip(ints, rng.integers(-3, 4, len(ints)))])
    variation = np.maximum(variation, ETA)
    centre = box.ExactCentre(ints, scale)
    exact = [Fraction(x, scale) for x in ints]
    assert centre.beyond(variation).tolist() == [abs(c) > Fraction(v) for c, v in zip(exact, variation.tolist())]
    bound = (np.array([float(abs(c)) for c in exact]) * (1 + 4 * U) + variation) * INFLATE + ETA
    assert centre.bound(variation).tobytes() == bound.tobytes()
    assert [centre.enclosure(k, float(v)).mid for k, v in enumerate(variation)] == exact


@pytest.mark.parametrize("bits, shift", [(200, 0), (1200, 200)])
def test_ball_decisions_and_bounds_match_the_fraction_formulas(bits, shift):
    # R = M/(f·2^P) ± ρ/(f·2^S): beyond(V) must mean |R| − ε > V for every such ball (and
    # say so whenever the margin exceeds the rounding of the test), bound ≥ |R| + ε + V
    rng = np.random.default_rng(11)
    f = math.factorial(9)
    scale = f << bits
    mids = [0, 1, -1] + [int(x) << int(e) for x, e in zip(rng.integers(-10**15, 10**15, 200), rng.integers(0, bits - 60, 200))]
    rads = np.abs(rng.standard_normal(len(mids))) * 2.0 ** rng.integers(-60, 60, len(mids))
    sums = BallSums(np.array(mids, dtype=object), rads, bits, shift, f)
    centre = box.BallCentre(sums)
    R = [Fraction(m, scale) for m in mids]
    eps = [Fraction(float(r)) / (f << shift) for r in rads]
    # variations near |R| − ε: on both sides of the decision, some within the rounding
    V = np.array([max(float(abs(r) - e) * float(1 + d), 0.0) for r, e, d in
                  zip(R, eps, rng.choice([-1e-3, -1e-15, 0.0, 1e-15, 1e-3], len(mids)))])
    beyond = centre.beyond(V)
    bound = centre.bound(V)
    for k in range(len(mids)):
        margin = abs(R[k]) - eps[k] - Fraction(float(V[k]))
        if beyond[k]:
            assert margin > 0
        elif margin > abs(R[k]) * Fraction(1, 10**12):
            pytest.fail(f"a clear failure not seen: {k}")
        assert Fraction(float(bound[k])) >= abs(R[k]) + eps[k] + Fraction(float(V[k]))
        e = centre.enclosure(k, float(V[k]))
        assert e.mid == R[k] and e.rad == eps[k] + Fraction(float(V[k]))


@pytest.mark.parametrize("data", [DENSE_DECIMAL, RK4_DECIMAL])
def test_one_direction_per_pass_gives_the_same_variation(monkeypatch, data):
    listing = ConditionListing(9, None)
    whole = _judged(data, listing)
    A, b = _box(*data)
    E = slopes.GradientContext(A, b).E
    monkeypatch.setattr(slopes, "MAX_GRADIENT_BYTES", 1)  # no pass fits: one direction each
    assert len(slopes.gradient_groups(listing, len(b), E)) == E
    split = _judged(data, listing)
    for n in sorted(listing.orders):
        # the same bound up to the order of float summation inside the matrix products
        # (BLAS may sum differently for another shape; each order is covered by the bound)
        assert np.allclose(split[n].variation, whole[n].variation, rtol=1e-12, atol=0)
        assert split[n].excludes_zero().tolist() == whole[n].excludes_zero().tolist()


def _report(data, order):
    result = check(Tableau.from_values(*data), CheckOptions(order=order))
    return json.dumps([(n, o.state.tolist(), o.digits.tolist()) for n, o in sorted(result.conditions.orders.items())]), \
        result.warnings


@pytest.mark.parametrize("data,order", [(RK4_DECIMAL, 11), (DENSE_DECIMAL, 9), (GAUSS2_DECIMAL, 10)])
def test_reports_are_those_of_the_exact_centre(monkeypatch, data, order):
    fast = _report(data, order)
    monkeypatch.setattr(box, "CENTRE_SPREAD", 0.0)  # every order around the exact R(x̃)
    assert _report(data, order) == fast


def test_a_box_too_large_for_one_pass_is_still_judged(monkeypatch):
    free = _report(RK4_DECIMAL, 10)
    monkeypatch.setattr(slopes, "MAX_GRADIENT_BYTES", 1)
    limited = _report(RK4_DECIMAL, 10)
    assert limited == free
    assert not any("too large" in w for w in limited[1])


def test_centre_bits_lie_beyond_the_narrowest_entry():
    A, b = _box(*GAUSS2_DECIMAL)
    # the narrowest entry: 0.03867513459481288, half a unit of its 17th decimal (5e-18),
    # widened at most to the rounding interval of the double it prints (ulp 2^-57 there)
    bits = box.centre_bits(A, b)
    assert Fraction(1, 2**bits) <= Fraction(2**-57) / 2**box.CENTRE_BITS_BEYOND_BOX
    assert Fraction(1, 2**bits) >= Fraction(5, 10**18) / 2**(box.CENTRE_BITS_BEYOND_BOX + 2)


def test_ctrl_c_keeps_the_orders_already_judged():
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    listing = ConditionListing(8, None)
    whole = _judged(RK4_DECIMAL, listing)
    A, b = _box(*RK4_DECIMAL)
    cA, cb = _exact(*RK4_DECIMAL)
    stop_at = sorted(listing.orders)[3]

    def on_order(n, _):
        if n == stop_at:
            raise KeyboardInterrupt

    with pytest.raises(EvaluationInterrupted) as info:
        box.judge_box(listing, A, b, cA, cb, sorted(listing.orders), on_order)
    finished = info.value.finished
    assert sorted(finished) == [n for n in sorted(listing.orders) if n <= stop_at]
    for n, sums in finished.items():  # judged over the box, as the whole run judged them
        assert sums.excludes_zero().tolist() == whole[n].excludes_zero().tolist()
        assert sums.magnitude_bound().tolist() == whole[n].magnitude_bound().tolist()


def test_ctrl_c_in_the_exact_centre_keeps_the_balls_verdicts(monkeypatch):
    from rkcheck.evaluation import modular
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    listing = ConditionListing(7, None)
    whole = _judged(RK4_DECIMAL, listing)
    monkeypatch.setattr(box, "CENTRE_SPREAD", 0.0)  # every order wants the exact centre

    def interrupted(*args, **kwargs):
        raise EvaluationInterrupted({})

    monkeypatch.setattr(modular, "exact_condition_sums", interrupted)
    with pytest.raises(EvaluationInterrupted) as info:
        _judged(RK4_DECIMAL, listing)
    finished = info.value.finished
    assert sorted(finished) == sorted(listing.orders)
    for n, sums in finished.items():  # judged over the box around the balls, never exact sums
        assert isinstance(sums, box.BoxSums) and isinstance(sums.centre, box.BallCentre)
        assert sums.excludes_zero().tolist() == whole[n].excludes_zero().tolist()
