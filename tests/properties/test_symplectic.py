"""Symplecticity (BA + AᵀB − bbᵀ = 0) and symmetry (adjoint = method up to a stage
permutation), on the irreducible form.

Independent routes: the defect matrix and the adjoint computed directly with sympy (not
through rkcheck), exact Gauss tableaux over sympy (tests/support/symbolic.py), published
facts (Hairer–Lubich–Wanner, Geometric Numerical Integration: Gauss methods are symplectic
and symmetric; Lobatto IIIA and IIIB are symmetric and not symplectic; Radau IIA is
neither), and the by-hand defect of the trapezoidal rule.
"""

from __future__ import annotations

import random
from fractions import Fraction as F

import pytest
import sympy
from support.disguise import permute, split
from support.paths import TABLEAUX
from support.symbolic import Sym, gauss

from rkcheck.energy.check import CheckOptions, check
from rkcheck.io.loader import load
from rkcheck.properties.reduction import reduce_tableau
from rkcheck.properties.symplectic import symmetry, symplecticity


def props(path: str):
    return check(load(str(TABLEAUX / path)), CheckOptions(degree=2, order=4)).properties


def sympy_defect(A, b):
    Am = sympy.Matrix([[sympy.sympify(x) for x in row] for row in A])
    bm = sympy.Matrix([sympy.sympify(x) for x in b])
    B = sympy.diag(*bm)
    M = B * Am + Am.T * B - bm * bm.T
    return M.applyfunc(lambda x: sympy.expand(sympy.radsimp(sympy.expand(x))))


@pytest.mark.parametrize("s", [1, 2, 3])
def test_gauss_is_symplectic_and_symmetric_exactly(s):
    A, b = gauss(s)
    red = reduce_tableau(A, b)
    assert symplecticity(red).verdict.state == "holds"
    sym = symmetry(red)
    assert sym.verdict.state == "holds" and sym.permutation == tuple(range(s, 0, -1))
    # sympy, directly: M = 0
    M = sympy_defect([[x.e for x in row] for row in A], [x.e for x in b])
    assert M == sympy.zeros(s, s)


@pytest.mark.parametrize("s", [2, 3, 4, 5])
def test_shipped_gauss_files_are_symplectic_and_symmetric(s):
    p = props(f"collocation/gauss-{s}.toml")
    # algebraic entries: exact with the tableau's exact values, else certified to digits
    for v in (p.symplectic.verdict, p.symmetric.verdict):
        assert v.state == "holds" or (v.state == "holds_to_digits" and v.digits >= 40)


@pytest.mark.parametrize("path", ["implicit-midpoint.toml"])
def test_gauss_1_file(path):
    p = props(f"collocation/{path}")
    assert p.symplectic.verdict.state == "holds" and p.symmetric.verdict.state == "holds"


@pytest.mark.parametrize("path", ["lobatto-iiia-2.toml", "lobatto-iiia-3.toml", "lobatto-iiia-4.toml",
                                  "lobatto-iiib-3.toml", "lobatto-iiib-4.toml"])
def test_lobatto_iiia_and_iiib_are_symmetric_and_not_symplectic(path):
    p = props(f"collocation/{path}")
    assert p.symmetric.holds
    assert p.symplectic.verdict.state == "fails"
    tab = load(str(TABLEAUX / "collocation" / path))
    if tab.is_rational:
        assert p.symmetric.verdict.state == "holds"
        M = sympy_defect(tab.exact_A(), tab.exact_b())
        biggest = max(abs(x) for x in M)
        assert F(str(biggest)) == abs(F(p.symplectic.defect))


def test_lobatto_iiib_2_is_the_implicit_midpoint_rule_after_reduction():
    # A = [[1/2, 0], [1/2, 0]], b = (1/2, 1/2): both stages solve Y = y0 + h/2 f(Y), so the
    # method is the implicit midpoint rule (1 stage, a = 1/2, b = 1), which is symplectic.
    p = props("collocation/lobatto-iiib-2.toml")
    assert p.reduction.reduced_stages == 1 and p.reduction.A == [[F(1, 2)]] and p.reduction.b == [F(1)]
    assert p.symplectic.verdict.state == "holds" and p.symmetric.verdict.state == "holds"


def test_trapezoidal_rule_defect_by_hand():
    # Lobatto IIIA-2: BA = [[0,0],[1/4,1/4]], AᵀB = [[0,1/4],[0,1/4]], bbᵀ = 1/4 everywhere:
    # M = [[−1/4, 0], [0, 1/4]]; its largest entry has size 1/4
    p = props("collocation/lobatto-iiia-2.toml")
    assert abs(p.symplectic.defect) == F(1, 4) and p.symplectic.defect_entry in ((1, 1), (2, 2))


@pytest.mark.parametrize("s", [1, 2, 3])
def test_radau_iia_is_neither(s):
    p = props(f"collocation/radau-iia-{s}.toml")
    assert p.symplectic.verdict.state == "fails" and p.symmetric.verdict.state == "fails"


def test_backward_euler_defect_by_hand():
    # a = 1, b = 1: M = b a + a b − b² = 1
    red = reduce_tableau([[F(1)]], [F(1)])
    assert symplecticity(red).defect == 1


def test_explicit_methods_are_neither():
    for name in ("rk4", "heun", "euler", "ssprk3"):
        p = props(f"explicit/{name}.toml")
        assert p.symplectic.verdict.state == "fails" and p.symmetric.verdict.state == "fails", name


def test_a_disguised_gauss_method_is_still_symplectic_and_symmetric():
    # Gauss-2 over sympy, one stage split in two and the stages permuted: as written
    # BA + AᵀB − bbᵀ ≠ 0, but the method is the same, and so are its properties.
    A, b = gauss(2)
    rng = random.Random(3)
    A3, b3 = split([row[:] for row in A], b[:], 0, rng)
    A3, b3 = permute(A3, b3, rng)
    M = sympy_defect([[x.e if isinstance(x, Sym) else x for x in row] for row in A3],
                     [x.e if isinstance(x, Sym) else x for x in b3])
    assert M != sympy.zeros(3, 3)
    red = reduce_tableau(A3, b3)
    assert red.reduced_stages == 2
    assert symplecticity(red).verdict.state == "holds" and symmetry(red).verdict.state == "holds"


def test_symmetry_finds_a_permutation_other_than_the_reversal():
    # Lobatto IIIA-3 with stages written in the order 2, 1, 3: the adjoint maps the node
    # 1/2 to itself and 0 ↔ 1, which is no longer the reversal of the written order
    tab = load(str(TABLEAUX / "collocation" / "lobatto-iiia-3.toml"))
    A, b = tab.exact_A(), tab.exact_b()
    p = [1, 0, 2]
    A2 = [[A[p[i]][p[j]] for j in range(3)] for i in range(3)]
    b2 = [b[p[i]] for i in range(3)]
    sym = symmetry(reduce_tableau(A2, b2))
    assert sym.verdict.state == "holds" and sym.permutation == (1, 3, 2)
    # check the permutation directly: adjoint row i = method row π(i)
    adj = [[b2[j] - A2[i][j] for j in range(3)] for i in range(3)]
    perm = [k - 1 for k in sym.permutation]
    assert all(adj[i][j] == A2[perm[i]][perm[j]] for i in range(3) for j in range(3))


def _decimal_properties(text: str):
    from rkcheck.evaluation.values import TableauValues
    from rkcheck.io.loader import loads
    from rkcheck.numbers.reading import Reading
    from rkcheck.properties.scalars import tableau_values
    from rkcheck.properties.tableau import properties_of_values

    values = TableauValues(loads(text, "t.toml"), Reading("auto"))
    return properties_of_values(*tableau_values(values))


def test_a_decimal_box_nonzero_throughout_is_not_symplectic_and_keeps_no_quadratic_invariant():
    # (1/2; 1.000001): M = b(1 − b) and e₂ of R(z)R(−z) − 1 (also b(1 − b)) lie in
    # [−1.5·10⁻⁶, −5·10⁻⁷] on the whole box b ∈ 1.000001 ± 5·10⁻⁷ (by hand), so both
    # certainly fail; a claim `symplectic = true` on such a file must not pass
    props = _decimal_properties('[tableau]\nA = [["1/2"]]\nb = ["1.000001"]\n')
    assert props.symplectic.verdict.state == "fails"
    assert props.stability.identity.state == "fails"


@pytest.mark.parametrize("digits", [8, 16])
def test_gauss_in_rounded_decimals_is_never_refuted(digits):
    # the box of a rounded Gauss tableau contains Gauss itself (M = 0, R(z)R(−z) = 1), so
    # neither may be "fails", whatever the mean value form sharpens
    r3 = sympy.sqrt(3)
    A = [[sympy.Rational(1, 4), sympy.Rational(1, 4) - r3 / 6], [sympy.Rational(1, 4) + r3 / 6, sympy.Rational(1, 4)]]
    rows = [", ".join(f'"{sympy.N(x, digits)}"' for x in row) for row in A]
    props = _decimal_properties(f'[tableau]\nA = [[{rows[0]}], [{rows[1]}]]\nb = ["0.5", "0.5"]\n')
    assert not props.exact
    assert props.symplectic.verdict.state == "holds_to_digits"
    assert props.stability.identity.state == "holds_to_digits"


def test_a_defect_too_long_to_print_exactly_reads_approximately():
    # M₁₁ = b(2a − b) = 2·10⁻⁶⁰·θ with θ = root(x⁵ − 3, 1): its exact text is longer than
    # the report prints, so the entry reads "≈ 2.49…e-60" (it read "= ≈ …")
    verdict = _decimal_properties('[tableau]\nA = [["1/2 + 10^-60*root(x^5-3,1)"]]\nb = ["1"]\n').symplectic
    assert verdict.verdict.state == "fails"
    assert "M[1][1] ≈ 2.49146187923e-60" in verdict.reason and "= ≈" not in verdict.reason
