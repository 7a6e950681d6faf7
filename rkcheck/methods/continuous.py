"""Continuous-stage Runge–Kutta methods (definitions §6): a kernel ``A(τ, σ)`` and a
weight ``B(τ)``, polynomials with coefficients in Q or in the number field of their
constants (square roots, ``root``).

A :class:`ContinuousMethod` keeps the kernel as written (its text and parsed expression,
so that decimal literals keep their meaning under the decimals rule of definitions §5)
and as exact polynomials over a :class:`~rkcheck.numbers.parametric.ParameterRing` in
the variables ``tau`` and ``sigma`` (its :class:`~rkcheck.methods.kernel.Kernel`).

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
from rkcheck.methods.kernel import Kernel
from rkcheck.methods.quadrature import positive_rule, rational_rule
from rkcheck.methods.tableau import MethodInfo, Tableau
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Constants
from rkcheck.numbers.formatting import count_text
from rkcheck.numbers.reading import DecimalsMode

#: the Greek letters accepted for a kernel's two variables (VARIABLES)
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
        from rkcheck.methods.arrays import refuse_masked

        refuse_masked(M, where)
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
    """An entry's text: an int or a Fraction at any length, a string, a sympy number, or
    a float as its shortest decimal (as ``Tableau.from_arrays`` reads floats, and a file
    its bare decimals)."""
    if isinstance(value, float):
        if not math.isfinite(value):
            raise UserError(f"{value} is not a finite number", place)
        return repr(value)
    if isinstance(value, (int, Fraction)) and not isinstance(value, bool):
        return ex.fraction_text(value)  # at any length
    if type(value).__module__.startswith("sympy"):  # a sympy number, as a family's entries read it: its text
        return str(value)
    if not isinstance(value, str):
        raise UserError(f"expected a number (int, Fraction, float) or a string, got {type(value).__name__}", place)
    return value


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
            if isinstance(text, (int, Fraction)) and not isinstance(text, bool):
                text = ex.fraction_text(text)  # at any length
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
        A_text = " + ".join(A_terms)
        if len(A_text) > ex.MAX_ENTRY_LENGTH:
            # every entry of the surrogate would hold this text: thousands of copies
            raise TableauError(f"with decimals, M is written term by term into A(τ, σ), here {count_text(len(A_text))} "
                               f"characters, above the limit of one entry (MAX_ENTRY_LENGTH = "
                               f"{count_text(ex.MAX_ENTRY_LENGTH)}); M of rationals is collected into a polynomial instead",
                               "M", info.source)
        return ContinuousMethod(A_text, " + ".join(b_terms), name, info, tuple(tuple(r) for r in rows))

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
        n_nodes, (x, w) = self._rule(vertices, positive)
        A, b = self.kernel.surrogate_entries(x, w, self.info.constants)
        info = self.info.replace(continuous=Surrogate(self, vertices, n_nodes, positive))
        return Tableau(A=A, b=b, c=None, name=self.name, info=info)

    def surrogate_size(self, vertices: int, positive: bool = False) -> tuple[int, int]:
        """The stages of :meth:`surrogate` and about how many characters the texts of
        its entries take (the longest of three rows of A, times the rows; and b), without
        building it: hundreds of nodes give n² entries of a thousand digits each, which a
        check weighs before it builds them.  The rows sampled are those of the nodes with
        the longest texts (at 0, 1/2 or 1 the powers of a node take few digits)."""
        n_nodes, (x, w) = self._rule(vertices, positive)
        rows = sorted(range(n_nodes), key=lambda i: (-len(str(x[i])), i))[:3]
        longest = max(self.kernel.row_characters(x, w, rows, self.info.constants))
        return n_nodes, (n_nodes + 1) * longest

    def _rule(self, vertices: int, positive: bool) -> tuple[int, tuple[list[Fraction], list[Fraction]]]:
        n_nodes = self.nodes_for(vertices, positive)
        if n_nodes > MAX_SURROGATE_NODES:
            raise UserError(f"the exact B-series to {vertices} vertices needs {n_nodes} quadrature nodes, "
                            f"more than the limit MAX_SURROGATE_NODES = {MAX_SURROGATE_NODES}; check a lower order",
                            source=self.info.source)
        return n_nodes, _rule(n_nodes, positive)


@lru_cache(maxsize=4)
def _rule(n_nodes: int, positive: bool) -> tuple[list[Fraction], list[Fraction]]:
    """The surrogate's nodes and weights, kept: a check weighs a surrogate's size on
    them, then builds it on them (hundreds of nodes take a fraction of a second)."""
    return positive_rule(n_nodes) if positive else rational_rule(n_nodes)


@dataclass(frozen=True)
class Surrogate:
    """What a surrogate tableau stands for: ``method``, exact for trees up to ``vertices``."""

    method: ContinuousMethod
    vertices: int
    nodes: int
    positive: bool = False  # on the rule of positive weights, not the equispaced one


# --------------------------------------------------------------------------- the kernel


def _poly_text(coeffs: dict[tuple[int, int], Fraction]) -> str:
    """``Σ c τ^i σ^j`` as an entry text, highest powers of τ last (``tau - 3*tau^2*sigma``)."""
    out = ""
    for (i, j), c in sorted(coeffs.items()):
        if c == 0:
            continue
        mono = (_monomial("tau", i) + _monomial("sigma", j)).lstrip("*")
        mag = abs(c)
        term = (ex.fraction_text(mag) if not mono or mag != 1 else "") + ("*" if mono and mag != 1 else "") + mono
        out += (" - " if c < 0 else " + ") + term if out else ("-" if c < 0 else "") + term
    return out or "0"


def _monomial(name: str, power: int) -> str:
    return "" if power == 0 else (f"*{name}" if power == 1 else f"*{name}^{power}")
