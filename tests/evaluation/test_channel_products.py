"""``x Aᵀ`` and ``x b`` modulo each channel's prime, at every stage count the channels
treat apart (whole, in float64 halves, in slices), against Python's exact integers —
with the largest residues too, where a sum that were not exact would show."""

from __future__ import annotations

import random

import numpy as np
import pytest

from rkcheck.evaluation.channels import SLICE, SPLIT_STAGES, PrimeChannels, primes


def _exact(x, M, p):
    """Rows of ``x`` times ``M`` modulo p in Python ints."""
    return [[sum(xi * M[i][j] for i, xi in enumerate(row)) % p for j in range(len(M[0]))] for row in x]


@pytest.mark.parametrize("stages", [3, SLICE, SLICE + 1, 33, SPLIT_STAGES, SPLIT_STAGES + 1])
@pytest.mark.parametrize("largest", [False, True])
def test_products_are_the_exact_residues(stages, largest):
    rng = random.Random(stages * 2 + largest)
    P = list(primes(3))
    pick = (lambda p: p - 1 - rng.randrange(3)) if largest else (lambda p: rng.randrange(p))
    A = np.array([[[pick(p) for _ in range(stages)] for _ in range(stages)] for p in P], dtype=np.int64)
    b = np.array([[pick(p) for _ in range(stages)] for p in P], dtype=np.int64)
    ctx = PrimeChannels(P, A, b)
    rows = 5
    x = np.array([[[pick(p) for _ in range(stages)] for _ in range(rows)] for p in P], dtype=np.int64)
    got, dots = ctx.matvec(x), ctx.dot(x)
    for k, p in enumerate(P):
        At = [[int(A[k][j][i]) for j in range(stages)] for i in range(stages)]  # x Aᵀ
        assert got[k].tolist() == _exact(x[k].tolist(), At, p)
        assert dots[k].tolist() == [r[0] for r in _exact(x[k].tolist(), [[int(v)] for v in b[k]], p)]
