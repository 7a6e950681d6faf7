"""The rows of the double-bush map, and ranks of it that a numerical cut-off cannot get wrong.

Two routes, used by :mod:`rkcheck.energy.double_bush` where exact elimination in the
rule's own number field is out of reach:

* **The node polynomial.**  With ``H = Vᵀ diag(b) N V`` (``V_ik = c_i^k``, k < s) the map
  ``N ↦ H`` is invertible when the nodes are distinct and every weight is nonzero, and
  ``bᵀC^a N c^k`` for any a, k is a rational combination of the entries of H: ``x^a mod
  ω(x)`` with ``ω = Π(x − c_i)`` rewrites ``c^a`` over ``c^0 … c^(s−1)``.  So
  ``M(N)_pq = p bᵀC^(p−1)Nc^q − q bᵀC^(q−1)Nc^p`` is a matrix with rational entries
  acting on H whenever ω has rational coefficients — as it has for every named rule
  (Gauss, Radau, Lobatto, ζ rational) — and its rank is exact, whatever the degree of
  the field of the nodes.  ``N·1 = 0`` is ``H[:, 0] = 0`` (the map is invertible).
* **Certified lower bounds.**  For data known only to enclosures, Gaussian elimination
  in ball arithmetic (python-flint ``arb``): every pivot whose ball excludes 0 proves one
  more independent row for every matrix in the box, so the count is a lower bound of
  the rank.  Nothing numerical can prove a singular value to be exactly 0, so the upper
  bound is the size of the matrix.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.polynomials import interval_arb


def pairs(m: int) -> list[tuple[int, int]]:
    """The double-bush conditions' (p, q), 1 ≤ p < q ≤ m−1."""
    return [(p, q) for q in range(2, m) for p in range(1, q)]


def map_row(b: Sequence[Any], c: Sequence[Any], p: int, q: int) -> list[Any]:
    """Row (p, q) of M acting on vec(A) (row-major: index i*s + j), in the number type of b, c."""
    s = len(b)
    return [p * b[i] * c[i] ** (p - 1) * c[j] ** q - q * b[i] * c[i] ** (q - 1) * c[j] ** p
            for i in range(s) for j in range(s)]


def map_rows(b: Sequence[Any], c: Sequence[Any], m: int) -> list[list[Any]]:
    """The rows of M acting on vec(A), for every (p, q) of :func:`pairs`."""
    return [map_row(b, c, p, q) for p, q in pairs(m)]


def row_sum_rows(s: int) -> list[list[int]]:
    """The constraints N·1 = 0 on vec(N)."""
    return [[1 if k // s == i else 0 for k in range(s * s)] for i in range(s)]


def powers_mod(poly: Sequence[Fraction], top: int) -> list[list[Fraction]]:
    """``x^a mod ω`` for a = 0..top, as the s coefficients (lowest first) of the
    remainder; ``poly`` holds ω's coefficients lowest first (any nonzero leading one)."""
    lead = poly[-1]
    w = [Fraction(x) / lead for x in poly]
    s = len(w) - 1
    cur = [Fraction(int(k == 0)) for k in range(s)]
    out = []
    for _ in range(top + 1):
        out.append(cur)
        carry = cur[-1]
        cur = [Fraction(0)] + cur[:-1]
        if carry:
            cur = [x - carry * w[k] for k, x in enumerate(cur)]
    return out


def reduced_rows(poly: Sequence[Fraction], m: int) -> list[list[Fraction]]:
    """The rows of the double-bush map acting on vec(H) (row-major, index l*s + k): row
    (p, q) has the coefficient ``p R[p−1][l] R[q][k] − q R[q−1][l] R[p][k]`` of
    ``H[l][k]``, R the powers of x modulo the node polynomial."""
    R = powers_mod(poly, m)
    s = len(poly) - 1
    rows = []
    for p, q in pairs(m):
        rows.append([p * R[p - 1][l] * R[q][k] - q * R[q - 1][l] * R[p][k] for l in range(s) for k in range(s)])
    return rows


def first_column_rows(s: int) -> list[list[Fraction]]:
    """``H[l][0] = 0`` for every l: the zero row sums ``N·1 = 0`` in H."""
    return [[Fraction(int(idx == l * s)) for idx in range(s * s)] for l in range(s)]


def rational_nullspace(rows: list[list[Fraction]], n: int) -> tuple[int, list[list[Fraction]]]:
    """(rank, basis of the null space) of a rational matrix (python-flint's reduced row
    echelon form: fast where Fractions would take minutes at s = 12, m = 40)."""
    from flint import fmpq, fmpq_mat

    if not rows:
        return 0, [[Fraction(int(i == j)) for i in range(n)] for j in range(n)]
    mat = fmpq_mat(len(rows), n, [fmpq(x.numerator, x.denominator) for r in rows for x in r])
    rref, rank = mat.rref()
    pivots = []
    for i in range(rank):
        pivots.append(next(j for j in range(n) if rref[i, j] != 0))
    basis = []
    for fj in (j for j in range(n) if j not in pivots):
        v = [Fraction(0)] * n
        v[fj] = Fraction(1)
        for i, pc in enumerate(pivots):
            x = rref[i, fj]
            v[pc] = -Fraction(int(x.p), int(x.q))
        basis.append(v)
    return rank, basis


def matrices_from_h(basis: list[list[Fraction]], b: Sequence[Any], c: Sequence[Any], dps: int) -> list[list[Any]]:
    """``N = diag(b)⁻¹ V⁻ᵀ H V⁻¹`` (mpmath at ``dps`` digits, b and c mpf) for each H of
    ``basis``, flattened row-major like the rows of M."""
    import mpmath

    s = len(c)
    with mpmath.workdps(dps):
        V = mpmath.matrix([[ci ** k for k in range(s)] for ci in c])
        Vinv = mpmath.inverse(V)
        left = mpmath.diag([1 / bi for bi in b]) * Vinv.T
        out = []
        for h in basis:
            H = mpmath.matrix([[mpmath.mpf(h[l * s + k].numerator) / h[l * s + k].denominator for k in range(s)]
                               for l in range(s)])
            N = left * H * Vinv
            out.append([N[i, j] for i in range(s) for j in range(s)])
    return out


# ------------------------------------------------------------------ certified


ball = interval_arb  # the arb enclosing an interval with rational end points


def certified_rank_lower(rows: list[list[Any]]) -> int:
    """A lower bound of the rank of every matrix inside the ball matrix ``rows`` (arbs):
    the pivots of Gaussian elimination with complete pivoting whose balls exclude 0."""
    M = [list(r) for r in rows]
    rank = 0
    while M and M[0]:
        best, bi, bj = None, -1, -1
        for i, r in enumerate(M):
            for j, x in enumerate(r):
                low = x.abs_lower()
                if low > 0 and (best is None or low > best):
                    best, bi, bj = low, i, j
        if best is None:
            break
        piv_row = M.pop(bi)
        piv = piv_row.pop(bj)
        for r in M:
            f = r.pop(bj) / piv
            for j in range(len(r)):
                r[j] = r[j] - f * piv_row[j]
        rank += 1
    return rank


def certified_map_rank_lower(b: Sequence[Interval], c: Sequence[Interval], m: int, bits: int,
                             with_row_sums: bool = False) -> int:
    """A certified lower bound of rank M (stacked with the row sums when asked) for every
    rule inside the enclosures ``b``, ``c``, in ball arithmetic at ``bits`` bits."""
    from flint import arb, ctx

    with ctx.workprec(bits):
        rows = map_rows([ball(x) for x in b], [ball(x) for x in c], m)
        if with_row_sums:
            rows = rows + [[arb(x) for x in r] for r in row_sum_rows(len(b))]
        return certified_rank_lower(rows)
