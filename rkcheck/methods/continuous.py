"""Continuous-stage Runge–Kutta methods (definitions §6): a kernel ``A(τ, σ)`` and a
weight ``B(τ)``, polynomials with coefficients in Q or in the number field of their
constants (square roots, ``root``).

A :class:`ContinuousMethod` keeps the kernel as written (its text and parsed expression,
so that decimal literals keep their meaning under the decimals rule of definitions §5)
and as exact polynomials over a :class:`~rkcheck.numbers.parametric.ParameterRing` in
the variables ``tau`` and ``sigma``.

Every B-series quantity goes through an exact *surrogate tableau*
(:meth:`ContinuousMethod.surrogate`): with ``N`` distinct rational nodes ``x_i`` and the
interpolatory weights ``w_i`` (exact for polynomials of degree ``< N``), the tableau
``a_ij = w_j A(x_i, x_j)``, ``b_i = w_i B(x_i)`` has exactly the method's elementary
weights for every tree with at most ``n`` vertices when
``N − 1 ≥ max(q + (n − 2)p, d_B + (n − 1)p)`` (``p = deg_τ A``, ``q = deg_σ A``,
``d_B = deg B``).  Why: the stage function of a tree whose root has ``k`` children is a
product of ``k`` functions ``∫A(τ,σ)g(σ)dσ``, each of τ-degree ≤ p, so it has degree
≤ kp; every integral the weight of a tree with n vertices needs is
``∫A(x, σ)g(σ)dσ`` with g the stage function of a proper subtree (≤ n − 1 vertices,
root with ≤ n − 2 children: degree ≤ q + (n − 2)p) or ``∫B g_t`` (root with ≤ n − 1
children: ≤ d_B + (n − 1)p); a rule exact to that degree reproduces each of them, and by
induction the surrogate's stage values are the stage functions at the nodes.

What is not a B-series property (the stability function, symplecticity and symmetry
of the surrogate, its stage count) is never read from the surrogate:
:mod:`rkcheck.energy.continuous` judges the kernel itself.
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property, lru_cache
from typing import Any, Mapping, Sequence

from rkcheck.errors import TableauError, UserError
from rkcheck.methods.quadrature import positive_rule, rational_rule, vandermonde
from rkcheck.methods.tableau import MethodInfo, Tableau
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Constants, Entry
from rkcheck.numbers.polynomials import to_fmpq, to_fraction
from rkcheck.numbers.reading import DecimalsMode

#: the two variables of a kernel, and the Greek letters accepted for them
VARIABLES = ("tau", "sigma")
ALIASES = {"τ": "tau", "σ": "sigma"}
#: the surrogate tableau never has more nodes than this (a kernel of τ-degree 4 checked
#: to order 12 needs 49)
MAX_SURROGATE_NODES = 400


def _unalias(text: str) -> str:
    for greek, name in ALIASES.items():
        text = text.replace(greek, name)
    return text


def with_written_columns(err: UserError, written: dict[str, str]) -> UserError:
    """``err`` with its ``column N`` counted in the entry as written, where τ and σ are one
    character each (the parser saw ``tau`` and ``sigma``); ``written`` maps places
    (``continuous.A``) to the texts as written."""
    text = written.get(err.place or "")
    if text is None or not any(greek in text for greek in ALIASES):
        return err
    columns: list[int] = []  # the written column of each character the parser saw
    for column, ch in enumerate(text, start=1):
        columns += [column] * len(ALIASES.get(ch, ch))

    def written_column(m: re.Match[str]) -> str:
        k = int(m.group(1))
        return f"column {columns[k - 1] if 0 < k <= len(columns) else k}"

    copy = UserError.__new__(type(err))
    UserError.__init__(copy, re.sub(r"column (\d+)", written_column, err.message), err.place, err.source)
    return copy


#: the Miyatake–Butcher matrix has at most this many rows and columns
MAX_KERNEL_MATRIX = 40


def matrix_rows(M: Any, where: str = "continuous.M") -> list[list[str]]:
    """The entry texts of a Miyatake–Butcher matrix, checked: a non-empty list of rows of
    one length, at most :data:`MAX_KERNEL_MATRIX` of each, entries numbers or strings."""
    if hasattr(M, "tolist"):  # numpy arrays, sympy matrices
        M = M.tolist()
    if isinstance(M, (str, bytes)) or not isinstance(M, Sequence) or not M:
        raise UserError("expected a non-empty list of rows", where)
    if len(M) > MAX_KERNEL_MATRIX:
        raise UserError(f"{len(M)} rows exceed the limit MAX_KERNEL_MATRIX = {MAX_KERNEL_MATRIX}", where)
    width = None
    rows = []
    for i, row in enumerate(M, start=1):
        if isinstance(row, (str, bytes)) or not isinstance(row, Sequence) or not row:
            raise UserError("expected a non-empty row (a list)", f"M[{i}]")
        if len(row) > MAX_KERNEL_MATRIX:
            raise UserError(f"{len(row)} columns exceed the limit MAX_KERNEL_MATRIX = {MAX_KERNEL_MATRIX}", f"M[{i}]")
        width = len(row) if width is None else width
        if len(row) != width:
            raise UserError(f"row has {len(row)} entries, expected {width} (every row of M has the same length)",
                            f"M[{i}]")
        rows.append([_matrix_entry(x, f"M[{i}][{j}]") for j, x in enumerate(row, start=1)])
    return rows


def _matrix_entry(value: Any, place: str) -> str:
    """An entry's text: an int, a Fraction, a string, or a float as its shortest decimal
    (as ``Tableau.from_arrays`` reads floats, and a file its bare decimals)."""
    if isinstance(value, float):
        if not math.isfinite(value):
            raise UserError(f"{value} is not a finite number", place)
        return repr(value)
    if isinstance(value, bool) or not isinstance(value, (int, str, Fraction)):
        raise UserError(f"expected a number (int, Fraction, float) or a string, got {type(value).__name__}", place)
    return str(value)


@dataclass(frozen=True)
class ContinuousMethod:
    """A continuous-stage method: ``A(τ, σ)`` and ``B(τ)`` as written (``A``, ``b``:
    expressions in ``tau`` and ``sigma``), ``M`` the Miyatake–Butcher matrix when the
    file gave one, a name and the file's :class:`MethodInfo`."""

    A: str
    b: str = "1"
    name: str = "continuous-stage method"
    info: MethodInfo = field(default_factory=MethodInfo, compare=False, repr=False)
    M: tuple[tuple[str, ...], ...] | None = None

    structure = "continuous"
    is_continuous = True

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):  # a report writes it as text, a catalogue sorts by it
            raise TableauError(f"expected a string, got {type(self.name).__name__}", "name")
        try:
            self.kernel  # noqa: B018 - parse now: a bad kernel is refused at construction
        except UserError as err:
            raise err.as_tableau_error() from None

    # ----------------------------------------------------------------- construction

    @staticmethod
    def from_kernel(A: str | int | Fraction, b: str | int | Fraction = "1", *, name: str = "continuous-stage method",
                    constants: dict[str, str] | None = None) -> "ContinuousMethod":
        """A method from its kernel ``A(τ, σ)`` and weight ``B(τ)`` (``rkcheck.ContinuousMethod``):
        expressions in tau and sigma, or numbers (an int or a Fraction, as a file's ``b = 2``)."""
        texts = []
        for what, value in (("A", A), ("b", b)):
            if isinstance(value, (int, Fraction)) and not isinstance(value, bool):
                value = ex.fraction_text(value)  # at any length
            if not isinstance(value, str):
                raise TableauError(f"expected an expression in tau and sigma (a str) or a number (an int or a "
                                   f"Fraction), got {type(value).__name__}", what)
            texts.append(value)
        A, b = texts
        if constants is not None and not isinstance(constants, Mapping):
            raise TableauError(f"expected a mapping of names to values, got {type(constants).__name__}", "constants")
        defs = {}
        for key, text in (constants or {}).items():
            try:
                defs[key] = ex.parse(str(text))
            except UserError as err:
                raise err.located(f"constants.{key}") from None
        consts = Constants(defs)
        try:
            return ContinuousMethod(_unalias(A), _unalias(b), name, MethodInfo(source=name, constants=consts))
        except UserError as err:
            raise with_written_columns(err, {"continuous.A": A, "continuous.b": b}) from None

    @staticmethod
    def from_matrix(M: Sequence[Sequence[Any]], *, name: str = "continuous-stage method",
                    info: MethodInfo | None = None) -> "ContinuousMethod":
        """The Miyatake–Butcher method of the matrix ``M`` (indices from 1):
        ``A(τ,σ) = Σ M_ij τ^i/i σ^(j−1)``, ``B(σ) = A(1, σ)``."""
        info = info or MethodInfo(source=name)
        try:
            rows = matrix_rows(M)
        except UserError as err:
            raise err.as_tableau_error() from None
        values: dict[tuple[int, int], Fraction | None] = {}
        decimal = False
        for i, row in enumerate(rows, start=1):
            for j, text in enumerate(row, start=1):
                try:
                    node = ex.parse(text)
                    info.constants.check_names(node)
                    values[i, j] = xp.evaluate_exact(node, info.constants.exact_values())
                except UserError as err:
                    raise err.located(f"M[{i}][{j}]").as_tableau_error() from None
                decimal = decimal or info.constants.uses_decimal(node)
        # rational: the polynomials collected; a decimal stays a literal of the kernel's
        # text, read by the decimals rule as in A and b (collected, it would be exact)
        if not decimal and all(v is not None for v in values.values()):
            A_coeffs: dict[tuple[int, int], Fraction] = {}
            b_coeffs: dict[tuple[int, int], Fraction] = {}
            for (i, j), v in values.items():
                term = Fraction(v or 0) / i
                A_coeffs[i, j - 1] = A_coeffs.get((i, j - 1), Fraction(0)) + term
                b_coeffs[j - 1, 0] = b_coeffs.get((j - 1, 0), Fraction(0)) + term
            return ContinuousMethod(_poly_text(A_coeffs), _poly_text(b_coeffs), name, info,
                                    tuple(tuple(r) for r in rows))
        A_terms, b_terms = [], []
        for (i, j), value in values.items():
            text = rows[i - 1][j - 1]
            coeff = (text if re.fullmatch(r"[\w.]+", text) else f"({text})") + ("" if i == 1 else f"/{i}")
            A_terms.append(coeff + _monomial("tau", i) + _monomial("sigma", j - 1))
            b_terms.append(coeff + _monomial("tau", j - 1))
        return ContinuousMethod(" + ".join(A_terms), " + ".join(b_terms), name, info, tuple(tuple(r) for r in rows))

    def replace(self, **changes: Any) -> "ContinuousMethod":
        return dataclasses.replace(self, **changes)

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state.pop("kernel", None)  # FLINT polynomials do not pickle; rebuilt on first use
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)

    # ----------------------------------------------------------------- the kernel

    @cached_property
    def kernel(self) -> "Kernel":
        return Kernel.of(self.A, self.b, self.info.constants, "M" if self.M is not None else None)

    @property
    def nodes(self) -> tuple[ex.Expr, ex.Expr]:
        return self.kernel.nodes

    @property
    def rounded_digits(self) -> int | None:
        """Fewest significant digits of a rounded decimal in the kernel (None: none)."""
        digits = [e.rounded_digits for e in self.kernel.entries if e.rounded_digits is not None]
        return min(digits) if digits else None

    def is_box(self, decimals: DecimalsMode) -> bool:
        """Some decimal literal of the kernel stands for an interval (definitions §5.2)."""
        return any(e.is_box(DecimalsMode(decimals)) for e in self.kernel.entries)

    @property
    def is_rational(self) -> bool:
        return self.kernel.ring.field is None

    # ----------------------------------------------------------------- the surrogate

    def nodes_for(self, vertices: int, box: bool = False) -> int:
        """How many rational nodes make the surrogate exact for trees up to ``vertices``;
        ``box``: for every kernel of the box of its decimals, by the degrees the kernel is
        written with (a decimal 0 at face value may be nonzero in the box)."""
        k = self.kernel
        d_tau, d_sigma, d_b = k.written_degrees if box else (k.deg_tau, k.deg_sigma, k.deg_b)
        need = max(d_sigma + max(vertices - 2, 0) * d_tau, d_b + (vertices - 1) * d_tau)
        return need + 1

    def surrogate(self, vertices: int, positive: bool = False) -> Tableau:
        """A tableau with the method's elementary weights for every tree with at most
        ``vertices`` vertices (module docstring); its ``info.continuous`` says so.
        ``positive``: on the rule of positive weights
        (:func:`~rkcheck.methods.quadrature.positive_rule`), for a kernel judged over
        the box of its decimals, whose widths the equispaced rule's weights would
        multiply by Σ|w_i| at every level of a tree."""
        n_nodes = self.nodes_for(vertices, positive)
        if n_nodes > MAX_SURROGATE_NODES:
            raise UserError(f"the exact B-series to {vertices} vertices needs {n_nodes} quadrature nodes, "
                            f"more than the limit MAX_SURROGATE_NODES = {MAX_SURROGATE_NODES}; check a lower order",
                            source=self.info.source)
        x, w = positive_rule(n_nodes) if positive else rational_rule(n_nodes)
        A, b = self.kernel.surrogate_entries(x, w, self.info.constants)
        info = self.info.replace(continuous=Surrogate(self, vertices, n_nodes, positive))
        return Tableau(A=A, b=b, c=None, name=self.name, info=info)


@dataclass(frozen=True)
class Surrogate:
    """What a surrogate tableau stands for: ``method``, exact for trees up to ``vertices``."""

    method: ContinuousMethod
    vertices: int
    nodes: int
    positive: bool = False  # on the rule of positive weights, not the equispaced one


# --------------------------------------------------------------------------- the kernel


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
                node = ex.parse(text)
                for used in xp.names(node):
                    if used.name not in VARIABLES and used.name not in constants.definitions:
                        raise UserError(f"unknown name {used.name!r} at column {used.column}: a kernel is a "
                                        "polynomial in tau and sigma (and the [constants])")
            except UserError as err:
                raise err.located(place) from None
            nodes.append(node)
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
        for place, text in zip(places, (A, b)):
            try:
                entries.append(Entry.parse(text, probe))
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

    def _at_nodes(self, p: Any, x: list[Fraction], w: list[Fraction], rows: bool = False) -> list[list[Any]]:
        """``w_j p(x_i, x_j)`` for the rational polynomial ``p(τ, σ)`` at every pair of
        nodes, or ``w_i p(x_i)`` (one column) with ``rows``, as FLINT rationals: ``V_τ C
        V_σᵀ``, ``C`` its coefficients and ``V`` the Vandermonde matrices of the nodes
        (node by node in Python, a surrogate of a few hundred nodes would take seconds)."""
        from flint import fmpq_mat

        t, s = self._index("tau"), self._index("sigma")
        monoms = [(int(m[t]), int(m[s])) for m in p.monoms()]
        C = fmpq_mat(1 + max((i for i, _ in monoms), default=0), 1 + max((j for _, j in monoms), default=0))
        for (i, j), c in zip(monoms, p.coeffs()):
            C[i, j] = c
        values = vandermonde(x, C.nrows()) * C
        if not rows:
            values = values * vandermonde(x, C.ncols()).transpose()
        weights = [to_fmpq(q) for q in w]
        return [[values[i, j] * weights[i if rows else j] for j in range(values.ncols())] for i in range(values.nrows())]

    def surrogate_entries(self, x: list[Fraction], w: list[Fraction],
                          constants: Constants) -> tuple[tuple[tuple[Entry, ...], ...], tuple[Entry, ...]]:
        """``a_ij = w_j A(x_i, x_j)``, ``b_i = w_i B(x_i)`` as tableau entries: exact
        fractions for a rational kernel without decimals, otherwise the kernel's own
        expression at the nodes (its decimals and roots then read as in any entry)."""
        n = len(x)
        plain = self.ring.field is None and not any(constants.uses_decimal(node) for node in self.nodes)
        if plain:
            A = tuple(tuple(_rational_entry(v) for v in row) for row in self._at_nodes(self.A_poly, x, w))
            b = tuple(_rational_entry(row[0]) for row in self._at_nodes(self.B_poly, x, w, rows=True))
            return A, b
        A = tuple(tuple(_entry_at(self.nodes[0], w[j], x[i], x[j], constants) for j in range(n)) for i in range(n))
        b = tuple(_entry_at(self.nodes[1], w[i], x[i], Fraction(0), constants) for i in range(n))
        return A, b


def _poly_text(coeffs: dict[tuple[int, int], Fraction]) -> str:
    """``Σ c τ^i σ^j`` as an entry text, highest powers of τ last (``tau - 3*tau^2*sigma``)."""
    out = ""
    for (i, j), c in sorted(coeffs.items()):
        if c == 0:
            continue
        mono = (_monomial("tau", i) + _monomial("sigma", j)).lstrip("*")
        mag = abs(c)
        term = (str(mag) if not mono or mag != 1 else "") + ("*" if mono and mag != 1 else "") + mono
        out += (" - " if c < 0 else " + ") + term if out else ("-" if c < 0 else "") + term
    return out or "0"


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


def _monomial(name: str, power: int) -> str:
    return "" if power == 0 else (f"*{name}" if power == 1 else f"*{name}^{power}")


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


def _entry_at(node: ex.Expr, weight: Fraction, tau: Fraction, sigma: Fraction, constants: Constants) -> Entry:
    value = xp.substituted(node, {"tau": _literal(tau), "sigma": _literal(sigma)})
    text = f"{weight.numerator}/{weight.denominator}*({xp.to_text(value)})"
    # built from the kernel's own nodes, not parsed from the text: a decimal of the
    # kernel is then one literal in every entry (numbers.literals), as it is one number
    return Entry.from_node(text, ex.Binary("*", _literal(weight), value, 1), constants, shares_literals=True)
