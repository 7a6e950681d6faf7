"""Residues of a degree-bounded listing read off an evaluation of all free trees
(rkcheck.evaluation.contained), as the claims' runs of a file use them.

Independent routes: the residues of the same listing evaluated on their own (no kept
evaluation: every pass run), and each condition's exact residual against the brute-force
reference of SPEC §3 (tests/support/reference.py, its own free trees and rootings)."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from support import reference as ref
from support.paths import TABLEAUX
from support.residues import random_tableau, reference_conditions

import rkcheck.evaluation.modular as modular
from rkcheck.energy.claims import judge_tableau
from rkcheck.evaluation.contained import _signed, contained_residues, contains, tree_map
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_field, scaled_rational
from rkcheck.io.loader import load
from rkcheck.options import CheckOptions
from rkcheck.trees.listing import ConditionListing

ORDER = 8  # conditions with 3 … 9 vertices


def no_passes(monkeypatch):
    """Fail any pass over a listing: what follows must be read off the kept evaluation."""
    def refuse(*args, **kwargs):
        raise AssertionError("a pass was run")

    monkeypatch.setattr(type(scaled_rational([[F(0)]], [F(1)])), "residues_at", refuse)


def evaluated_alone(scaled, listing):
    """The listing's residues with no kept evaluation to read from."""
    kept = scaled.__dict__.pop("_all_trees", None)
    try:
        return exact_condition_sums(scaled, listing)
    finally:
        if kept is not None:
            scaled.__dict__["_all_trees"] = kept


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("degree", [2, 3, 4])
def test_rational_residues_equal_their_own_evaluation_and_the_reference(monkeypatch, seed, degree):
    A, b = random_tableau(seed)
    scaled = scaled_rational(A, b)
    exact_condition_sums(scaled, ConditionListing(ORDER, None))  # the main run: all H, kept
    alone = evaluated_alone(scaled, ConditionListing(ORDER, degree))
    listing = ConditionListing(ORDER, degree)
    with monkeypatch.context() as m:
        no_passes(m)
        read = exact_condition_sums(scaled, listing)
    refs = reference_conditions(ORDER)
    for n, sums in read.items():  # before any value: a value completes the small orders' primes along
        assert sums.primes == alone[n].primes
        assert np.array_equal(sums.residues, alone[n].residues), n
    nonzero = 0
    for n, sums in read.items():
        for k in range(len(sums)):
            rec = listing.record(n, k)
            assert rec.max_degree <= degree
            value = sums.value(k) * listing.flip(n, k)
            assert value == ref.energy_residual(refs[rec.level_sequence], A, b), rec.id
            nonzero += value != 0
    assert nonzero > 0  # random data: not 0 == 0


def test_field_residues_equal_their_own_evaluation():
    # Gauss-3 over Q(√15): two roots per prime, one channel copied from the other
    tab = load(str(TABLEAUX / "collocation" / "gauss-3.toml"))
    scaled = scaled_field(tab.exact_values())
    exact_condition_sums(scaled, ConditionListing(10, None))
    listing = ConditionListing(10, 3)
    read = exact_condition_sums(scaled, listing)
    alone = evaluated_alone(scaled, ConditionListing(10, 3))
    assert any(np.any(s.residues) for s in read.values())
    for n in alone:
        assert np.array_equal(read[n].residues, alone[n].residues), n
        assert read[n].primes == alone[n].primes


def test_only_a_listing_of_all_trees_to_the_order_is_read():
    A, b = random_tableau(3)
    scaled = scaled_rational(A, b)
    low = ConditionListing(6, None)
    sums = exact_condition_sums(scaled, low)
    assert scaled.__dict__["_all_trees"][0] is low
    higher = ConditionListing(ORDER, 3)
    assert not contains(low, higher)  # a lower order
    assert not contains(ConditionListing(ORDER, 4), higher)  # bounded: other tree ids
    assert contained_residues(low, sums, higher, {n: 1 for n in higher.orders}, []) is None
    # more primes than the kept evaluation has
    small = ConditionListing(6, 3)
    count = {n: len(sums[n].primes) + 1 for n in small.orders}
    assert contained_residues(low, sums, small, count, scaled.primes_for(400)) is None


def test_a_tree_map_that_does_not_check_out_is_refused():
    source, listing = ConditionListing(ORDER, None).complete(), ConditionListing(ORDER, 3).complete()
    assert tree_map(source, listing, ORDER) is not None
    source.right[source.first[5]:source.first[6]] = source.right[source.first[5]:source.first[6]][::-1].copy()
    assert tree_map(source, listing, ORDER) is None


def test_signs_negate_residues_modulo_each_prime():
    residues = np.array([[[3], [0]], [[5], [7]]], dtype=np.int32)  # 2 conditions, 2 primes, 1 root
    got = _signed(residues.copy(), np.array([1, -1], dtype=np.int8), [11, 13])
    assert got.tolist() == [[[3], [0]], [[11 - 5], [13 - 7]]]


def test_claims_judged_the_same_with_and_without_reading(monkeypatch):
    # Gauss-3's claims (degree 2: "all", degree 3: exactly 6) after a main run on all H
    def judged():
        tab = load(str(TABLEAUX / "collocation" / "gauss-3.toml"))
        result = judge_tableau(tab, CheckOptions(degree=None, order=9))
        return [(c.claim.kind, c.claim.degree, c.met, c.found, c.note) for c in result.claims]

    real, used = modular._contained, []

    def spy(*args):
        got = real(*args)
        used.append(got is not None)
        return got

    monkeypatch.setattr(modular, "_contained", spy)
    read = judged()
    assert used == [False, True, True]  # the main run evaluates; the runs for degrees 2 and 3 read it
    monkeypatch.setattr(modular, "_contained", lambda *args: None)
    alone = judged()
    assert read == alone
    assert all(met for _, _, met, _, _ in read)


def test_a_pass_sent_to_a_worker_carries_no_kept_evaluation():
    import pickle

    A, b = random_tableau(4)
    scaled = scaled_rational(A, b)
    exact_condition_sums(scaled, ConditionListing(ORDER, None))
    assert "_all_trees" in scaled.__dict__
    sent = pickle.loads(pickle.dumps(scaled))
    assert "_all_trees" not in sent.__dict__
    listing = ConditionListing(4, None)
    assert all(np.array_equal(x, y) for x, y in zip(sent.residues_at(listing, [(sent.primes_for(30)[0][0], 0)], [5]).values(),
                                                   scaled.residues_at(listing, [(scaled.primes_for(30)[0][0], 0)], [5]).values()))
