"""Everything the tableau itself says, computed once per check: the irreducible form, the
stability function, symplecticity, symmetry, and the certificates of every order.

This is what :func:`rkcheck.energy.check.check` calls (one call) and the
reports read.  The scalars are exact whenever the tableau is (rational, or algebraic
through the tableau's ``exact_values()``), otherwise the enclosures the check already
made (:mod:`rkcheck.properties.scalars`).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from rkcheck.properties import scalars as sc
from rkcheck.properties.avf import AvfVerdict, avf_of_reduction
from rkcheck.properties.linear import LinearCertificate
from rkcheck.properties.lineintegral import (
    Certificate,
    LineIntegralCertificate,
    certificate_of_reduction,
)
from rkcheck.properties.quadratic import prefer, quadratic_certificate
from rkcheck.properties.reduction import Reduction, reduce_tableau
from rkcheck.properties.stability import StabilityFunction, stability_function
from rkcheck.properties.symplectic import PropertyVerdict, symmetry, symplecticity


@dataclass(frozen=True)
class TableauProperties:
    """The order-free properties of a tableau: its reduction, R(z), symplecticity and symmetry."""

    exact: bool  # computed over exact scalars (holds/fails only)
    reduction: Reduction
    stability: StabilityFunction
    symplectic: PropertyVerdict
    symmetric: PropertyVerdict

    def certificates(self, degree: int) -> tuple[AvfVerdict, Certificate]:
        """The AVF verdict for ``degree`` and the best certificate of every order: the
        line-integral one (σ = 1 is AVF), and for degree 2 the stability function's
        ``R(z)R(−z) ≡ 1`` when it proves more (exactly where the other holds only to digits,
        or at all)."""
        avf = self.avf(degree)
        if degree == 1:  # no condition exists; every method preserves linear energy
            return avf, LinearCertificate()
        cert: Certificate = self.line_integral(degree)
        if degree == 2:
            cert = prefer(cert, quadratic_certificate(self.stability, degree))
        return avf, cert

    def avf(self, degree: int) -> AvfVerdict:
        return avf_of_reduction(self.reduction, degree)

    def line_integral(self, degree: int) -> LineIntegralCertificate:
        return certificate_of_reduction(self.reduction, degree)


def properties_of_values(A: sc.Matrix, b: sc.Vector, series: list[Fraction] | None = None) -> TableauProperties:
    """The properties of the tableau with these scalars: exact ones, or the check's
    enclosures (:func:`rkcheck.properties.scalars.tableau_values` chooses); ``series``:
    R(z)'s ``r_0 … r_2s`` over Q when the tableau's node form gives them."""
    red = reduce_tableau(A, b)
    exact = sc.is_exact(sc.sample(A, b))
    return TableauProperties(
        exact=exact,
        reduction=red,
        stability=stability_function(A, b, series if exact else None),
        symplectic=symplecticity(red),
        symmetric=symmetry(red),
    )
