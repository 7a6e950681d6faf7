"""A decimal box's variation bounded along one direction (evaluation/majorant.py) and the
route of ``judge_box`` that decides with it first, against values derived independently:

* the residuals at points of the box from the brute-force reference (exact Fractions):
  ``|R(x) − R(x̃)| ≤ V̄`` wherever x lies in the box;
* the route with every direction over the whole listing (the one the majorant route
  must agree with): the same verdicts, digits and mid-points, the radii of the
  conditions the majorant decided the same bit for bit, the others' close (their sums
  come from other blocks of the same terms: Gauss-3's within 2⁻⁴⁰; where derivatives
  cancel heavily, parts per million, docs/decisions.md).
"""

from __future__ import annotations

import math
import pickle
import random
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from support import reference as ref

from rkcheck.errors import RkcheckError
from rkcheck.evaluation import box as box_module
from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.box import BallCentre, box_radii, judge_box
from rkcheck.evaluation.majorant import MajorantContext
from rkcheck.evaluation.slopes import GradientContext
from rkcheck.evaluation.values import TableauValues
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.reading import Reading
from rkcheck.trees.listing import ConditionListing
from rkcheck.verdicts import classify_bounds


def _decimal(x, digits: int) -> str:
    mpmath.mp.dps = digits + 10
    if isinstance(x, Fraction):
        x = mpmath.mpf(x.numerator) / x.denominator
    return mpmath.nstr(mpmath.mpf(x), digits, min_fixed=-5, max_fixed=5, strip_zeros=False)


def _box(A, b, digits: int):
    """A tableau of ``digits``-digit decimals, its values, face values and radii."""
    tab = Tableau.from_values([[_decimal(x, digits) for x in row] for row in A], [_decimal(x, digits) for x in b])
    assert tab.is_box("auto")
    values = TableauValues(tab, Reading())
    return tab, values


def _gauss3(digits: int):
    mpmath.mp.dps = digits + 20
    r = mpmath.sqrt(15)
    A = [[mpmath.mpf(5) / 36, mpmath.mpf(2) / 9 - r / 15, mpmath.mpf(5) / 36 - r / 30],
         [mpmath.mpf(5) / 36 + r / 24, mpmath.mpf(2) / 9, mpmath.mpf(5) / 36 - r / 24],
         [mpmath.mpf(5) / 36 + r / 30, mpmath.mpf(2) / 9 + r / 15, mpmath.mpf(5) / 36]]
    return _box(A, [mpmath.mpf(5) / 18, mpmath.mpf(4) / 9, mpmath.mpf(5) / 18], digits)


def _majorant(values, tab):
    """The majorant context of a box, its radii laid out per entry."""
    whole = GradientContext(values.A, values.b)
    radii = box_radii(values.A, values.b, tab.exact_A(), tab.exact_b(), whole)
    s = len(values.b)
    rA, rb = [[0.0] * s for _ in range(s)], [0.0] * s
    for r, (i, j) in zip(radii, whole.a_vars):
        rA[i][j] = float(r)
    for r, i in zip(radii[len(whole.a_vars):], whole.b_vars):
        rb[i] = float(r)
    return MajorantContext(rA, rb, tab.exact_A(), tab.exact_b())


@pytest.mark.parametrize("seed", range(4))
def test_the_majorant_bounds_every_change_of_a_residual_on_the_box(seed):
    rng = random.Random(seed)
    s = 3
    A = [[Fraction(rng.randint(-9, 9), rng.randint(1, 9)) for _ in range(s)] for _ in range(s)]
    b = [Fraction(rng.randint(1, 9), rng.randint(1, 9)) for _ in range(s)]
    tab, values = _box(A, b, digits=6)  # wide boxes (six digits): the variation is far from negligible
    listing = ConditionListing(5, None)
    sums = condition_sums(listing, _majorant(values, tab), s, sorted(listing.orders))
    centre_A, centre_b = tab.exact_A(), tab.exact_b()
    boxes = [(x.lo, x.hi) for row in values.A for x in row] + [(x.lo, x.hi) for x in values.b]
    points = [[lo for lo, _ in boxes], [hi for _, hi in boxes]]
    points += [[rng.choice((lo, hi)) for lo, hi in boxes] for _ in range(12)]
    points += [[lo + (hi - lo) * Fraction(rng.randint(0, 100), 100) for lo, hi in boxes] for _ in range(12)]
    checked = 0
    for n, (_, G) in sums.items():
        reference = {c["id"]: c for c in ref.energy_conditions(n)}
        for k in range(len(G)):
            cond = reference[listing.record(n, k).level_sequence]
            at_centre = ref.energy_residual(cond, centre_A, centre_b)
            bound = Fraction(float(G[k, 0]))
            for p in points:
                Ap = [p[i * s:(i + 1) * s] for i in range(s)]
                assert abs(ref.energy_residual(cond, Ap, p[s * s:]) - at_centre) <= bound, (n, k)
            checked += 1
    assert checked == sum(len(listing.orders[n]) for n in listing.orders)


def _both_routes(listing, values, tab, monkeypatch, on_order=None):
    new = judge_box(listing, values.A, values.b, tab.exact_A(), tab.exact_b(), sorted(listing.orders), on_order)
    with monkeypatch.context() as m:
        m.setattr(box_module, "MAJORANT_MIN_VERTICES", 10**6)
        old = judge_box(listing, values.A, values.b, tab.exact_A(), tab.exact_b(), sorted(listing.orders))
    return new, old


def _verdicts(sums):
    return classify_bounds(sums.excludes_zero(), sums.magnitude_bound())


def test_the_majorant_route_gives_the_verdicts_and_enclosures_of_every_direction(monkeypatch):
    tab, values = _gauss3(16)
    listing = ConditionListing(14, None)  # 15 vertices: MAJORANT_MIN_VERTICES
    told = []
    new, old = _both_routes(listing, values, tab, monkeypatch, lambda n, _: told.append(n))
    assert told == sorted(listing.orders)
    decided = opened = 0
    for n in sorted(old):
        a, b = new[n], old[n]
        assert a.refined is not None  # the majorant decided first
        mask = a.refined[2]
        decided, opened = decided + int(mask.sum()), opened + int((~mask).sum())
        for x, y in zip(_verdicts(a), _verdicts(b)):
            assert np.array_equal(x, y), n
        for k in range(len(b)):
            ea, eb = a.enclosure(k), b.enclosure(k)
            assert ea.mid == eb.mid and ea.exact == eb.exact
            if mask[k]:  # decided by V̄, shown with every direction's V: the same
                assert ea.rad == eb.rad
            else:
                assert math.isclose(float(ea.rad), float(eb.rad), rel_tol=2.0**-40, abs_tol=0.0)
    # Gauss-3 satisfies a few of these conditions: both kinds occur, the decided far more
    assert opened > 0 and decided > 20 * opened


def test_results_of_the_majorant_route_pickle_with_what_shows_them(monkeypatch):
    tab, values = _gauss3(16)
    listing = ConditionListing(14, None)
    new, old = _both_routes(listing, values, tab, monkeypatch)
    n = max(new)
    back = pickle.loads(pickle.dumps(new[n]))
    decided = np.flatnonzero(back.refined[2])[:5]
    assert len(decided) == 5
    for k in decided.tolist():
        assert back.enclosure(int(k)) == old[n].enclosure(int(k))


def test_a_method_that_satisfies_most_conditions_takes_every_direction_at_once(monkeypatch):
    # AVF over the 3-point Gauss rule (A = c bᵀ) satisfies every condition of degree ≤ 6:
    # the probe's orders leave most conditions open, and the route gives way
    mpmath.mp.dps = 40
    c = [mpmath.mpf(1) / 2 - mpmath.sqrt(15) / 10, mpmath.mpf(1) / 2, mpmath.mpf(1) / 2 + mpmath.sqrt(15) / 10]
    bw = [mpmath.mpf(5) / 18, mpmath.mpf(4) / 9, mpmath.mpf(5) / 18]
    tab, values = _box([[ci * bj for bj in bw] for ci in c], bw, 16)
    monkeypatch.setattr(box_module, "MAJORANT_MIN_VERTICES", 8)
    listing = ConditionListing(9, None)
    new, old = _both_routes(listing, values, tab, monkeypatch)
    for n in sorted(old):
        assert new[n].refined is None
        assert np.array_equal(new[n].variation, old[n].variation)
        for x, y in zip(_verdicts(new[n]), _verdicts(old[n])):
            assert np.array_equal(x, y)


def test_the_decided_conditions_fail_at_their_centre(monkeypatch):
    # the majorant only ever decides `fails`, and only where the centre's ball lies beyond it
    tab, values = _gauss3(16)
    listing = ConditionListing(14, None)
    new, _ = _both_routes(listing, values, tab, monkeypatch)
    for n, sums in new.items():
        mask = sums.refined[2]
        assert np.all(sums.excludes_zero()[mask])
        assert isinstance(sums.centre, BallCentre) or not mask.any() or np.all(sums.centre.beyond(sums.variation)[mask])


def _outcome(listing, values, tab, minimum, monkeypatch):
    """The verdicts of every order, or the one line a refusal says."""
    with monkeypatch.context() as m:
        m.setattr(box_module, "MAJORANT_MIN_VERTICES", minimum)
        try:
            out = judge_box(listing, values.A, values.b, tab.exact_A(), tab.exact_b(), sorted(listing.orders))
        except RkcheckError as err:
            return str(err)
    return [[x.tolist() for x in _verdicts(out[n])] for n in sorted(out)]


@pytest.mark.parametrize("big", ["1.234567e30", "1.234567e300", "1.234567e320"])
def test_entries_near_or_past_the_float_range_fare_as_with_every_direction(monkeypatch, big):
    # a corner |x̃| + r or a radius past float64's range: the majorant cannot be formed, or
    # claims nothing; whatever every direction gives (verdicts, or a refusal), it gives
    A = [["0.1234567", big, "0.3456789"], ["0.4567891", "0.5678912", "0.6789123"],
         ["0.7891234", "0.8912345", "0.9123456"]]
    tab = Tableau.from_values(A, ["0.2345678", "0.3456789", "0.4197533"])
    values = TableauValues(tab, Reading())
    listing = ConditionListing(8, None)
    assert _outcome(listing, values, tab, 8, monkeypatch) == _outcome(listing, values, tab, 10**6, monkeypatch)


def test_ctrl_c_keeps_the_orders_the_majorant_route_judged(monkeypatch):
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    tab, values = _gauss3(16)
    listing = ConditionListing(14, None)
    whole, _ = _both_routes(listing, values, tab, monkeypatch)
    stop_at = sorted(listing.orders)[-2]

    def on_order(n, _):
        if n == stop_at:
            raise KeyboardInterrupt

    with pytest.raises(EvaluationInterrupted) as info:
        judge_box(listing, values.A, values.b, tab.exact_A(), tab.exact_b(), sorted(listing.orders), on_order)
    finished = info.value.finished
    assert sorted(finished) == [n for n in sorted(listing.orders) if n <= stop_at]
    for n, sums in finished.items():  # judged as the whole run judged them
        assert sums.refined is not None
        for x, y in zip(_verdicts(sums), _verdicts(whole[n])):
            assert np.array_equal(x, y)


def test_an_order_whose_open_conditions_are_many_goes_over_the_listing(monkeypatch):
    # with no subset allowed, each order's open conditions take every direction over the
    # listing: the same verdicts, and then the same radii bit for bit
    tab, values = _gauss3(16)
    listing = ConditionListing(14, None)
    monkeypatch.setattr(box_module.Subset, "build", staticmethod(lambda *args, **kwargs: None))
    new, old = _both_routes(listing, values, tab, monkeypatch)
    for n in sorted(old):
        assert new[n].refined is not None
        for x, y in zip(_verdicts(new[n]), _verdicts(old[n])):
            assert np.array_equal(x, y)
        assert [new[n].enclosure(k) for k in range(len(old[n]))] == [old[n].enclosure(k) for k in range(len(old[n]))]


def test_ctrl_c_during_the_probe_keeps_no_order(monkeypatch):
    # the probe's sums are the majorant's, not verdicts: nothing is finished yet
    from rkcheck.evaluation import algorithm
    from rkcheck.evaluation.algorithm import EvaluationInterrupted

    tab, values = _gauss3(16)
    listing = ConditionListing(14, None)
    real = algorithm._weights_and_sums

    def interrupted(listing, ctx, s, wanted, out, on_order):
        if wanted[-1] <= box_module._PROBE_VERTICES:  # the probe's pass
            real(listing, ctx, s, wanted[:2], out, on_order)
            raise KeyboardInterrupt
        real(listing, ctx, s, wanted, out, on_order)

    monkeypatch.setattr(algorithm, "_weights_and_sums", interrupted)
    with pytest.raises(EvaluationInterrupted) as info:
        judge_box(listing, values.A, values.b, tab.exact_A(), tab.exact_b(), sorted(listing.orders))
    assert info.value.finished == {}
