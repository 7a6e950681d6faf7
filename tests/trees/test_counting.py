"""Counts of conditions and terms from generating functions (``rkcheck.trees.counting``)
against published sequences, the brute-force reference, and the listing."""

from __future__ import annotations

import pytest
from support import reference as ref

from rkcheck.trees.counting import (
    condition_counts,
    listing_size,
    rooted_counts,
    term_counts,
)
from rkcheck.trees.listing import ConditionListing
from rkcheck.trees.table import TreeTable

# OEIS A000081 (rooted trees) and A000055 (free trees), n = 1..21
A000081 = [1, 1, 2, 4, 9, 20, 48, 115, 286, 719, 1842, 4766, 12486, 32973, 87811, 235381, 634847,
           1721159, 4688676, 12826228, 35221832]
A000055 = [1, 1, 1, 2, 3, 6, 11, 23, 47, 106, 235, 551, 1301, 3159, 7741, 19320, 48629, 123867,
           317955, 823065, 2144505]
# OEIS A000672 (trees with max degree <= 3), A000602 ... we use the reference for bounded counts


def test_unbounded_counts_are_the_oeis_sequences():
    assert list(rooted_counts(21))[1:] == A000081
    conditions = condition_counts(21, None)
    for n in range(3, 22):
        superfluous = A000081[n // 2 - 1] if n % 2 == 0 else 0
        assert conditions[n] == A000055[n - 1] - superfluous


@pytest.mark.parametrize("m", [1, 2, 3, 4, 5])
def test_bounded_counts_equal_the_reference_brute_force(m):
    # expected: reference.count_nonsuperfluous (networkx enumeration) up to 10 vertices
    counts = condition_counts(10, m)
    for n in range(3, 11):
        assert counts[n] == ref.count_nonsuperfluous(n, m), (m, n)


@pytest.mark.parametrize("m", [None, 2, 3, 4])
def test_counts_equal_what_the_engine_builds(m):
    table = TreeTable(13, m, None if m is None else m - 1)
    assert [table.count(n) for n in range(1, 14)] == list(term_counts(13, m))[1:]
    listing = ConditionListing(12, m)
    assert [len(listing.orders[n]) if n in listing.orders else 0 for n in range(3, 14)] == \
        list(condition_counts(13, m))[3:]


def test_rooted_counts_with_few_children():
    # k = 1: the paths, one per order; k = 0: only τ (by definition)
    assert rooted_counts(9, 1)[1:] == (1,) * 9
    assert rooted_counts(5, 0)[1:] == (1, 0, 0, 0, 0)


def test_listing_size_of_order_20_matches_the_issue():
    # the counts the scale issue quotes: 80 936 to order 16, 522 472 to 18, 3 489 323 to 20
    assert listing_size(16, None)[0] == 80936
    assert listing_size(18, None)[0] == 522472
    assert listing_size(20, None)[0] == 3489323
