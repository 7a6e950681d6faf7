"""The properties of a family's tableau from its node form, without the field of its nodes.

What :mod:`rkcheck.properties.tableau` computes entry by entry over the tableau's scalars
is here one polynomial identity each in ``Q[x, y]/(P(x), P(y))``
(:class:`~rkcheck.methods.node_algebra.NodeAlgebra`): ``c = A·1`` is x, a sum over the
stages a trace, and an entry a report names an exact :class:`NodeValue`.  The verdicts
and the texts are those of the generic route — the same functions make them from what
this module computes (:func:`~rkcheck.properties.avf.avf_verdict`,
:func:`~rkcheck.properties.lineintegral.line_integral_certificate`,
:func:`~rkcheck.properties.symplectic.symplectic_verdict`).

The route applies to a consistent tableau (``Σ_j F(x, c_j) = x``) whose weights are all
nonzero (:meth:`NodeAlgebra.irreducible`): its nodes are distinct, so it is its own
irreducible form (no stage is dead, no two merge).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Iterator

from rkcheck.methods.node_algebra import NodeAlgebra
from rkcheck.methods.quadrature import shifted_legendre
from rkcheck.numbers.polynomials import integral
from rkcheck.properties.avf import AvfVerdict, avf_verdict
from rkcheck.properties.lineintegral import (
    LineIntegralCertificate,
    line_integral_certificate,
)
from rkcheck.properties.orders import OrderResult, quadrature_order_of
from rkcheck.properties.reduction import Reduction
from rkcheck.properties.stability import stability_of_series
from rkcheck.properties.symplectic import (
    PropertyVerdict,
    not_symmetric,
    symmetric,
    symplectic_verdict,
)
from rkcheck.properties.tableau import TableauProperties
from rkcheck.verdicts import HOLDS, Verdict


@dataclass(frozen=True)
class NodeProperties(TableauProperties):
    """:class:`TableauProperties` whose certificates are decided in the node algebra."""

    algebra: Any = field(default=None, compare=False, repr=False)

    def avf(self, degree: int) -> AvfVerdict:
        alg = self.algebra
        D = alg.F - alg.x * alg.W_y  # A − (A·1)bᵀ with A·1 = c
        n = alg.n
        entries = iter(()) if alg.is_zero(D) else ((i, j, alg.value(D, i, j)) for i in range(n) for j in range(n))
        return avf_verdict(self.reduction, degree, entries, quadrature_residuals(alg))

    def line_integral(self, degree: int) -> LineIntegralCertificate:
        alg = self.algebra
        rhs = alg.constant(0)

        def matches(sigma: int) -> list[Verdict] | None:
            nonlocal rhs
            j = sigma - 1
            P = shifted_legendre(j)
            rhs += alg.poly(integral(P), alg.x) * alg.poly(P, alg.y) * alg.W_y * (2 * j + 1)
            return [] if alg.is_zero(alg.F - rhs) else None

        return line_integral_certificate(self.reduction, degree, quadrature_residuals(alg), matches)


def quadrature_residuals(alg: NodeAlgebra) -> Iterator[Fraction]:
    """``Σ_i W(c_i) c_i^(k−1) − 1/k`` for k = 1, 2, …: traces, rational."""
    term, k = alg.W_x, 1
    while True:
        yield alg.trace(term) - Fraction(1, k)
        term, k = alg.reduce(term * alg.x), k + 1


def node_quadrature_order(alg: NodeAlgebra) -> OrderResult:
    return quadrature_order_of(quadrature_residuals(alg), alg.n)


def node_properties(alg: NodeAlgebra) -> NodeProperties:
    """The properties of the tableau; R(z) from its series over Q."""
    n = alg.n
    red = Reduction(A=[[alg.value(alg.F, i, j) for j in range(n)] for i in range(n)],
                    b=[alg.value(alg.W_x, j) for j in range(n)], classes=[(i,) for i in range(n)], stages=n)
    return NodeProperties(
        exact=True, reduction=red, stability=stability_of_series(alg.form.stability_series(2 * n), n),
        symplectic=_symplecticity(alg, red), symmetric=_symmetry(alg, red), algebra=alg,
    )


def _symplecticity(alg: NodeAlgebra, red: Reduction) -> PropertyVerdict:
    M = alg.W_x * alg.F + alg.W_y * alg.swap(alg.F) - alg.W_x * alg.W_y
    n = alg.n
    entries = iter(()) if alg.is_zero(M) else ((alg.value(M, i, j), i, j) for i in range(n) for j in range(i, n))
    return symplectic_verdict(red, entries)


def _symmetry(alg: NodeAlgebra, red: Reduction) -> PropertyVerdict:
    """The adjoint ``b_j − A_ij`` is ``A`` at the stages of the nodes ``Σb − c``, when
    ``P(Σb − x) = ±P(x)`` (else some ``Σb − c_i`` is no node at all): the only
    permutation the generic search can find, checked as two identities."""
    total = alg.weight_sum()
    x, y = alg.x, alg.y
    P = alg.poly(alg.form.P, x)
    if P.compose(alg.constant(total) - x, y) != P * (-1) ** alg.n:
        return not_symmetric(red, False)
    W_ref = alg.reflect(alg.W_x, total)
    if alg.is_zero(W_ref - alg.W_x) and alg.is_zero(alg.reflect(alg.F, total) - (alg.W_y - alg.F)):
        return symmetric(red, alg.reflected_stages(total), Verdict(HOLDS))
    # stage i's only candidate is the stage of Σb − c_i: it needs the same weight and
    # b_i − A_ii = A at that stage's diagonal
    diagonal = alg.F.compose(x, x)
    E = alg.W_x - diagonal - alg.reflect(diagonal, total)
    candidates = all(alg.value(W_ref - alg.W_x, i).is_zero() and alg.value(E, i).is_zero() for i in range(alg.n))
    return not_symmetric(red, candidates)
