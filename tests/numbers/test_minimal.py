"""Minimal polynomials shared by conjugates, the quick modular test and the exact root
test (rkcheck.numbers.minimal) against sympy's exact algebra."""

from fractions import Fraction

import pytest
import sympy as sp

from rkcheck.numbers import grammar as ex
from rkcheck.numbers import minimal
from rkcheck.numbers.field_builder import field_of

X = sp.Symbol("X")
# sqrt(2) + sqrt(3) and its three conjugates, a conjugate of sqrt(2) alone, and an element
# of degree 4 that is not conjugate to them; all in Q(sqrt(2), sqrt(3), 5^(1/4))
TEXTS = ["sqrt(2) + sqrt(3)", "sqrt(2) - sqrt(3)", "-sqrt(2) + sqrt(3)", "-sqrt(2) - sqrt(3)",
         "-sqrt(2)", "root(x^4 - 5, 2) + 1/3"]
EXPRS = [sp.sqrt(2) + sp.sqrt(3), sp.sqrt(2) - sp.sqrt(3), -sp.sqrt(2) + sp.sqrt(3), -sp.sqrt(2) - sp.sqrt(3),
         -sp.sqrt(2), sp.root(5, 4) + sp.Rational(1, 3)]


def _sympy_minpoly(expr) -> list[Fraction]:
    coeffs = sp.Poly(sp.minimal_polynomial(expr, X), X).monic().all_coeffs()[::-1]
    return [Fraction(int(sp.Rational(c).p), int(sp.Rational(c).q)) for c in coeffs]


@pytest.fixture(scope="module")
def values():
    return field_of([ex.parse(t) for t in TEXTS]).values


def test_conjugates_share_one_polynomial_and_every_answer_is_sympys(values):
    known = minimal.MinimalPolynomials()
    found = [known.of(v) for v in values]
    assert found == [_sympy_minpoly(e) for e in EXPRS]
    # the four conjugates of sqrt(2) + sqrt(3) and -sqrt(2) found 3 polynomials, not 6
    assert len(known._known) == 3


def test_the_root_test_agrees_with_horner_in_sympy(values):
    # every polynomial up to degree 11 built from a minimal polynomial (a multiple: a root;
    # plus a nonzero constant: not a root), judged exactly and against sympy
    for v, e in zip(values, EXPRS):
        P = _sympy_minpoly(e)
        for extra in ([1], [0, 1], [Fraction(-2, 3), 0, 1, 5], [1, 1, 1, 1, 1, 1, 1]):
            multiple = [sum((P[i] * Fraction(extra[k - i]) for i in range(len(P)) if 0 <= k - i < len(extra)), Fraction(0))
                        for k in range(len(P) + len(extra) - 1)]
            shifted = [multiple[0] + 1] + multiple[1:]
            for Q in (multiple, shifted):
                value = sp.expand(sum(sp.Rational(c.numerator, c.denominator) * e**k for k, c in enumerate(Q)))
                truth = sp.simplify(value) == 0
                assert minimal.is_root(Q, v) is truth
                # the modular test may say "maybe" for a non-root, never "no" for a root
                assert minimal.may_be_root(Q, v) or not truth


def test_the_quick_test_rejects_with_a_small_prime(values):
    # with p = 7 the reduction still never rejects a true root (p divides no denominator)
    v = values[0]
    P = _sympy_minpoly(EXPRS[0])
    assert minimal.may_be_root(P, v, 7)
    assert not minimal.may_be_root([P[0] + 1] + P[1:], v, 1_000_003)
    # a denominator divisible by p: no test, "maybe"
    assert minimal.may_be_root([Fraction(1, 7)] + P[1:], v, 7)
