"""Disguised tableaux: the same Runge–Kutta method written with more stages.

Each operation here changes the tableau but not the method (its B-series, its numerical
map): a reference the stage reduction of rkcheck must see through.  Imports nothing from
rkcheck; Fractions only.

* ``split``: stage j becomes two stages with identical rows; column j is split into two
  columns summing to it, and b_j into two weights summing to it;
* ``dead``: a stage with b = 0 that no live stage uses (its row is arbitrary and may use
  anything);
* ``dead_chain``: several dead stages, each using the previous one;
* ``cancelling_pair``: two stages with identical arbitrary rows, weights w and −w, and
  columns v and −v in every other row (merged, they are one dead stage);
* ``permute``: the stages in another order.
"""

from __future__ import annotations

import random
from fractions import Fraction

#: AVF over rational rules: (name, nodes c, weights b, quadrature order)
RATIONAL_RULES = [
    ("gauss-1", [Fraction(1, 2)], [Fraction(1)], 2),
    ("lobatto-2", [Fraction(0), Fraction(1)], [Fraction(1, 2), Fraction(1, 2)], 2),
    ("radau-ii-2", [Fraction(1, 3), Fraction(1)], [Fraction(3, 4), Fraction(1, 4)], 3),
    ("radau-i-2", [Fraction(0), Fraction(2, 3)], [Fraction(1, 4), Fraction(3, 4)], 3),
    ("lobatto-3", [Fraction(0), Fraction(1, 2), Fraction(1)], [Fraction(1, 6), Fraction(2, 3), Fraction(1, 6)], 4),
]


def avf_tableau(c, b):
    """A = c bᵀ (definitions §4)."""
    return [[ci * bj for bj in b] for ci in c], list(b)


def _rand(rng: random.Random, lo: int = -9, hi: int = 9, den: int = 12) -> Fraction:
    return Fraction(rng.randint(lo, hi), rng.randint(1, den))


def _nonzero(rng: random.Random) -> Fraction:
    x = Fraction(0)
    while x == 0:
        x = _rand(rng)
    return x


def split(A, b, j, rng):
    s = len(b)
    u = [_rand(rng) for _ in range(s)]
    A2 = [row[:j + 1] + [row[j] - u[i]] + row[j + 1:] for i, row in enumerate(A)]
    for i in range(s):
        A2[i][j] = u[i]
    A2.insert(j + 1, A2[j][:])  # the copy's row is the split stage's row
    beta = _rand(rng)
    b2 = b[:j] + [beta, b[j] - beta] + b[j + 1:]
    return A2, b2


def dead(A, b, rng):
    s = len(b)
    A2 = [row + [Fraction(0)] for row in A]
    A2.append([_rand(rng) for _ in range(s + 1)])
    return A2, b + [Fraction(0)]


def dead_chain(A, b, rng, length: int = 3):
    for k in range(length):
        s = len(b)
        A2 = [row + [Fraction(0)] for row in A]
        new = [Fraction(0)] * (s + 1)
        if k > 0:
            new[s - 1] = _nonzero(rng)  # uses the previous dead stage
        new[rng.randrange(s)] += _rand(rng)
        A2.append(new)
        A, b = A2, b + [Fraction(0)]
    return A, b


def cancelling_pair(A, b, rng):
    s = len(b)
    v = [_rand(rng) for _ in range(s)]
    A2 = [row + [v[i], -v[i]] for i, row in enumerate(A)]
    shared = [_rand(rng) for _ in range(s + 2)]
    A2.append(shared[:])
    A2.append(shared[:])
    w = _nonzero(rng)
    return A2, b + [w, -w]


def permute(A, b, rng):
    s = len(b)
    p = list(range(s))
    rng.shuffle(p)
    return [[A[p[i]][p[j]] for j in range(s)] for i in range(s)], [b[p[i]] for i in range(s)]


def disguise(A, b, rng: random.Random, operations: int = 3):
    """Apply ``operations`` random method-preserving operations, then permute."""
    for _ in range(operations):
        op = rng.choice(["split", "split", "dead", "dead_chain", "cancelling_pair"])
        if op == "split":
            A, b = split(A, b, rng.randrange(len(b)), rng)
        elif op == "dead":
            A, b = dead(A, b, rng)
        elif op == "dead_chain":
            A, b = dead_chain(A, b, rng, rng.randint(2, 3))
        else:
            A, b = cancelling_pair(A, b, rng)
    return permute(A, b, rng)
