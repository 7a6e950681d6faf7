"""Free trees drawn from level sequences: the drawing, read back, is the tree of the level
sequence (vertices, edges, up to isomorphism), with its centres and the given rooting's
root where the brute-force reference puts them."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import networkx as nx
import pytest
from support import reference as ref
from support.clirun import run_cli

from rkcheck.trees.drawing import VERTEX, draw


def read_back(lines: list[str]) -> tuple[tuple[int, ...], list[list[str]]]:
    """The level sequence a drawing shows (a vertex's level = its column / 4 + 1: each
    generation is indented four columns) and each vertex's labels."""
    levels, labels = [], []
    for line in lines:
        col = line.index(VERTEX)
        assert col % 4 == 0 and set(line[:col]) <= set("│├└─ "), line
        levels.append(col // 4 + 1)
        labels.append([x for x in line[col + 1:].strip().split(", ") if x])
    return tuple(levels), labels


def graph(seq) -> nx.Graph:
    adj = ref.level_sequence_to_adj(seq)
    return nx.Graph([(v, w) for v in adj for w in adj[v]]) if len(seq) > 1 else nx.empty_graph(1)


def rooting(seq, vertex) -> tuple:
    return ref.canonical_level_sequence(ref.level_sequence_to_adj(seq), vertex)


@pytest.mark.parametrize("n", range(1, 9))
def test_the_drawing_is_the_tree_of_the_level_sequence(n):
    for given in ref.rooted_trees(n):
        lines = draw(given).lines()
        shown, labels = read_back(lines)
        assert ref.is_level_sequence(shown) and len(shown) == n
        G, H = graph(given), graph(shown)
        assert H.number_of_edges() == n - 1 and nx.is_isomorphic(G, H), (given, lines)
        # the top is the designated centre; "centre" marks the reference's centres
        assert rooting(shown, 0) == ref.centre_canonical_id(G)
        marked = [v for v, lab in enumerate(labels) if "centre" in lab]
        assert sorted(rooting(shown, v) for v in marked) == sorted(rooting(given, c) for c in ref.centres(G))
        # "root" marks the vertex whose rooting is the one given
        (root,) = [v for v, lab in enumerate(labels) if "root" in lab]
        assert rooting(shown, root) == ref.canonicalize(given)


def test_explain_draws_the_quoted_tree(capsys):
    # 1,2,3,3,2,2 is superfluous (two centres, equal halves): drawn all the same
    r = run_cli(capsys, "explain", "1,2,3,3,2,2")
    lines = [line for line in r.out.splitlines() if VERTEX in line]
    shown, labels = read_back(lines)
    assert nx.is_isomorphic(graph(shown), graph((1, 2, 3, 3, 2, 2)))
    assert sum("centre" in lab for lab in labels) == len(ref.centres(graph((1, 2, 3, 3, 2, 2)))) == 2


def test_verify_draw_draws_each_failing_condition(capsys):
    # Heun's method for quadratic H to order 4: one failing condition, drawn below its table
    r = run_cli(capsys, "verify", "@heun", "--degree", "2", "--order", "4", "--draw", "--fail-on", "conditions")
    ids = [line.split()[0] for line in r.out.splitlines() if re.match(r"\s+1,[\d,]+\s+\[", line)]
    assert ids == ["1,2,3,2,3"]
    after = r.out.split("drawn from the centre:")[1].splitlines()
    assert after[1].strip() == ids[0]
    block = []
    for line in after[2:]:
        if VERTEX not in line:
            break
        block.append(line.rstrip())
    shown, labels = read_back(block)
    seq = tuple(int(x) for x in ids[0].split(","))
    assert nx.is_isomorphic(graph(shown), graph(seq)) and not any("root" in lab for lab in labels)


def test_explain_draws_a_picture(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    given = (1, 2, 3, 4, 2, 3, 2, 2)
    out = tmp_path / "tree.svg"
    r = run_cli(capsys, "explain", ",".join(map(str, given)), "--draw", str(out))
    assert r.code == 0, r.err
    ids = [el.get("id") for el in ET.parse(out).iter() if el.get("id")]
    vertices = [i for i in ids if i.startswith("vertex-")]
    edges = [tuple(map(int, i.split("-")[1:])) for i in ids if i.startswith("edge-")]
    assert len(vertices) == len(given) and len(edges) == len(given) - 1
    G = nx.Graph(edges)
    assert nx.is_isomorphic(G, graph(given))
    assert len([v for v in vertices if v.endswith("-centre")]) == len(ref.centres(graph(given)))
    (root,) = [int(i.split("-")[1]) for i in ids if i.startswith("root-")]
    adj = {v: set(G[v]) for v in G}
    assert ref.canonical_level_sequence(adj, root) == ref.canonicalize(given)
    png = tmp_path / "tree.png"
    assert run_cli(capsys, "explain", "1,2,3", "--draw", str(png)).code == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    bad = run_cli(capsys, "explain", "1,2,3", "--draw", str(tmp_path / "tree.txt"))
    assert bad.code == 2 and "--draw" in bad.err


def test_explain_picture_without_matplotlib_is_one_line(capsys, tmp_path, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "matplotlib", None)  # as if the plot extra were missing
    r = run_cli(capsys, "explain", "1,2,3", "--draw", str(tmp_path / "t.svg"))
    assert r.code == 2 and "rkcheck[plot]" in r.err and len(r.err.strip().splitlines()) == 1


@pytest.mark.parametrize("given, what", [
    # one vertex: no edge, so nothing superfluous about it; below the conditions (3 vertices)
    ("1", "1 vertex — fewer than 3 vertices; no energy condition"),
    # two vertices: τ∘τ, equal halves across the edge (definitions §3)
    ("1,2", "2 vertices — superfluous free tree: a rooting u∘u exists"),
])
def test_explain_says_why_a_small_tree_gives_no_condition(capsys, given, what):
    r = run_cli(capsys, "explain", given)
    assert r.code == 0 and r.out.splitlines()[0].startswith(f"{given}: {what}"), r.out
