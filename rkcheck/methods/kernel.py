"""A continuous-stage method's kernel as written and as exact polynomials: ``A(τ, σ)`` and
``B(τ)`` parsed (their nodes keep each decimal literal, definitions §5), over a
:class:`~rkcheck.numbers.parametric.ParameterRing` in ``tau`` and ``sigma``, with their
degrees, the identities :mod:`rkcheck.energy.continuous` tests, and the entries of the
surrogate tableau (:meth:`~rkcheck.methods.continuous.ContinuousMethod.surrogate`).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property, lru_cache
from typing import Any

from rkcheck.errors import UserError
from rkcheck.methods.quadrature import vandermonde
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Constants, Entry
from rkcheck.numbers.polynomials import to_fmpq, to_fraction

#: the two variables of a kernel
VARIABLES = ("tau", "sigma")

@dataclass(frozen=True)
class Kernel:
    """``A`` and ``B`` parsed (``nodes``, ``entries`` as written) and as exact
    polynomials (``A_poly``, ``B_poly`` over ``ring``: variables θ?, tau, sigma)."""

    nodes: tuple[ex.Expr, ex.Expr]
    entries: tuple[Entry, Entry]
    ring: Any
    A_poly: Any
    B_poly: Any
    parsed: Any

    @staticmethod
    def of(A: str, b: str, constants: Constants, matrix_place: str | None = None) -> "Kernel":
        from rkcheck.numbers.parametric import ParametricEntries

        nodes = []
        places = [matrix_place or "continuous.A", matrix_place or "continuous.b"]
        for place, text in zip(places, (A, b)):
            try:
                # from M, a text of up to 40 × 40 terms, each entry of M within the limit
                node = ex.parse(text, None if matrix_place else ex.MAX_ENTRY_LENGTH)
                for used in xp.names(node):
                    if used.name not in VARIABLES and used.name not in constants.definitions:
                        raise UserError(f"unknown name {used.name!r} at column {used.column}: a kernel is a "
                                        "polynomial in tau and sigma (and the [constants])")
            except UserError as err:
                raise err.located(place) from None
            nodes.append(node)
        written = list(nodes)
        nodes[1] = b_in_tau(nodes[1], matrix_place or "continuous.b")
        if matrix_place:
            nodes[1] = _same_literals(nodes[0], nodes[1])
        try:
            parsed = ParametricEntries(nodes, [matrix_place or "continuous.A", matrix_place or "continuous.b"],
                                       VARIABLES, constants.definitions)
        except UserError as err:
            raise UserError(err.message.replace("parameter", "variable (tau, sigma)").replace(
                "entries must be polynomials in the variable (tau, sigma)s", "a kernel is a polynomial in tau and sigma"),
                err.place) from None
        A_poly, B_poly = parsed.values
        # each as a number (its decimals, its roots): tau and sigma read as the constant 0,
        # which divides nothing now that both are known to be polynomials
        probe = Constants(dict(constants.definitions) | {v: ex.parse("0") for v in VARIABLES})
        entries = []
        for place, text, node in zip(places, (A, b), written):
            try:
                entries.append(Entry.from_node(text, node, probe))
            except UserError as err:
                raise err.located(place) from None
        return Kernel((nodes[0], nodes[1]), (entries[0], entries[1]), parsed.ring, A_poly, B_poly, parsed)

    # ---------------------------------------------------------------- structure

    def _index(self, name: str) -> int:
        return int(self.ring.variables.index(name))

    def degree(self, p: Any, name: str) -> int:
        if p.is_zero():
            return 0
        return int(max(m[self._index(name)] for m in p.monoms()))

    @property
    def deg_tau(self) -> int:
        return self.degree(self.A_poly, "tau")

    @property
    def deg_sigma(self) -> int:
        return self.degree(self.A_poly, "sigma")

    @property
    def deg_b(self) -> int:
        return self.degree(self.B_poly, "tau")

    @cached_property
    def written_degrees(self) -> tuple[int, int, int]:
        """The degrees of A in τ and in σ and of B in τ as the kernel is written, every
        literal counted nonzero: bounds of the degrees of every kernel of its box, where
        ``deg_tau`` … are those at face value."""
        def combine(n: ex.Expr, vals: list[tuple[int, int]]) -> tuple[int, int]:
            if isinstance(n, ex.Name) and n.name in VARIABLES:
                return (1, 0) if n.name == "tau" else (0, 1)
            if isinstance(n, ex.Power):
                k = int(xp.evaluate_exact(n.exponent, {}) or 0)  # checked when the kernel was read
                return vals[0][0] * k, vals[0][1] * k
            if isinstance(n, ex.Binary) and n.op == "*":
                return vals[0][0] + vals[1][0], vals[0][1] + vals[1][1]
            if isinstance(n, ex.Binary) and n.op == "/":
                return vals[0]  # a number divides
            return (max((v[0] for v in vals), default=0), max((v[1] for v in vals), default=0))

        A = xp.fold(self.nodes[0], combine, xp.polynomial_operands)
        B = xp.fold(self.nodes[1], combine, xp.polynomial_operands)
        return A[0], A[1], max(B)

    def gens(self) -> tuple[Any, Any]:
        return self.ring.parameter("tau"), self.ring.parameter("sigma")

    def substitute(self, p: Any, tau: Any, sigma: Any) -> Any:
        """``p`` with tau and sigma replaced by polynomials of the ring."""
        args = [self.ring.theta] if self.ring.theta is not None else []
        return self.ring.reduce(p.compose(*args, tau, sigma, ctx=self.ring.ctx))

    def integrate(self, p: Any, name: str) -> Any:
        """``∫₀¹ p d(name)``."""
        k = self._index(name)
        out = self.ring.constant(0)
        for monom, c in zip(p.monoms(), p.coeffs()):
            e = list(monom)
            power = e[k]
            e[k] = 0
            term = self.ring.ctx.from_dict({tuple(e): c})
            out = out + term * self.ring.constant(Fraction(1, int(power) + 1))
        return out

    def is_zero(self, p: Any) -> bool:
        return bool(self.ring.is_zero(p))

    def number(self, p: Any) -> Any:
        """A constant polynomial as a Fraction or an element of the field."""
        ring = self.ring
        if ring.field is None:
            if p.is_zero():
                return Fraction(0)
            (c,) = p.coeffs()
            return Fraction(int(c.p), int(c.q))
        return self.parsed._field_element(p) if not p.is_zero() else ring.field([Fraction(0)] * ring.field.degree)

    # ---------------------------------------------------------------- surrogate

    def _at_nodes(self, p: Any, x: list[Fraction], w: list[Fraction], rows: bool = False,
                  only: list[int] | None = None) -> list[list[Any]]:
        """``w_j p(x_i, x_j)`` for the rational polynomial ``p(τ, σ)`` at every pair of
        nodes, or ``w_i p(x_i)`` (one column) with ``rows``, as FLINT rationals: ``V_τ C
        V_σᵀ``, ``C`` its coefficients and ``V`` the Vandermonde matrices of the nodes
        (node by node in Python, a surrogate of a few hundred nodes would take seconds);
        ``only``: the rows ``i`` in this list alone (pairs only)."""
        from flint import fmpq_mat

        t, s = self._index("tau"), self._index("sigma")
        monoms = [(int(m[t]), int(m[s])) for m in p.monoms()]
        C = fmpq_mat(1 + max((i for i, _ in monoms), default=0), 1 + max((j for _, j in monoms), default=0))
        for (i, j), c in zip(monoms, p.coeffs()):
            C[i, j] = c
        values = vandermonde(x if only is None else [x[i] for i in only], C.nrows()) * C
        if not rows:
            values = values * vandermonde(x, C.ncols()).transpose()
        weights = [to_fmpq(q) for q in w]
        return [[values[i, j] * weights[i if rows else j] for j in range(values.ncols())] for i in range(values.nrows())]

    def _plain(self, constants: Constants) -> bool:
        """Whether the surrogate's entries are exact fractions (a rational kernel without
        decimals), not the kernel's own expression at the nodes."""
        return self.ring.field is None and not any(constants.uses_decimal(node) for node in self.nodes)

    def row_characters(self, x: list[Fraction], w: list[Fraction], rows: list[int], constants: Constants) -> list[int]:
        """The characters the texts of :meth:`surrogate_entries` take in each row of A in
        ``rows``, written as there but not read back (a few rows of a surrogate cost what
        a check may weigh before it builds all n² entries)."""
        if self._plain(constants):
            return [sum(len(str(v)) for v in row) for row in self._at_nodes(self.A_poly, x, w, only=rows)]
        return [sum(len(_weighted_text(w[j], _value_at(self.nodes[0], x[i], x[j]))) for j in range(len(x))) for i in rows]

    def surrogate_entries(self, x: list[Fraction], w: list[Fraction],
                          constants: Constants) -> tuple[tuple[tuple[Entry, ...], ...], tuple[Entry, ...]]:
        """``a_ij = w_j A(x_i, x_j)``, ``b_i = w_i B(x_i)`` as tableau entries: exact
        fractions for a rational kernel without decimals, otherwise the kernel's own
        expression at the nodes (its decimals and roots then read as in any entry)."""
        n = len(x)
        if self._plain(constants):
            A = tuple(tuple(_rational_entry(v) for v in row) for row in self._at_nodes(self.A_poly, x, w))
            b = tuple(_rational_entry(row[0]) for row in self._at_nodes(self.B_poly, x, w, rows=True))
            return A, b
        A = tuple(tuple(_entry_at(self.nodes[0], w[j], x[i], x[j], constants) for j in range(n)) for i in range(n))
        b = tuple(_entry_at(self.nodes[1], w[i], x[i], Fraction(0), constants) for i in range(n))
        return A, b



def _rational_entry(v: Any) -> Entry:
    """The entry of the FLINT rational ``v`` built directly (what ``Entry.of`` parses,
    without the parser: a surrogate has thousands of entries, whose numerators run to
    hundreds of digits — FLINT writes them out, once each)."""
    q = to_fraction(v)
    digits = str(abs(v.p))
    num: ex.Expr = ex.Num(Fraction(abs(q.numerator)), digits, None, 0)
    text = digits
    if q.numerator < 0:
        num, text = ex.Unary("-", num), "-" + digits
    if q.denominator == 1:
        return Entry(text, num, _NO_CONSTANTS, q, False, None)
    under = str(v.q)
    node = ex.Binary("/", num, ex.Num(Fraction(q.denominator), under, None, 0), len(text) + 1)
    return Entry(f"{text}/{under}", node, _NO_CONSTANTS, q, False, None)


_NO_CONSTANTS = Constants()


@lru_cache(maxsize=4096)
def _literal(q: Fraction) -> ex.Expr:
    # the nodes are frozen: one per value, shared by the surrogate's n² entries
    return ex.parse(f"({q.numerator}/{q.denominator})")


def b_in_tau(node: ex.Expr, place: str) -> ex.Expr:
    """B as a polynomial in tau: written in sigma (as B(σ) = A(1, σ)) it is renamed; in
    both variables it is refused at ``place``."""
    used = {n.name for n in xp.names(node)}
    if {"tau", "sigma"} <= used:
        raise UserError("B is a polynomial in one variable (tau); it uses both tau and sigma", place)
    return xp.substituted(node, {"sigma": ex.Name("tau", 1)}) if "sigma" in used else node


def _same_literals(A_node: ex.Expr, B_node: ex.Expr) -> ex.Expr:
    """B of a Miyatake–Butcher matrix with the literals of A's nodes: both are written
    term by term from the same entries M_ij (:meth:`ContinuousMethod.from_matrix`), so
    their decimal literals pair up in order, and each M_ij is then one literal — one
    number — in A and in B alike (:mod:`rkcheck.numbers.literals`)."""
    in_A = [n for n in xp.literals(A_node) if n.is_decimal]
    in_B = [n for n in xp.literals(B_node) if n.is_decimal]
    if len(in_A) != len(in_B) or any(x.text != y.text for x, y in zip(in_A, in_B)):
        return B_node
    same = {id(y): x for x, y in zip(in_A, in_B)}
    return xp.rebuilt(B_node, lambda n: same.get(id(n), n))


def _value_at(node: ex.Expr, tau: Fraction, sigma: Fraction) -> ex.Expr:
    return xp.substituted(node, {"tau": _literal(tau), "sigma": _literal(sigma)})


def _weighted_text(weight: Fraction, value: ex.Expr) -> str:
    return f"{weight.numerator}/{weight.denominator}*({xp.to_text(value)})"


def _entry_at(node: ex.Expr, weight: Fraction, tau: Fraction, sigma: Fraction, constants: Constants) -> Entry:
    value = _value_at(node, tau, sigma)
    text = _weighted_text(weight, value)
    # built from the kernel's own nodes, not parsed from the text: a decimal of the
    # kernel is then one literal in every entry (numbers.literals), as it is one number
    return Entry.from_node(text, ex.Binary("*", _literal(weight), value, 1), constants, shares_literals=True)
