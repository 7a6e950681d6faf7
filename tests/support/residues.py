"""Shared inputs of the residue cross-checks: the reference's conditions up to an order
(by id) and small random rational tableaux with Σb = 1."""

from __future__ import annotations

import random
from fractions import Fraction as F
from functools import lru_cache

from support import reference as ref


@lru_cache(maxsize=None)
def reference_conditions(order: int) -> dict:
    """Every condition with 3 … order + 1 vertices of the reference, by id."""
    return {d["id"]: d for n in range(3, order + 2) for d in ref.energy_conditions(n)}


def random_tableau(seed: int, s: int = 3) -> tuple[list[list[F]], list[F]]:
    """A dense s-stage tableau of small fractions, its weights summing to 1."""
    rng = random.Random(seed)
    A = [[F(rng.randint(-4, 4), rng.randint(1, 4)) for _ in range(s)] for _ in range(s)]
    b = [F(rng.randint(-4, 4), rng.randint(1, 4)) for _ in range(s)]
    b[-1] = 1 - sum(b[:-1])
    return A, b
