"""The number contexts of the one weight algorithm against independent values.

* exact residues (multi-modular, ``rkcheck.evaluation.modular``) rebuild exactly the
  residuals of the brute-force reference (``tests/support/reference.py``, Fractions);
* certified balls at any precision, and the float64 screen, enclose those exact values;
* chunked evaluation (small chunks: many partial sums and bins) is bit-identical to
  one-chunk evaluation;
* the float screen never says ``fails`` where exact arithmetic says ``holds``.
"""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
import pytest
from support import reference as ref
from support.heavy import shipped_params
from support.numbers import exact_under
from support.paths import tableau_files

import rkcheck.evaluation.algorithm as algorithm
import rkcheck.trees.classes as classes
import rkcheck.trees.table as table_module
from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.balls import BallContext, FloatContext
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_rational
from rkcheck.evaluation.values import TableauValues
from rkcheck.io.loader import load
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.precision import bits_for_dps
from rkcheck.numbers.reading import DecimalsMode, Reading
from rkcheck.studies.accuracy import evaluate_backend
from rkcheck.trees.listing import ConditionListing
from rkcheck.verdicts import FAILS, HOLDS, classify


def random_tableau(seed: int, big: bool = False):
    rng = random.Random(seed)
    s = rng.randint(1, 4)
    den = 10**9 if big else 12  # large denominators: many channels
    A = [[Fraction(rng.randint(-12, 12), rng.randint(1, den)) for _ in range(s)] for _ in range(s)]
    b = [Fraction(rng.randint(-12, 12), rng.randint(1, den)) for _ in range(s)]
    if rng.random() < 0.5:  # some with Σb = 1, so that low-order conditions can vanish
        b[-1] = 1 - sum(b[:-1])
    if rng.random() < 0.3:  # a dead stage
        b[0] = Fraction(0)
    return A, b


def points(A, b):
    return [[Interval.point(x) for x in r] for r in A], [Interval.point(x) for x in b]


def exact_by_id(listing, A, b):
    sums = exact_condition_sums(scaled_rational(A, b), listing)
    out = {}
    for n, o in sums.items():
        zero = o.is_zero()
        for k in range(len(listing.orders[n])):
            rec = listing.record(n, k)
            value = o.value(k) * listing.flip(n, k)
            assert (value == 0) == bool(zero[k])
            out[rec.level_sequence] = value
    return out


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("degree", [None, 3])
def test_exact_residues_rebuild_the_reference_residuals(seed, degree):
    A, b = random_tableau(seed, big=seed % 3 == 0)
    listing = ConditionListing(7, degree)
    got = exact_by_id(listing, A, b)
    for n in range(3, 9):
        for d in ref.energy_conditions(n, degree):
            assert got[d["id"]] == ref.energy_residual(d, A, b), d["id"]
    assert len(got) == sum(len(ref.energy_conditions(n, degree)) for n in range(3, 9))


@pytest.mark.parametrize("seed", range(4))
def test_chunked_evaluation_is_bit_identical(seed, monkeypatch):
    # tiny chunks split every order into many parts (listing and sums); results must not move
    A, b = random_tableau(seed)
    whole = exact_by_id(ConditionListing(9, None), A, b)
    S, P = points(A, b)
    balls_whole = condition_sums(ConditionListing(9, None), BallContext(S, P, 200), len(b))
    monkeypatch.setattr(algorithm, "_TERM_CHUNK", 5)
    monkeypatch.setattr(classes, "_CHUNK", 7)
    monkeypatch.setattr(table_module, "_CHUNK", 7)
    listing = ConditionListing(9, None)  # built anew with the small chunks (not the cached one)
    assert exact_by_id(listing, A, b) == whole
    balls_chunked = condition_sums(listing, BallContext(S, P, 200), len(b))
    for n in balls_whole:
        assert list(balls_chunked[n].mids) == list(balls_whole[n].mids)


def random_algebraic_tableau(seed: int):
    """Entries ``p + q·sqrt(d)`` (and once ``root(x^3 - 2, 1)``, a cubic field)."""
    from rkcheck.methods.tableau import Tableau

    rng = random.Random(1000 + seed)
    s = rng.randint(2, 3)
    root = "sqrt(2)" if seed % 2 else ("sqrt(3)" if seed % 3 else "root(x^3 - 2, 1)")

    def entry() -> str:
        return f"{rng.randint(-6, 6)}/{rng.randint(1, 9)} + {rng.randint(-4, 4)}/{rng.randint(1, 9)}*{root}"

    return Tableau.from_values([[entry() for _ in range(s)] for _ in range(s)], [entry() for _ in range(s)])


def field_sums(listing, tab):
    from rkcheck.evaluation.scaled import scaled_field

    sums = exact_condition_sums(scaled_field(tab.exact_values()), listing)
    return {n: [o.value(k) for k in range(len(listing.orders[n]))] for n, o in sums.items()}


@pytest.mark.parametrize("seed", range(3))
def test_chunked_evaluation_is_bit_identical_in_number_fields(seed, monkeypatch):
    # the same for algebraic tableaux to order 10, exact field elements
    tab = random_algebraic_tableau(seed)
    assert tab.exact_values().field is not None
    whole = field_sums(ConditionListing(10, None), tab)
    monkeypatch.setattr(algorithm, "_TERM_CHUNK", 5)
    monkeypatch.setattr(classes, "_CHUNK", 7)
    monkeypatch.setattr(table_module, "_CHUNK", 7)
    assert field_sums(ConditionListing(10, None), tab) == whole


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("dps", [15, 50, 400, 1000])
def test_balls_enclose_the_exact_values_at_every_precision(seed, dps):
    A, b = random_tableau(seed)
    listing = ConditionListing(8 if dps <= 50 else 6, None)
    truth = exact_condition_sums(scaled_rational(A, b), listing)
    S, P = points(A, b)
    balls = condition_sums(listing, BallContext(S, P, bits_for_dps(dps)), len(b))
    for n, sums in balls.items():
        for k in range(len(sums)):
            e, t = sums.enclosure(k), truth[n].value(k)
            assert abs(e.mid - t) <= e.rad and e.rad < Fraction(1, 10**dps) * max(1, abs(t))


@pytest.mark.parametrize("seed", range(10))
def test_float_screen_encloses_and_never_fails_where_exact_holds(seed):
    A, b = random_tableau(seed)
    listing = ConditionListing(9, None)
    truth = exact_condition_sums(scaled_rational(A, b), listing)
    S, P = points(A, b)
    screen = condition_sums(listing, FloatContext(S, P), len(b))
    detected = failing = 0
    for n, sums in screen.items():
        zero = truth[n].is_zero()
        for k in range(len(sums)):
            e, t = sums.enclosure(k), truth[n].value(k)
            assert abs(Fraction(e.mid) - t) <= Fraction(e.rad)
            v = classify(e)
            if zero[k]:
                assert v.state != FAILS
            else:
                failing += 1
                detected += v.state == FAILS
    assert failing == 0 or detected / failing > 0.9  # random data fails by O(1): the screen sees it


FILES = tableau_files()


@pytest.mark.parametrize("path", shipped_params(FILES))
def test_shipped_tableaux_balls_agree_with_exact_and_screen_is_safe(path):
    tab = load(path)
    listing = ConditionListing(8, tab.info.check.get("degree"))
    values = TableauValues(tab, Reading(DecimalsMode.ROUNDED))
    balls = evaluate_backend(listing, values, "dps:50")
    if exact_under(tab, "rounded"):
        exact = evaluate_backend(listing, values, "exact")
        screen = evaluate_backend(listing, values, "float64")
        for key, (e, v) in exact.items():
            assert abs(Fraction(balls[key][0].mid) - e.mid) <= balls[key][0].rad
            if v.state == HOLDS:
                assert screen[key][1].state != FAILS and balls[key][1].state != FAILS
            else:
                assert balls[key][1].state == FAILS


def test_block_bins_add_each_conditions_terms_in_their_order():
    # the float screen sums a block's terms per condition through these bins; summed
    # here term by term in Python floats, block after block, the sums must be the same bits
    from rkcheck.evaluation.balls import BlockBins

    rng = np.random.default_rng(7)
    k = 50
    bins, acc = BlockBins(k), [0.0] * k
    sums = np.zeros(k)
    for size in (0, 1, 30, 400, 5):  # the table is reused from block to block
        cond = rng.integers(0, k, size=size).astype(np.int32)
        x = rng.standard_normal(size) * 10.0 ** rng.integers(-8, 8, size=size)
        uniq, inv = bins(cond)
        assert len(set(uniq.tolist())) == len(uniq) and np.array_equal(uniq[inv], cond)
        sums[uniq] += np.bincount(inv, weights=x, minlength=len(uniq))
        block = {}
        for c, v in zip(cond.tolist(), x.tolist()):
            block[c] = block.get(c, 0.0) + v
        for c, v in block.items():
            acc[c] += v
    assert sums.tolist() == acc
