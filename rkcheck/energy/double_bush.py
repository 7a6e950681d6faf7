"""The double-bush map M of the seed (Lemma "DBmono"), its rank and kernel.

For a rule ``(b, c)`` and a degree m, the double-bush conditions

    p bᵀC^(p−1) A c^q − q bᵀC^(q−1) A c^p = 1/(q+1) − 1/(p+1),   1 ≤ p < q ≤ m−1,

are linear in A: ``M(A)`` with ``M: R^(s×s) → R^((m−1)(m−2)/2)``; the coefficient of
``a_ij`` in row (p, q) is ``p b_i c_i^(p−1) c_j^q − q b_i c_i^(q−1) c_j^p``.  The seed
proves ``rank M = s²−1`` with kernel ``(1−c)bᵀ`` for Gauss and m = 2s, and for m = 2s−1
with nodes the zeros of ``P_s − ζP_{s−1}``: ``s²−3`` (ζ ≠ −1) and ``s²−s−1`` (ζ = −1);
the part of the kernel with zero row sums is one-dimensional ("onedim").

The rank is never a guess.  Rational and algebraic rules are handled exactly: Gaussian
elimination over Q or over the number field of the nodes
(:mod:`rkcheck.numbers.algebraic`), rank and basis exact.  A named rule whose field is
beyond the degree limit (Gauss with 6 or more nodes) still has an exact rank, by
rational elimination on its node polynomial (:mod:`rkcheck.energy.double_bush_rank`),
and a numerical basis.  Only a tableau whose entries are not exact numbers falls back to
singular values at the working precision: the rank is then bracketed — a certified lower
bound from ball arithmetic, the matrix size above — and said to be undetermined unless
the two meet (a numerical cut-off can sit above true singular values: s = 6, m = 12 at 15
digits once printed rank 31 for 35).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

from rkcheck.energy.double_bush_rank import map_rows, row_sum_rows
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.precision import mpmath_bits
from rkcheck.numbers.reading import DecimalsMode

# ------------------------------------------------------------------- exact


def nullspace_exact(rows: list[list[Any]], n: int) -> tuple[int, list[list[Any]]]:
    """(rank, basis of the null space) over Q or a number field (entries Fractions or
    field elements of one field), by reduced row echelon form with exact zero tests."""
    M = [[x if hasattr(x, "field") else Fraction(x) for x in r] for r in rows]
    zero = next((x * 0 for r in M for x in r if hasattr(x, "field")), Fraction(0))
    pivots: list[int] = []
    r = 0
    for col in range(n):
        piv = next((k for k in range(r, len(M)) if M[k][col] != 0), None)
        if piv is None:
            continue
        M[r], M[piv] = M[piv], M[r]
        inv = 1 / M[r][col]
        M[r] = [x * inv for x in M[r]]
        for k in range(len(M)):
            if k != r and M[k][col] != 0:
                f = M[k][col]
                M[k] = [x - f * y for x, y in zip(M[k], M[r])]
        pivots.append(col)
        r += 1
        if r == len(M):
            break
    free = [j for j in range(n) if j not in pivots]
    basis = []
    for fj in free:
        v = [zero] * n
        v[fj] = zero + 1
        for k, pc in enumerate(pivots):
            v[pc] = -M[k][fj]
        basis.append(v)
    return len(pivots), basis


# ------------------------------------------------------------------ numeric


@dataclass
class NumericRank:
    rank: int
    singular_values: list[Any]  # mpf, decreasing
    basis: list[list[Any]]  # kernel vectors (mpf)

    def around_cut(self, k: int = 2) -> list[tuple[int, Any]]:
        lo = max(0, self.rank - k)
        hi = min(len(self.singular_values), self.rank + k)
        return [(i + 1, self.singular_values[i]) for i in range(lo, hi)]


def nullspace_numeric(rows: list[list[Any]], n: int, dps: int, at_least: int = 0) -> NumericRank:
    """Numerical rank and null space by SVD at ``dps`` digits: singular values above
    10^-(dps/2) relative to the largest count, and at least ``at_least`` (a certified
    lower bound) do."""
    import mpmath

    with mpmath.workdps(dps):
        nrow = len(rows)
        # pad to a square matrix so that the full right singular basis is returned
        size = max(nrow, n)
        M = mpmath.zeros(size, n)
        for i, r in enumerate(rows):
            for j, x in enumerate(r):
                M[i, j] = x
        U, S, V = mpmath.svd_r(M, full_matrices=True)
        svals = sorted([S[i] for i in range(min(size, n))], reverse=True)
        svals += [mpmath.mpf(0)] * (n - len(svals))
        top = svals[0] if svals and svals[0] > 0 else mpmath.mpf(1)
        tol = top * mpmath.mpf(10) ** (-(dps // 2))
        rank = max(at_least, sum(1 for x in svals if x > tol))
        order = sorted(range(min(size, n)), key=lambda i: -S[i])
        small = order[rank:] + list(range(min(size, n), n))
        basis = [[V[i, j] for j in range(n)] for i in small]
    return NumericRank(rank, svals, basis)


# ------------------------------------------------------------------ results


@dataclass(frozen=True)
class Kernel:
    """The rank of the double-bush map ``M`` on s×s matrices at a quadrature rule, a basis
    of ``ker M`` and of its part with zero row sums (each matrix scaled so that its
    largest entry is 1); ``tableau`` or ``rule`` says where the rule came from.

    ``exact`` says whether the basis is exact (Fractions or number-field elements) or
    numerical (mpmath).  ``rank_bounds`` brackets rank M with certainty: ``(rank, rank)``
    when the rank is exact (:attr:`rank_certain`), else a certified lower bound and the
    size of the matrix, with ``rank`` the numerical cut between them and the singular
    values around it; ``zero_row_sum_bounds`` brackets ``dim(ker M ∩ {N·1 = 0})`` alike."""

    s: int
    degree: int
    exact: bool  # whether the basis is exact arithmetic (then so is the rank)
    rank: int  # exact when rank_certain; else the numerical cut inside rank_bounds
    conditions: int  # rows of M: the double-bush conditions 1 ≤ p < q ≤ m−1
    basis: list[list[list[Any]]]  # a basis of ker M, as s×s matrices
    # a basis of ker M ∩ {N·1 = 0}: the directions A → A + βN that keep every condition
    # linear in A (seed Lemma "onedim")
    zero_row_sum: list[list[list[Any]]]
    singular_values: list[tuple[int, Any]] | None = None  # around the cut (numeric)
    zero_row_sum_singular_values: list[tuple[int, Any]] | None = None
    tableau: Any = None
    rule: str | None = None
    rank_bounds: tuple[int, int] | None = None  # None: (rank, rank)
    zero_row_sum_bounds: tuple[int, int] | None = None  # None: the dimension is certain

    def __post_init__(self) -> None:
        if self.rank_bounds is None:
            object.__setattr__(self, "rank_bounds", (self.rank, self.rank))
        if self.zero_row_sum_bounds is None:
            k = len(self.zero_row_sum)
            object.__setattr__(self, "zero_row_sum_bounds", (k, k))

    @property
    def rank_certain(self) -> bool:
        """Whether :attr:`rank` is proven (exact elimination, or certified bounds that meet)."""
        lo, hi = self.rank_bounds  # type: ignore[misc]
        return lo == hi

    @property
    def dimension(self) -> int:
        """dim ker M = s² − rank M."""
        return self.s * self.s - self.rank

    def __repr__(self) -> str:
        lo, hi = self.rank_bounds  # type: ignore[misc]
        rank = f"rank {self.rank}" if self.rank_certain else f"rank {self.rank}? (certainly {lo}..{hi})"
        return (f"<Kernel: s = {self.s}, degree {self.degree}, {rank}, dim ker {self.dimension}, "
                f"{len(self.zero_row_sum)} with zero row sums{'' if self.exact else ' (numerical basis)'}>")


def _matrix(v: list[Any], s: int) -> list[list[Any]]:
    return [v[i * s:(i + 1) * s] for i in range(s)]


def _normalise(v: list[Any]) -> list[Any]:
    """Scale so that the entry of largest magnitude is 1 (exact for rationals)."""
    big = max(v, key=lambda x: abs(x))
    return [x / big for x in v] if big != 0 else v


def kernel_of(b: Sequence[Any], c: Sequence[Any], degree: int, exact: bool, dps: int = 50) -> Kernel:
    """Rank and kernel of the double-bush map at the rule (b, c), and the zero-row-sum part:
    ``exact`` — b, c Fractions or field elements; else enclosures (Intervals) of them."""
    s = len(b)
    n = s * s
    if not exact:
        return _kernel_numeric(b, c, degree, dps)
    rows = map_rows(b, c, degree)
    rank, basis = nullspace_exact(rows, n)
    _, zr = nullspace_exact(rows + row_sum_rows(s), n)
    return Kernel(s, degree, True, rank, len(rows),
                  [_matrix(_normalise(v), s) for v in basis], [_matrix(_normalise(v), s) for v in zr])


def _kernel_numeric(b: Sequence[Interval], c: Sequence[Interval], degree: int, dps: int) -> Kernel:
    """Singular values at ``dps`` digits, the rank bracketed by a certified lower bound
    (ball elimination over the enclosures) and the size of the matrix."""
    import mpmath

    from rkcheck.energy.double_bush_rank import certified_map_rank_lower

    s = len(b)
    n = s * s
    bits = mpmath_bits(dps)
    low = certified_map_rank_lower(b, c, degree, bits)
    low_zr = certified_map_rank_lower(b, c, degree, bits, with_row_sums=True)
    with mpmath.workdps(dps + 10):  # the rows themselves at the working precision
        bm, cm = [_mpf(x.mid) for x in b], [_mpf(x.mid) for x in c]
        rows = map_rows(bm, cm, degree)
    num = nullspace_numeric(rows, n, dps, low)
    num_zr = nullspace_numeric(rows + row_sum_rows(s), n, dps, low_zr)
    with mpmath.workdps(dps + 10):  # normalise at the working precision, not at 15 digits
        kernel = [_matrix(_normalise(v), s) for v in num.basis]
        zero_row_sum = [_matrix(_normalise(v), s) for v in num_zr.basis]
    high = min(len(rows), n)
    # dim(ker M ∩ {N·1 = 0}) = n − rank of M stacked with the s row sums
    zr_bounds = (n - min(len(rows) + s, n), n - low_zr)
    return Kernel(s, degree, False, num.rank, len(rows), kernel, zero_row_sum, num.around_cut(),
                  num_zr.around_cut(), rank_bounds=(low, high), zero_row_sum_bounds=zr_bounds)


def _mpf(x: Fraction) -> Any:
    import mpmath

    return mpmath.mpf(x.numerator) / x.denominator


def node_polynomial_kernel(poly: Sequence[Fraction], b: Sequence[Any], c: Sequence[Any], degree: int,
                           dps: int) -> Kernel:
    """The exact rank of M (and of M with the row sums) by rational elimination on the
    node polynomial ``poly`` (:mod:`rkcheck.energy.double_bush_rank`: the nodes distinct,
    the weights nonzero), with the kernel bases mapped to s×s matrices at ``dps`` digits
    (b, c mpf)."""
    import mpmath

    from rkcheck.energy.double_bush_rank import (
        first_column_rows,
        matrices_from_h,
        rational_nullspace,
        reduced_rows,
    )

    s = len(c)
    rows = reduced_rows(poly, degree)
    rank, basis = rational_nullspace(rows, s * s)
    _, zr = rational_nullspace(rows + first_column_rows(s), s * s)
    work = dps + 10 + 2 * s  # V⁻¹ of the nodes loses digits (its condition number)
    kernel = matrices_from_h(basis, b, c, work)
    zero_row_sum = matrices_from_h(zr, b, c, work)
    with mpmath.workdps(dps + 10):
        kernel = [_matrix(_normalise(v), s) for v in kernel]
        zero_row_sum = [_matrix(_normalise(v), s) for v in zero_row_sum]
    return Kernel(s, degree, False, rank, len(rows), kernel, zero_row_sum)


def rule_values(rule_name: str, s: int, dps: int) -> tuple[list[Any], list[Any], bool]:
    """(b, c, exact) of a named rule: Fractions or field elements when exact, else
    enclosures (Intervals) at the bits of ``dps`` digits."""
    from rkcheck.methods.quadrature import rule

    r = rule(rule_name, s)
    if r.is_rational:
        c, b = r.exact_nodes_weights()
        return b, c, True
    exact = algebraic_rule(r)
    if exact is not None:
        return exact[0], exact[1], True
    c_i, b_i = r.enclosures(mpmath_bits(dps))
    return b_i, c_i, False


def rule_kernel(rule_name: str, s: int, degree: int, dps: int) -> Kernel:
    """The kernel at a named rule: exact when its field is within the degree limit, else
    an exact rank from its (rational) node polynomial with a basis at ``dps`` digits."""
    import mpmath

    from rkcheck.methods.quadrature import rule

    b, c, exact = rule_values(rule_name, s, dps)
    if exact or any(x.contains_zero() for x in b):  # a zero weight: the map N ↦ H is singular
        return kernel_of(b, c, degree, exact, dps)
    with mpmath.workdps(dps + 10 + 2 * s):
        bm, cm = [_mpf(x.mid) for x in b], [_mpf(x.mid) for x in c]
    return node_polynomial_kernel(rule(rule_name, s).nodes[0].poly, bm, cm, degree, dps)


ALGEBRAIC_RULE_MAX_DEGREE = 12


def algebraic_rule(r: Any) -> tuple[list[Any], list[Any]] | None:
    """(b, c) of a quadrature rule exactly in the number field of its nodes (the weights
    from ``Σ b_i c_i^(k−1) = 1/k``, k = 1..s, solved in the field), or None when the field
    is beyond :data:`ALGEBRAIC_RULE_MAX_DEGREE`."""
    from rkcheck.numbers import grammar as ex
    from rkcheck.numbers.algebraic import NotAlgebraic
    from rkcheck.numbers.field_builder import field_of

    forms = r.node_closed_forms()
    if forms is None:
        return None
    try:
        # elimination on an s² × s² map in a field of degree D costs about D² times the
        # rational one: beyond degree 12 (e.g. the degree-24 fields of Radau 5) the
        # numerical rank, with its singular values printed, is the practical answer
        c = field_of([ex.parse(t) for t in forms], max_degree=ALGEBRAIC_RULE_MAX_DEGREE).values
    except NotAlgebraic:
        return None
    s = len(c)
    rows = [[ci ** k for ci in c] + [c[0] * 0 + Fraction(1, k + 1)] for k in range(s)]
    # Gauss–Jordan on the Vandermonde system (nodes distinct: always solvable)
    for col in range(s):
        piv = next(k for k in range(col, s) if rows[k][col] != 0)
        rows[col], rows[piv] = rows[piv], rows[col]
        inv = 1 / rows[col][col]
        rows[col] = [x * inv for x in rows[col]]
        for k in range(s):
            if k != col and rows[k][col] != 0:
                f = rows[k][col]
                rows[k] = [x - f * y for x, y in zip(rows[k], rows[col])]
    return [rows[i][s] for i in range(s)], list(c)


def tableau_rule(tableau: Any, dps: int) -> tuple[list[Any], list[Any], bool]:
    """(b, c = A·1, exact) of a tableau: exact values at face value, else enclosures
    (Intervals) at the bits of ``dps`` digits."""
    from rkcheck.numbers.intervals import interval_sum

    exact = tableau.exact_values()  # at face value
    if exact is not None and exact.entries() is not None:
        return exact.b, [sum(row, Fraction(0)) for row in exact.A], True
    A, b = tableau.enclosures(mpmath_bits(dps), DecimalsMode.EXACT)
    return b, [interval_sum(row) for row in A], False
