"""Screened exact evaluations (rkcheck.evaluation.modular, rkcheck.evaluation.subset):
after a pass over the listing modulo the first prime, the further primes are evaluated
only for the conditions that are zero there, on the trees their terms need.

Independent routes: a pass over the whole listing in the same channels (every condition,
no subset), an evaluation that is not screened, and each condition's exact residual
against the brute-force reference of SPEC §3 (tests/support/reference.py)."""

from __future__ import annotations

import random
from fractions import Fraction as F

import numpy as np
import pytest
from support import reference as ref
from support.paths import TABLEAUX
from support.residues import random_tableau, reference_conditions

import rkcheck.evaluation.modular as modular
import rkcheck.evaluation.scaled as scaled_module
import rkcheck.evaluation.subset as subset_module
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_field, scaled_rational
from rkcheck.evaluation.subset import Subset
from rkcheck.io.loader import load
from rkcheck.trees.listing import ConditionListing

ORDER = 8  # conditions with 3 … 9 vertices


def lobatto_iiia_3():
    """Lobatto IIIA with 3 stages (rational, symmetric: many conditions hold)."""
    A = [[F(0), F(0), F(0)], [F(5, 24), F(1, 3), F(-1, 24)], [F(1, 6), F(2, 3), F(1, 6)]]
    return A, [F(1, 6), F(2, 3), F(1, 6)]


def gauss_3():
    return scaled_field(load(str(TABLEAUX / "collocation" / "gauss-3.toml")).exact_values())


def one_channel_per_pass(monkeypatch):
    """Listings this small fit every channel in one pass: one per pass makes them screen."""
    monkeypatch.setattr(scaled_module, "PASS_BYTES", 0)


def not_screened(scaled, listing, monkeypatch):
    with monkeypatch.context() as m:
        m.setattr(modular, "_screened", lambda *args: False)
        return exact_condition_sums(scaled, listing)


@pytest.mark.parametrize("make", ["random", "lobatto", "gauss"])
def test_subset_residues_equal_a_pass_over_the_listing(make):
    # any conditions (zero or not), every order, several primes and roots at once
    if make == "gauss":
        scaled = gauss_3()
    else:
        scaled = scaled_rational(*(lobatto_iiia_3() if make == "lobatto" else random_tableau(5)))
    listing = ConditionListing(ORDER, None)
    rng = random.Random(7)
    selected = {n: np.array(sorted(rng.sample(range(len(listing.orders[n])), max(1, len(listing.orders[n]) // 3))))
                for n in listing.orders}
    subset = Subset.build(listing, selected, scaled.s)
    assert subset is not None
    assert len(subset.trees) < listing.first[ORDER + 1]  # not every tree
    pairs = [(p, r) for p, roots in scaled.primes_for(70) for r in roots]
    got = subset.residues(scaled.channels(pairs))
    whole = scaled.residues_at(listing, pairs, list(listing.orders))
    for n in listing.orders:
        assert np.array_equal(got[n], whole[n][selected[n]]), n


@pytest.mark.parametrize("make", ["random", "lobatto"])
def test_screened_verdicts_and_values_equal_the_reference(monkeypatch, make):
    A, b = lobatto_iiia_3() if make == "lobatto" else random_tableau(2)
    one_channel_per_pass(monkeypatch)
    scaled = scaled_rational(A, b)
    listing = ConditionListing(ORDER, None)
    sums = exact_condition_sums(scaled, listing)
    assert any(o.full is not None for o in sums.values())  # screened
    plain = not_screened(scaled_rational(A, b), ConditionListing(ORDER, None), monkeypatch)
    refs = reference_conditions(ORDER)
    for n, o in sums.items():
        assert np.array_equal(o.is_zero(), plain[n].is_zero()), n
        assert np.array_equal(o.residues, plain[n].residues), n  # the rest evaluated on demand
        for k, value in enumerate(o.values()):
            rec = listing.record(n, k)
            assert value * listing.flip(n, k) == ref.energy_residual(refs[rec.level_sequence], A, b), rec.id
    if make == "lobatto":
        assert any(o.is_zero().any() and not o.is_zero().all() for o in sums.values())


def test_screened_field_verdicts_equal_unscreened(monkeypatch):
    one_channel_per_pass(monkeypatch)
    scaled = gauss_3()
    sums = exact_condition_sums(scaled, ConditionListing(10, None))
    plain = not_screened(scaled, ConditionListing(10, None), monkeypatch)
    assert any(o.full is not None for o in sums.values())
    for n, o in sums.items():
        zero = o.is_zero()
        assert np.array_equal(zero, plain[n].is_zero()), n
        full = len(o.primes) if o.full is None else o.full
        # the known residues are those of the unscreened evaluation
        assert np.array_equal(o.screened[:, :full], plain[n].residues[:, :full]), n
        assert np.array_equal(o.screened[zero], plain[n].residues[zero]), n
        k = int(np.flatnonzero(~zero)[0]) if (~zero).any() else None
        if k is not None:
            assert o.value(k) == plain[n].value(k)


def test_many_zeros_are_evaluated_over_the_listing(monkeypatch):
    # every condition selected is no subset: the passes go on over the listing
    one_channel_per_pass(monkeypatch)
    monkeypatch.setattr(subset_module, "_CHUNK", 0)  # the share decides even on small listings
    A, b = [[F(1, 4), F(1, 4)], [F(1, 4), F(1, 4)]], [F(1, 2), F(1, 2)]
    listing = ConditionListing(ORDER, None)
    selected = {n: np.arange(len(listing.orders[n])) for n in listing.orders}
    assert Subset.build(listing, selected, 2) is None
    monkeypatch.setattr(Subset, "build", staticmethod(lambda *args: None))
    sums = exact_condition_sums(scaled_rational(A, b), listing)
    plain = not_screened(scaled_rational(A, b), ConditionListing(ORDER, None), monkeypatch)
    for n, o in sums.items():
        assert o.full is None
        assert np.array_equal(o.is_zero(), plain[n].is_zero())


def test_claims_read_screened_residues_of_the_main_run(monkeypatch):
    one_channel_per_pass(monkeypatch)
    A, b = lobatto_iiia_3()
    scaled = scaled_rational(A, b)
    exact_condition_sums(scaled, ConditionListing(ORDER, None))  # the main run, screened and kept
    listing = ConditionListing(ORDER, 3)
    with monkeypatch.context() as m:
        m.setattr(type(scaled), "residues_at", lambda *args: (_ for _ in ()).throw(AssertionError("a pass was run")))
        read = exact_condition_sums(scaled, listing)
        zeros = {n: o.is_zero() for n, o in read.items()}
    assert any(o.full is not None for o in read.values())
    refs = reference_conditions(ORDER)
    for n, o in read.items():
        for k in range(len(o)):
            rec = listing.record(n, k)
            want = ref.energy_residual(refs[rec.level_sequence], A, b)
            assert zeros[n][k] == (want == 0), rec.id
            assert o.value(k) * listing.flip(n, k) == want, rec.id


def test_a_runner_s_passes_after_the_first_prime_are_left_when_screened(monkeypatch):
    # a runner is given every pass; once the first prime is complete and its zeros are
    # few, the others are not waited for (closing the runner: a cluster cancels them)
    from rkcheck.evaluation.passes import passes_run_by

    one_channel_per_pass(monkeypatch)
    A, b = lobatto_iiia_3()
    sent, ran, closed = [], [], []

    def runner(scaled, listing, jobs):
        sent.extend(jobs)
        try:
            for g, (pairs, orders) in enumerate(jobs):
                ran.append(g)
                yield g, scaled.residues_at(listing, pairs, orders)
        finally:
            closed.append(True)

    scaled = scaled_rational(A, b)
    with passes_run_by(runner):
        sums = exact_condition_sums(scaled, ConditionListing(ORDER, None))
    plain = not_screened(scaled_rational(A, b), ConditionListing(ORDER, None), monkeypatch)
    assert len(sent) == max(len(o.primes) for o in sums.values()) > 1  # one pass per prime
    assert ran == [0] and closed == [True]
    for n, o in sums.items():
        assert np.array_equal(o.is_zero(), plain[n].is_zero()), n


def test_the_first_value_completes_the_small_orders_in_the_same_passes(monkeypatch):
    # 12 stages: the orders of at most 12 conditions (3 … 6 vertices) need the primes
    # beyond the screen for their values; the first value asked for evaluates them for
    # all of them at once, and each value is the reference's
    A, b = random_tableau(3, s=12)
    one_channel_per_pass(monkeypatch)
    scaled = scaled_rational(A, b)
    listing = ConditionListing(6, None)
    sums = exact_condition_sums(scaled, listing)
    pending = sorted(n for n, o in sums.items() if o.full is not None)
    assert len(pending) >= 3
    calls = []
    real = modular.channel_passes
    monkeypatch.setattr(modular, "channel_passes", lambda *args: calls.append(args) or real(*args))
    sums[pending[0]].value(0)
    assert len(calls) == 1 and all(sums[n].full is None for n in pending)
    refs = reference_conditions(6)
    for n, o in sums.items():
        for k, value in enumerate(o.values()):
            rec = listing.record(n, k)
            assert value * listing.flip(n, k) == ref.energy_residual(refs[rec.level_sequence], A, b), rec.id
    assert len(calls) == 1  # completed once
