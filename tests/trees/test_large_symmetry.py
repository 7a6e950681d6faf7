"""Symmetry factors beyond int64 (21!, the bush with 22 vertices, and up) against the
brute-force reference, and the coefficients ``(n−1)!/σ`` they give.

Expected values: ``math.factorial`` for the bushes, ``support.reference.sigma`` (σ from
the level sequence, exact Python integers) for every tree of small tables whose root may
carry up to 23 children.
"""

from __future__ import annotations

import math

from support import reference as ref

from rkcheck.trees.classes import _signed_coefficients
from rkcheck.trees.table import SIGMA_LIMIT, TreeTable


def test_the_bushes_have_sigma_a_factorial_up_to_23_vertices():
    table = TreeTable(23, root_bound=23, inner_bound=0)  # one tree per order: the bush
    for n in range(1, 24):
        (t,) = table.ids_of_order(n)
        assert table.sigma_value(int(table.sigma[t])) == math.factorial(n - 1)
    assert math.factorial(21) > 2**63  # the case: beyond int64


def test_every_sigma_equals_the_reference_where_the_root_carries_many_children():
    # a root with paths below it (spiders): σ is a product of factorials of the
    # multiplicities of equal paths, 21! and beyond among them
    table = TreeTable(23, root_bound=23, inner_bound=1)
    big = 0
    for n in range(20, 24):
        for t in table.ids_of_order(n):
            want = ref.sigma(table.level_sequence(t))
            assert table.sigma_value(int(table.sigma[t])) == want
            big += want >= SIGMA_LIMIT
    assert big  # the large values were among them


def test_the_coefficient_of_a_large_sigma_is_exact():
    table = TreeTable(23, root_bound=23, inner_bound=0)
    keys = {int(table.sigma[t]): i for i, t in enumerate(table.ids_of_order(n).start for n in (21, 22, 23))}
    got = _signed_coefficients(keys, 23, table.sigma_value)
    # (22)!/σ for σ = 20!, 21!, 22!: 22·21, 22, 1
    assert got == [462, -462, 22, -22, 1, -1]
