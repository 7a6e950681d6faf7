"""The joint box of decimal inputs (definitions §5.2) computed the fast way, against
routes derived independently:

* the centre ``R(x̃)`` (exact, from one pass of balls rounded to the integer it must be)
  against the brute-force reference (``reference.energy_residual``: exact Fractions of
  SPEC §3) at the face values, and against the residues modulo primes (the route the
  balls replaced, still the fallback);
* the decisions ``|R(x̃)| > V`` and the bound ``|R(x̃)| + V`` against the same formulas in
  Fractions;
* the derivatives computed one direction per pass (what a box too large for one pass
  gets, instead of being skipped) against all directions in one pass (the same up to
  the order of float summation in the matrix products);
* whole ``verify`` reports with the fast centre against the residue route: identical.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
from support import reference as ref

import rkcheck.evaluation.box as box
from rkcheck.energy.check import check
from rkcheck.evaluation.balls import ETA, INFLATE, U
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_rational
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.intervals import Interval
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
    t = Tableau.from_values(A, b)
    from rkcheck.evaluation.values import TableauValues

    values = TableauValues.of(t, CheckOptions().reading)
    return values.A, values.b


@pytest.mark.parametrize("balls_always", [False, True])
@pytest.mark.parametrize("data", [RK4_DECIMAL, DENSE_DECIMAL, GAUSS2_DECIMAL])
def test_centre_is_the_reference_residual_at_the_face_values(monkeypatch, data, balls_always):
    if balls_always:  # the balls also for dense tableaux, which take the residues otherwise
        monkeypatch.setattr(box, "CENTRE_BALL_MAX_NONZERO", 1.0)
    A, b = _exact(*data)
    listing = ConditionListing(7, None)
    got = box.centre_integers(listing, A, b, sorted(listing.orders))
    for n in sorted(listing.orders):
        ints, scale = got[n]
        by_id = {d["id"]: d for d in ref.energy_conditions(n)}
        for k in range(len(listing.orders[n])):
            rec = listing.record(n, k)
            expected = ref.energy_residual(by_id[rec.level_sequence], A, b)
            assert Fraction(ints[k], scale) * listing.flip(n, k) == expected


@pytest.mark.parametrize("data,order", [(RK4_DECIMAL, 12), (DENSE_DECIMAL, 10), (GAUSS2_DECIMAL, 11)])
def test_centre_equals_the_residue_route(data, order):
    A, b = _exact(*data)
    listing = ConditionListing(order, None)
    wanted = sorted(listing.orders)
    got = box.centre_integers(listing, A, b, wanted)
    residues = exact_condition_sums(scaled_rational(A, b), listing, wanted)
    for n in wanted:
        assert got[n] == (residues[n].integers(), residues[n].scale)


def test_a_ball_too_wide_falls_back_to_residues(monkeypatch):
    A, b = _exact(*DENSE_DECIMAL)
    listing = ConditionListing(8, None)
    wanted = sorted(listing.orders)
    calls = []
    real = box._round_to_integers

    def spy(sums, dpow):
        out = real(sums, dpow)
        calls.append(out is None)
        return out

    monkeypatch.setattr(box, "_round_to_integers", spy)
    monkeypatch.setattr(box, "CENTRE_GUARD_BITS", -60)  # far too few bits: balls wider than 1
    monkeypatch.setattr(box, "CENTRE_BALL_MAX_NONZERO", 1.0)  # balls first, although dense
    got = box.centre_integers(listing, A, b, wanted)
    assert any(calls)  # the fallback ran
    residues = exact_condition_sums(scaled_rational(A, b), listing, wanted)
    for n in wanted:
        assert got[n] == (residues[n].integers(), residues[n].scale)


def test_decisions_and_bounds_match_the_fraction_formulas():
    rng = np.random.default_rng(7)
    scale = 3**40 * 10**20
    ints = [0, 1, -1, scale, -scale] + [int(x) * 10**int(e) for x, e in zip(rng.integers(-10**9, 10**9, 60),
                                                                             rng.integers(0, 40, 60))]
    variation = np.array([float(Fraction(abs(x) + int(d), scale)) for x, d in
                          zip(ints, rng.integers(-3, 4, len(ints)))] + [])
    variation = np.maximum(variation, ETA)
    refinement = box.BoxRefinement(ints, scale, variation)
    centre = [Fraction(x, scale) for x in ints]
    fails = [abs(c) > Fraction(v) for c, v in zip(centre, variation.tolist())]
    assert refinement.fails().tolist() == fails
    bound = (np.array([float(abs(c)) for c in centre]) * (1 + 4 * U) + variation) * INFLATE + ETA
    assert refinement.bound().tobytes() == bound.tobytes()
    assert refinement.centre == centre


@pytest.mark.parametrize("data", [DENSE_DECIMAL, RK4_DECIMAL])
def test_one_direction_per_pass_gives_the_same_variation(monkeypatch, data):
    A, b = _box(*data)
    cA, cb = _exact(*data)
    listing = ConditionListing(9, None)
    wanted = sorted(listing.orders)
    whole = box.refine_box(listing, A, b, cA, cb, wanted)
    E = box.GradientContext(A, b).E
    monkeypatch.setattr(box, "MAX_GRADIENT_BYTES", 1)  # no pass fits: one direction each
    assert len(box.gradient_groups(listing, len(b), E)) == E
    split = box.refine_box(listing, A, b, cA, cb, wanted)
    for n in wanted:
        # the same bound up to the order of float summation inside the matrix products
        # (BLAS may sum differently for another shape; each order is covered by the bound)
        assert np.allclose(split[n].variation, whole[n].variation, rtol=1e-12, atol=0)
        assert split[n].integers == whole[n].integers


def _report(data, order):
    result = check(Tableau.from_values(*data), CheckOptions(order=order))
    return json.dumps([(n, o.state.tolist(), o.digits.tolist()) for n, o in sorted(result.conditions.orders.items())]), [
        str(c.enclosure) for c in result.conditions], result.warnings


@pytest.mark.parametrize("data,order", [(RK4_DECIMAL, 11), (DENSE_DECIMAL, 9), (GAUSS2_DECIMAL, 10)])
def test_reports_are_those_of_the_residue_route(monkeypatch, data, order):
    fast = _report(data, order)
    monkeypatch.setattr(box, "_round_to_integers", lambda sums, dpow: None)  # every order by residues
    assert _report(data, order) == fast


def test_a_box_too_large_for_one_pass_is_still_judged(monkeypatch):
    free = _report(RK4_DECIMAL, 10)
    monkeypatch.setattr(box, "MAX_GRADIENT_BYTES", 1)
    limited = _report(RK4_DECIMAL, 10)
    assert limited == free
    assert not any("too large" in w for w in limited[2])


def test_guard_bits_cover_the_rounding_of_a_long_pass():
    # the ball's radius after a pass is far below 2^-CENTRE_GUARD_BITS of the integer's
    # bound: no order of these needed the fallback
    A, b = _exact(*RK4_DECIMAL)
    listing = ConditionListing(12, None)
    scaled = scaled_rational(A, b)
    from rkcheck.evaluation.algorithm import condition_sums
    from rkcheck.evaluation.balls import BallContext

    bits = max(scaled.coefficient_bits(n, listing.orders[n].max_terms) for n in listing.orders) + box.CENTRE_GUARD_BITS
    sums = condition_sums(listing, BallContext([[Interval(x, x) for x in r] for r in A], [Interval(x, x) for x in b], bits),
                          4, sorted(listing.orders))
    for n, s in sums.items():
        assert box._round_to_integers(s, scaled.d ** (n - 1)) is not None
        assert math.isfinite(float(np.max(s.rads)))


def test_a_listing_too_large_for_the_balls_takes_the_residues(monkeypatch):
    A, b = _exact(*GAUSS2_DECIMAL)
    listing = ConditionListing(9, None)
    wanted = sorted(listing.orders)
    fast = box.centre_integers(listing, A, b, wanted)
    monkeypatch.setattr(box, "MAX_CENTRE_BALL_BYTES", 0)
    monkeypatch.setattr(box, "_round_to_integers", lambda sums, dpow: pytest.fail("no balls expected"))
    assert box.centre_integers(listing, A, b, wanted) == fast


def test_a_dense_tableau_takes_the_residues_and_a_sparse_one_the_balls(monkeypatch):
    # every weight of the dense tableau may be nonzero: residues (faster there); RK4's
    # pattern of zeros leaves 8 % of the weights to 14 vertices nonzero: balls
    calls = []
    real = box._round_to_integers
    monkeypatch.setattr(box, "_round_to_integers", lambda sums, dpow: calls.append(1) or real(sums, dpow))
    listing = ConditionListing(9, None)
    wanted = sorted(listing.orders)
    A, b = _exact(*DENSE_DECIMAL)
    dense = box.centre_integers(listing, A, b, wanted)
    assert not calls
    residues = exact_condition_sums(scaled_rational(A, b), listing, wanted)
    assert all(dense[n] == (residues[n].integers(), residues[n].scale) for n in wanted)
    large = ConditionListing(14, None)
    box.centre_integers(large, *_exact(*RK4_DECIMAL), sorted(large.orders))
    assert calls


def test_the_support_counter_counts_the_weights_that_are_not_zero():
    # RK4's weights by brute force (the reference's elementary weight vectors, exact):
    # a weight the counter calls zero is zero, and it counts every one that is not
    from rkcheck.evaluation.algorithm import store_weights

    A, b = _exact(*RK4_DECIMAL)
    listing = ConditionListing(7, None)
    top = max(listing.orders)
    counter = box._SupportCounter(A, b)
    store_weights(listing, counter, 4, top)
    seq_of = listing.tree_level_sequence
    nonzero = 0
    for t in range(listing.first[top]):  # the stored a and w: trees with <= top − 1 vertices
        seq = seq_of(t)
        phi = ref.elementary_weight_vector(seq, A)
        a = ref.elementary_weight(seq, A, b)
        nonzero += a != 0
        if t < listing.first[max(top - 1, 2)]:  # φ and ψ up to top − 2 vertices
            psi = [sum(A[i][j] * phi[j] for j in range(4)) for i in range(4)]
            nonzero += sum(x != 0 for x in phi) + sum(x != 0 for x in psi)
    # w(u) = Π a(children): nonzero exactly when every child's a is (exact values)
    for t in range(listing.first[top]):
        kids = ref.subtrees_at_root(seq_of(t))
        nonzero += all(ref.elementary_weight(k, A, b) != 0 for k in kids)
    # the pattern bounds the count from above; RK4's entries are nonnegative, so no sum
    # cancels and the bound is the count
    assert counter.nonzero == nonzero


def test_entries_too_large_for_float_radii_take_the_residues():
    # entries near 1e200: the balls' float radii overflow (a UserError in a ball check);
    # the centre comes from the residues instead, and equals the reference
    A = [[Fraction(0), Fraction(0)], [Fraction(10**200, 3), Fraction(0)]]
    b = [Fraction(10**200, 7), Fraction(1, 3)]
    listing = ConditionListing(6, None)
    got = box.centre_integers(listing, A, b, sorted(listing.orders))
    for n in sorted(listing.orders):
        ints, scale = got[n]
        by_id = {d["id"]: d for d in ref.energy_conditions(n)}
        for k in range(len(listing.orders[n])):
            expected = ref.energy_residual(by_id[listing.record(n, k).level_sequence], A, b)
            assert Fraction(ints[k], scale) * listing.flip(n, k) == expected
