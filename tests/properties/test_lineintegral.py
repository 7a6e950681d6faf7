"""The line-integral certificate is sound: every certified tableau holds every condition
(the engine's exact conditions are the independent judge), and it is tight for HBVM."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest

from rkcheck.energy.check import CheckOptions, check
from rkcheck.methods.quadrature import shifted_legendre
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.polynomials import evaluate, integral


def li_tableau(c: list[Fraction], sigma: int) -> Tableau:
    """A = Σ_{j<σ} (2j+1) G_j(c)(P_j(c) ⊙ b)ᵀ over the interpolatory rule with nodes c."""
    n = len(c)
    # weights b_i = ∫ ℓ_i from the Vandermonde system Σ b_i c_i^(k−1) = 1/k, k = 1..n
    M = [[ci ** k for ci in c] + [Fraction(1, k + 1)] for k in range(n)]
    for col in range(n):  # Gauss–Jordan over Q
        piv = next(r for r in range(col, n) if M[r][col] != 0)
        M[col], M[piv] = M[piv], M[col]
        M[col] = [x / M[col][col] for x in M[col]]
        for r in range(n):
            if r != col and M[r][col] != 0:
                M[r] = [x - M[r][col] * y for x, y in zip(M[r], M[col])]
    b = [M[i][n] for i in range(n)]
    A = [
        [
            b[l] * sum((2 * j + 1) * evaluate(integral(shifted_legendre(j)), c[i]) * evaluate(shifted_legendre(j), c[l])
                       for j in range(sigma))
            for l in range(n)
        ]
        for i in range(n)
    ]
    return Tableau.from_values(A, b)


@pytest.mark.parametrize("seed", range(6))
def test_certificate_on_random_rational_rules_is_sound(seed):
    rng = random.Random(seed)
    n = 4
    c = sorted({Fraction(rng.randint(1, 97), 97) for _ in range(20)})[:n]
    # random distinct nodes: quadrature order exactly n (generically), so σ = 2 gives m = 2
    tab = li_tableau(c, 2)
    res = check(tab, CheckOptions(degree=2, order=10))
    assert res.backend == "exact"
    assert res.certificate.certified and res.certificate.sigma == 2
    assert res.failures == []  # every odd-path condition to order 10 vanishes exactly
    res3 = check(tab, CheckOptions(degree=3, order=8))
    assert not res3.certificate.certified  # needs quadrature order 6 > 4
    assert res3.failures  # ... and indeed some degree-3 condition fails


@pytest.mark.parametrize("k, s", [(2, 1), (3, 1), (3, 2), (4, 2), (4, 3), (5, 3)])
def test_hbvm_is_certified_exactly_up_to_2k_over_s(k, s):
    from rkcheck.methods.families import FamilySpec, family_tableau

    tab = family_tableau(FamilySpec("hbvm", s, k=k))
    m = (2 * k) // s
    res = check(tab, CheckOptions(degree=m, order=8))
    assert res.certificate.certified and res.certificate.sigma == s and res.failures == []
    # degree m+1: no certificate, and a condition fails at order 2k+1 (first failure found
    # by the engine: HBVM's energy error is the k-point Gauss quadrature error, O(h^(2k+1)))
    res = check(tab, CheckOptions(degree=m + 1, order=2 * k + 1))
    assert not res.certificate.certified
    assert res.energy_order == 2 * k
