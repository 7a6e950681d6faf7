"""Elementary weights of continuous-stage methods: the surrogate tableau against exact
symbolic integration (sympy) of the definitions §6 recursion, tree by tree."""

from fractions import Fraction

import pytest

sympy = pytest.importorskip("sympy")

from rkcheck.methods.continuous import ContinuousMethod  # noqa: E402
from rkcheck.methods.quadrature import positive_rule, rational_rule  # noqa: E402

tau, sigma = sympy.symbols("tau sigma")


def rooted_trees(n):
    """Every rooted tree with n vertices, as nested tuples of children (sorted)."""
    if n == 1:
        return [()]
    out = set()

    def forests(m, smallest):
        if m == 0:
            yield ()
            return
        for k in range(1, m + 1):
            for t in rooted_trees(k):
                if (k, t) < smallest:
                    continue
                for rest in forests(m - k, (k, t)):
                    yield ((k, t),) + rest

    for f in forests(n - 1, (0, ())):
        out.add(tuple(sorted(t for _, t in f)))
    return sorted(out)


def stage_sympy(tree, A):
    """g_t(τ) = Π_k ∫₀¹ A(τ,σ) g_{t_k}(σ) dσ, integrated exactly."""
    g = sympy.Integer(1)
    for child in tree:
        gc = stage_sympy(child, A).subs(tau, sigma)
        g *= sympy.integrate(sympy.expand(A * gc), (sigma, 0, 1))
    return sympy.expand(g)


def weight_sympy(tree, A, B):
    return Fraction(str(sympy.integrate(sympy.expand(B * stage_sympy(tree, A)), (tau, 0, 1))))


def weight_tableau(tree, A, b):
    """a(t) = Σ b_i Π_k (A g_k)_i with plain Fractions."""
    def stage(t):
        v = [Fraction(1)] * len(b)
        for child in t:
            gc = stage(child)
            Ag = [sum(a * g for a, g in zip(row, gc)) for row in A]
            v = [x * y for x, y in zip(v, Ag)]
        return v
    return sum(bi * gi for bi, gi in zip(b, stage(tree)))


KERNELS = [
    ("tau", "1"),
    ("2*tau*sigma", "1"),
    ("tau + 3*(tau^2 - tau)*(2*sigma - 1)", "1"),
    ("tau - tau^2*sigma + 2*tau*sigma^2/3", "3/2 - tau"),
]


@pytest.mark.parametrize("A_text,b_text", KERNELS)
def test_surrogate_weights_equal_exact_integrals(A_text, b_text):
    method = ContinuousMethod.from_kernel(A_text, b_text)
    n = 6
    tab = method.surrogate(n)
    A = [[e.exact for e in row] for row in tab.A]
    b = [e.exact for e in tab.b]
    A_sym = sympy.sympify(A_text.replace("^", "**"))
    B_sym = sympy.sympify(b_text.replace("^", "**"))
    for size in range(1, n + 1):
        for tree in rooted_trees(size):
            assert weight_tableau(tree, A, b) == weight_sympy(tree, A_sym, B_sym), (size, tree)


def test_surrogate_entries_are_the_kernel_at_the_nodes_times_the_weights():
    # a_ij = w_j A(x_i, x_j), b_i = w_i B(x_i), by sympy node by node; and each entry's
    # text reads back as its value
    from rkcheck.numbers.entries import Entry

    A_text, b_text = "tau - 7*tau^2*sigma + 2*tau*sigma^2/3", "3/2 - tau"
    tab = ContinuousMethod.from_kernel(A_text, b_text).surrogate(5)
    x, w = rational_rule(tab.stages)
    A_sym, B_sym = sympy.sympify(A_text.replace("^", "**")), sympy.sympify(b_text.replace("^", "**"))
    for i, xi in enumerate(x):
        assert tab.b[i].exact == Fraction(str(w[i] * B_sym.subs(tau, xi)))
        for j, xj in enumerate(x):
            assert tab.A[i][j].exact == Fraction(str(w[j] * A_sym.subs({tau: xi, sigma: xj})))
    assert any(e.exact < 0 for e in tab.entries())
    assert all(Entry.parse(e.text).exact == e.exact for e in tab.entries())


def test_node_bound_is_needed():
    """With one node fewer than the bound, the tallest-degree tree's weight is wrong:
    the bound is not loose for this kernel."""
    A_text, b_text = "tau - tau^2*sigma + 2*tau*sigma^2/3", "1"
    method = ContinuousMethod.from_kernel(A_text, b_text)
    n = 4
    N = method.nodes_for(n)
    # q = 2, p = 2, deg B = 0: N − 1 = 6 nodes, an even count, exact to degree 5 only
    # (an odd count of equispaced nodes is exact one degree beyond, by symmetry)
    assert N - 1 == max(2 + (n - 2) * 2, 0 + (n - 1) * 2) == 6
    x, w = rational_rule(N - 1)
    k = method.kernel
    A = [[wj * k.number(k.substitute(k.A_poly, k.ring.constant(xi), k.ring.constant(xj)))
          for xj, wj in zip(x, w)] for xi in x]
    b = [wi * k.number(k.substitute(k.B_poly, k.ring.constant(xi), k.ring.constant(0))) for xi, wi in zip(x, w)]
    bush = ((), (), ())  # the root's three leaves: ∫B C³, degree 3·2 = 6 = N − 1
    A_sym, B_sym = sympy.sympify("tau - tau**2*sigma + 2*tau*sigma**2/3"), sympy.sympify("1")
    assert weight_tableau(bush, A, b) != weight_sympy(bush, A_sym, B_sym)


@pytest.mark.parametrize("n", [2, 6, 24, 25])
def test_rational_rule_is_exact_to_its_degree(n):
    # the moment equations determine the n weights; an even count is exact to degree
    # n − 1 only, an odd one (symmetric about 1/2) to n
    x, w = rational_rule(n)
    assert x == [Fraction(i, n - 1) for i in range(n)]
    top = n + n % 2
    for k in range(top):
        assert sum(wi * xi ** k for xi, wi in zip(x, w)) == Fraction(1, k + 1)
    assert sum(wi * xi ** top for xi, wi in zip(x, w)) != Fraction(1, top + 1)


@pytest.mark.parametrize("n", [3, 6, 9, 19, 24, 31])
def test_positive_rule_is_exact_positive_and_symmetric(n):
    # the same moment equations on other nodes: exact to degree n − 1, n for an odd
    # count (the nodes are symmetric about 1/2); every weight positive, so Σ|w| = 1
    x, w = positive_rule(n)
    assert len(set(x)) == n and x[0] == 0 and x[-1] == 1
    assert all(xi + xj == 1 for xi, xj in zip(x, reversed(x)))
    assert all(wi > 0 for wi in w)
    top = n + n % 2
    for k in range(top):
        assert sum(wi * xi ** k for xi, wi in zip(x, w)) == Fraction(1, k + 1)
    assert sum(wi * xi ** top for xi, wi in zip(x, w)) != Fraction(1, top + 1)


def gamma(tree):
    """The density γ(t) = |t| Π γ(children)."""
    def size(t):
        return 1 + sum(size(c) for c in t)
    out = size(tree)
    for c in tree:
        out *= gamma(c)
    return out


def test_miyatake_butcher_4x4_classical_order_by_sympy():
    """The 4×4 Miyatake–Butcher matrix of the library: a(t) = 1/γ(t) for every tree with
    ≤ 4 vertices, not for every tree with 5 — classical order 4, by symbolic integration."""
    M = [["-6/5", "72/5", "-36", "24"], ["72/5", "-144/5", "-48", "72"],
         ["-36", "-48", "720", "-720"], ["24", "72", "-720", "720"]]
    A = sum(sympy.Rational(M[i][j]) * tau ** (i + 1) / (i + 1) * sigma ** j for i in range(4) for j in range(4))
    B = A.subs(tau, 1).subs(sigma, tau)
    ok = {n: all(weight_sympy(t, A, B) == Fraction(1, gamma(t)) for t in rooted_trees(n)) for n in range(1, 6)}
    assert ok == {1: True, 2: True, 3: True, 4: True, 5: False}
    method = ContinuousMethod.from_matrix(M)
    import rkcheck

    assert rkcheck.verify(method, order=5).classical_order == 4
