"""Conditions enumerated and evaluated by centroid (rkcheck.trees.centroid,
rkcheck.evaluation.centroid) against the independent reference: the same conditions
(ids, maximum degree, rootings), and the same exact residual of each, sign included.

Independent routes: ``support.reference`` (brute force over networkx's free trees,
nothing from rkcheck) for the conditions and rational residuals; SPEC §3's counts of
non-superfluous free trees; for a number field, the rooted-tree listing's residuals,
which tests/evaluation/test_field_residuals.py checks against sympy."""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import pytest
from support import reference as ref

import rkcheck
import rkcheck.energy.check as check
from rkcheck.trees.centroid import CENTROID_FROM_ORDER, CentroidListing
from rkcheck.trees.graph import adjacency, distinct_rootings

DENSE = ([[Fraction(1, 7), Fraction(-2, 9), Fraction(3, 11)], [Fraction(2, 5), Fraction(1, 8), Fraction(-1, 6)],
          [Fraction(-1, 12), Fraction(5, 9), Fraction(1, 4)]], [Fraction(1, 5), Fraction(3, 10), Fraction(1, 2)])
RK4 = ([[Fraction(0)] * 4, [Fraction(1, 2), 0, 0, 0], [0, Fraction(1, 2), 0, 0], [0, 0, Fraction(1), 0]],
       [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)])


def verify(A, b, **options):
    tab = rkcheck.from_arrays([[str(x) for x in row] for row in A], [str(x) for x in b])
    return rkcheck.verify(tab, **options)


@pytest.fixture
def by_centroid(monkeypatch):
    """Every exact check enumerated by centroid, whatever its order."""
    monkeypatch.setattr(check, "CENTROID_FROM_ORDER", 1)


@pytest.mark.parametrize("tableau", [DENSE, RK4], ids=["dense", "rk4"])
@pytest.mark.parametrize("degree", [None, 3, 4])
def test_every_residual_is_the_references(by_centroid, tableau, degree):
    A, b = tableau
    result = verify(A, b, order=7, degree=degree)
    assert isinstance(result.conditions.listing, CentroidListing)
    got = {c.level_sequence: c.residual for c in result.conditions}
    want = {cond["id"]: ref.energy_residual(cond, A, b)
            for n in range(3, 9) for cond in ref.energy_conditions(n, degree)}
    assert got == want


def test_the_conditions_are_the_references_with_their_degree_and_rootings():
    listing = CentroidListing(10, None)
    for n in range(3, 12):
        mine = {t.level_sequence: (t.max_degree, t.rootings) for t in listing.records(n)}
        theirs = {cond["id"]: (cond["max_degree"], len(cond["terms"])) for cond in ref.energy_conditions(n)}
        assert mine == theirs, n
    for m in (2, 3, 4):
        bounded = CentroidListing(9, m)
        for n in range(3, 11):
            assert {t.level_sequence for t in bounded.records(n)} == {c["id"] for c in ref.energy_conditions(n, m)}


def test_the_counts_are_specs():
    # SPEC §3: non-superfluous free trees with 3 … 12 vertices
    listing = CentroidListing(11, None)
    assert [len(listing.records(n)) for n in range(3, 13)] == [1, 1, 3, 4, 11, 19, 47, 97, 235, 531]


def test_distinct_rootings_are_counted_by_brute_force():
    for n in range(1, 11):
        for G in nx.nonisomorphic_trees(n) if n > 1 else [nx.empty_graph(1)]:
            adj = [sorted(G.neighbors(v)) for v in range(n)]
            brute = {ref.canonical_level_sequence(ref._adj(G), v) for v in G.nodes}
            assert distinct_rootings(adj) == len(brute)
    assert distinct_rootings(adjacency((1, 2, 3, 2, 3))) == 3  # the path of 5: its ends, their neighbours, the middle


def test_a_number_field_gives_the_listing_routes_residuals(monkeypatch):
    gauss3 = "tableaux/collocation/gauss-3.toml"
    # each run reads the file into a field of its own, the same field: residuals compare
    listing_route = {c.level_sequence: c.residual for c in rkcheck.verify(gauss3, order=7, degree=None).conditions}
    monkeypatch.setattr(check, "CENTROID_FROM_ORDER", 1)
    result = rkcheck.verify(gauss3, order=7, degree=None)
    assert isinstance(result.conditions.listing, CentroidListing)
    assert {c.level_sequence: c.residual for c in result.conditions} == listing_route
    assert len(set(listing_route.values())) > 2  # Gauss-3 fails conditions of order 7


def test_passes_on_other_processes_give_the_reference_residuals(by_centroid, monkeypatch):
    from rkcheck.evaluation.scaled import ScaledTableau

    monkeypatch.setattr(ScaledTableau, "channels_per_pass", lambda self, listing, top: 1)  # several passes
    A, b = DENSE
    result = verify(A, b, order=6, jobs=2)
    assert isinstance(result.conditions.listing, CentroidListing)
    assert {c.level_sequence: c.residual for c in result.conditions} == {
        cond["id"]: ref.energy_residual(cond, A, b) for n in range(3, 8) for cond in ref.energy_conditions(n)}


def test_a_check_to_the_centroid_order_uses_it():
    """The real threshold, end to end on the odd paths (degree 2): each residual is the
    reference's residual of the path graph."""
    A, b = RK4
    result = verify(A, b, order=CENTROID_FROM_ORDER, degree=2)
    assert isinstance(result.conditions.listing, CentroidListing)
    got = {c.level_sequence: c.residual for c in result.conditions}
    want = {}
    for n in range(3, CENTROID_FROM_ORDER + 2, 2):  # paths with an even number of vertices are superfluous
        G = nx.path_graph(n)
        centre, cid = ref.designated_centre(G)
        terms = [(u, -1 if parity else 1, ref.sigma(u), ref.subtrees_at_root(u)) for u, parity in ref.rootings(G, centre)]
        want[cid] = ref.energy_residual({"terms": terms}, A, b)
    assert got == want
    assert result.energy_order == 5  # R(z)R(−z) = 1 − z⁶/72 + …: the path of 7 vertices (order 6) fails
