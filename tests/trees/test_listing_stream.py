"""The listing built order by order: an order is built when first asked for, with every
order below it and nothing above; built in steps, or with some orders read from a store,
it is the listing built in one go; its counts come without building it; and a check
that stops at a failing low order (``--fail-fast``) builds nothing above that order."""

from __future__ import annotations

import numpy as np
import pytest

from rkcheck.energy.check import check
from rkcheck.methods.tableau import Tableau
from rkcheck.options import CheckOptions
from rkcheck.trees import listing as listing_module
from rkcheck.trees.listing import ConditionListing, condition_listing, use_store

from trees.test_listing import nonsuperfluous

ARRAYS = ("counts", "rep_left", "rep_right", "tall", "rest", "max_degree")


@pytest.fixture(autouse=True)
def no_default_store():
    previous = use_store(None)
    yield
    use_store(previous)


class MemoryStore:
    """A store in a dict (what the disk cache does, without the disk)."""

    def __init__(self, min_terms: int = 0):
        self.records: dict[tuple, tuple] = {}
        self.min_terms = min_terms
        self.loads: list[int] = []

    def load(self, key, into=None):
        self.loads.append(key["vertices"])
        got = self.records.get(tuple(sorted(key.items(), key=str)))
        return None if got is None else ({k: v.copy() for k, v in got[0].items()}, dict(got[1]))

    def save(self, key, arrays, meta):
        self.records[tuple(sorted(key.items(), key=str))] = ({k: np.array(v) for k, v in arrays.items()}, meta)


def same_listing(a: ConditionListing, b: ConditionListing) -> None:
    """Equal as data: factors of every tree, and per order every term's condition and
    signed coefficient (the index into the coefficients may differ), and the conditions."""
    assert a.first == b.first
    np.testing.assert_array_equal(a.left, b.left)
    np.testing.assert_array_equal(a.right, b.right)
    assert list(a.orders) == list(b.orders)
    for n in a.orders:
        x, y = a.orders[n], b.orders[n]
        for name in ARRAYS:
            np.testing.assert_array_equal(getattr(x, name), getattr(y, name), err_msg=f"{name} at {n} vertices")
        (xc, xi), (yc, yi) = x.block(0, x.rows), y.block(0, y.rows)
        np.testing.assert_array_equal(xc, yc, err_msg=f"condition at {n} vertices")
        cx = np.array(x.coefficients, dtype=object)[xi]
        cy = np.array(y.coefficients, dtype=object)[yi]
        assert (cx == cy).all()
        assert x.superfluous == y.superfluous and x.first_id == y.first_id == a.first[n]
    assert [t.id for t in a.sorted_records()] == [t.id for t in b.sorted_records()]


@pytest.mark.parametrize("order, degree", [(9, None), (10, 3), (8, 2), (9, 4)])
def test_built_in_steps_is_built_in_one_go(order, degree):
    whole = ConditionListing(order, degree).complete()
    steps = ConditionListing(order, degree)
    for n in (4, 4, 7, order + 1):
        steps.ensure(n)
        assert steps._built == n  # every order up to n, nothing above
    same_listing(whole, steps)


def test_an_order_is_built_when_first_asked_for_and_nothing_above():
    listing = ConditionListing(12, None)
    assert list(listing.orders) == list(range(3, 14))  # every key known, none built
    assert 5 in listing.orders and listing._built == 2
    assert len(listing.orders[5]) == nonsuperfluous(5)
    assert listing._built == 5


@pytest.mark.parametrize("order", [6, 11])
def test_counts_need_no_building_and_match_the_built_orders(order):
    listing = ConditionListing(order, None)
    counts = listing.counts_by_order()
    assert listing._built == 2
    # the published counts (OEIS A000055 minus the superfluous trees)
    assert counts == {k: nonsuperfluous(k + 1) for k in range(2, order + 1)}
    assert len(listing) == sum(counts.values())
    listing.complete()
    assert counts == {n - 1: len(listing.orders[n]) for n in listing.orders}


@pytest.mark.parametrize("degree", [None, 3])
def test_orders_read_from_a_store_equal_the_orders_built(degree):
    store = MemoryStore()
    first = ConditionListing(10, degree, store).complete()
    assert first.cache_hits == [] and len(store.records) == 9  # 3 … 11 vertices saved
    second = ConditionListing(10, degree, store).complete()
    assert second.cache_hits == list(range(3, 12))
    same_listing(first, second)
    same_listing(ConditionListing(10, degree).complete(), second)


def test_a_gap_in_the_store_rebuilds_the_table_below_it():
    """Orders 3 … 7 from the store, 8 missing: the tree table is built anew up to 7 to
    classify 8; the orders after it come from the store again."""
    store = MemoryStore()
    ConditionListing(10, None, store).complete()
    del store.records[next(k for k in store.records if dict(k)["vertices"] == 8)]
    listing = ConditionListing(10, None, store).complete()
    assert listing.cache_hits == [3, 4, 5, 6, 7, 9, 10, 11]
    same_listing(ConditionListing(10, None).complete(), listing)


def test_a_store_is_not_asked_for_orders_below_its_minimum():
    store = MemoryStore(min_terms=1000)  # 1842 rooted trees with 11 vertices, 719 with 10
    ConditionListing(10, None, store).complete()
    assert sorted(dict(k)["vertices"] for k in store.records) == [11]
    assert store.loads == [11]


def test_a_lower_order_listing_shares_the_store_of_a_higher_one():
    store = MemoryStore()
    ConditionListing(10, None, store).complete()
    listing = ConditionListing(7, None, store).complete()  # 3 … 8 vertices: all saved
    assert listing.cache_hits == list(range(3, 9))
    same_listing(ConditionListing(7, None).complete(), listing)


EULER = Tableau.from_values([["0"]], ["1"])  # energy order 1: fails at 3 vertices


def test_fail_fast_builds_only_the_orders_up_to_the_failing_one():
    listing_module.forget_listings()
    result = check(EULER, CheckOptions(order=14, degree=None, fail_fast=True))
    assert result.energy_order == 1 and sorted(result.conditions.orders) == [3]
    assert condition_listing(14, None, lazy=True)._built == 3  # nothing above 3 vertices
    # the report still counts every order's conditions (counted, not built)
    assert [p.conditions for p in result.per_order] == [nonsuperfluous(k + 1) for k in range(2, 15)]


def test_a_complete_check_is_the_same_after_a_fail_fast_one():
    listing_module.forget_listings()
    fast = check(EULER, CheckOptions(order=8, degree=None, fail_fast=True))
    full = check(EULER, CheckOptions(order=8, degree=None))
    listing_module.forget_listings()
    fresh = check(EULER, CheckOptions(order=8, degree=None))
    assert [p.failed for p in full.per_order] == [p.failed for p in fresh.per_order]
    assert fast.per_order[0] == fresh.per_order[0]
    assert [c.tree.id for c in full.failures] == [c.tree.id for c in fresh.failures]


def test_small_listings_stay_shared_past_the_last_four_and_large_ones_do_not_pile_up(monkeypatch):
    listing_module.forget_listings()
    small = [(8, d) for d in (2, 3, 4, 5, 6, None)]  # a scan's claims: one order, many degrees
    first = {key: condition_listing(*key, lazy=True) for key in small}
    assert all(condition_listing(*key, lazy=True) is first[key] for key in small)
    # a listing above the per-listing size is one of the last few only
    monkeypatch.setattr(listing_module, "SMALL_LISTING_TERMS", 100)
    big = [(k, None) for k in (9, 10, 11, 12, 13)]  # not built: lazy
    assert all(listing_module.listing_size(*key)[1] > 100 for key in big)
    kept = [condition_listing(*key, lazy=True) for key in big]
    assert condition_listing(9, None, lazy=True) is not kept[0]  # evicted by the four after it
    assert all(condition_listing(*key, lazy=True) is first[key] for key in small)  # small ones are still there
    listing_module.forget_listings()
    assert condition_listing(8, 3, lazy=True) is not first[(8, 3)]
