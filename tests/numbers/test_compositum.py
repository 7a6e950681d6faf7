"""The characteristic polynomial of θ + tγ, against the characteristic polynomial of the
Kronecker sum of the companion matrices (built here, fmpq_mat) and sympy's resultant."""

from __future__ import annotations

import random

import sympy as sp
from flint import fmpq, fmpq_mat, fmpq_poly

from rkcheck.numbers.compositum import charpoly_sum


def _companion(p: fmpq_poly) -> fmpq_mat:
    n = p.degree()
    M = fmpq_mat(n, n)
    for i in range(1, n):
        M[i, i - 1] = 1
    for i in range(n):
        M[i, n - 1] = -p[i] / p[n]
    return M


def _kronecker_charpoly(g: fmpq_poly, f: fmpq_poly, t: int) -> fmpq_poly:
    """det(x − (C_g ⊗ I + t·I ⊗ C_f)): its eigenvalues are the sums θ_i + t·γ_j."""
    Cg, Cf = _companion(g), _companion(f)
    m, n = g.degree(), f.degree()
    M = fmpq_mat(m * n, m * n)
    for i in range(m):
        for j in range(m):
            for k in range(n):
                M[i * n + k, j * n + k] += Cg[i, j]
        for k in range(n):
            for l in range(n):
                M[i * n + k, i * n + l] += t * Cf[k, l]
    return M.charpoly()


def test_random_pairs_agree_with_the_kronecker_sum():
    rng = random.Random(7)
    for _ in range(40):
        g = fmpq_poly([fmpq(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(rng.randint(1, 7))]
                      + [fmpq(rng.randint(1, 4))])
        f = fmpq_poly([fmpq(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(rng.randint(1, 5))]
                      + [fmpq(rng.choice([-2, 1, 3]))])
        t = rng.choice([1, -1, 2, -3, 5, 13])
        assert charpoly_sum(g, f, t) == _kronecker_charpoly(g, f, t)


def test_sqrt2_plus_2_sqrt3_is_sympys_resultant():
    x, z = sp.symbols("x z")
    g, f = fmpq_poly([-2, 0, 1]), fmpq_poly([-3, 0, 1])  # √2, √3
    # Π (x − θ_i − 2γ_j) = Res_z(f(z), g(x − 2z)) for monic f of even degree
    expected = sp.Poly(sp.resultant(z**2 - 3, (x - 2 * z) ** 2 - 2, z), x).all_coeffs()[::-1]
    assert charpoly_sum(g, f, 2) == fmpq_poly([int(c) for c in expected])
    # by hand: x = ±√2 ± 2√3 gives x² = 14 ± 4√6, so (x² − 14)² = 96
    assert charpoly_sum(g, f, 2) == fmpq_poly([100, 0, -28, 0, 1])
