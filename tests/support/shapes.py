"""Free trees of the seed's named shapes as networkx graphs (shared by the tests)."""

from __future__ import annotations

import networkx as nx


def double_bush(p, q):
    """t_{p,q}: two adjacent centres X, Y carrying p and q leaves."""
    G = nx.Graph([("X", "Y")])
    G.add_edges_from(("X", f"x{i}") for i in range(p))
    G.add_edges_from(("Y", f"y{i}") for i in range(q))
    return G


def triple_bush(p, r, q):
    """t_{p,r,q}: a path X–M–Y with p, r, q leaves on X, M, Y."""
    G = nx.Graph([("X", "M"), ("M", "Y")])
    G.add_edges_from(("X", f"x{i}") for i in range(p))
    G.add_edges_from(("M", f"m{i}") for i in range(r))
    G.add_edges_from(("Y", f"y{i}") for i in range(q))
    return G


def asymbush(q):
    """One leaf L and q branches of length two on a vertex V."""
    G = nx.Graph([("V", "L")])
    for i in range(q):
        G.add_edges_from([("V", f"w{i}"), (f"w{i}", f"z{i}")])
    return G
