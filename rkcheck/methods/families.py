"""Method families computed at any precision (the ``[family]`` table and ``rkcheck new``).

==================  ==============================================================  ============
family              coefficients                                                    parameters
==================  ==============================================================  ============
``avf``             ``a_ij = c_i b_j`` over a rule (definitions §4)                         rule, s
``gauss``           collocation at Gauss nodes: ``a_ij = ∫₀^{c_i} ℓ_j``              s
``lobatto-iiia``    collocation at Lobatto nodes                                     s >= 2
``lobatto-iiib``    ``a_ij = (b_j/b_i) ∫_{c_j}^1 ℓ_i`` (condition D(s)), Lobatto     s >= 2
``radau-iia``       collocation at Radau II nodes (c_s = 1)                          s
``radau-ia``        ``a_ij = (b_j/b_i) ∫_{c_j}^1 ℓ_i`` at Radau I nodes (c_1 = 0)    s
``hbvm``            HBVM(k, s): k Gauss nodes, ``A = I_s P_sᵀ Ω``                    k >= s >= 1
``kernel``          the seed's ``c bᵀ + β N``, ``N = ((ζ−1)1 − 2ζc) bᵀ(I−2C)``, s = 2  zeta, beta
==================  ==============================================================  ============

HBVM (Brugnano, Iavernaro, Trigiante): with orthonormal shifted Legendre polynomials
``P̂_j = √(2j+1) P_j``, ``(I_s)_{ij} = ∫₀^{c_i} P̂_{j−1}``, ``(P_s)_{ij} = P̂_{j−1}(c_i)``,
``Ω = diag(b)``; the square roots cancel: ``a_il = b_l Σ_{j<s} (2j+1) G_j(c_i) P_j(c_l)``
with ``G_j = ∫₀^x P_j``.  HBVM(k, s) conserves polynomial H of degree ≤ 2k/s.

Every coefficient is a certified interval at the requested number of bits (computed from
the certified nodes of :mod:`rkcheck.methods.quadrature`), and an exact rational when the rule is
rational.  :func:`expression_texts` gives the same coefficients as exact entry
expressions over closed-form node constants, for ``rkcheck new``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from functools import partial
from typing import Any

from rkcheck.methods.family_spec import FamilySpec, parse_spec
from rkcheck.methods.quadrature import (
    lagrange_integral,
    line_integral_matrix,
)
from rkcheck.methods.tableau import ExactValues, MethodInfo, Tableau
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode


def coefficients(spec: FamilySpec, bits: int) -> tuple[list[list[Interval]], list[Interval]]:
    """(A, b) of the family at ``bits`` bits (exact points for rational rules)."""
    r = spec.base_rule()
    c, b = r.enclosures(bits)
    n = len(c)
    zero, one = Interval.point(0), Interval.point(1)
    if spec.name == "avf":
        A = [[c[i] * b[j] for j in range(n)] for i in range(n)]
    elif spec.name in ("gauss", "lobatto-iiia", "radau-iia"):
        A = [[lagrange_integral(c, j, zero, c[i], bits) for j in range(n)] for i in range(n)]
    elif spec.name in ("lobatto-iiib", "radau-ia"):
        A = [
            [(b[j] / b[i] * lagrange_integral(c, i, c[j], one, bits)).round_out(bits + 32) for j in range(n)]
            for i in range(n)
        ]
    elif spec.name == "hbvm":
        A = [[x.round_out(bits + 32) for x in row] for row in line_integral_matrix(c, b, spec.s)]
    else:
        assert spec.zeta is not None and spec.beta is not None  # the kernel family is given both (parse_spec)
        zeta, beta = Interval.point(spec.zeta), Interval.point(spec.beta)
        A = [
            [
                c[i] * b[j] + beta * ((zeta - one) - Interval.point(2) * zeta * c[i]) * b[j] * (one - Interval.point(2) * c[j])
                for j in range(n)
            ]
            for i in range(n)
        ]
    return A, b


class ComputedEntry:
    """A coefficient computed by a family at whatever precision is asked for.

    It answers the same questions as :class:`~rkcheck.numbers.entries.Entry`; its value
    comes from the family's shared coefficients (one computation per precision, shared by
    all entries of the tableau).  ``where`` is ``("A", i, j)`` or ``("b", j)``, 0-based.
    Plain data throughout, so that family tableaux can be pickled (scan workers send
    their results back to the parent).
    """

    rounded_digits = None
    bare_number = False
    computed = True
    is_rounded = False

    def __init__(self, shared: "_Shared", where: tuple[Any, ...], exact: Fraction | None, label: str):
        self._shared = shared
        self._where = where
        self.exact = exact
        self.uses_sqrt = exact is None
        self.label = label

    def _value(self, bits: int) -> Interval:
        A, b = self._shared.get(bits)
        value: Interval = A[self._where[1]][self._where[2]] if self._where[0] == "A" else b[self._where[1]]
        return value

    @property
    def text(self) -> str:
        if self.exact is not None:
            return str(self.exact)
        from rkcheck.numbers.formatting import decimal_string

        return "≈" + decimal_string(self._value(80).mid, 15)

    @property
    def is_rational(self) -> bool:
        return self.exact is not None

    def is_box(self, decimals: DecimalsMode) -> bool:
        return False  # computed coefficients are numbers (enclosed), never a box of inputs

    def enclosure(self, bits: int, decimals: DecimalsMode = DecimalsMode.EXACT) -> Interval:
        if self.exact is not None:
            return Interval.point(self.exact)
        return self._value(bits)

    def is_zero(self) -> bool:
        return self.exact == 0

    def family_values(self) -> tuple[ExactValues | None, str | None]:
        """The family's whole tableau exactly, when its nodes have closed forms."""
        return self._shared.exact_values()


@dataclass
class _Shared:
    spec: FamilySpec
    cache: dict[int, tuple[list[list[Interval]], list[Interval]]] = field(default_factory=dict)
    exact: tuple[Any, str | None] | None = None

    def get(self, bits: int) -> tuple[list[list[Interval]], list[Interval]]:
        if bits not in self.cache:
            self.cache[bits] = coefficients(self.spec, bits)
        return self.cache[bits]

    def exact_values(self) -> tuple[Any, str | None]:
        """``(ExactValues or None, reason)`` for the family's tableau (computed once)."""
        if self.exact is None:
            from rkcheck.methods.node_algebra import node_algebra
            from rkcheck.methods.node_form import node_form
            from rkcheck.numbers.algebraic import NotAlgebraic

            form = node_form(self.spec)
            algebra = node_algebra(self.spec, form)
            if algebra is not None:  # checked over Q: the field only if something reads an entry
                self.exact = (ExactValues(None, None, None, None, form, algebra,
                                          load=partial(_field_entries, self.spec)), None)
                return self.exact
            try:
                field, A, b = _field_entries(self.spec)
            except NotAlgebraic as err:
                self.exact = (None, str(err))
            else:
                self.exact = (ExactValues(field, A, b, None, form if field is not None else None), None)
        return self.exact

    def __getstate__(self) -> dict[str, Any]:
        # coefficients are recomputed where needed; the exact values travel (they are
        # the slow part, and plain data)
        return {"spec": self.spec, "cache": {}, "exact": self.exact}


def _field_entries(spec: FamilySpec) -> tuple[Any, list[list[Any]], list[Any]]:
    """The family's field and its A and b in it (:class:`ExactValues`' ``load``)."""
    from rkcheck.methods.closed_forms import family_exact_values
    from rkcheck.numbers.algebraic import NotAlgebraic

    found, reason = family_exact_values(spec)
    if found is None:
        raise NotAlgebraic(reason or "the nodes have no closed form")
    v = found.values
    n = math.isqrt(len(v) + 1) - 1
    return found.field, [v[i * n:(i + 1) * n] for i in range(n)], v[n * n:n * n + n]


def family_tableau(spec: FamilySpec, name: str | None = None, info: MethodInfo | None = None) -> Tableau:
    """The family as a :class:`Tableau` whose entries are computed at the check's
    precision; ``name`` defaults to the family's title."""
    shared = _Shared(spec)
    rule = spec.base_rule()
    n = rule.s
    # a rational rule's entries are exact points; the others are enclosed when read
    A0, b0 = shared.get(64) if rule.is_rational else ([[None] * n] * n, [None] * n)

    def entry(where: tuple[Any, ...], value: Interval | None, label: str) -> ComputedEntry:
        exact = value.lo if value is not None and value.is_point else None
        return ComputedEntry(shared, where, exact, label)

    A = tuple(tuple(entry(("A", i, j), A0[i][j], f"A[{i + 1}][{j + 1}]") for j in range(n)) for i in range(n))
    b = tuple(entry(("b", j), b0[j], f"b[{j + 1}]") for j in range(n))
    info = (info or MethodInfo()).replace(family=spec.params())
    return Tableau(A=A, b=b, c=None, name=name or spec.title(), info=info)


def build_family(table: dict[str, Any], name: str | None, info: MethodInfo) -> Tableau:
    """The loader's hook for ``[family]`` tables (``name``: the file's ``[method]``
    name, if it gave one)."""
    return family_tableau(parse_spec(table), name, info)
