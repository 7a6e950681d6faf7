"""Packing an order's condition and coefficient index into one word: every term reads
back the values it had, and an order whose values would not fit stays as it was."""

from __future__ import annotations

import numpy as np

from rkcheck.trees.classes import classify
from rkcheck.trees.table import TreeTable
from rkcheck.trees.terms import OrderTerms


def _unpacked(n: int) -> OrderTerms:
    table = TreeTable(n)
    return classify(table, n)


def test_packed_terms_read_back_their_condition_and_coefficient():
    for n in (3, 6, 9):
        terms = _unpacked(n)
        condition, index = terms.condition.copy(), terms.coefficient_index.copy()
        signs = [terms.sign(i) for i in range(terms.rows)]
        members = [terms.terms_of(k).tolist() for k in range(len(terms))]
        terms.pack()
        assert terms.packed is not None and terms.condition is None and terms.coefficient_index is None
        got_c, got_i = terms.block(0, terms.rows)
        np.testing.assert_array_equal(got_c, condition)
        np.testing.assert_array_equal(got_i, index)
        for i0, i1 in ((0, 1), (1, terms.rows), (terms.rows // 3, terms.rows // 2)):
            c, k = terms.block(i0, i1)
            np.testing.assert_array_equal(c, condition[i0:i1])
            np.testing.assert_array_equal(k, index[i0:i1])
        assert [terms.sign(i) for i in range(terms.rows)] == signs
        assert [terms.terms_of(k).tolist() for k in range(len(terms))] == members
        # terms picked at any positions, in any order
        pick = np.random.default_rng(n).integers(0, terms.rows, size=50)
        c, k = terms.at(pick)
        np.testing.assert_array_equal(c, condition[pick])
        np.testing.assert_array_equal(k, index[pick])


def test_an_order_whose_values_do_not_fit_one_word_stays_unpacked():
    terms = _unpacked(8)
    # 2^30 conditions (a view of one value: no memory) need 31 bits, the coefficients 2 more
    terms.rep_left = np.broadcast_to(np.int32(0), (1 << 30,))
    condition = terms.condition
    terms.pack()
    assert terms.packed is None and terms.condition is condition
    np.testing.assert_array_equal(terms.block(0, terms.rows)[0], condition)
