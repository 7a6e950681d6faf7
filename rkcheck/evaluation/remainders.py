"""Chinese remaindering of residues modulo many primes (the exact values of
:mod:`rkcheck.evaluation.modular`): the moduli merged pairwise in a product tree, whose
products and inverses are the same for every condition of an order and are kept."""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any, Callable

import numpy as np


def crt_columns(columns: list[list[int]], moduli: list[int]) -> list[int]:
    """The integers in [0, Π moduli) with residues ``columns[i][k]`` modulo ``moduli[i]``,
    for every k: the moduli are merged pairwise, a product tree, so thousands of primes (a
    decimal of thousands of digits) cost O(M(N) log k) per integer where Garner's digits
    cost k² vector operations (52 s for 3 559 primes)."""
    number = big_integers(len(moduli))
    nodes = [[number(int(x)) for x in col] for col in columns]
    for level in crt_tree(tuple(moduli)):
        merged = [[a + ma * (((b - a) * inv) % mb) for a, b in zip(xa, xb)]
                  for xa, xb, (ma, mb, inv) in zip(nodes[::2], nodes[1::2], level)]
        if len(nodes) % 2:
            merged.append(nodes[-1])
        nodes = merged
    return [int(x) for x in nodes[0]]


#: from this many moduli on, Chinese remaindering runs in GMP's integers (gmpy2): its
#: products and inverses of numbers of thousands of bits are far faster than Python's,
#: while a few primes (an everyday rational tableau) need no import of it
GMP_MODULI = 32


def big_integers(count: int) -> Callable[[int], Any]:
    """The integer type the remaindering of ``count`` moduli runs in."""
    if count < GMP_MODULI:
        return int
    from gmpy2 import mpz

    big: Callable[[int], Any] = mpz
    return big


@lru_cache(maxsize=4)
def product(moduli: tuple[int, ...]) -> int:
    """Π moduli (the same for every condition of an order)."""
    return math.prod(moduli)


@lru_cache(maxsize=4)
def crt_tree(moduli: tuple[int, ...]) -> list[list[tuple[Any, Any, Any]]]:
    """The product tree of ``moduli`` merged pairwise, level by level: each pair's
    moduli and the inverse of the first modulo the second.  The same for every
    condition of an order (a report reads their values one at a time): the inverses of
    the large products, most of the work, are computed once."""
    number = big_integers(len(moduli))
    levels, nodes = [], [number(m) for m in moduli]
    while len(nodes) > 1:
        pairs = [(ma, mb, number(pow(ma, -1, mb))) for ma, mb in zip(nodes[::2], nodes[1::2])]
        levels.append(pairs)
        nodes = [ma * mb for ma, mb, _ in pairs] + ([nodes[-1]] if len(nodes) % 2 else [])
    return levels


#: the other way: many large integers reduced modulo many primes at once, through their
#: 16-bit limbs and float64 products (BLAS): a limb times a power of 2^16 modulo a
#: prime below 2^30 is below 2^46, and LIMB_CHUNK of them sum below 2^53, exactly
LIMB_CHUNK = 128
#: rows of limbs taken into float64 at once (bounds the temporaries)
LIMB_ROWS = 8192


class LimbResidues:
    """Integers ``values`` (kept as their 16-bit limbs) and their residues modulo any
    primes below 2^30: what Python's ``v % p`` gives, for a whole batch of primes in a
    few matrix products instead of one big-integer division per value and prime."""

    def __init__(self, values: list[int]):
        self.negative = np.array([v < 0 for v in values], dtype=bool)
        width = max((abs(v).bit_length() for v in values), default=0) // 16 + 1
        raw = b"".join(abs(v).to_bytes(2 * width, "little") for v in values)
        self.limbs = np.frombuffer(raw, dtype="<u2").reshape(len(values), width)

    def modulo(self, moduli: list[int]) -> np.ndarray:
        """``(values, moduli)`` int64: each value modulo each prime, in [0, p)."""
        P = np.array(moduli, dtype=np.int64)
        n, width = self.limbs.shape
        powers = np.empty((width, len(P)), dtype=np.int64)
        powers[0] = 1 % P
        for k in range(1, width):
            powers[k] = (powers[k - 1] << 16) % P
        out = np.zeros((n, len(P)), dtype=np.int64)
        for r0 in range(0, n, LIMB_ROWS):
            rows = slice(r0, r0 + LIMB_ROWS)
            for k0 in range(0, width, LIMB_CHUNK):
                part = self.limbs[rows, k0:k0 + LIMB_CHUNK].astype(np.float64) @ powers[k0:k0 + LIMB_CHUNK].astype(np.float64)
                out[rows] = (out[rows] + part.astype(np.int64) % P) % P
        out[self.negative] = (P - out[self.negative]) % P
        return out
