"""The energy conditions as listed by the engine (``rkcheck.trees.listing``) against
independently derived values.

Expected values come from
* the published counts: OEIS A000055 (free trees) and A000081 (rooted trees), whose
  difference for even n is the number of non-superfluous free trees (definitions §3);
* ``tests/support/reference.py`` (``energy_conditions``, ``rootings``, ``centres``);
* a brute force written here on ``networkx.nonisomorphic_trees`` with its own degree,
  superfluity (rooted isomorphism of the two halves of an edge, via networkx) and
  centre (``networkx.center``) computations.
"""

from __future__ import annotations

from functools import lru_cache

import networkx as nx
import pytest
from support import reference as ref
from support.heavy import heavy

from rkcheck.energy.explain import explain
from rkcheck.trees.listing import ConditionListing
from rkcheck.trees.rooted import level_sequence_of_forest

# OEIS, n = 1..21 (published sequences, not computed by either implementation)
A000081 = [1, 1, 2, 4, 9, 20, 48, 115, 286, 719, 1842, 4766, 12486, 32973, 87811, 235381, 634847,
           1721159, 4688676, 12826228, 35221832]
A000055 = [1, 1, 1, 2, 3, 6, 11, 23, 47, 106, 235, 551, 1301, 3159, 7741, 19320, 48629, 123867,
           317955, 823065, 2144505]


def nonsuperfluous(n: int) -> int:
    """A000055(n) minus the superfluous trees, A000081(n/2) for even n (definitions §3)."""
    return A000055[n - 1] - (A000081[n // 2 - 1] if n % 2 == 0 else 0)


@lru_cache(maxsize=None)
def ref_conditions(n: int, m):
    return tuple(ref.energy_conditions(n, m))


@lru_cache(maxsize=None)
def listing(degree, order: int = 9) -> ConditionListing:
    return ConditionListing(order, degree)  # conditions with 3..order+1 vertices


def records(L: ConditionListing):
    return [r for n in L.orders for r in L.records(n)]


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


def test_published_counts_are_consistent():
    # the definitions §3 list for n = 3..12 is A000055 − A000081(n/2)
    assert [nonsuperfluous(n) for n in range(3, 13)] == [1, 1, 3, 4, 11, 19, 47, 97, 235, 531]


def test_counts_and_superfluous_trees_to_16_vertices():
    # expected: OEIS; every free tree is either a condition or superfluous, and the
    # superfluous ones with 2k vertices are exactly A000081(k).  With an odd number of
    # vertices nothing is superfluous, so every rooted tree is a term of exactly one
    # condition: the terms are A000081(n).
    L = listing(None, 15)
    for n in range(3, 17):
        o = L.orders[n]
        assert len(o) == nonsuperfluous(n), n
        assert o.superfluous == (A000081[n // 2 - 1] if n % 2 == 0 else 0), n
        if n % 2:
            assert o.terms == A000081[n - 1], n
        assert int(o.counts.sum()) == o.terms and int(o.counts.min()) >= 1


@heavy
def test_counts_to_20_vertices():
    # the counts the scale issue plans with: 80 936 conditions to order 16, 522 472 to 18
    # and the published per-order counts up to 20 vertices (counts only beyond 16)
    L = ConditionListing(19, None)
    assert [len(L.orders[n]) for n in range(3, 21)] == [nonsuperfluous(n) for n in range(3, 21)]
    assert sum(nonsuperfluous(n) for n in range(3, 18)) == 80936
    assert sum(nonsuperfluous(n) for n in range(3, 20)) == 522472
    assert sum(nonsuperfluous(n) for n in range(3, 22)) == 3489323  # order 20 (not built here)


def test_degree_one_and_two():
    # definitions §3: m = 1 leaves nothing; m = 2 leaves the odd paths, one per even order
    assert len(ConditionListing(9, 1)) == 0
    conds = records(ConditionListing(9, 2))
    assert sorted(c.vertices for c in conds) == [3, 5, 7, 9]
    for c in conds:  # a path rooted at its centre: (1, 2, ..., k+1, 2, ..., k+1)
        k = (c.vertices - 1) // 2
        assert c.level_sequence == (1,) + tuple(range(2, k + 2)) + tuple(range(2, k + 2))


# ---------------------------------------------- degree-bounded condition sets


@pytest.mark.parametrize("m", [None, 1, 2, 3, 4, 5, 6])
def test_condition_sets_equal_reference_and_bruteforce(m):
    # expected: reference.energy_conditions(n, m) and the networkx brute force above
    conds = records(listing(m))
    for n in range(3, 11):
        got = [(c.level_sequence, c.max_degree) for c in conds if c.vertices == n]
        assert len(got) == len(set(got)), "a condition was listed twice"
        want_ref = {(d["id"], d["max_degree"]) for d in ref_conditions(n, m)}
        assert set(got) == want_ref, (m, n)
        assert set(got) == bf_conditions(n, m), (m, n)
    for c in conds:
        assert c.order == c.vertices - 1
        assert c.id == ",".join(map(str, c.level_sequence))


# ---------------------------------------------------------------- rootings


@lru_cache(maxsize=None)
def ref_graphs(n: int):
    """{centre id: G} for the non-superfluous free trees with n vertices."""
    return {ref.centre_canonical_id(G): G for G in ref.free_trees(n) if not ref.is_superfluous(G)}


@pytest.mark.parametrize("m", [None, 2, 3, 4])
def test_condition_terms_equal_reference(m):
    # expected: reference.energy_conditions terms (u, sign, σ(u), B₋(u)) up to 10 vertices:
    # every rooting once, its sign relative to the designated centre, σ and B₋(u)
    L = listing(m)
    for n in range(3, 11):
        ref_by_id = {d["id"]: d for d in ref_conditions(n, m)}
        for k in range(len(L.orders.get(n, ()))):
            rec = L.record(n, k)
            d = ref_by_id[rec.level_sequence]
            got = {(level_sequence_of_forest(forest), sign, sigma, tuple(sorted(forest, reverse=True)))
                   for sign, sigma, forest in L.term_forests(n, k)}
            want = {(u, sign, sig, tuple(forest)) for u, sign, sig, forest in d["terms"]}
            assert got == want, rec.id
            assert rec.rootings == len(want)
            assert rec.bracket == ref.butcher_bracket(rec.level_sequence)


@pytest.mark.parametrize("n", range(3, 10))
def test_rootings_and_bicentrality_equal_reference(n):
    # expected: reference.rootings and reference.centres
    L = listing(None)
    graphs = ref_graphs(n)
    assert len(L.orders[n]) == len(graphs)
    for k in range(len(L.orders[n])):
        rec = L.record(n, k)
        G = graphs[rec.level_sequence]
        assert rec.max_degree == ref.max_degree(G)
        assert (L.orders[n].tall[k] >= 0) == (len(ref.centres(G)) == 2)


def test_canonical_id_two_centres_takes_the_larger():
    # expected: definitions §3 convention, the two centre rootings computed with the reference
    seen_bicentral = 0
    for n in range(4, 11):
        for c in (c for c in records(listing(None)) if c.vertices == n):
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
    conds = {c.level_sequence for c in records(listing(None))}
    for p in range(1, 4):
        for q in range(p + 1, 8 - p):
            big = (1, 2) + (3,) * q + (2,) * p
            small = (1, 2) + (3,) * p + (2,) * q
            assert big > small
            assert big in conds and small not in conds


def test_explain_finds_the_condition_of_any_rooting():
    # every rooting (from the reference) of a free tree maps back to that tree's condition,
    # with the reference's terms (explain works on the tree itself, not on the listing)
    for n in range(3, 9):
        for cid, G in ref_graphs(n).items():
            d = {x["id"]: x for x in ref_conditions(n, None)}[cid]
            want = {(u, sign, sig) for u, sign, sig, _ in d["terms"]}
            for u, _ in ref.rootings(G, ref.designated_centre(G)[0]):
                ex = explain(u)
                assert ex.level_sequence == cid
                assert {(t.level_sequence, t.sign, t.sigma) for t in ex.terms} == want


def test_named_conditions_are_remembered_up_to_the_limit(monkeypatch):
    """Names (free tree, designated sign) read twice, or past the limit of remembered
    ones, are the reference's every time."""
    import rkcheck.trees.naming as naming

    monkeypatch.setattr(naming, "NAMED_CONDITIONS", 5)
    L = ConditionListing(7, None)
    for _ in range(2):
        for n in range(3, 9):
            want = {d["id"]: d for d in ref_conditions(n, None)}
            got = [L.record(n, k) for k in range(len(L.orders[n]))]
            assert {c.level_sequence for c in got} == set(want)
            assert all(c.max_degree == want[c.level_sequence]["max_degree"] for c in got)
    assert len(L._named) == 5


def test_whole_orders_read_past_the_limit_give_the_reference_residuals(monkeypatch):
    """A whole order read at once names each condition once (tree and designated sign
    together): past the limit of remembered names, every residual still has the sign of
    the reference's designated rooting."""
    import random
    from fractions import Fraction

    import rkcheck
    import rkcheck.trees.listing as listing_module
    import rkcheck.trees.naming as naming

    monkeypatch.setattr(naming, "NAMED_CONDITIONS", 3)
    listing_module.forget_listings()
    try:
        rng = random.Random(5)
        A = [[Fraction(rng.randint(-5, 5), rng.randint(1, 6)) for _ in range(3)] for _ in range(3)]
        b = [Fraction(rng.randint(-5, 5), rng.randint(1, 6)) for _ in range(3)]
        result = rkcheck.verify(rkcheck.from_arrays(A, b), order=9, degree="none")
        got = {c.level_sequence: c.residual for c in result.conditions}
        want = {d["id"]: ref.energy_residual(d, A, b) for n in range(3, 11) for d in ref.energy_conditions(n)}
        assert got == want
    finally:
        listing_module.forget_listings()
