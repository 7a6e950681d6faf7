"""The tree table and the listing generated in chunks of a few rows against the same in
one chunk, and every id against the product of its factors.

Expected values: a tree's id is the product of its Butcher factors (the definition of
the ids, ``id(u ∘ v)``), looked up independently of the generation; the counts are OEIS
A000081 (unbounded) and the reference's brute force (bounded).  Small chunks make every
order cross many chunk boundaries, where the generation keeps running totals.
"""

from __future__ import annotations

import numpy as np
import pytest
from support import reference as ref

from rkcheck.trees import classes
from rkcheck.trees import table as table_module
from rkcheck.trees.listing import ConditionListing
from rkcheck.trees.table import TreeTable

# OEIS A000081, n = 1..10 (published sequence)
A000081 = [1, 1, 2, 4, 9, 20, 48, 115, 286, 719]

BOUNDS = [(None, None), (3, 2), (4, 3), (2, 2)]


def _fields(table: TreeTable) -> dict[str, np.ndarray]:
    n = len(table)
    names = ("left", "right", "nchild", "h1", "h2", "tall", "rest", "sigma", "mult", "order", "inner_max")
    return {k: np.array(getattr(table, k)[:n]) for k in names}


@pytest.mark.parametrize("root_bound, inner_bound", BOUNDS)
def test_a_table_in_small_chunks_equals_the_table_in_one(root_bound, inner_bound, monkeypatch):
    whole = TreeTable(10, root_bound, inner_bound)
    monkeypatch.setattr(table_module, "_CHUNK", 5)
    chunked = TreeTable(10, root_bound, inner_bound)
    assert chunked.first == whole.first
    a, b = _fields(whole), _fields(chunked)
    for k in a:
        assert np.array_equal(a[k], b[k]), k


@pytest.mark.parametrize("root_bound, inner_bound", BOUNDS)
def test_every_id_is_the_product_of_its_factors(root_bound, inner_bound):
    table = TreeTable(10, root_bound, inner_bound)
    ids = np.arange(1, len(table), dtype=np.int32)
    assert np.array_equal(table.product(table.left[ids], table.right[ids]), ids)
    # and the trees one order above, generated without being stored, in id order
    n = table.max_order + 1
    size = table.prepare_order(n)
    got = np.concatenate([table.product(U, V) for U, V in table.pairs(n)])
    assert np.array_equal(got, np.arange(table.first[n], table.first[n] + size))


def test_the_unbounded_counts_are_a000081():
    table = TreeTable(10)
    assert [table.count(n) for n in range(1, 11)] == A000081
    assert table.prepare_order(11) == 1842  # A000081 at 11


@pytest.mark.parametrize("k", [2, 3])
def test_the_bounded_counts_equal_the_reference(k):
    table = TreeTable(9, root_bound=k, inner_bound=k)
    for n in range(1, 10):
        want = sum(1 for s in ref.rooted_trees(n)
                   if max(len(c) - (0 if v == 0 else 1) for v, c in ref.level_sequence_to_adj(s).items()) <= k)
        assert table.count(n) == want


@pytest.mark.parametrize("degree", [None, 3, 4])
def test_a_listing_in_small_chunks_equals_the_listing_in_one(degree, monkeypatch):
    whole = ConditionListing(9, degree, store=None).complete()
    monkeypatch.setattr(table_module, "_CHUNK", 7)
    monkeypatch.setattr(classes, "_CHUNK", 7)
    chunked = ConditionListing(9, degree, store=None).complete()
    assert np.array_equal(whole.left, chunked.left)
    assert np.array_equal(np.asarray(whole.right), np.asarray(chunked.right))
    for n in whole.orders:
        a, b = whole.orders[n], chunked.orders[n]
        for name in ("counts", "rep_left", "rep_right", "tall", "rest", "max_degree"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), (n, name)
        # the coefficient indices number the distinct σ as they first appear, chunk by
        # chunk: compare the coefficients they stand for
        ca, ia = a.block(0, a.rows)
        cb, ib = b.block(0, b.rows)
        assert np.array_equal(ca, cb)
        assert [a.coefficients[i] for i in ia.tolist()] == [b.coefficients[i] for i in ib.tolist()]
