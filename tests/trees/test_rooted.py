"""Rooted trees of the engine (``rkcheck.trees.table``, ``rkcheck.trees.rooted``) against
independently derived values.

Expected values come from
* ``tests/reference.py`` (brute force: canonicalise every ordered tree, SPEC §2 formulas
  for σ, γ and the bracket notation), never from ``rkcheck``;
* OEIS A000081 (number of rooted trees) and the examples written in SPEC §2.
"""

from __future__ import annotations

import random
from collections import Counter
from functools import lru_cache

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from support import reference as ref

from rkcheck.trees.rooted import bracket, canonical_level_sequence, parse_level_sequence
from rkcheck.trees.table import TAU, TreeTable

# OEIS A000081, n = 1..9 (published sequence, not computed by either implementation)
A000081 = [1, 1, 2, 4, 9, 20, 48, 115, 286]


@pytest.fixture(scope="module")
def table9() -> TreeTable:
    return TreeTable(9)


@lru_cache(maxsize=None)
def ref_trees(n: int) -> tuple:
    return tuple(ref.rooted_trees(n))


def max_children(seq) -> int:
    """Largest number of children of a vertex of a level sequence (computed here from
    the reference adjacency: the root has deg children, every other vertex deg - 1)."""
    adj = ref.level_sequence_to_adj(seq)
    return max(len(adj[v]) - (0 if v == 0 else 1) for v in adj)


def shuffle_children(seq, rng: random.Random) -> tuple:
    """A random reordering of the children at every vertex (same unordered tree)."""
    blocks = [shuffle_children(ch, rng) for ch in ref.split_children(seq)]
    rng.shuffle(blocks)
    return (1,) + tuple(d + 1 for bl in blocks for d in bl)


# ------------------------------------------------------------------ tree sets


def test_counts_are_oeis_a000081(table9):
    # expected: OEIS A000081
    assert [len(table9.ids_of_order(n)) for n in range(1, 10)] == A000081
    assert len(table9) == sum(A000081)


@pytest.mark.parametrize("n", range(1, 10))
def test_rooted_trees_equal_reference(table9, n):
    # expected: reference.rooted_trees (canonicalised brute force over all ordered trees)
    seqs = [table9.level_sequence(t) for t in table9.ids_of_order(n)]
    assert len(seqs) == len(set(seqs)), "a tree was generated twice"
    assert set(seqs) == set(ref_trees(n))
    assert all(table9.order[t] == n for t in table9.ids_of_order(n))


def test_ids_grow_with_order(table9):
    # documented convention: the ids of each order form consecutive ranges, order by order
    ids = [t for n in range(1, 10) for t in table9.ids_of_order(n)]
    assert ids == list(range(len(table9)))
    assert table9.level_sequence(TAU) == (1,)


def test_sigma_and_gamma_equal_reference(table9):
    # expected: reference.sigma / reference.gamma (SPEC §2 recursions on level sequences)
    for n in range(1, 9):
        for t in table9.ids_of_order(n):
            seq = table9.level_sequence(t)
            assert table9.sigma[t] == ref.sigma(seq), seq
            assert table9.gamma([t])[0] == ref.gamma(seq), seq


def test_sigma_gamma_hand_values(table9):
    # hand values from SPEC §2: σ([τ²]) = 2!, σ([τ³]) = 3!, σ([[τ]²]) = 2!·1², γ([τ²]) = 3,
    # γ([[τ]²]) = 5·2·2 = 20, γ([[τ]]) = 3·2 = 6, γ([[τ]τ]) = 4·2·1 = 8
    cases = {(1, 2, 2): (2, 3), (1, 2, 2, 2): (6, 4), (1, 2, 3, 2, 3): (2, 20),
             (1, 2, 3): (1, 6), (1, 2, 3, 2): (1, 8)}
    for seq, (sig, gam) in cases.items():
        t = table9.id_of_level_sequence(seq)
        assert (table9.sigma[t], table9.gamma([t])[0]) == (sig, gam), seq


def test_children_keys_height_and_lookup(table9):
    # expected: B₋(t) from reference.subtrees_at_root; height = (max depth) - 1 by definition
    for n in range(1, 10):
        for t in table9.ids_of_order(n):
            seq = table9.level_sequence(t)
            key = table9.children(t)
            assert list(key) == sorted(key, reverse=True), "children must be in decreasing id order"
            kids = sorted((table9.level_sequence(c) for c in key), reverse=True)
            assert kids == ref.subtrees_at_root(seq)
            assert table9.order[t] == 1 + sum(table9.order[c] for c in key)
            assert table9.height[t] == max(seq) - 1
            assert table9.id_of_children(key) == t
            assert table9.id_of_children(tuple(reversed(key))) == t  # any order of the key
            assert table9.id_of_level_sequence(seq) == t


def test_lookup_of_absent_tree_raises():
    table = TreeTable(3)
    with pytest.raises(KeyError):
        table.id_of_children((table.id_of_level_sequence((1, 2, 3)),) * 2)  # 7 vertices > 3


def test_bracket_examples_from_spec(table9):
    # SPEC §2 writes: τ, [τ], [τ²], [[τ]τ]
    for seq, text in {(1,): "τ", (1, 2): "[τ]", (1, 2, 2): "[τ²]", (1, 2, 3, 2): "[[τ]τ]"}.items():
        assert table9.bracket(table9.id_of_level_sequence(seq)) == text
        assert bracket(seq) == text


def test_brackets_equal_reference(table9):
    # expected: reference.butcher_bracket for every tree up to order 7
    for n in range(1, 8):
        for t in table9.ids_of_order(n):
            seq = table9.level_sequence(t)
            assert table9.bracket(t) == ref.butcher_bracket(seq)
            assert bracket(seq) == ref.butcher_bracket(seq)


def test_bracket_of_noncanonical_level_sequence():
    # (1,2,3,4,3,2,3,3,4) is [[[τ]τ]²] written with its two equal subtrees in different
    # child orders; expected from reference.butcher_bracket (canonicalises first)
    seq = (1, 2, 3, 4, 3, 2, 3, 3, 4)
    assert ref.butcher_bracket(seq) == "[[[τ]τ]²]"
    assert bracket(seq) == ref.butcher_bracket(seq)


# ------------------------------------------------------ children-bounded tables


@pytest.mark.parametrize("k", [0, 1, 2, 3])
def test_children_bounded_tables_equal_filtered_reference(k):
    # expected: reference trees whose vertices all have <= k children (counted here)
    table = TreeTable(8, root_bound=k, inner_bound=k)
    for n in range(1, 9):
        got = [table.level_sequence(t) for t in table.ids_of_order(n)]
        want = {s for s in ref_trees(n) if max_children(s) <= k}
        assert len(got) == len(set(got))
        assert set(got) == want, (k, n)
        for t in table.ids_of_order(n):
            seq = table.level_sequence(t)
            assert table.sigma[t] == ref.sigma(seq)
            assert table.gamma([t])[0] == ref.gamma(seq)
    if k == 1:  # only the paths ("tall trees"): one per order
        assert all(len(table.ids_of_order(n)) == 1 for n in range(1, 9))


# ------------------------------------------------------------- canonical forms


def test_canonical_form_of_shuffled_trees(table9):
    # expected: the tree itself (canonical form is a tree invariant) and reference.canonicalize
    rng = random.Random(20240601)
    for n in range(1, 9):
        for t in table9.ids_of_order(n):
            canon = table9.level_sequence(t)
            for _ in range(3):
                seq = shuffle_children(canon, rng)
                assert canonical_level_sequence(seq) == canon == ref.canonicalize(seq)
                assert table9.id_of_level_sequence(seq) == t


@st.composite
def level_sequences(draw, max_size: int = 12):
    """Arbitrary (mostly non-canonical) level sequences: root 1, then each depth in
    2..previous+1."""
    n = draw(st.integers(1, max_size))
    seq = [1]
    for _ in range(n - 1):
        seq.append(draw(st.integers(2, seq[-1] + 1)))
    return tuple(seq)


@settings(max_examples=300, deadline=None)
@given(level_sequences())
def test_canonical_level_sequence_matches_reference(seq):
    # expected: reference.canonicalize
    want = ref.canonicalize(seq)
    assert canonical_level_sequence(seq) == want
    assert canonical_level_sequence(want) == want  # idempotent
    assert parse_level_sequence(",".join(map(str, seq))) == seq


@settings(max_examples=200, deadline=None)
@given(level_sequences(max_size=9))
def test_id_of_level_sequence_matches_reference(seq):
    # expected: the engine id of a sequence has the reference canonical form
    table = _table9_cached()
    t = table.id_of_level_sequence(seq)
    assert table.level_sequence(t) == ref.canonicalize(seq)
    assert table.sigma[t] == ref.sigma(seq)


@lru_cache(maxsize=1)
def _table9_cached() -> TreeTable:
    return TreeTable(9)


def test_parse_refuses_empty_places_between_commas():
    # "1,,2" is a typo, not the tree 1,2; spaces alone still separate
    for text in ("1,,2", "1,2,2,", ",1,2"):
        with pytest.raises(ValueError):
            parse_level_sequence(text)
    assert parse_level_sequence("1 2 2") == parse_level_sequence("[1, 2, 2]") == (1, 2, 2)


@pytest.mark.parametrize("text", ["1,3", "2,3", "1,2,4", "", "a,b", "1,1"])
def test_parse_rejects_invalid_level_sequences(text):
    # invalid by the definition of a level sequence (reference.is_level_sequence)
    parts = [p for p in text.split(",") if p]
    if parts and all(p.isdigit() for p in parts):
        assert not ref.is_level_sequence(tuple(int(p) for p in parts))
    with pytest.raises(ValueError):
        parse_level_sequence(text)


def test_parse_accepts_documented_forms():
    # forms listed in the parse_level_sequence docstring
    for text in ["1,2,3,2", "[1, 2, 3, 2]", "1 2 3 2"]:
        assert parse_level_sequence(text) == (1, 2, 3, 2)


def test_level_sequence_multiset_of_children_counts(table9):
    # independent sanity: the multiset of child counts of every vertex equals the
    # reference adjacency's, for all trees of order 8
    for t in table9.ids_of_order(8):
        seq = table9.level_sequence(t)
        adj = ref.level_sequence_to_adj(seq)
        want = Counter(len(adj[v]) - (0 if v == 0 else 1) for v in adj)

        def counts(u):
            c = Counter([len(table9.children(u))])
            for ch in table9.children(u):
                c += counts(ch)
            return c

        assert counts(t) == want
