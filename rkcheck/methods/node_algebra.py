"""Exact facts about a family's tableau in node form without the field of its nodes.

A tableau in node form (:mod:`rkcheck.methods.node_form`) has ``A_ij = F(c_i, c_j)`` and
``b_j = W(c_j)`` over the roots ``c`` of a square-free P.  A property that must hold at
every pair of stages — symplecticity, ``A = (A·1)bᵀ``, the line-integral identity, the
adjoint's match — is then one polynomial identity ``G ≡ 0`` in the algebra
``Q[x, y]/(P(x), P(y))``: G vanishes at every pair of roots exactly when its remainder
modulo P in each variable is zero.  Sums over the stages are traces (``Σ_j G(x, c_j)``
is ``Tr_y G``), rational where nothing else is left.

Where a report names one entry (the largest entry of a nonzero M, the first nonzero entry
of ``A − (A·1)bᵀ``), that entry ``v = G(c_i, c_j)`` is still exact: the characteristic
polynomial χ of multiplication by G on the algebra is ``∏_(k,l) (t − G(c_k, c_l))``, so v
is a root of exactly one of χ's irreducible factors over Q — its minimal polynomial —,
which certified balls around the stage nodes pick out.  v is zero, rational, or the
k-th real root of that polynomial, written ``root(f, k)`` in the entry grammar.

The field of the nodes (degree 48 for the six Gauss-6 nodes, over the limit for Radau IIA
with six) is never built here.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cached_property, partial
from typing import TYPE_CHECKING, Any, Callable, Sequence

from rkcheck.methods.node_form import (
    NodeForm,
    pair_charpoly,
    pair_polynomial,
    pair_ring,
    reduce_pair,
)
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.polynomials import (
    evaluate,
    from_flint,
    to_arb,
    to_flint,
    to_fmpq,
    to_fraction,
)

if TYPE_CHECKING:
    from rkcheck.methods.family_spec import FamilySpec

#: the precision a ball starts at, and the one past which an exact fact is not sought
#: further (never reached: distinct algebraic numbers separate at a few hundred bits)
START_BITS, MAX_BITS = 128, 1 << 15


class NodeAlgebra:
    """``Q[x, y]/(P(x), P(y))`` for a :class:`NodeForm`, with F, ``W(x)`` and ``W(y)`` in
    it; ``nodes(bits)``: certified enclosures of the stage nodes, in stage order."""

    def __init__(self, form: NodeForm, nodes: Callable[[int], Sequence[Interval]]):
        self.form, self.nodes, self.n = form, nodes, form.stages

    # ----------------------------------------------------------- the algebra

    @cached_property
    def _ring(self) -> tuple[Any, Any]:
        _, x, y = pair_ring()
        return x, y

    def __getstate__(self) -> dict[str, Any]:
        return {"form": self.form, "nodes": self.nodes, "n": self.n}  # FLINT objects are rebuilt

    @property
    def x(self) -> Any:
        return self._ring[0]

    @property
    def y(self) -> Any:
        return self._ring[1]

    def constant(self, q: Fraction | int) -> Any:
        return pair_ring()[0].constant(to_fmpq(Fraction(q)))

    def poly(self, coeffs: Sequence[Fraction | int], var: Any) -> Any:
        """The univariate polynomial ``coeffs`` (ascending) in ``var`` (x or y)."""
        power = (lambda k: (k, 0)) if var == self.x else (lambda k: (0, k))
        return pair_polynomial((power(k), Fraction(c)) for k, c in enumerate(coeffs))

    def reduce(self, g: Any) -> Any:
        """g modulo P(x) and P(y): the remainder has degree below s in each variable."""
        return reduce_pair(self.form.P, g)

    def is_zero(self, g: Any) -> bool:
        """Does g vanish at every pair of nodes?"""
        return bool(self.reduce(g).is_zero())

    @cached_property
    def F(self) -> Any:
        return pair_polynomial(self.form.F)

    @cached_property
    def W_x(self) -> Any:
        return self.poly(self._W, self.x)

    @cached_property
    def W_y(self) -> Any:
        return self.poly(self._W, self.y)

    @property
    def _W(self) -> list[Fraction]:
        out = [Fraction(0)] * self.n
        for k, c in self.form.W:
            out[k] = c
        return out

    def swap(self, g: Any) -> Any:
        """``g(y, x)``."""
        return g.compose(self.y, self.x)

    def reflect(self, g: Any, about: Fraction) -> Any:
        """``g(about − x, about − y)``."""
        return g.compose(self.constant(about) - self.x, self.constant(about) - self.y)

    def trace_y(self, g: Any) -> Any:
        """``Σ_j g(x, c_j)`` as a polynomial in x."""
        out = self.constant(0)
        for (a, b), c in self.reduce(g).to_dict().items():
            out += self.x**a * (to_fmpq(self.form.power_traces[b]) * c)
        return out

    def trace(self, g: Any) -> Fraction:
        """``Σ_i g(c_i)`` of a polynomial in x alone."""
        return sum((to_fraction(c) * self.form.power_traces[a] for (a, _), c in self.reduce(g).to_dict().items()),
                   Fraction(0))

    def weight_sum(self) -> Fraction:
        return self.trace(self.W_x)

    def irreducible(self) -> bool:
        """``c = A·1`` (``Σ_j F(x, c_j) = x``) and every weight nonzero (W prime to P):
        with distinct nodes the tableau is then its own irreducible form."""
        W = to_flint(self._W)
        return self.is_zero(self.trace_y(self.F) - self.x) and W.gcd(to_flint(list(self.form.P))).degree() == 0

    def reflected_stages(self, about: Fraction) -> list[int]:
        """``image[i]``: the stage whose node is ``about − c_i`` (0-based), when every
        ``about − c_i`` is a node (P(about − x) = ±P(x)): the enclosures, refined until
        each meets one node's, tell which."""
        bits = 64
        while bits <= MAX_BITS:
            nodes = self.nodes(bits)
            image = []
            for ci in nodes:
                mirror = Interval(about - ci.hi, about - ci.lo)
                meets = [k for k, ck in enumerate(nodes) if not (ck.hi < mirror.lo or ck.lo > mirror.hi)]
                if len(meets) != 1:
                    break
                image.append(meets[0])
            else:
                return image
            bits *= 2
        raise ArithmeticError(f"the nodes' enclosures do not separate at {MAX_BITS} bits")

    # ----------------------------------------------------------- one entry

    def function(self, g: Any) -> NodeFunction:
        """g as a function of two stages (kept while g is: a loop over the stages asks
        for the same g at every pair)."""
        kept = self._functions.get(id(g))
        if kept is None or kept[0] is not g:
            kept = self._functions[id(g)] = (g, NodeFunction(self, g))
        return kept[1]

    @cached_property
    def _functions(self) -> dict[int, tuple[Any, NodeFunction]]:
        return {}

    def value(self, g: Any, i: int, j: int = 0) -> NodeValue:
        """``g(c_i, c_j)`` (0-based stages) as an exact scalar."""
        return NodeValue(self.function(g), i, j)

    def powers(self, prec: int) -> list[list[Any]]:
        """``c_i^a`` (a < s) as balls from the nodes' enclosures at ``prec`` bits, kept."""
        from flint import arb, ctx

        from rkcheck.numbers.polynomials import interval_arb

        if prec not in self._kept_powers:
            with ctx.workprec(prec + 32):
                rows = []
                for node in self.nodes(prec):
                    ball = interval_arb(node)
                    row = [arb(1)]
                    for _ in range(1, self.n):
                        row.append(row[-1] * ball)
                    rows.append(row)
            self._kept_powers[prec] = rows
        return self._kept_powers[prec]

    @cached_property
    def _kept_powers(self) -> dict[int, list[list[Any]]]:
        return {}

    def charpoly(self, g: Any) -> Any:
        """χ of multiplication by g on the algebra: ``∏_(k,l) (t − g(c_k, c_l))``."""
        return pair_charpoly(self.form.P, g)


def node_algebra(spec: FamilySpec, form: NodeForm | None) -> NodeAlgebra | None:
    """The family's algebra when its properties can be decided in it — a node form that
    is consistent with nonzero weights (:meth:`NodeAlgebra.irreducible`) — and its nodes
    need more than one square root: a field ``Q(√d)`` is built at once and writes its
    values exactly in d, which a report keeps."""
    if form is None or _square_root_field(form.P):
        return None
    algebra = NodeAlgebra(form, partial(_rule_nodes, spec))
    return algebra if algebra.irreducible() else None


def _rule_nodes(spec: FamilySpec, bits: int) -> list[Interval]:
    return [node.enclosure(bits) for node in spec.base_rule().nodes]


def _square_root_field(P: Sequence[Fraction]) -> bool:
    """Are P's roots rational or in one field ``Q(√d)``?  (Factors of degree ≤ 2 whose
    discriminants differ by rational squares.)"""
    import math

    def square(q: Fraction) -> bool:
        return q >= 0 and math.isqrt(q.numerator) ** 2 == q.numerator and math.isqrt(q.denominator) ** 2 == q.denominator

    _, factors = to_flint(list(P)).factor()
    first = None
    for f, _ in factors:
        if f.degree() > 2:
            return False
        if f.degree() == 2:
            a, b, c = (to_fraction(f[k]) for k in (2, 1, 0))
            d = b * b - 4 * a * c
            first = d if first is None else first
            if not square(d * first):
                return False
    return True


def _monic(f: list[Fraction]) -> list[Fraction]:
    return [c / f[-1] for c in f]


class NodeFunction:
    """A polynomial g of the algebra as a function of two stages: its values
    ``g(c_i, c_j)`` in balls, and what χ says of all of them at once."""

    def __init__(self, algebra: NodeAlgebra, g: Any):
        self.algebra = algebra
        self.terms = [(a, b, to_fraction(c)) for (a, b), c in algebra.reduce(g).to_dict().items()]
        self._coefficients: dict[int, list[Any]] = {}

    def __getstate__(self) -> dict[str, Any]:
        return {k: v for k, v in self.__dict__.items() if k not in ("_coefficients", "polynomial")}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state, _coefficients={})

    @cached_property
    def polynomial(self) -> Any:
        return pair_polynomial(((a, b), c) for a, b, c in self.terms)

    @cached_property
    def factors(self) -> list[list[Fraction]]:
        """The distinct irreducible factors of χ over Q, monic (ascending)."""
        _, found = self.algebra.charpoly(self.polynomial).factor()
        return [_monic(from_flint(f)) for f, _ in found]

    @cached_property
    def some_rational(self) -> bool:
        """Is some value rational (χ has a linear factor)?"""
        return any(len(f) == 2 for f in self.factors)

    @cached_property
    def some_zero(self) -> bool:
        """Is some value zero (t divides χ)?"""
        return [Fraction(0), Fraction(1)] in self.factors

    def ball(self, i: int, j: int, prec: int) -> Any:
        """An Arb ball around ``g(c_i, c_j)`` from the nodes' enclosures at ``prec`` bits."""
        from flint import arb, ctx

        powers = self.algebra.powers(prec)
        with ctx.workprec(prec + 32):
            if prec not in self._coefficients:
                self._coefficients[prec] = [to_arb(c) for _, _, c in self.terms]
            total = arb(0)
            for (a, b, _), c in zip(self.terms, self._coefficients[prec]):
                total += c * powers[i][a] * powers[j][b]
            return total


class NodeValue:
    """``g(c_i, c_j)`` exactly: a scalar of :mod:`rkcheck.properties.scalars` (zero test,
    rational value, enclosure, exact text) known by its minimal polynomial over Q."""

    def __init__(self, function: NodeFunction, i: int, j: int):
        self.function, self.i, self.j = function, i, j
        self._enclosures: dict[int, Interval] = {}

    def __getstate__(self) -> dict[str, Any]:
        self.minimal  # decided before it travels (Fractions; FLINT objects are rebuilt)
        return dict(self.__dict__)

    @cached_property
    def minimal(self) -> list[Fraction]:
        """The minimal polynomial of v over Q (monic, ascending): the one factor of χ that
        vanishes in v's ball."""
        from flint import ctx

        prec = START_BITS
        while prec <= MAX_BITS:
            v = self.function.ball(self.i, self.j, prec)
            with ctx.workprec(prec + 32):
                hits = [f for f in self.function.factors if evaluate([to_arb(c) for c in f], v, to_arb(0)).contains(0)]
            if len(hits) == 1:
                return hits[0]
            prec *= 2
        raise ArithmeticError(f"no factor of χ isolates the value at {MAX_BITS} bits")

    def is_zero(self) -> bool:
        return self.function.some_zero and self.minimal == [Fraction(0), Fraction(1)]

    def rational(self) -> Fraction | None:
        if not self.function.some_rational or len(self.minimal) != 2:
            return None
        return -self.minimal[0]

    def enclosure(self, bits: int) -> Interval:
        """An interval of width at most ``2^-bits`` around v (the point, when rational)."""
        from rkcheck.numbers.polynomials import arb_interval

        q = self.rational()
        if q is not None:
            return Interval.point(q)
        if bits not in self._enclosures:
            prec = bits + 32
            while True:
                ball = arb_interval(self.function.ball(self.i, self.j, prec))
                if ball.hi - ball.lo <= Fraction(1, 1 << bits):
                    break
                prec *= 2
            self._enclosures[bits] = ball
        return self._enclosures[bits]

    def text(self) -> str:
        """``root(f, k)``: the k-th smallest real root of the minimal polynomial f (the
        rational itself when f is linear)."""
        from rkcheck.numbers.polynomials import poly_text, real_root_intervals

        q = self.rational()
        if q is not None:
            return str(q)
        f, bits = self.minimal, 64
        while True:
            near = self.enclosure(bits)
            meets = [k for k, r in enumerate(real_root_intervals(f, bits), start=1)
                     if not (r.hi < near.lo or r.lo > near.hi)]
            if len(meets) == 1:
                return f"root({poly_text(f)}, {meets[0]})"
            bits *= 2
