"""The right factors of a listing read through RightFactors are the plain int32 ids."""

from __future__ import annotations

import numpy as np
import pytest

import rkcheck.trees.factors as factors
from rkcheck.trees.factors import RightFactors, non_decreasing
from rkcheck.trees.listing import ConditionListing
from rkcheck.trees.table import TreeTable


def plain_right(order: int, degree: int | None) -> np.ndarray:
    """Every tree's right factor from a tree table grown to the listing's top order."""
    m = degree
    table = TreeTable(order + 1, root_bound=m, inner_bound=None if m is None else m - 1)
    return np.array(table.right[:table.first[order + 2]])


def every_read(got: RightFactors, want: np.ndarray, rng: np.random.Generator) -> None:
    assert len(got) == len(want)
    np.testing.assert_array_equal(np.asarray(got), want)
    for _ in range(300):
        a = int(rng.integers(0, len(want)))
        b = int(rng.integers(a, len(want) + 1))
        np.testing.assert_array_equal(got[a:b], want[a:b])
        np.testing.assert_array_equal(got[a:b:3], want[a:b:3])
        ids = rng.integers(0, len(want), 40)
        np.testing.assert_array_equal(got[ids], want[ids])
        np.testing.assert_array_equal(got[ids.reshape(5, 8)], want[ids.reshape(5, 8)])
        assert got[a] == want[a] and got[-1 - a] == want[-1 - a]
    mask = rng.random(len(want)) < 0.1
    np.testing.assert_array_equal(got[mask], want[mask])
    assert len(got[np.zeros(0, dtype=np.intp)]) == 0


@pytest.mark.parametrize("degree", [None, 3])
@pytest.mark.parametrize("low_bits", [2, 5, 16])
def test_reads_equal_the_plain_ids(degree, low_bits, monkeypatch):
    # few low bits: the high bits step often, within blocks of terms too
    monkeypatch.setattr(factors, "_LOW_BITS", low_bits)
    listing = ConditionListing(9, degree).complete()
    want = plain_right(9, degree)
    assert isinstance(listing.right, RightFactors)
    every_read(listing.right, want, np.random.default_rng(low_bits))


def test_factors_that_decrease_are_kept_as_they_are():
    values = np.array([5, 9, 3, 70000, 12], dtype=np.int32)
    assert not non_decreasing(values)
    right = RightFactors(np.array([-1, 0], dtype=np.int32), len(values))
    right.set_top(values)
    every_read(right, np.concatenate([[-1, 0], values]).astype(np.int32), np.random.default_rng(0))


def test_writes_reach_the_trees_below_the_top_order_only():
    right = RightFactors(np.array([-1, 0, 0, 1], dtype=np.int32), 3)
    right.set_top(np.array([0, 1, 2], dtype=np.int32))
    right[2:4] = [7, 8]
    assert np.asarray(right).tolist() == [-1, 0, 7, 8, 0, 1, 2]
    with pytest.raises(TypeError):
        right[3:5] = [1, 2]
    with pytest.raises(ValueError):
        right.set_top(np.array([0, 1], dtype=np.int32))


@pytest.mark.parametrize("low_bits", [2, 5, 16])
def test_searching_an_order_equals_searching_its_plain_ids(low_bits, monkeypatch):
    monkeypatch.setattr(factors, "_LOW_BITS", low_bits)
    listing = ConditionListing(9, None).complete()
    want = plain_right(9, None)
    rng = np.random.default_rng(low_bits)
    for n in (8, 9, 10):  # below the top order, and the top order's
        lo, hi = listing.first[n], listing.first[n + 1]
        values = np.concatenate([rng.integers(-3, lo + 3, 500), want[lo:hi][::7], [0, lo - 1, lo, 1 << 20]])
        got = listing.right.searchsorted(lo, hi, values)
        np.testing.assert_array_equal(got, np.searchsorted(want[lo:hi], values, side="left"))
