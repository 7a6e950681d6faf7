"""Slow, independent reference implementation for the rkcheck test-suite.

Everything here is derived by brute force from the definitions in
``docs/definitions.md`` §2 and §3 (Celledoni/Owren/Sun, Section 2;
Chartier/Faou/Murua Theorem 2).  Nothing is imported from ``rkcheck``.
Speed is irrelevant; clarity is the point.

Conventions
-----------
* A rooted tree is a *level sequence*: the depth of every vertex in
  depth-first (pre-)order, the root having depth 1.  ``(1,)`` is the one-node
  tree tau, ``(1, 2, 3, 2)`` is ``[[tau] tau]``.
* Canonical form = the lexicographically LARGEST level sequence over all
  orderings of children (same convention as RootedTrees.jl).
* Free trees are ``networkx.Graph`` objects (unrooted trees).
* Tableaux: ``A`` is a list of rows (lists) of ``Fraction``, ``b`` a list of
  ``Fraction``.  ``c = A.1`` is never passed: it is implicit in the
  recursion ``Phi([t1..tq]) = (A Phi(t1)) * ... * (A Phi(tq))``.
"""

from __future__ import annotations

import itertools
import math
from collections import Counter, deque
from fractions import Fraction

import networkx as nx

LevelSeq = tuple  # tuple[int, ...]

# ---------------------------------------------------------------------------
# Rooted trees as level sequences
# ---------------------------------------------------------------------------


def is_level_sequence(seq) -> bool:
    """True iff ``seq`` is the level sequence of some (ordered) rooted tree."""
    seq = tuple(seq)
    if not seq or seq[0] != 1:
        return False
    for i in range(1, len(seq)):
        if seq[i] < 2 or seq[i] > seq[i - 1] + 1:
            return False
    return True


def split_children(level_seq) -> list[tuple]:
    """Sub-sequences of the children of the root, re-based to root depth 1,
    in the order in which they appear in ``level_seq`` (NOT canonicalised)."""
    seq = tuple(level_seq)
    assert is_level_sequence(seq), seq
    blocks: list[list[int]] = []
    for d in seq[1:]:
        if d == 2:
            blocks.append([])
        blocks[-1].append(d - 1)
    return [tuple(bl) for bl in blocks]


def level_sequence_to_adj(level_seq) -> dict:
    """Adjacency dict {vertex index: set(neighbours)} of a level sequence;
    vertex 0 is the root, vertices numbered in depth-first order."""
    seq = tuple(level_seq)
    assert is_level_sequence(seq), seq
    adj: dict[int, set] = {i: set() for i in range(len(seq))}
    stack: list[int] = []  # stack[k] = most recent vertex at depth k+1
    for i, d in enumerate(seq):
        del stack[d - 1:]
        if stack:
            parent = stack[-1]
            adj[i].add(parent)
            adj[parent].add(i)
        stack.append(i)
    return adj


def canonical_level_sequence(adj, root) -> tuple:
    """Canonical (lexicographically largest) level sequence of the tree given
    by the adjacency mapping ``adj`` (vertex -> iterable of neighbours),
    rooted at ``root``.

    Children blocks are canonicalised recursively and concatenated in
    decreasing lexicographic (Python tuple) order.  Why that is the maximum:
    with the positions of the blocks fixed each block must itself be maximal;
    and since every child block starts with its only '2', comparing two
    concatenations reduces to comparing blocks where a shorter prefix loses
    (the next block's '2' is smaller than any continuation >= 3).  The test
    file cross-checks this against a max over all permutations.
    """

    def rec(v, parent):
        blocks = [rec(w, v) for w in adj[v] if w != parent]
        blocks.sort(reverse=True)
        out = [1]
        for bl in blocks:
            out.extend(d + 1 for d in bl)
        return tuple(out)

    return rec(root, None)


def canonicalize(level_seq) -> tuple:
    """Canonical form of a (possibly non-canonical) level sequence."""
    return canonical_level_sequence(level_sequence_to_adj(level_seq), 0)


def canonical_level_sequence_bruteforce(level_seq) -> tuple:
    """Canonical form by literally maximising over every permutation of the
    children at every vertex (exponential; only for self-checks)."""

    def rec(seq):
        children = split_children(seq)
        kids = [rec(ch) for ch in children]
        best = None
        for perm in itertools.permutations(kids):
            cand = (1,) + tuple(d + 1 for bl in perm for d in bl)
            if best is None or cand > best:
                best = cand
        return best if best is not None else (1,)

    return rec(tuple(level_seq))


def all_level_sequences(n: int):
    """Every level sequence (ordered rooted tree) with n vertices."""
    if n < 1:
        return
    def rec(prefix):
        if len(prefix) == n:
            yield tuple(prefix)
            return
        for d in range(2, prefix[-1] + 2):
            prefix.append(d)
            yield from rec(prefix)
            prefix.pop()
    yield from rec([1])


def rooted_trees(n: int) -> list[tuple]:
    """All (unordered) rooted trees with n vertices, as canonical level
    sequences, by brute force: canonicalise every ordered rooted tree with n
    vertices (Catalan(n-1) of them) and deduplicate.  Sorted ascending."""
    return sorted({canonicalize(s) for s in all_level_sequences(n)})


def subtrees_at_root(level_seq) -> list[tuple]:
    """The forest B_-(u): canonical level sequences of the subtrees hanging
    from the root, each re-based to root depth 1.  Sorted descending (a
    multiset: repetitions are kept)."""
    return sorted((canonicalize(ch) for ch in split_children(level_seq)),
                  reverse=True)


def sigma(level_seq) -> int:
    """Symmetry coefficient: sigma(tau)=1,
    sigma([t1^r1 ... tp^rp]) = prod r_i! * sigma(t_i)^r_i."""
    kids = subtrees_at_root(level_seq)
    result = 1
    for t, r in Counter(kids).items():
        result *= math.factorial(r) * sigma(t) ** r
    return result


def gamma(level_seq) -> int:
    """Density: gamma(tau)=1, gamma(t) = |t| * prod gamma(children)."""
    result = len(level_seq)
    for t in subtrees_at_root(level_seq):
        result *= gamma(t)
    return result


def order_of(level_seq) -> int:
    return len(level_seq)


def butcher_bracket(level_seq) -> str:
    """Butcher bracket notation, e.g. 'τ', '[τ]', '[τ²]', '[[τ]τ]'."""
    sup = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")
    kids = subtrees_at_root(level_seq)
    if not kids:
        return "τ"
    parts = []
    for t, r in sorted(Counter(kids).items(), reverse=True):
        s = butcher_bracket(t)
        parts.append(s if r == 1 else s + str(r).translate(sup))
    return "[" + "".join(parts) + "]"


# ---------------------------------------------------------------------------
# Elementary weights
# ---------------------------------------------------------------------------


def _check_tableau(A, b):
    s = len(b)
    assert len(A) == s and all(len(row) == s for row in A), "A must be s x s"


def elementary_weight_vector(level_seq, A) -> list[Fraction]:
    """Phi(t): Phi(tau) = 1 (ones), Phi([t1..tq]) = (A Phi(t1)) * ... *
    (A Phi(tq)) componentwise."""
    s = len(A)
    phi = [Fraction(1)] * s
    for t in split_children(level_seq):
        child = elementary_weight_vector(t, A)
        a_child = [sum((Fraction(A[i][j]) * child[j] for j in range(s)),
                       Fraction(0)) for i in range(s)]
        phi = [phi[i] * a_child[i] for i in range(s)]
    return phi


def elementary_weight(level_seq, A, b) -> Fraction:
    """a(t) = b^T Phi(t)."""
    _check_tableau(A, b)
    phi = elementary_weight_vector(level_seq, A)
    return sum((Fraction(b[i]) * phi[i] for i in range(len(b))), Fraction(0))


def forest_weight(forest, A, b) -> Fraction:
    """a(t1 ... tq) = prod a(t_k); empty forest -> 1."""
    result = Fraction(1)
    for t in forest:
        result *= elementary_weight(t, A, b)
    return result


def classical_order(A, b, max_order: int) -> int:
    """Largest p <= max_order such that a(t) = 1/gamma(t) for every rooted
    tree with at most p vertices (0 if even a(tau) = sum(b) != 1)."""
    p = 0
    for n in range(1, max_order + 1):
        if all(elementary_weight(t, A, b) == Fraction(1, gamma(t))
               for t in rooted_trees(n)):
            p = n
        else:
            break
    return p


# ---------------------------------------------------------------------------
# Free trees
# ---------------------------------------------------------------------------


def free_trees(n: int) -> list[nx.Graph]:
    """All free (unrooted) trees with n vertices, via networkx."""
    if n < 1:
        return []
    if n == 1:
        g = nx.Graph()
        g.add_node(0)
        return [g]
    if n == 2:
        return [nx.path_graph(2)]
    return [nx.Graph(g) for g in nx.nonisomorphic_trees(n)]


def free_tree_classes_bruteforce(n: int) -> set[frozenset]:
    """Free trees with n vertices identified with their set of rootings,
    computed from rooted_trees(n) only (no networkx enumeration); used to
    cross-check free_trees()."""
    classes = set()
    for t in rooted_trees(n):
        adj = level_sequence_to_adj(t)
        classes.add(frozenset(canonical_level_sequence(adj, v) for v in adj))
    return classes


def _adj(G) -> dict:
    return {v: list(G.neighbors(v)) for v in G.nodes}


def _graph_max_degree(G) -> int:
    return max((d for _, d in G.degree()), default=0)


def max_degree(G) -> int:
    """Maximum number of edges at a vertex (0 for the one-vertex tree)."""
    return _graph_max_degree(G)


def _distances(G, source) -> dict:
    """Breadth-first graph distances from ``source`` (own BFS)."""
    dist = {source: 0}
    queue = deque([source])
    while queue:
        v = queue.popleft()
        for w in G.neighbors(v):
            if w not in dist:
                dist[w] = dist[v] + 1
                queue.append(w)
    return dist


def _component(G, start, removed_edge) -> set:
    """Vertices reachable from ``start`` without using ``removed_edge``."""
    u0, v0 = removed_edge
    seen = {start}
    stack = [start]
    while stack:
        v = stack.pop()
        for w in G.neighbors(v):
            if {v, w} == {u0, v0}:
                continue
            if w not in seen:
                seen.add(w)
                stack.append(w)
    return seen


def edge_halves(G, u, v) -> tuple[tuple, tuple]:
    """Canonical level sequences of the two halves left by removing edge
    {u, v}, rooted at u and v respectively."""
    halves = []
    for root in (u, v):
        comp = _component(G, root, (u, v))
        sub_adj = {x: [y for y in G.neighbors(x) if y in comp] for x in comp}
        halves.append(canonical_level_sequence(sub_adj, root))
    return halves[0], halves[1]


def is_superfluous(G) -> bool:
    """True iff some edge's removal leaves two isomorphic rooted halves
    (rooted at the edge's endpoints), i.e. some rooting is u∘u."""
    for u, v in G.edges():
        h1, h2 = edge_halves(G, u, v)
        if h1 == h2:
            return True
    return False


def rootings(G, designated_root) -> list[tuple[tuple, int]]:
    """The DISTINCT rooted trees pi^{-1}(G) with the parity of the distance
    kappa from ``designated_root``.

    Each rooted tree appears once.  For a non-superfluous G all vertices giving
    the same rooted tree have the same parity (asserted).  For a superfluous G
    the parity is ill-defined; the parity of the vertex with smallest distance
    from the designated root is returned.  Sorted by level sequence,
    descending."""
    adj = _adj(G)
    dist = _distances(G, designated_root)
    assert len(dist) == G.number_of_nodes(), "G must be connected"
    parities: dict[tuple, set] = {}
    best: dict[tuple, int] = {}
    for v in G.nodes:
        t = canonical_level_sequence(adj, v)
        parities.setdefault(t, set()).add(dist[v] % 2)
        if t not in best or dist[v] < best[t]:
            best[t] = dist[v]
    if not is_superfluous(G):
        for t, ps in parities.items():
            assert len(ps) == 1, (t, ps)
    return sorted(((t, best[t] % 2) for t in best), reverse=True)


def centres(G) -> list:
    """Vertices of minimal eccentricity (own BFS)."""
    ecc = {v: max(_distances(G, v).values()) for v in G.nodes}
    m = min(ecc.values())
    return [v for v in G.nodes if ecc[v] == m]


def designated_centre(G):
    """(vertex, canonical level sequence) of the designated rooting: the
    centre, or for two centres the one with the larger level sequence
    (ties -- only possible for superfluous trees -- broken arbitrarily)."""
    adj = _adj(G)
    cands = [(canonical_level_sequence(adj, v), v) for v in centres(G)]
    assert 1 <= len(cands) <= 2
    seq, v = max(cands, key=lambda p: p[0])
    return v, seq


def centre_canonical_id(G) -> tuple:
    return designated_centre(G)[1]


# ---------------------------------------------------------------------------
# Energy conditions
# ---------------------------------------------------------------------------


def energy_conditions(n: int, max_degree=None) -> list[dict]:
    """One dict per non-superfluous free tree with n vertices whose maximum
    vertex degree is <= max_degree (None: no bound).

    keys: id (centre canonical id), max_degree, terms = list of
    (u, sign, sigma(u), B_-(u)), sign = (-1)^dist(designated centre, root of u).
    Sorted by id descending.

    NB: for n = 1 this returns the one-vertex tree (terms [((1,), 1, 1, [])],
    residual 1); the paper's sum starts at n >= 2, so it is not a condition.
    n = 2 gives nothing (the single edge is superfluous)."""
    bound = max_degree
    out = []
    for G in free_trees(n):
        if is_superfluous(G):
            continue
        md = _graph_max_degree(G)
        if bound is not None and md > bound:
            continue
        centre, cid = designated_centre(G)
        terms = []
        for u, parity in rootings(G, centre):
            terms.append((u, -1 if parity else 1, sigma(u),
                          subtrees_at_root(u)))
        out.append({"id": cid, "max_degree": md, "terms": terms})
    out.sort(key=lambda d: d["id"], reverse=True)
    ids = [d["id"] for d in out]
    assert len(set(ids)) == len(ids), "free trees must be pairwise distinct"
    return out


def energy_residual(cond, A, b) -> Fraction:
    """R = sum_u sign/sigma(u) * prod_{t in B_-(u)} a(t)."""
    total = Fraction(0)
    for u, sign, sig, forest in cond["terms"]:
        total += Fraction(sign, sig) * forest_weight(forest, A, b)
    return total


def count_nonsuperfluous(n: int, max_degree=None) -> int:
    bound = max_degree
    return sum(1 for G in free_trees(n)
               if not is_superfluous(G)
               and (bound is None or _graph_max_degree(G) <= bound))
