"""Self-checks of tests/reference.py against published values only
(OEIS, SPEC.md §2–3, the seed paper's Section 2, classical RK4)."""

import math
import random
from fractions import Fraction as F

import networkx as nx
import pytest

from support import reference as ref

A000081 = [1, 1, 2, 4, 9, 20, 48, 115, 286]            # n = 1..9
A000055 = [1, 1, 1, 2, 3, 6, 11, 23, 47, 106, 235, 551]  # n = 1..12
NONSUPERFLUOUS = {3: 1, 4: 1, 5: 3, 6: 4, 7: 11, 8: 19, 9: 47, 10: 97,
                  11: 235, 12: 531}                      # SPEC §3

RK4_A = [[F(0), F(0), F(0), F(0)],
         [F(1, 2), F(0), F(0), F(0)],
         [F(0), F(1, 2), F(0), F(0)],
         [F(0), F(0), F(1), F(0)]]
RK4_B = [F(1, 6), F(1, 3), F(1, 3), F(1, 6)]


def random_tableau(rng, s, sum_b_one=True):
    A = [[F(rng.randint(-9, 9), rng.randint(1, 7)) for _ in range(s)]
         for _ in range(s)]
    b = [F(rng.randint(-9, 9), rng.randint(1, 7)) for _ in range(s)]
    if sum_b_one:
        b[-1] = 1 - sum(b[:-1])
    return A, b


def row_sums(A):
    return [sum(row, F(0)) for row in A]


def tableau_with_quadrature(rng, s):
    """Random A with distinct row sums c and b solving the quadrature
    conditions sum b c^(k-1) = 1/k, k = 1..s (exact Gauss elimination)."""
    while True:
        c = [F(rng.randint(-20, 20), rng.randint(1, 9)) for _ in range(s)]
        if len(set(c)) == s:
            break
    M = [[c[j] ** k for j in range(s)] + [F(1, k + 1)] for k in range(s)]
    for col in range(s):  # Gauss-Jordan on the (invertible) Vandermonde
        piv = next(r for r in range(col, s) if M[r][col] != 0)
        M[col], M[piv] = M[piv], M[col]
        M[col] = [x / M[col][col] for x in M[col]]
        for r in range(s):
            if r != col and M[r][col] != 0:
                f = M[r][col]
                M[r] = [x - f * y for x, y in zip(M[r], M[col])]
    b = [M[k][s] for k in range(s)]
    A = [[F(rng.randint(-9, 9), rng.randint(1, 7)) for _ in range(s)]
         for _ in range(s)]
    for i in range(s):
        A[i][-1] = c[i] - sum(A[i][:-1])
    for k in range(1, s + 1):
        assert sum(bi * ci ** (k - 1) for bi, ci in zip(b, c)) == F(1, k)
    assert row_sums(A) == c
    return A, b, c


def condition_for(G, max_n_bound=None):
    """The energy condition (from energy_conditions) of free tree G."""
    cid = ref.centre_canonical_id(G)
    conds = [d for d in ref.energy_conditions(G.number_of_nodes())
             if d["id"] == cid]
    assert len(conds) == 1
    return conds[0]


# ---------------------------------------------------------------- trees


def test_level_sequence_convention():
    # [[τ]τ]: root with a child that has a child, and a leaf child.
    adj = {0: [1, 3], 1: [0, 2], 2: [1], 3: [0]}
    assert ref.canonical_level_sequence(adj, 0) == (1, 2, 3, 2)
    adj2 = {0: [3, 1], 1: [0], 3: [0, 2], 2: [3]}  # other child order
    assert ref.canonical_level_sequence(adj2, 0) == (1, 2, 3, 2)
    assert ref.canonicalize((1, 2, 2, 3)) == (1, 2, 3, 2)
    assert ref.butcher_bracket((1, 2, 3, 2)) == "[[τ]τ]"
    assert ref.butcher_bracket((1, 2, 2)) == "[τ²]"
    assert ref.butcher_bracket((1,)) == "τ"


def test_sorted_children_is_lexicographic_maximum():
    for n in range(1, 9):
        for s in ref.all_level_sequences(n):
            assert ref.canonicalize(s) == \
                ref.canonical_level_sequence_bruteforce(s)
            assert ref.canonicalize(s) >= s


@pytest.mark.parametrize("n", range(1, 10))
def test_rooted_tree_counts_A000081(n):
    trees = ref.rooted_trees(n)
    assert len(trees) == A000081[n - 1]
    assert all(len(t) == n for t in trees)


def test_rooted_trees_small_explicit():
    assert ref.rooted_trees(3) == [(1, 2, 2), (1, 2, 3)]
    assert ref.rooted_trees(4) == [(1, 2, 2, 2), (1, 2, 3, 2),
                                   (1, 2, 3, 3), (1, 2, 3, 4)]


@pytest.mark.parametrize("t,s,g", [
    ((1,), 1, 1),
    ((1, 2), 1, 2),
    ((1, 2, 2), 2, 3),        # [τ²]
    ((1, 2, 3), 1, 6),        # [[τ]]
    ((1, 2, 3, 2), 1, 8),     # [[τ]τ]
    ((1, 2, 2, 2), 6, 4),     # [τ³]
    ((1, 2, 3, 3), 2, 12),    # [[τ²]]
    ((1, 2, 3, 4), 1, 24),    # [[[τ]]]
    ((1, 2, 3, 2, 3), 2, 20),  # [[τ]²]
    ((1, 2, 2, 2, 2), 24, 5),  # [τ⁴]
])
def test_sigma_gamma_by_hand(t, s, g):
    assert ref.sigma(t) == s
    assert ref.gamma(t) == g


@pytest.mark.parametrize("n", range(1, 8))
def test_sum_over_trees_identities(n):
    # Published identities (Butcher; Hairer–Nørsett–Wanner I.2):
    # Σ_{|t|=n} α(t) = (n−1)! with α(t) = n!/(σ(t)γ(t)) (increasing labelled
    # trees), and Σ_{|t|=n} n!/σ(t) = n^(n−1) (labelled rooted trees, Cayley).
    trees = ref.rooted_trees(n)
    assert sum(F(math.factorial(n), ref.sigma(t) * ref.gamma(t))
               for t in trees) == math.factorial(n - 1)
    assert sum(F(math.factorial(n), ref.sigma(t)) for t in trees) == \
        n ** (n - 1)


def test_subtrees_at_root():
    assert ref.subtrees_at_root((1,)) == []
    assert sorted(ref.subtrees_at_root((1, 2, 3, 2))) == [(1,), (1, 2)]
    assert ref.subtrees_at_root((1, 2, 2, 2)) == [(1,)] * 3
    assert ref.subtrees_at_root((1, 2, 3, 4, 3)) == [(1, 2, 3, 2)]


# ---------------------------------------------------------- weights


def test_elementary_weights_formulas():
    rng = random.Random(1)
    A, b = random_tableau(rng, 3, sum_b_one=False)
    c = row_sums(A)
    Ac = [sum(A[i][j] * c[j] for j in range(3)) for i in range(3)]
    assert ref.elementary_weight((1,), A, b) == sum(b)
    assert ref.elementary_weight((1, 2), A, b) == \
        sum(bi * ci for bi, ci in zip(b, c))
    assert ref.elementary_weight((1, 2, 2), A, b) == \
        sum(bi * ci ** 2 for bi, ci in zip(b, c))
    assert ref.elementary_weight((1, 2, 3), A, b) == \
        sum(bi * x for bi, x in zip(b, Ac))
    assert ref.elementary_weight((1, 2, 3, 2), A, b) == \
        sum(bi * ci * x for bi, ci, x in zip(b, c, Ac))


def test_rk4_classical_order_is_exactly_4():
    assert ref.classical_order(RK4_A, RK4_B, 8) == 4
    for n in range(1, 5):
        for t in ref.rooted_trees(n):
            assert ref.elementary_weight(t, RK4_A, RK4_B) == \
                F(1, ref.gamma(t))
    assert any(ref.elementary_weight(t, RK4_A, RK4_B) != F(1, ref.gamma(t))
               for t in ref.rooted_trees(5))


def test_other_classical_orders():
    # explicit Euler: order 1; midpoint (implicit, Gauss s=1): order 2;
    # Lobatto IIIA s=3: order 4.
    assert ref.classical_order([[F(0)]], [F(1)], 6) == 1
    assert ref.classical_order([[F(1, 2)]], [F(1)], 6) == 2
    lob_A = [[F(0), F(0), F(0)],
             [F(5, 24), F(1, 3), F(-1, 24)],
             [F(1, 6), F(2, 3), F(1, 6)]]
    lob_b = [F(1, 6), F(2, 3), F(1, 6)]
    assert ref.classical_order(lob_A, lob_b, 6) == 4
    assert ref.classical_order([[F(0)]], [F(2)], 6) == 0


# ------------------------------------------------------------ free trees


@pytest.mark.parametrize("n", range(1, 13))
def test_free_tree_counts_A000055(n):
    assert len(ref.free_trees(n)) == A000055[n - 1]


@pytest.mark.parametrize("n", range(1, 10))
def test_free_trees_match_bruteforce_classes(n):
    from_nx = {frozenset(t for t, _ in ref.rootings(G, next(iter(G.nodes))))
               for G in ref.free_trees(n)}
    assert from_nx == ref.free_tree_classes_bruteforce(n)
    assert len(from_nx) == A000055[n - 1]


@pytest.mark.parametrize("n", range(3, 13))
def test_nonsuperfluous_counts(n):
    assert ref.count_nonsuperfluous(n) == NONSUPERFLUOUS[n]


@pytest.mark.parametrize("k", range(1, 7))
def test_superfluous_counts_A000081(k):
    n = 2 * k
    sup = sum(1 for G in ref.free_trees(n) if ref.is_superfluous(G))
    assert sup == A000081[k - 1]
    assert sum(1 for G in ref.free_trees(n - 1)
               if ref.is_superfluous(G)) == 0  # odd orders: none


def test_degree_bounded_counts():
    # m = 2: only the odd paths survive; m = 1: nothing (n >= 2).
    for n in range(2, 13):
        assert ref.count_nonsuperfluous(n, 2) == (n % 2)
        assert ref.count_nonsuperfluous(n, 1) == 0
    # degree bound >= n-1 is no bound
    for n in range(3, 10):
        assert ref.count_nonsuperfluous(n, n - 1) == NONSUPERFLUOUS[n]
    # brute force over the conditions list agrees with count
    for n in range(3, 10):
        for m in range(1, n):
            conds = ref.energy_conditions(n, m)
            assert len(conds) == ref.count_nonsuperfluous(n, m)
            assert all(d["max_degree"] <= m for d in conds)


def test_centre_id_two_centres_takes_larger():
    # double bush t_{1,2}: x has 1 leaf, y has 2 leaves
    G = nx.Graph([("x", "y"), ("x", "l1"), ("y", "m1"), ("y", "m2")])
    v, cid = ref.designated_centre(G)
    assert set(ref.centres(G)) == {"x", "y"}
    assert cid == max((1, 2, 3, 3, 2), (1, 2, 3, 2, 2)) == (1, 2, 3, 3, 2)
    assert v == "x"
    assert ref.centre_canonical_id(nx.path_graph(5)) == (1, 2, 3, 2, 3)
    assert ref.max_degree(G) == 3


def test_parity_well_defined_for_nonsuperfluous():
    # rootings() asserts it internally; exercise all trees up to 10 vertices
    for n in range(1, 11):
        for G in ref.free_trees(n):
            if not ref.is_superfluous(G):
                ref.rootings(G, ref.designated_centre(G)[0])


def test_superfluous_path_has_ambiguous_parity():
    # path with 4 vertices: rooting (1,2,3,4) arises at both ends (distance 3
    # apart -> different parities), which is why it gives no condition.
    G = nx.path_graph(4)
    assert ref.is_superfluous(G)
    assert not ref.is_superfluous(nx.path_graph(5))
    assert not ref.is_superfluous(nx.star_graph(3))


# ------------------------------------------------------ energy conditions


@pytest.mark.parametrize("k", range(2, 7))
def test_star_residual_is_quadrature_condition(k):
    """Star with k leaves, designated centre = hub: u = [τ^k] (sign +,
    σ = k!, a(B_-) = (Σb)^k = 1) and u' = [[τ^(k−1)]] (sign −, σ = (k−1)!,
    a(B_-) = Σ b c^(k−1)).  So R = 1/k! − Σ b c^(k−1)/(k−1)!
    = −(Σ b c^(k−1) − 1/k)/(k−1)!."""
    rng = random.Random(100 + k)
    A, b = random_tableau(rng, 3)
    c = row_sums(A)
    G = nx.star_graph(k)  # hub 0 and k leaves
    cond = condition_for(G)
    assert ref.designated_centre(G)[0] == 0
    assert len(cond["terms"]) == 2
    assert cond["max_degree"] == k
    quad = sum(bi * ci ** (k - 1) for bi, ci in zip(b, c))
    R = ref.energy_residual(cond, A, b)
    assert R == -(quad - F(1, k)) / math.factorial(k - 1)


@pytest.mark.parametrize("p,q", [(1, 2), (1, 3), (2, 3), (1, 4)])
def test_double_bush_linear_condition(p, q):
    """Seed eq. (DBmono): given the quadrature conditions,
    R(t_{p,q}) ∝ p bᵀC^{p−1}Ac^q − q bᵀC^{q−1}Ac^p − (1/(q+1) − 1/(p+1)).
    By hand (rootings at leaf of x, x, y, leaf of y with σ = (p−1)!q!,
    p!q!, p!q!, p!(q−1)!, and designated centre x):
    R = −(LHS − RHS)/(p! q!)."""
    rng = random.Random(10 * p + q)
    A, b, c = tableau_with_quadrature(rng, q + 1)
    s = len(b)
    edges = [("x", "y")] + [("x", f"l{i}") for i in range(p)] + \
        [("y", f"m{i}") for i in range(q)]
    G = nx.Graph(edges)
    cond = condition_for(G)
    assert len(cond["terms"]) == 4

    def bCAc(e1, e2):  # bᵀ C^e1 A c^e2
        return sum(b[i] * c[i] ** e1 * sum(A[i][j] * c[j] ** e2
                                           for j in range(s))
                   for i in range(s))

    lhs = p * bCAc(p - 1, q) - q * bCAc(q - 1, p)
    rhs = F(1, q + 1) - F(1, p + 1)
    centre = ref.designated_centre(G)[0]
    sign = 1 if centre == "x" else -1
    R = ref.energy_residual(cond, A, b)
    assert R == -sign * (lhs - rhs) / (math.factorial(p) * math.factorial(q))


def test_avf_simpson_preserves_degree_4():
    """A = c bᵀ with Simpson's rule (exact to degree 3, i.e. quadrature
    conditions k = 1..4) is the AVF method for H of degree <= 4 (seed §1):
    every condition with max degree <= 4 vanishes; the star with 5 leaves
    fails (Σ b c^4 = 5/24 ≠ 1/5)."""
    c = [F(0), F(1, 2), F(1)]
    b = [F(1, 6), F(2, 3), F(1, 6)]
    A = [[ci * bj for bj in b] for ci in c]
    for n in range(3, 9):
        for cond in ref.energy_conditions(n, 4):
            assert ref.energy_residual(cond, A, b) == 0, cond["id"]
    star5 = condition_for(nx.star_graph(5))
    assert ref.energy_residual(star5, A, b) == \
        -(F(5, 24) - F(1, 5)) / math.factorial(4)


def test_midpoint_preserves_quadratic_energy():
    """Implicit midpoint (Gauss s = 1) is AVF for quadratic H: all
    conditions with max degree <= 2 (odd paths) vanish, but not degree 3."""
    A, b = [[F(1, 2)]], [F(1)]
    for n in range(3, 12, 2):
        (cond,) = ref.energy_conditions(n, 2)
        assert ref.energy_residual(cond, A, b) == 0
    assert ref.energy_residual(condition_for(nx.star_graph(3)), A, b) != 0


def test_sign_flips_with_designated_root_but_not_zero_ness():
    rng = random.Random(7)
    A, b = random_tableau(rng, 3)
    for n in range(3, 8):
        for G in ref.free_trees(n):
            if ref.is_superfluous(G):
                continue
            centre = ref.designated_centre(G)[0]
            nbr = next(iter(G.neighbors(centre)))
            r0 = ref.rootings(G, centre)
            r1 = ref.rootings(G, nbr)
            assert [t for t, _ in r0] == [t for t, _ in r1]
            assert all(p0 != p1 for (_, p0), (_, p1) in zip(r0, r1))


def test_energy_conditions_terms_consistent():
    for n in range(3, 9):
        for cond in ref.energy_conditions(n):
            us = [u for u, *_ in cond["terms"]]
            assert len(set(us)) == len(us)
            assert cond["id"] in us
            for u, sign, sig, forest in cond["terms"]:
                assert len(u) == n and sign in (1, -1)
                assert sig == ref.sigma(u)
                assert forest == ref.subtrees_at_root(u)
                if u == cond["id"]:
                    assert sign == 1
