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

The form is built from the polynomials the family's entry texts are written with
(:func:`rkcheck.methods.closed_forms.evaluation_texts`: the Lagrange basis over the roots
of P, the Legendre polynomials of HBVM), in ``Q[x, y]`` and reduced modulo P in each
variable, not by parsing those texts back; the tests evaluate ``F`` and ``W`` at the
nodes in the field the texts are evaluated in and compare them with every entry.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Any, Iterable

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
    """χ of multiplication by g on ``Q[x, y]/(P(x), P(y))``, an fmpq_poly:
    ``∏_(k,l) (t − g(c_k, c_l))`` over the pairs of roots of P, which for a monic P is
    ``Res_x(P(x), Res_y(P(y), t − g(x, y)))`` up to its sign (FLINT's resultants: a
    third of the time of the s² × s² matrix's characteristic polynomial at s = 6)."""
    from flint import fmpq_mpoly_ctx, fmpq_poly

    ctx = fmpq_mpoly_ctx.get(("x", "y", "t"), "lex")
    G = ctx.from_dict({(int(a), int(b), 0): c for (a, b), c in g.to_dict().items()})
    moduli = [ctx.from_dict({(k, 0, 0) if var == "x" else (0, k, 0): to_fmpq(c) for k, c in enumerate(P)})
              for var in ("x", "y")]
    found = (ctx.gens()[2] - G).resultant(moduli[1], "y").resultant(moduli[0], "x").to_dict()
    degree = (len(P) - 1) ** 2
    lead = found[(0, 0, degree)]
    return fmpq_poly([found.get((0, 0, k), 0) / lead for k in range(degree + 1)])


@lru_cache(maxsize=16)
def node_form(spec: FamilySpec) -> NodeForm | None:
    """The family's :class:`NodeForm`, or None when its entries are not written exactly
    (:func:`rkcheck.methods.closed_forms.exact_node_polynomial`)."""
    from rkcheck.methods.closed_forms import exact_node_polynomial

    P = exact_node_polynomial(spec)
    if P is None or len(P) - 1 != spec.base_rule().s or not _square_free(P):
        return None  # the argument needs the nodes to be exactly the roots of P, each once
    F, W = _family_polynomials(spec, P)
    terms = reduce_pair(tuple(P), F).to_dict().items()
    return NodeForm(tuple(P), tuple(sorted(((int(a), int(b)), to_fraction(c)) for (a, b), c in terms)),
                    tuple((k, c) for k, c in enumerate(from_flint(W)) if c != 0))


def _square_free(P: list[Fraction]) -> bool:
    f = to_flint(P)
    return bool(f.gcd(f.derivative()).degree() == 0)


def _family_polynomials(spec: FamilySpec, P: list[Fraction]) -> tuple[Any, Any]:
    """``(F, W)``, F in x and y (not yet reduced), W an fmpq_poly reduced modulo P: the
    polynomials :func:`rkcheck.methods.closed_forms.evaluation_texts` writes each family's
    entries with, ``ℓ_j(x) = Σ_k U_k(c_j) x^k`` the Lagrange basis polynomial of node j."""
    from rkcheck.methods.closed_forms import lagrange_parts
    from rkcheck.methods.quadrature import shifted_legendre
    from rkcheck.numbers.polynomials import integral, inverse_mod

    ctx, x, y = pair_ring()
    U, W = lagrange_parts(P)
    n = len(P) - 1

    def of(p: Any, var: int) -> Any:  # a univariate polynomial as one in x (0) or y (1)
        coefficients = p if isinstance(p, list) else from_flint(p)
        return pair_polynomial((((k, 0) if var == 0 else (0, k)), c) for k, c in enumerate(coefficients) if c != 0)

    name, Wy = spec.name, of(W, 1)
    if name == "avf":  # A = c bᵀ
        F = x * Wy
    elif name in ("gauss", "lobatto-iiia", "radau-iia"):  # ∫_0^(c_i) ℓ_j
        F = sum((x ** (k + 1) * of(U[k], 1) / (k + 1) for k in range(n)), ctx.constant(0))
    elif name in ("lobatto-iiib", "radau-ia"):  # b_j/b_i·∫_(c_j)^1 ℓ_i
        integrals = sum(((1 - y ** (k + 1)) * of(U[k], 0) / (k + 1) for k in range(n)), ctx.constant(0))
        F = Wy * of(inverse_mod(W, to_flint(list(P))), 0) * integrals
    elif name == "hbvm":  # b_j·Σ_(l<s) (2l + 1)·∫_0^(c_i) P_l·P_l(c_j), P_l the shifted Legendre polynomials
        F = Wy * sum((of(integral(shifted_legendre(l)), 0) * of(shifted_legendre(l), 1) * (2 * l + 1)
                      for l in range(spec.s)), ctx.constant(0))
    else:  # the seed's kernel family: c_i b_j + β((ζ − 1) − 2ζ c_i) b_j (1 − 2 c_j)
        assert spec.zeta is not None and spec.beta is not None  # the kernel family is given both (parse_spec)
        z, beta = to_fmpq(spec.zeta), to_fmpq(spec.beta)
        F = x * Wy + beta * ((z - 1) - 2 * z * x) * Wy * (1 - 2 * y)
    return F, W
