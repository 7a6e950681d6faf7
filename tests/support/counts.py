"""How many energy conditions there are, from published counts of trees."""

from __future__ import annotations

# OEIS A000055 (free trees with n vertices) and A000081 (rooted trees with n vertices),
# n = 0, 1, ...: an energy condition is a free tree that is not superfluous, and a free
# tree with an even number n of vertices is superfluous when the two halves across its
# central edge are the same rooted tree with n/2 vertices (A000081(n/2) of them).
A000055 = [1, 1, 1, 1, 2, 3, 6, 11, 23, 47, 106, 235, 551, 1301, 3159, 7741, 19320, 48629, 123867, 317955]
A000081 = [0, 1, 1, 2, 4, 9, 20, 48, 115, 286]


def conditions_with(vertices: int) -> int:
    return A000055[vertices] - (A000081[vertices // 2] if vertices % 2 == 0 else 0)
