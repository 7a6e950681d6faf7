"""A kernel's symmetry, symplecticity and equality with AVF read from its B-series, where
the kernel's own form does not show them (:mod:`rkcheck.energy.continuous`).

The tests on ``(A, B)`` themselves are sufficient, not necessary: one method has many
kernels (``σ ↦ φ(σ)`` reparametrises it, ``A(τ, σ) = σ`` is the midpoint rule written with
a stage for each τ), and a kernel that fails a test may still have the property.  The
B-series decides: with the stage functions ``G_τ ≡ 1``,
``G_[t1…tq](τ) = Π_k ∫₀¹ A(τ, σ) G_{t_k}(σ) dσ`` and the weights ``a(t) = ∫₀¹ B G_t``
(definitions §6),

* **symmetric** ⇔ ``a(t) = a*(t)`` for every rooted tree, ``a*`` the weights of the
  adjoint kernel ``(B(σ) − A(τ, σ), B(τ))`` (as ``(1bᵀ − A, b)`` is a tableau's adjoint);
* **symplectic** ⇔ ``a(u∘v) + a(v∘u) = a(u) a(v)`` for all rooted trees u, v (Calvo &
  Sanz-Serna; Hairer, Lubich & Wanner VI.7.6), and the left side minus the right is
  ``∫∫ M(τ, σ) G_u(τ) G_v(σ)`` with ``M = B(τ)A(τ,σ) + B(σ)A(σ,τ) − B(τ)B(σ)``;
* **equals AVF for degree m** ⇔ ``a(t)`` is AVF's (``1`` for τ,
  ``a(t1)…a(tq)/(q+1)``) for every rooted tree whose vertices have at most m − 1
  children: the elementary differentials of those trees are independent already for
  Hamiltonians of degree m (``H = Σ_v p_v Π_{c child of v} q_c`` gives the q-components
  the vector field whose differentials separate the trees), and the others vanish.

A tree where the two sides differ — enclosed in interval arithmetic, over the whole box of
a kernel with rounded decimals — proves the property false.  When every tree up to
:data:`SERIES_VERTICES` vertices agrees, nothing is proven either way: the property is
``undecided``, never ``no``.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Callable, Iterable, Iterator

from rkcheck.energy.kernel_box import Poly, interval_poly
from rkcheck.numbers.formatting import short
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode
from rkcheck.trees.rooted import (
    bracket,
    children_of_level_sequence,
    level_sequence_of_forest,
)

#: The smallest trees searched for a witness (u∘v of this many vertices for
#: symplecticity); a check searches up to its own order + 1 where that is more.
SERIES_VERTICES = 10

#: Products of coefficients one search may spend: a kernel of high degree has stage
#: functions of high degree, and the search stops at the trees it could afford.
SERIES_WORK = 4_000_000

#: Bits of the Arb balls of a kernel that is not exact (roots, or a box of decimals).
SERIES_BITS = 256

Tree = tuple[int, ...]


@dataclass(frozen=True)
class SeriesAnswer:
    """The B-series' word on one property: ``witness`` names a tree (or a pair) where it
    certainly fails, None when every tree searched agrees; ``vertices``: every tree up to
    this size was searched."""

    witness: str | None
    vertices: int


class _OutOfWork(Exception):
    pass


@functools.lru_cache(maxsize=None)
def trees_of(n: int) -> tuple[Tree, ...]:
    """Every rooted tree of ``n`` vertices, as canonical level sequences (each is u∘v of
    two smaller ones); built once per process, as the searches first need them."""
    if n == 1:
        return ((1,),)
    found = {level_sequence_of_forest([*children_of_level_sequence(u), v])
             for k in range(1, n) for u in trees_of(n - k) for v in trees_of(k)}
    return tuple(sorted(found, reverse=True))


def rooted_trees(max_vertices: int) -> Iterator[Tree]:
    """Every rooted tree up to ``max_vertices`` vertices, smaller trees first, each size
    built only when the one before is used up (a witness is usually small)."""
    for n in range(1, max_vertices + 1):
        yield from trees_of(n)


class Kernel:
    """``A(τ, σ) = Σ A[i][j] τ^i σ^j`` and ``B(τ) = Σ B[i] τ^i`` over one arithmetic:
    exact rationals where every coefficient is a point, else Arb balls of
    :data:`SERIES_BITS` bits that contain the coefficients' intervals (roots enclosed, or
    a box of decimals) — python-flint either way.  Everything the searches need is linear
    in moments ``m_j(g) = ∫₀¹ σ^j g(σ) dσ``: ``∫ A(τ, σ) g(σ) dσ = Σ_i τ^i Σ_j A[i][j]
    m_j(g)``, ``a(t) = Σ_i B[i] m_i(G_t)``."""

    def __init__(self, A: Poly, B: Poly, work: int = SERIES_WORK):
        import flint

        self.exact = all(c.is_point for c in [*A.values(), *B.values()])
        self.scalar: Any = flint.fmpq if self.exact else flint.arb
        self.poly: Any = flint.fmpq_poly if self.exact else flint.arb_poly
        p = 1 + max((i for i, _ in [*A, *B]), default=0)
        q = 1 + max((j for _, j in A), default=0)
        self.A = [[self._number(A.get((i, j))) for j in range(q)] for i in range(p)]
        self.B = [self._number(B.get((i, 0))) for i in range(p)]
        self.left = work
        self._reciprocals: list[Any] = [self.zero]

    def _number(self, c: Interval | None) -> Any:
        import flint

        if c is None:
            return self.zero
        lo, hi = (flint.fmpq(x.numerator, x.denominator) for x in (c.lo, c.hi))
        return lo if self.exact else flint.arb(lo).union(flint.arb(hi))  # a ball around [lo, hi]

    @property
    def zero(self) -> Any:
        return self.scalar(0)

    def spend(self, work: int) -> None:
        self.left -= work
        if self.left < 0:
            raise _OutOfWork

    def mul(self, f: list[Any], g: list[Any]) -> list[Any]:
        """The product of two polynomials in τ (coefficient lists)."""
        self.spend(len(f) * len(g))
        return list((self.poly(f) * self.poly(g)).coeffs())

    def moments(self, g: list[Any], n: int) -> list[Any]:
        """``m_j(g)`` for j < n."""
        self.spend(len(g) * n)
        inv = self.reciprocals(n + len(g))
        out = []
        for j in range(n):
            total = self.zero
            for c, r in zip(g, inv[j + 1:]):
                total += c * r
            out.append(total)
        return out

    def reciprocals(self, n: int) -> list[Any]:
        """``[0, 1, 1/2, …, 1/n]``: the moments' weights, made once per kernel."""
        inv = self._reciprocals
        while len(inv) <= n:
            inv.append(self.scalar(1) / len(inv))
        return inv

    def reciprocal(self, n: int) -> Any:
        return self.reciprocals(n)[n]

    def apply(self, g: list[Any]) -> list[Any]:
        """``∫₀¹ A(τ, σ) g(σ) dσ`` as a polynomial in τ."""
        m = self.moments(g, len(self.A[0]))
        return [sum((a * x for a, x in zip(row, m)), self.zero) for row in self.A]

    def weight(self, g: list[Any]) -> Any:
        return sum((b * x for b, x in zip(self.B, self.moments(g, len(self.B)))), self.zero)

    def nonzero(self, x: Any) -> bool:
        return bool(x != 0) if self.exact else not x.contains(0)

    def text(self, x: Any) -> str:
        if self.exact:  # p/q, as the weights are written (never a decimal beside a fraction)
            q = Fraction(int(x.p), int(x.q))
            # by bits first: Python refuses to write an integer past its digit limit
            if q.numerator.bit_length() + q.denominator.bit_length() <= 140 and len(str(q)) <= 40:
                return str(q)
            return f"≈ {short(q)}"
        return f"≈ {short(Fraction(float(x.mid())))}"

    def adjoint(self) -> "Kernel":
        """The adjoint kernel ``(B(σ) − A(τ, σ), B(τ))`` in the same arithmetic."""
        other = object.__new__(Kernel)
        other.exact, other.left, other.scalar, other.poly = self.exact, self.left, self.scalar, self.poly
        other._reciprocals = self._reciprocals
        q = max(len(self.A[0]), len(self.B))
        rows = [[-a for a in row] + [self.zero] * (q - len(row)) for row in self.A]
        rows[0] = [b + x for b, x in zip([*self.B, *[self.zero] * (q - len(self.B))], rows[0])]
        other.A, other.B = rows, list(self.B)
        return other


def _searched(search: Callable[..., SeriesAnswer]) -> Callable[..., SeriesAnswer]:
    """``search`` with Arb balls of :data:`SERIES_BITS` bits (python-flint's precision is
    one global setting: ``workprec`` restores it after)."""
    @functools.wraps(search)
    def run(*args: Any, **kwargs: Any) -> SeriesAnswer:
        from flint import ctx

        with ctx.workprec(SERIES_BITS):
            return search(*args, **kwargs)

    return run


class _Stages:
    """Stage functions ``G_t`` of one kernel, each tree once."""

    def __init__(self, kernel: Kernel):
        self.kernel = kernel
        self.G: dict[Tree, list[Any]] = {}
        self._applied: dict[Tree, list[Any]] = {}

    def __call__(self, t: Tree) -> list[Any]:
        if t not in self.G:
            g = [self.kernel.reciprocal(1)]
            for child in children_of_level_sequence(t):
                if child not in self._applied:
                    self._applied[child] = self.kernel.apply(self(child))
                g = self.kernel.mul(g, self._applied[child])
            self.G[t] = g
        return self.G[t]

    def weight(self, t: Tree) -> Any:
        return self.kernel.weight(self(t))


def kernel_polys(method: Any, decimals: DecimalsMode, bits: int = SERIES_BITS) -> tuple[Poly, Poly]:
    """``A(τ, σ)`` and ``B(τ)`` with interval coefficients: exact where the kernel is
    rational, enclosures of its roots, or its decimals' box under ``decimals``."""
    consts = method.info.constants.enclosures(bits, decimals)
    return interval_poly(method.nodes[0], decimals, consts, bits), interval_poly(method.nodes[1], decimals, consts, bits)


def _first(trees: Iterable[Tree], differs: Callable[[Tree], str | None], vertices: int) -> SeriesAnswer:
    """The first tree that ``differs`` (smaller trees first), or how far the search got."""
    for t in trees:
        try:
            why = differs(t)
        except _OutOfWork:
            return SeriesAnswer(None, len(t) - 1)
        if why is not None:
            return SeriesAnswer(why, vertices)
    return SeriesAnswer(None, vertices)


@_searched
def symmetric_witness(A: Poly, B: Poly, vertices: int = SERIES_VERTICES) -> SeriesAnswer:
    """A rooted tree whose weight differs from the adjoint kernel's, if one of at most
    ``vertices`` vertices does."""
    kernel = Kernel(A, B)
    own, adjoint = _Stages(kernel), _Stages(kernel.adjoint())

    def differs(t: Tree) -> str | None:
        a, b = own.weight(t), adjoint.weight(t)
        if kernel.nonzero(a - b):
            return f"its weight of {bracket(t)} is not its adjoint's ({kernel.text(a)} against {kernel.text(b)})"
        return None

    return _first(rooted_trees(vertices), differs, vertices)


@_searched
def symplectic_witness(A: Poly, B: Poly, vertices: int = SERIES_VERTICES) -> SeriesAnswer:
    """Rooted trees u, v (|u| + |v| at most ``vertices``) with a(u∘v) + a(v∘u) ≠ a(u)a(v):
    ``m(G_u)ᵀ M m(G_v)`` with ``M[i][j]`` the coefficients of ``B(τ)A(τ,σ) + B(σ)A(σ,τ) −
    B(τ)B(σ)``.  Many trees share a stage function: each distinct pair is tried once."""
    kernel = Kernel(A, B)
    stages = _Stages(kernel)
    n_m = max(len(kernel.A) + len(kernel.B), len(kernel.A[0]) + len(kernel.B))
    M = [[kernel.zero] * n_m for _ in range(n_m)]
    for i, b in enumerate(kernel.B):
        for k, row in enumerate(kernel.A):
            for j, a in enumerate(row):
                M[i + k][j] = M[i + k][j] + b * a  # B(τ)A(τ, σ)
                M[j][i + k] = M[j][i + k] + b * a  # B(σ)A(σ, τ)
        for j, b2 in enumerate(kernel.B):
            M[i][j] = M[i][j] - b * b2
    distinct: dict[int, list[Tree]] = {}
    rows: dict[Tree, list[Any]] = {}
    moments_of: dict[Tree, list[Any]] = {}

    def moments(t: Tree) -> list[Any]:  # each tree's moments once, for every pair it is in
        if t not in moments_of:
            moments_of[t] = kernel.moments(stages(t), n_m)
        return moments_of[t]

    n = 1
    try:
        for n in range(2, vertices + 1):  # pairs of n vertices in all, smaller first
            distinct[n - 1] = _distinct(stages, list(trees_of(n - 1)))
            for size_u in range(1, n):
                for u in distinct[size_u]:
                    if u not in rows:  # m(G_u)ᵀ M
                        m = moments(u)
                        rows[u] = [sum((m[i] * M[i][j] for i in range(n_m)), kernel.zero) for j in range(n_m)]
                    for v in distinct[n - size_u]:
                        m_v = moments(v)
                        defect = sum((r * x for r, x in zip(rows[u], m_v)), kernel.zero)
                        if kernel.nonzero(defect):
                            value = kernel.text(defect)
                            value = value if value.startswith("≈") else f"= {value}"
                            return SeriesAnswer(f"a(u∘v) + a(v∘u) − a(u)a(v) {value} for u = "
                                                f"{bracket(u)}, v = {bracket(v)}", vertices)
    except _OutOfWork:
        return SeriesAnswer(None, n - 1)
    return SeriesAnswer(None, vertices)


def _distinct(stages: _Stages, trees: list[Tree]) -> list[Tree]:
    """One of ``trees`` for each distinct stage function among them."""
    found: dict[Any, Tree] = {}
    for t in trees:
        found.setdefault(tuple(str(c) for c in stages(t)), t)
    return list(found.values())


@_searched
def avf_witness(A: Poly, B: Poly, degree: int | None, vertices: int = SERIES_VERTICES) -> SeriesAnswer:
    """A rooted tree (each vertex with at most m − 1 children) whose weight is not AVF's."""
    kernel = Kernel(A, B)
    stages = _Stages(kernel)
    avf: dict[Tree, Any] = {}

    def avf_weight(t: Tree) -> Any:
        if t not in avf:
            kids = children_of_level_sequence(t)
            w = kernel.reciprocal(len(kids) + 1)
            for child in kids:
                w = w * avf_weight(child)
            avf[t] = w
        return avf[t]

    def differs(t: Tree) -> str | None:
        a, e = stages.weight(t), avf_weight(t)
        if kernel.nonzero(a - e):
            return f"its weight of {bracket(t)} is not AVF's ({kernel.text(a)} against {kernel.text(e)})"
        return None

    trees = (t for t in rooted_trees(vertices) if degree is None or _widest(t) <= degree - 1)
    return _first(trees, differs, vertices)


def _widest(t: Tree) -> int:
    """The most children of any vertex."""
    kids = children_of_level_sequence(t)
    return max([len(kids), *(_widest(c) for c in kids)])
