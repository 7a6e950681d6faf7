"""A family's tableau as two polynomials in its nodes: ``A_ij = F(c_i, c_j)`` and
``b_j = W(c_j)``, with ``F`` and ``W`` over Q and the nodes ``c_1 … c_s`` all the roots of
one square-free polynomial ``P`` over Q.

Such a tableau is *equivariant*.  An automorphism σ of the nodes' field permutes the
roots of P, ``σ(c_i) = c_π(i)``, so it maps ``A_ij`` to ``A_π(i)π(j)`` and ``b_j`` to
``b_π(j)``: the same tableau with its stages numbered otherwise.  A quantity that does not
depend on how the stages are numbered — an elementary weight, an energy condition, a
coefficient of R(z) — is therefore fixed by every automorphism of the field, and so is
rational, whatever the degree of the field (48 for the six Gauss-6 nodes).  Modulo a prime
over which P splits into distinct linear factors, it is the same expression with the nodes
replaced by those roots, in any order (:mod:`rkcheck.evaluation.split_nodes`).

The form is read off the texts the family's entries are evaluated from
(:func:`rkcheck.methods.closed_forms.evaluation_texts`), each entry as a polynomial in the
nodes reduced modulo P in each of them; it is a :class:`NodeForm` only when every
off-diagonal entry is the same ``F``, every diagonal one ``F(x, x)`` and every weight the
same ``W`` — which is what the argument above needs, checked rather than assumed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Any, Iterable

from rkcheck.numbers.expressions import binary
from rkcheck.numbers.polynomials import from_flint, to_flint, to_fmpq, to_fraction

if TYPE_CHECKING:
    from rkcheck.methods.family_spec import FamilySpec

#: ``{(a, b): coefficient}`` of ``Σ f_ab x^a y^b`` (a, b below the number of nodes)
Bivariate = tuple[tuple[tuple[int, int], Fraction], ...]


@dataclass(frozen=True)
class NodeForm:
    """``A_ij = F(c_i, c_j)``, ``b_j = W(c_j)`` over the roots ``c`` of ``P`` (module
    docstring); ``P`` monic and ascending, ``F`` and ``W`` reduced modulo P."""

    P: tuple[Fraction, ...]
    F: Bivariate
    W: tuple[tuple[int, Fraction], ...]

    @property
    def stages(self) -> int:
        return len(self.P) - 1

    def integrality_scale(self) -> int:
        """The least positive integer ``e`` with every ``e·A_ij`` and ``e·b_j`` an
        algebraic integer.  The characteristic polynomial of multiplication by F on
        ``Q[x, y]/(P(x), P(y))`` has the roots ``F(c_i, c_j)`` over all pairs, that of W on
        ``Q[x]/(P)`` the ``W(c_j)``; by Gauss's lemma ``λ^m χ(X/λ)`` is integral exactly
        when it is for each irreducible factor of χ, so the least λ that makes both
        integral is the least common integrality denominator of the entries."""
        from flint import fmpq_mat

        from rkcheck.numbers.minimal import integral_scale

        n = self.stages
        C = _companion(self.P)
        powers = [fmpq_mat(n, n, [int(i == j) for i in range(n) for j in range(n)])]
        for _ in range(1, n):
            powers.append(powers[-1] * C)
        F = pair_polynomial(self.F)
        mul_W = fmpq_mat(n, n)
        for b, coeff in self.W:
            mul_W += powers[b] * to_fmpq(coeff)
        return max(1, math.lcm(int(integral_scale(from_flint(pair_charpoly(self.P, F)))),
                               int(integral_scale(from_flint(mul_W.charpoly())))))

    @cached_property
    def power_traces(self) -> list[Fraction]:
        """``Tr(x^m) = Σ_k c_k^m`` for m < s, the trace of ``Q[x]/(P)`` on its basis
        (Newton's identities, from P's coefficients)."""
        P, n = self.P, self.stages
        e = [(-1) ** k * P[n - k] for k in range(n + 1)]  # elementary symmetric functions
        p = [Fraction(n)]
        for m in range(1, n):
            p.append((-1) ** (m - 1) * m * e[m] + sum(((-1) ** (i - 1) * e[i] * p[m - i] for i in range(1, m)),
                                                      Fraction(0)))
        return p

    def stability_series(self, count: int) -> list[Fraction]:
        """``r_0 … r_count`` with ``r_k = bᵀA^(k−1)1`` (r_0 = 1), over Q.  A stage vector
        ``v_i = V(c_i)`` (V modulo P) goes to ``(Av)_i = Σ_a c_i^a Tr(F_a·V)``, with
        ``F(x, y) = Σ_a x^a F_a(y)`` and Tr the trace of ``Q[y]/(P)`` (the sum over the
        roots), and ``bᵀv = Tr(W·V)``: the powers of A applied to 1 stay polynomials of
        degree below s, and every term is rational (the module docstring)."""
        from flint import fmpq_poly

        P, traces = to_flint(list(self.P)), self.power_traces

        def trace(U: Any) -> Fraction:
            return sum((c * traces[m] for m, c in enumerate(from_flint(U % P))), Fraction(0))

        rows: dict[int, Any] = {}
        for (a, b), coeff in self.F:
            rows[a] = rows.get(a, fmpq_poly([])) + fmpq_poly([0] * b + [1]) * to_fmpq(coeff)
        W = fmpq_poly([])
        for b, coeff in self.W:
            W += fmpq_poly([0] * b + [1]) * to_fmpq(coeff)
        series, V = [Fraction(1)], fmpq_poly([1])
        for _ in range(count):
            series.append(trace(W * V))
            V = sum((fmpq_poly([0] * a + [1]) * to_fmpq(trace(Fa * V)) for a, Fa in rows.items()), fmpq_poly([]))
        return series


def _companion(P: tuple[Fraction, ...]) -> Any:
    """The matrix of multiplication by x on ``Q[x]/(P)`` in the basis ``1, x, …``
    (columns: images of the basis)."""
    from flint import fmpq_mat

    n = len(P) - 1
    C = fmpq_mat(n, n)
    for k in range(n - 1):
        C[k + 1, k] = 1
    for k in range(n):
        C[k, n - 1] = to_fmpq(-P[k])
    return C


def pair_ring() -> tuple[Any, Any, Any]:
    """The polynomials in x and y over Q (FLINT's context, one per process) and x, y."""
    from flint import fmpq_mpoly_ctx

    ctx = fmpq_mpoly_ctx.get(("x", "y"), "lex")
    x, y = ctx.gens()
    return ctx, x, y


def pair_polynomial(terms: Iterable[tuple[tuple[int, int], Fraction]]) -> Any:
    """``Σ c·x^a·y^b`` over the terms ``((a, b), c)``."""
    return pair_ring()[0].from_dict({ab: to_fmpq(c) for ab, c in terms})


def reduce_pair(P: tuple[Fraction, ...], g: Any) -> Any:
    """g modulo P(x) and P(y): degree below s in each variable."""
    Px, Py = _pair_moduli(P)
    return divmod(divmod(g, Px)[1], Py)[1]


@lru_cache(maxsize=16)
def _pair_moduli(P: tuple[Fraction, ...]) -> tuple[Any, Any]:
    return pair_polynomial(((k, 0), c) for k, c in enumerate(P)), pair_polynomial(((0, k), c) for k, c in enumerate(P))


def pair_charpoly(P: tuple[Fraction, ...], g: Any) -> Any:
    """χ of multiplication by g on ``Q[x, y]/(P(x), P(y))`` (basis ``x^a y^b``), an
    fmpq_poly: ``∏_(k,l) (t − g(c_k, c_l))`` over the pairs of roots of P."""
    from flint import fmpq_mat

    _, x, y = pair_ring()
    n = len(P) - 1
    M = fmpq_mat(n * n, n * n)
    for col, (a, b) in enumerate((a, b) for a in range(n) for b in range(n)):
        for (p, q), c in reduce_pair(P, g * x**a * y**b).to_dict().items():
            M[p * n + q, col] = c
    return M.charpoly()


@lru_cache(maxsize=16)
def node_form(spec: FamilySpec) -> NodeForm | None:
    """The family's :class:`NodeForm`, or None when its entries are not polynomials of
    their two nodes over the roots of the node polynomial (no closed-form nodes, an entry
    that divides by a node, or entries that differ from one another)."""
    from rkcheck.methods.closed_forms import evaluation_trees

    trees = evaluation_trees(spec)
    if trees is None:
        return None
    P, definitions, A, b = trees
    if len(P) - 1 != len(b) or not _square_free(P):
        return None  # the argument needs the nodes to be exactly the roots of P, each once
    polys = _NodePolynomials(P, definitions)
    try:
        entries = [[polys.of(A[i][j], {i, j}) for j in range(len(b))] for i in range(len(b))]
        weights = [polys.of(x, {j}) for j, x in enumerate(b)]
    except _NotPolynomial:
        return None
    return _uniform(P, entries, weights)


def _square_free(P: list[Fraction]) -> bool:
    f = to_flint(P)
    return f.gcd(f.derivative()).degree() == 0


class _NotPolynomial(Exception):
    pass


class _NodePolynomials:
    """Parsed entries as FLINT polynomials in the nodes ``c1 … cn`` (every name defined
    in ``definitions`` over them), reduced modulo P in each node."""

    def __init__(self, P: list[Fraction], definitions: dict[str, Any]):
        from flint import fmpq_mpoly_ctx

        n = len(P) - 1
        self.ctx = fmpq_mpoly_ctx.get(tuple(f"c{i + 1}" for i in range(n)), "lex")
        self.gens = dict(zip(self.ctx.names(), self.ctx.gens()))
        self.moduli = [sum((g**k * to_fmpq(x) for k, x in enumerate(P)), self.ctx.constant(0)) for g in self.ctx.gens()]
        self.definitions = definitions
        self.known: dict[str, Any] = {}

    def of(self, node: Any, nodes: set[int]) -> Any:
        """The parsed entry ``node`` reduced modulo P in each node; it must use only ``nodes``."""
        from rkcheck.numbers import expressions as xp

        value = xp.fold(node, self._combine)
        used = {k for k, d in enumerate(value.degrees()) if d > 0}
        if not used <= nodes:
            raise _NotPolynomial
        for k in sorted(nodes):
            value = divmod(value, self.moduli[k])[1]
        return value

    def _name(self, name: str) -> Any:
        from rkcheck.numbers import expressions as xp

        if name in self.gens:
            return self.gens[name]
        if name not in self.definitions:
            raise _NotPolynomial
        if name not in self.known:
            self.known[name] = xp.fold(self.definitions[name], self._combine)
        return self.known[name]

    def _combine(self, node: Any, vals: list[Any]) -> Any:
        from rkcheck.numbers import grammar as ex

        if isinstance(node, ex.Num):
            return self.ctx.constant(to_fmpq(node.value))
        if isinstance(node, ex.Name):
            return self._name(node.name)
        if isinstance(node, ex.Unary):
            return -vals[0]
        if isinstance(node, ex.Power):
            base, exponent = vals
            if not exponent.is_constant() or exponent.leading_coefficient().denom() != 1:
                raise _NotPolynomial
            k = int(exponent.leading_coefficient().numer())
            if k < 0:
                raise _NotPolynomial
            return base**k
        if not isinstance(node, ex.Binary):
            raise _NotPolynomial  # a root: not a polynomial in the nodes
        left, right = vals
        if node.op == "/":  # by a nonzero rational only: a node's inverse is no polynomial
            if not right.is_constant() or right.is_zero():
                raise _NotPolynomial
            right = right.leading_coefficient()
        return binary(node.op, left, right)


def _uniform(P: list[Fraction], entries: list[list[Any]], weights: list[Any]) -> NodeForm | None:
    """The NodeForm when every entry is the same polynomial of its nodes, else None."""

    n = len(P) - 1

    def pairs(poly: Any, i: int, j: int) -> dict[tuple[int, int], Fraction]:
        return {(int(m[i]), int(m[j])): to_fraction(c) for m, c in poly.to_dict().items()}

    def single(poly: Any, j: int) -> dict[int, Fraction]:
        return {int(m[j]): to_fraction(c) for m, c in poly.to_dict().items()}

    F = pairs(entries[0][1], 0, 1) if n > 1 else None
    W = single(weights[0], 0)
    if any(single(w, j) != W for j, w in enumerate(weights)):
        return None
    for i in range(n):
        for j in range(n):
            if i != j and pairs(entries[i][j], i, j) != F:
                return None
    if F is None:  # one node: the entry is a constant polynomial in it
        F = {(a, 0): c for a, c in single(entries[0][0], 0).items()}
    diagonal = _diagonal(P, F)
    if any(single(entries[i][i], i) != diagonal for i in range(n)):
        return None
    return NodeForm(tuple(P), tuple(sorted(F.items())), tuple(sorted(W.items())))


def _diagonal(P: list[Fraction], F: dict[tuple[int, int], Fraction]) -> dict[int, Fraction]:
    """``F(x, x)`` modulo P, as ``{power: coefficient}``."""
    from flint import fmpq_poly

    g = fmpq_poly([])
    for (a, b), c in F.items():
        g += fmpq_poly([0] * (a + b) + [1]) * to_fmpq(c)
    r = from_flint(g % to_flint(P))
    return {k: c for k, c in enumerate(r) if c != 0}
