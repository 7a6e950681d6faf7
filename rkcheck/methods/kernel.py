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
        nodes, or ``w_i p(x_i)`` (one column) with ``rows``, as FLINT rationals
        (:func:`_at_nodes`); ``only``: the rows ``i`` in this list alone (pairs only)."""
        t, s = self._index("tau"), self._index("sigma")
        terms = {(int(m[t]), int(m[s])): c for m, c in zip(p.monoms(), p.coeffs())}
        return _at_nodes(terms, x, w, rows, only)

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
        parts = self._in_literals[0]
        if parts is not None:
            return [sum(len(text) for text, _ in row) for row in _combined(parts, self.nodes[0], x, w, False, rows)]
        return [sum(len(_weighted_text(w[j], _value_at(self.nodes[0], x[i], x[j]))) for j in range(len(x))) for i in rows]

    @cached_property
    def _in_literals(self) -> tuple[LiteralParts | None, LiteralParts | None]:
        """A and B as sums of monomials in their decimal literals times rational
        polynomials in τ and σ (:func:`in_literals`), or None where they are not."""
        literals: dict[int, int] = {}
        return in_literals(self.nodes[0], literals), in_literals(self.nodes[1], literals)

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
        A_parts, B_parts = self._in_literals
        if A_parts is not None and B_parts is not None:
            # the kernel's values at the nodes formed once by FLINT for each monomial in
            # the decimals; an entry is then a short sum over them, which the enclosures
            # and derivatives along the literals read at a fraction of the kernel's cost
            A = tuple(tuple(Entry.from_node(text, node, constants, shares_literals=True) for text, node in row)
                      for row in _combined(A_parts, self.nodes[0], x, w, False))
            b = tuple(Entry.from_node(text, node, constants, shares_literals=True)
                      for (text, node), in _combined(B_parts, self.nodes[1], x, w, True))
            return A, b
        A = tuple(tuple(_entry_at(self.nodes[0], w[j], x[i], x[j], constants) for j in range(n)) for i in range(n))
        b = tuple(_entry_at(self.nodes[1], w[i], x[i], Fraction(0), constants) for i in range(n))
        return A, b


def _at_nodes(terms: dict[tuple[int, int], Any], x: list[Fraction], w: list[Fraction], rows: bool = False,
              only: list[int] | None = None) -> list[list[Any]]:
    """``w_j p(x_i, x_j)`` for ``p(τ, σ) = Σ c τ^i σ^j`` (``terms``: (i, j) → c) at
    every pair of nodes, or ``w_i p(x_i)`` (one column) with ``rows``, as FLINT
    rationals: ``V_τ C V_σᵀ``, ``C`` the coefficients and ``V`` the Vandermonde matrices
    of the nodes (node by node in Python, a surrogate of a few hundred nodes would take
    seconds)."""
    from flint import fmpq_mat

    C = fmpq_mat(1 + max((i for i, _ in terms), default=0), 1 + max((j for _, j in terms), default=0))
    for (i, j), c in terms.items():
        C[i, j] = c
    values = vandermonde(x if only is None else [x[i] for i in only], C.nrows()) * C
    if not rows:
        values = values * vandermonde(x, C.ncols()).transpose()
    weights = [to_fmpq(q) for q in w]
    return [[values[i, j] * weights[i if rows else j] for j in range(values.ncols())] for i in range(values.nrows())]


#: a kernel part: each monomial in the decimal literals (None: the part without them)
#: with the polynomial in τ and σ it multiplies ((i, j) → coefficient)
LiteralParts = list[tuple[ex.Expr | None, dict[tuple[int, int], Any]]]

#: terms of a kernel expanded in its decimals, τ and σ beyond which the entries are formed
#: from its expression instead (each term costs every entry a product)
MAX_LITERAL_TERMS = 64


class _NotPolynomial(Exception):
    """A part of the kernel that is no polynomial in its decimals, τ and σ."""


def in_literals(node: ex.Expr, literals: dict[int, int]) -> LiteralParts | None:
    """The kernel ``node`` as ``Σ_μ m_μ · p_μ(τ, σ)``: ``m_μ`` a monomial in its decimal
    literals (the kernel's own nodes, so that each is one number in every entry of the
    surrogate), ``p_μ`` rational; None when it names a constant, has a root or divides
    by more than a number, or expands to more than :data:`MAX_LITERAL_TERMS` terms.
    ``literals``: the decimals met so far (a node's id → its variable), shared by A and B."""
    from flint import fmpq_mpoly_ctx

    nodes = [n for n in xp.walk(node) if isinstance(n, ex.Num) and n.is_decimal]
    for n in nodes:
        literals.setdefault(id(n), len(literals))
    by_index = {literals[id(n)]: n for n in nodes}
    ctx = fmpq_mpoly_ctx.get(("tau", "sigma") + tuple(f"l{k}" for k in range(len(literals))), "lex")
    gens = ctx.gens()

    def combine(n: ex.Expr, vals: list[Any]) -> Any:
        if isinstance(n, ex.Num):
            return gens[2 + literals[id(n)]] if n.is_decimal else ctx.constant(to_fmpq(n.value))
        if isinstance(n, ex.Name) and n.name in VARIABLES:
            return gens[VARIABLES.index(n.name)]
        if isinstance(n, ex.Unary):
            return -vals[0]
        if isinstance(n, ex.Binary) and n.op in "+-*":
            out = vals[0] + vals[1] if n.op == "+" else vals[0] - vals[1] if n.op == "-" else vals[0] * vals[1]
        elif isinstance(n, ex.Binary) and vals[1].is_constant() and not vals[1].is_zero():
            out = vals[0] / vals[1]
        elif isinstance(n, ex.Power) and (k := _natural(vals[1])) is not None:
            out = ctx.constant(1)
            for _ in range(k):  # factor by factor: a long power is given up as it grows
                out = out * vals[0]
                if len(out) > MAX_LITERAL_TERMS:
                    raise _NotPolynomial
        else:
            raise _NotPolynomial
        if len(out) > MAX_LITERAL_TERMS:
            raise _NotPolynomial
        return out

    try:
        poly = xp.fold(node, combine)
    except _NotPolynomial:
        return None
    grouped: dict[tuple[int, ...], dict[tuple[int, int], Any]] = {}
    for monom, c in zip(poly.monoms(), poly.coeffs()):
        grouped.setdefault(tuple(int(e) for e in monom[2:]), {})[int(monom[0]), int(monom[1])] = c
    # a decimal the expansion cancels (times 0, to the power 0) is still written in the
    # kernel, a number of its box like any other (definitions §5): 0 times it
    kept = {k for powers in grouped for k, e in enumerate(powers) if e}
    for k in sorted(set(by_index) - kept):
        grouped[tuple(int(i == k) for i in range(len(literals)))] = {}
    return [(_monomial(powers, by_index), terms) for powers, terms in grouped.items()]


def _natural(p: Any) -> int | None:
    """The exponent the constant polynomial ``p`` is (0 … MAX_EXPONENT), else None."""
    if not p.is_constant():
        return None
    c = to_fraction(p.coeffs()[0]) if not p.is_zero() else Fraction(0)
    return int(c) if c.denominator == 1 and 0 <= c <= ex.MAX_EXPONENT else None


def _monomial(powers: tuple[int, ...], nodes: dict[int, ex.Num]) -> ex.Expr | None:
    """The product of the literals to their ``powers`` (None: no literal)."""
    out: ex.Expr | None = None
    for k, e in enumerate(powers):
        if e:
            factor: ex.Expr = nodes[k] if e == 1 else ex.Power(nodes[k], ex.Num(Fraction(e), str(e), None, 0), 0)
            out = factor if out is None else ex.Binary("*", out, factor, 0)
    return out


def _combined(parts: LiteralParts, kernel: ex.Expr, x: list[Fraction], w: list[Fraction], rows: bool,
              only: list[int] | None = None) -> list[list[tuple[str, ex.Expr]]]:
    """The text and expression of every entry ``w_j A(x_i, x_j)`` (``rows``: of b,
    ``w_i B(x_i)``, one column; ``kernel``: A or B as written): the text is the
    kernel's at the nodes, the expression ``Σ_μ v_μ·m_μ`` with ``v_μ`` the rational
    ``w_j p_μ(x_i, x_j)`` one number — a product per monomial in every pass over the
    entries, where the kernel's own expression costs its every operation on the nodes'
    long fractions; ``only``: these rows alone (pairs only)."""
    tables = [(m, _at_nodes(terms, x, w, rows, only)) for m, terms in parts]
    template = _text_template(kernel)
    out = []
    for k, i in enumerate(range(len(x)) if only is None else only):
        row = []
        for j in range(1 if rows else len(x)):
            node: ex.Expr | None = None
            for m, values in tables:
                # every monomial, 0 times it too: the entry holds each decimal of the
                # kernel, as the kernel's expression at the nodes does (its digits, its
                # literal in the box)
                q = to_fraction(values[k][j])
                # no text of its own: hundreds of digits per entry, written only if shown
                term: ex.Expr = ex.Num(q, "", None, 0) if m is None else ex.Binary("*", ex.Num(q, "", None, 0), m, 0)
                node = term if node is None else ex.Binary("+", node, term, 0)
            weight = w[i] if rows else w[j]
            text = f"{weight.numerator}/{weight.denominator}*({template(x[i], Fraction(0) if rows else x[j])})"
            row.append((text, node or ex.Num(Fraction(0), "0", None, 0)))
        out.append(row)
    return out


def _text_template(kernel: ex.Expr) -> Any:
    """``(τ, σ) ↦`` the kernel's text with the two nodes in place of tau and sigma (what
    the kernel's expression at them reads as; written once, filled in per entry)."""
    import re

    pieces = re.split(r"\b(tau|sigma)\b", xp.to_text(kernel))

    def fill(tau: Fraction, sigma: Fraction) -> str:
        at = {"tau": f"({tau.numerator}/{tau.denominator})", "sigma": f"({sigma.numerator}/{sigma.denominator})"}
        return "".join(at[p] if k % 2 else p for k, p in enumerate(pieces))

    return fill


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
