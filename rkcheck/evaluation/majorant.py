"""One bound of a decimal box's variation for every condition, along a single direction
(definitions §5.2).

The mean value form of :mod:`~rkcheck.evaluation.box` needs, for each condition,
``V = Σ_e sup_X |∂R/∂x_e| · r_e`` over the interval entries ``e``: one direction of
derivatives per entry.  A bound of V needs only one.  A condition is
``R = Σ_u c_u w(u)``, and every weight ``w(u)`` is a polynomial in the entries with
nonnegative integer coefficients (products of entries and sums of such products), so
on the box, where ``|x_e| ≤ y_e = |x̃_e| + r_e``,

    |∂R/∂x_e (x)| ≤ Σ_u |c_u| ∂w(u)/∂x_e (|x|) ≤ Σ_u |c_u| ∂w(u)/∂x_e (y),

and summing with the radii, ``V ≤ V̄ = Σ_u |c_u| D_r w(u)(y)``: the derivative of the
*majorant* ``R̄ = Σ_u |c_u| w(u)`` at the corner ``y`` along the radii ``r``.  This
context computes ``V̄`` on the float screen (forward-mode differentiation along one
direction, :class:`~rkcheck.evaluation.slopes.GradientContext`'s kernel), every operation
rounded outwards; all of its values are nonnegative, so the upper end of a sum's
enclosure bounds it.

``V̄`` is the directions' cost divided by their number, but it ignores the cancellation
between terms: 20–70 times ``V`` (median) on decimal Gauss-3.  So it only decides: a
condition whose centre lies farther from 0 than ``V̄`` fails, as it would with ``V``;
the others get their directions (:func:`~rkcheck.evaluation.box.judge_box`).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

import numpy as np

from rkcheck.evaluation.balls import FloatContext, _float_coefficients
from rkcheck.evaluation.slopes import GradientContext, _add
from rkcheck.numbers.intervals import Interval, float_above


def _points(rows: Sequence[Sequence[Fraction]]) -> list[list[Interval]]:
    return [[Interval.point(x) for x in row] for row in rows]


class MajorantContext(GradientContext):
    """Values of the weights at the corner ``y = |x̃| + r`` and their derivative along the
    radii ``r`` (one direction), summed with the coefficients' absolute values: the
    condition sums are :class:`~rkcheck.evaluation.balls.FloatSums` of ``R̄(y)`` and a
    one-column ``G`` whose entries bound ``V̄`` (module docstring).

    ``radii_A``/``radii_b``: each entry's ``r_e`` (floats rounded up; 0 for an exact
    entry), ``centre_A``/``centre_b``: the face values ``x̃`` (exact rationals, or narrow
    enclosures of irrational ones)."""

    def __init__(self, radii_A: Sequence[Sequence[float]], radii_b: Sequence[float],
                 centre_A: Sequence[Sequence[Any]], centre_b: Sequence[Any]):
        s = len(radii_b)

        def corner(x: Any, r: float) -> Fraction:
            size = max(abs(x.lo), abs(x.hi)) if isinstance(x, Interval) else abs(Fraction(x))
            return Fraction(float_above(size + Fraction(r)))

        self.f = FloatContext(_points([[corner(centre_A[i][j], radii_A[i][j]) for j in range(s)] for i in range(s)]),
                              [Interval.point(corner(centre_b[i], radii_b[i])) for i in range(s)])
        # the seed of the direction: ∂A = (r_ij), ∂b = (r_i), as a context of its own
        self.seed = FloatContext(_points([[Fraction(r) for r in row] for row in radii_A]),
                                 [Interval.point(Fraction(r)) for r in radii_b])
        self.a_vars, self.b_vars = [], []
        self.EA = 1 if any(r > 0 for row in radii_A for r in row) else 0
        self.E = 1

    def matvec(self, x: Any) -> Any:
        """``∂(Ax) = A ∂x + (∂A) x`` along the one direction."""
        value = self.f.matvec(x[0])
        if not self.EA:
            return value, self._zeros(value[0].shape, 0)
        gm, gr = x[1]
        grad = _add(self.f.matvec((gm[..., 0], gr[..., 0])), self.seed.matvec(x[0]))
        return value, (grad[0][..., None], grad[1][..., None])

    def dot(self, x: Any) -> Any:
        """``∂(bᵀx) = bᵀ∂x + (∂b)ᵀx`` along the one direction."""
        value = self.f.dot(x[0])
        grad = self.seed.dot(x[0])
        if self.EA:
            gm, gr = x[1]
            grad = _add(self.f.dot((gm[..., 0], gr[..., 0])), grad)
        return value, (grad[0][..., None], grad[1][..., None])

    def add_terms(self, acc: Any, w_terms: Any, terms: Any, n: int, i0: int, i1: int) -> None:
        """The terms with ``|c|`` (the majorant's coefficients)."""
        cond, idx = terms.block(i0, i1)
        self._add_block(acc, w_terms, cond, np.abs(_float_coefficients(terms, n)[idx]))
