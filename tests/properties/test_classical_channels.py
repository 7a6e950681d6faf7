"""The exact classical order decides each order on all its channels at once (the channels
opened for an order form one batch): the orders and the first failing trees are those of
the reference's exact rational weights, batches of one order's primes or of several."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import support.reference as ref
from support.paths import TABLEAUX

from rkcheck.evaluation.values import TableauValues
from rkcheck.io.loader import load
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.reading import Reading
from rkcheck.properties.orders import _residues, classical_order


def _tableau(A, b) -> Tableau:
    return Tableau.from_values([[str(x) for x in row] for row in A], [str(x) for x in b])


def _first_failing(A, b, order):
    """The reference's failing trees with ``order`` vertices, as Butcher brackets."""
    return {ref.butcher_bracket(t) for t in ref.rooted_trees(order)
            if ref.elementary_weight(t, A, b) != Fraction(1, ref.gamma(t))}


@pytest.mark.parametrize("name", ["explicit/rk4.toml", "explicit/rk38.toml", "explicit/ssprk3.toml",
                                  "explicit/heun.toml", "collocation/radau-iia-2.toml",
                                  "collocation/lobatto-iiia-3.toml"])
@pytest.mark.parametrize("nudge", [None, (0, 0), (1, 0), (2, 1), (3, 2)])
def test_classical_order_is_the_reference_one(name, nudge):
    tab = load(str(TABLEAUX / name))
    A, b = [list(row) for row in tab.exact_A()], list(tab.exact_b())
    if nudge is not None:  # one entry of A moved by 1/997: most methods lose orders
        i, j = nudge[0] % len(b), nudge[1] % len(b)
        A[i][j] += Fraction(1, 997)
    top = 7
    expected = ref.classical_order(A, b, top)
    found = classical_order(TableauValues.of(_tableau(A, b), Reading()), top)
    assert found.order == expected
    if expected < top:
        assert found.checked == expected + 1
        failing = _first_failing(A, b, expected + 1)
        assert found.first_failure == "Σ b_i = 1" or found.first_failure.split(" = ")[0][2:-1] in failing


def test_residues_of_small_and_large_ints():
    P = np.array([[1_000_003], [(1 << 30) - 35]], dtype=np.int64)
    for values in ([1, 2, 6, 24, 3_628_800], [2 ** 70 + 1, 7, 5 * 10 ** 30], []):
        arr = np.array(values, dtype=object)
        for largest in (max(values, default=0), 1 << 62):  # the int64 route when it may, else ints
            got = _residues(arr, P, largest)
            assert got.shape == (2, len(values))
            assert got.tolist() == [[v % int(q) for v in values] for q in P[:, 0]]
