"""How many conditions and terms an order has, without listing them (definitions §3).

Counted by generating functions, exactly, in milliseconds — what the resource estimate
needs before deciding whether a check fits the machine:

* Rooted trees whose vertices have at most ``k`` children (Pólya):
  ``T_k(x) = x · Σ_{j ≤ k} h_j``, where ``h_j`` counts multisets of ``j`` trees:
  ``h_0 = 1``, ``j·h_j = Σ_{i=1..j} T_k(x^i)·h_{j−i}``.  Unbounded: ``k = n``
  (A000081).
* The terms of the conditions with ``n`` vertices for degree ≤ m are the rooted trees
  whose root has at most ``m`` children and every other vertex at most ``m − 1``:
  ``x · Σ_{j ≤ m} h_j[T_{m−1}]``.
* Free trees with maximum degree ≤ m (Otter's dissimilarity theorem: vertices − edges
  + symmetric edges = 1 for a tree): ``F = R − (T² − T(x²))/2`` with ``R`` the rooted
  count above and ``T = T_{m−1}``.  The superfluous ones with ``2k`` vertices are the
  pairs ``u∘u``: ``T_{m−1}`` at ``k``.  Conditions = free − superfluous.
"""

from __future__ import annotations

from functools import lru_cache


def _series_mul(a: list[int], b: list[int], size: int) -> list[int]:
    out = [0] * size
    for i, x in enumerate(a):
        if x:
            for j in range(min(len(b), size - i)):
                out[i + j] += x * b[j]
    return out


def _dilate(a: list[int], i: int, size: int) -> list[int]:
    """a(x^i) truncated."""
    out = [0] * size
    for k, x in enumerate(a):
        if k * i < size:
            out[k * i] = x
    return out


def _multisets(t: list[int], k: int, size: int) -> list[list[int]]:
    """h_0 … h_k for the series t (multisets of j trees counted by total size)."""
    h = [[1] + [0] * (size - 1)]
    powers = [_dilate(t, i, size) for i in range(1, k + 1)]
    for j in range(1, k + 1):
        acc = [0] * size
        for i in range(1, j + 1):
            term = _series_mul(powers[i - 1], h[j - i], size)
            acc = [x + y for x, y in zip(acc, term)]
        h.append([x // j for x in acc])  # exact: j·h_j has integer coefficients divisible by j
    return h


@lru_cache(maxsize=64)
def rooted_counts(max_vertices: int, children: int | None = None) -> tuple[int, ...]:
    """Rooted trees with n = 0 … max_vertices vertices whose vertices have at most
    ``children`` children (None: any).

    Coefficient by coefficient: ``T[n] = Σ_j h_j[n − 1]``, and then ``h_j[n]`` from
    ``j·h_j = Σ_i T(x^i)·h_{j−i}``, which needs T up to n only (the series of all
    multisets recomputed for every n cost 40 ms at 17 vertices, in every check)."""
    size = max_vertices + 1
    k = max_vertices if children is None else children
    t = [0] * size
    h = [[1] + [0] * (size - 1)] + [[0] * size for _ in range(k)]
    for n in range(1, size):
        t[n] = sum(h[j][n - 1] for j in range(min(k, n - 1) + 1))
        for j in range(1, min(k, n) + 1):
            acc = 0
            for i in range(1, j + 1):
                below = h[j - i]
                # T(x^i) has the coefficient t[q] at x^(i·q)
                acc += sum(t[q] * below[n - i * q] for q in range(1, n // i + 1))
            h[j][n] = acc // j  # exact: j·h_j has integer coefficients divisible by j
    return tuple(t)


@lru_cache(maxsize=64)
def term_counts(max_vertices: int, degree: int | None) -> tuple[int, ...]:
    """Rooted trees with n vertices whose free tree has maximum degree ≤ ``degree`` (the
    rootings; all terms of the conditions plus the rootings of superfluous trees)."""
    if degree is None:
        return rooted_counts(max_vertices)
    size = max_vertices + 1
    inner = list(rooted_counts(max_vertices, degree - 1))
    h = _multisets(inner, degree, size)
    total = [sum(col) for col in zip(*h)]
    return tuple([0] + total[: size - 1])


@lru_cache(maxsize=64)
def condition_counts(max_vertices: int, degree: int | None) -> tuple[int, ...]:
    """Conditions (non-superfluous free trees of max degree ≤ degree) with n = 0 …
    max_vertices vertices; zero below 3 vertices."""
    size = max_vertices + 1
    inner = list(rooted_counts(max_vertices, None if degree is None else degree - 1))
    rooted = term_counts(max_vertices, degree)
    square = _series_mul(inner, inner, size)
    dilated = _dilate(inner, 2, size)
    out = []
    for n in range(size):
        free = rooted[n] - (square[n] - dilated[n]) // 2
        superfluous = inner[n // 2] if n % 2 == 0 else 0
        out.append(free - superfluous if n >= 3 else 0)
    if degree is not None and degree < 2:
        out = [0] * size
    return tuple(out)


def listing_size(order: int, degree: int | None) -> tuple[int, int, int]:
    """(conditions, terms, trees kept as factors) of a check to ``order``: the terms are
    the rootings with 3 … N+1 vertices, the factors the trees with at most N vertices."""
    conditions = sum(condition_counts(order + 1, degree))
    terms = term_counts(order + 1, degree)
    return conditions, sum(terms[3:]), sum(terms[1:order + 1])


class CountOnly:
    """The counts of a listing without the listing (``rkcheck conditions --count``)."""

    def __init__(self, order: int, degree: int | None):
        self.order, self.degree = order, degree
        self._counts = condition_counts(order + 1, degree)

    def __len__(self) -> int:
        return sum(self._counts)

    def counts_by_order(self) -> dict[int, int]:
        return {k: self._counts[k + 1] for k in range(2, self.order + 1)}
