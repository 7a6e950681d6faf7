"""Free trees and the set of energy conditions (``rkcheck.freetrees``, ``rkcheck.conditions``)
against independently derived values.

Expected values come from
* SPEC §3 (counts of non-superfluous free trees, n = 3..12) and OEIS A000081 / A000055;
* ``tests/reference.py`` (``energy_conditions``, ``rootings``, ``centres``);
* a brute force written here on ``networkx.nonisomorphic_trees`` with its own degree,
  superfluity (rooted isomorphism of the two halves of an edge, via networkx) and
  centre (``networkx.center``) computations.
"""

from __future__ import annotations

from functools import lru_cache

import networkx as nx
import pytest
from support import reference as ref

from rkcheck.trees.conditions import ConditionTable
from rkcheck.trees.free import FreeTreeGenerator, table_for
from rkcheck.trees.rooted import level_sequence_of_forest

A000081 = [1, 1, 2, 4, 9, 20, 48, 115, 286]  # rooted trees, n = 1..9 (OEIS)
A000055 = [1, 1, 1, 2, 3, 6, 11, 23, 47, 106, 235, 551]  # free trees, n = 1..12 (OEIS)
NONSUPERFLUOUS = {3: 1, 4: 1, 5: 3, 6: 4, 7: 11, 8: 19, 9: 47, 10: 97, 11: 235, 12: 531}  # SPEC §3


@lru_cache(maxsize=None)
def generator(max_vertices: int, degree):
    return FreeTreeGenerator(table_for(max_vertices - 1, degree), degree)


@lru_cache(maxsize=None)
def ref_conditions(n: int, m):
    return tuple(ref.energy_conditions(n, m))


@lru_cache(maxsize=None)
def engine_conditions(degree):
    return ConditionTable(9, degree)  # conditions with 3..10 vertices


def rooting_seqs(table, tree):
    """Engine rootings as {(level sequence, parity)}."""
    return [(level_sequence_of_forest([table.level_sequence(b) for b in key]), parity)
            for key, parity in tree.rootings]


# ------------------------------------------------------------- brute force


def bf_rooted_canonical(G, root, parent=None) -> tuple:
    """Lexicographically largest level sequence of G rooted at ``root`` (children
    blocks sorted decreasingly; see the reference docstring for why that is the max)."""
    blocks = sorted((bf_rooted_canonical(G, w, root) for w in G.neighbors(root) if w != parent),
                    reverse=True)
    return (1,) + tuple(d + 1 for bl in blocks for d in bl)


def bf_superfluous(G) -> bool:
    """Some edge leaves two halves isomorphic as rooted trees (rooted at its endpoints)."""
    for u, v in G.edges():
        H = G.copy()
        H.remove_edge(u, v)
        halves = []
        for root in (u, v):
            comp = nx.node_connected_component(H, root)
            S = nx.Graph(H.subgraph(comp))
            nx.set_node_attributes(S, {x: x == root for x in S}, "root")
            halves.append(S)
        if nx.is_isomorphic(halves[0], halves[1], node_match=lambda a, b: a["root"] == b["root"]):
            return True
    return False


def bf_id(G) -> tuple:
    """Centre rooting (networkx.center); for two centres the larger level sequence."""
    return max(bf_rooted_canonical(G, c) for c in nx.center(G))


@lru_cache(maxsize=None)
def bf_trees(n: int):
    """(id, max degree, superfluous) for every free tree with n >= 3 vertices."""
    out = []
    for G in nx.nonisomorphic_trees(n):
        out.append((bf_id(G), max(d for _, d in G.degree()), bf_superfluous(G)))
    return tuple(out)


def bf_conditions(n: int, m) -> set:
    return {(i, md) for i, md, sup in bf_trees(n) if not sup and (m is None or md <= m)}


# ------------------------------------------------------------------ counts


@pytest.mark.parametrize("n", range(3, 13))
def test_nonsuperfluous_counts_match_spec(n):
    # expected: SPEC §3 list (A000055 minus A000081(n/2))
    trees = list(generator(12, None).free_trees(n))
    assert len(trees) == NONSUPERFLUOUS[n]
    assert not any(t.superfluous for t in trees)


@pytest.mark.parametrize("n", range(1, 13))
def test_superfluous_counts_are_a000081_of_half(n):
    # expected: OEIS A000081(n/2) superfluous trees for even n, none for odd n;
    # together with the others exactly A000055(n) free trees
    trees = list(generator(12, None).free_trees(n, include_superfluous=True))
    sup = sum(1 for t in trees if t.superfluous)
    assert sup == (A000081[n // 2 - 1] if n % 2 == 0 else 0)
    assert len(trees) == A000055[n - 1]


def test_condition_table_counts_by_order():
    # expected: SPEC §3 list; order = vertices - 1
    counts = engine_conditions(None).counts_by_order()
    assert counts == {k: NONSUPERFLUOUS.get(k + 1, 0) for k in range(2, 10)}
    assert counts[2] == 1 and counts[9] == 97


def test_degree_one_and_two():
    # SPEC §3: m = 1 leaves nothing; m = 2 leaves the odd paths, one per even order
    assert len(ConditionTable(9, 1)) == 0
    conds = ConditionTable(9, 2).conditions
    assert sorted(c.vertices for c in conds) == [3, 5, 7, 9]
    for c in conds:  # a path rooted at its centre: (1, 2, ..., k+1, 2, ..., k+1)
        k = (c.vertices - 1) // 2
        assert c.level_sequence == (1,) + tuple(range(2, k + 2)) + tuple(range(2, k + 2))


# ---------------------------------------------- degree-bounded condition sets


@pytest.mark.parametrize("m", [None, 1, 2, 3, 4, 5, 6])
def test_condition_sets_equal_reference_and_bruteforce(m):
    # expected: reference.energy_conditions(n, m) and the networkx brute force above
    conds = engine_conditions(m).conditions
    for n in range(3, 11):
        got = [(c.level_sequence, c.max_degree) for c in conds if c.vertices == n]
        assert len(got) == len(set(got)), "a condition was generated twice"
        want_ref = {(d["id"], d["max_degree"]) for d in ref_conditions(n, m)}
        assert set(got) == want_ref, (m, n)
        assert set(got) == bf_conditions(n, m), (m, n)
        for c in conds:
            assert c.order == c.vertices - 1
            assert c.id == ",".join(map(str, c.level_sequence))


@pytest.mark.parametrize("m", [2, 3, 4, 5])
def test_generator_agrees_with_condition_table(m):
    # the FreeTreeGenerator on a degree-bounded table gives the same trees (and the
    # reference max degrees) as the ConditionTable
    gen = generator(10, m)
    for n in range(3, 11):
        got = {(level_sequence_of_forest([gen.table.level_sequence(b) for b in t.centre]), t.max_degree)
               for t in gen.free_trees(n)}
        assert got == {(d["id"], d["max_degree"]) for d in ref_conditions(n, m)}


# ---------------------------------------------------------------- rootings


@lru_cache(maxsize=None)
def ref_graphs(n: int):
    """{centre id: G} for the non-superfluous free trees with n vertices."""
    return {ref.centre_canonical_id(G): G for G in ref.free_trees(n) if not ref.is_superfluous(G)}


@pytest.mark.parametrize("n", range(3, 10))
def test_rootings_and_parities_equal_reference(n):
    # expected: reference.rootings(G, designated centre) (distinct rooted trees, parity of
    # the distance from the centre) and reference.sigma of every rooting
    gen = generator(9, None)
    graphs = ref_graphs(n)
    trees = list(gen.free_trees(n))
    assert len(trees) == len(graphs)
    for tree in trees:
        seqs = rooting_seqs(gen.table, tree)
        cid = seqs[0][0]
        assert seqs[0][1] == 0, "the designated rooting comes first, at distance 0"
        G = graphs[cid]
        centre, _ = ref.designated_centre(G)
        want = ref.rootings(G, centre)
        assert len(seqs) == len(set(seqs)) == len(want), "each rooted tree once"
        assert set(seqs) == set(want)
        assert tree.vertices == n
        assert tree.max_degree == ref.max_degree(G)
        assert tree.bicentral == (len(ref.centres(G)) == 2)


def test_condition_terms_equal_reference():
    # expected: reference.energy_conditions terms (u, sign, σ(u), B₋(u)) up to 9 vertices
    conds = engine_conditions(None).conditions
    for n in range(3, 10):
        ref_by_id = {d["id"]: d for d in ref_conditions(n, None)}
        for c in (c for c in conds if c.vertices == n):
            d = ref_by_id[c.level_sequence]
            got = {(c.term_level_sequence(t), t.sign, t.sigma,
                    tuple(sorted((c.table.level_sequence(b) for b in t.branches), reverse=True)))
                   for t in c.terms}
            want = {(u, sign, sig, tuple(forest)) for u, sign, sig, forest in d["terms"]}
            assert got == want, c.id
            assert c.terms[0].sign == 1 and c.term_level_sequence(c.terms[0]) == c.level_sequence


def test_canonical_id_two_centres_takes_the_larger():
    # expected: SPEC §3 convention, the two centre rootings computed with the reference
    seen_bicentral = 0
    for n in range(4, 11):
        for c in (c for c in engine_conditions(None).conditions if c.vertices == n):
            G = ref_graphs(n)[c.level_sequence]
            cs = ref.centres(G)
            adj = {v: list(G.neighbors(v)) for v in G}
            rooted = [ref.canonical_level_sequence(adj, v) for v in cs]
            assert c.level_sequence == max(rooted)
            if len(cs) == 2:
                seen_bicentral += 1
                assert rooted[0] != rooted[1]  # non-superfluous: the halves differ
                assert c.level_sequence != min(rooted)
    assert seen_bicentral > 50  # the convention was actually exercised


def test_double_bush_id_is_rooted_at_the_smaller_bush():
    # hand derivation: t_{p,q} (p < q) rooted at the centre with p leaves has level
    # sequence (1, 2, 3^q, 2^p); rooted at the other centre (1, 2, 3^p, 2^q), smaller
    conds = {c.level_sequence for c in engine_conditions(None).conditions}
    for p in range(1, 4):
        for q in range(p + 1, 8 - p):
            big = (1, 2) + (3,) * q + (2,) * p
            small = (1, 2) + (3,) * p + (2,) * q
            assert big > small
            assert big in conds and small not in conds


def test_condition_for_level_sequence_of_any_rooting():
    # every rooting (from the reference) of a free tree maps back to that tree's condition
    table = engine_conditions(None)
    for n in range(3, 9):
        for cid, G in ref_graphs(n).items():
            for u, _ in ref.rootings(G, ref.designated_centre(G)[0]):
                c = table.condition_for_level_sequence(u)
                assert c.level_sequence == cid
