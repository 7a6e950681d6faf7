"""A family of methods: a tableau whose entries are polynomials in free parameters.

Written as a tableau file with a ``[parameters]`` table (``beta = "free"``); the entries
and ``[constants]`` may use the parameters like constants.  What the entries may be, and
how they are represented exactly: :mod:`rkcheck.numbers.parametric`.
"""

from __future__ import annotations

import dataclasses
import numbers
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from decimal import Decimal
from fractions import Fraction
from typing import Any, Callable, Mapping, overload

from rkcheck.errors import OptionError, UserError
from rkcheck.methods.tableau import MethodInfo, Tableau
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.formatting import count_text
from rkcheck.numbers.parametric import ParameterRing, ParametricEntries

#: What a parameter may be declared as (free real parameters only, for now).
PARAMETER_KINDS = ("free",)


#: a family file's warning about its claims: a member's are judged (``Family.at``)
CLAIMS_OF_A_FAMILY = ("the [expect] claims are not judged for a family with free [parameters]: they state what one "
                      "method does (check a member: `rkcheck verify FILE --at NAME=VALUE`, or "
                      "rkcheck.load_family(…).at(values))")


@dataclass(frozen=True)
class Family:
    """``name``, the parameters, the entries as written (``A``, ``b`` texts) and as
    polynomials over one :class:`ParameterRing`, and what the file says besides
    (``info``).

    A family of continuous-stage kernels (:mod:`rkcheck.methods.continuous_family`) has
    its kernel's texts (``kernel``: A, B) and entries that are a surrogate tableau's,
    whose elementary weights are the kernel's for trees of up to ``reach`` vertices only:
    :meth:`covering` gives the family with a surrogate wide enough for the trees a
    computation reads; its A has no texts (``A_text`` empty: its entries are formed
    from the kernel's coefficients as read, :class:`KernelMatrix`).  A tableau family
    has ``reach`` None (every tree)."""

    name: str
    parameters: tuple[str, ...]
    A_text: tuple[tuple[str, ...], ...]
    b_text: tuple[str, ...]
    entries: ParametricEntries
    info: MethodInfo
    kernel: tuple[str, str] | None = None
    reach: int | None = None
    widen: Callable[[int], "Family"] | None = field(default=None, compare=False, repr=False)
    #: a kernel family's A as a product ``V C Wᵀ`` (:class:`KernelMatrix`), or None
    factors: tuple[Any, Any, Any] | None = field(default=None, compare=False, repr=False)
    #: warnings about the family as a whole (parameters no entry uses, options that do
    #: not apply to a family), not about one of its methods: a member has none of them
    notes: tuple[str, ...] = ()

    def __repr__(self) -> str:
        return f"<Family {self.name!r}: {self.stages} stages, parameters {', '.join(self.parameters)}>"

    @property
    def warnings(self) -> tuple[str, ...]:
        """What the file says beside the entries, then what holds of the family as a
        whole: its claims are not judged, and its :attr:`notes`."""
        return (*self.info.warnings, *((CLAIMS_OF_A_FAMILY,) if self.info.claims else ()), *self.notes)

    @property
    def stages(self) -> int:
        return len(self.b_text)

    def covering(self, vertices: int) -> "Family":
        """This family with entries whose elementary weights are exact for every tree of
        up to ``vertices`` vertices: itself for a tableau family or a surrogate that
        reaches that far, else the kernel's surrogate built for them."""
        if isinstance(vertices, bool) or not isinstance(vertices, int) or vertices < 1:
            raise UserError(f"expected a positive number of vertices, got {vertices!r}", "vertices")
        if self.reach is None or vertices <= self.reach or self.widen is None:
            return self
        try:
            return dataclasses.replace(self.widen(vertices), notes=self.notes)
        except UserError as err:
            raise err.located(source=self.info.source) from None

    @property
    def ring(self) -> ParameterRing:
        return self.entries.ring

    @property
    def A(self) -> Sequence[list[Any]]:
        """A's rows of polynomials (a kernel family's: :class:`KernelMatrix`, formed as read)."""
        if self.factors is not None:
            return KernelMatrix(self.factors)
        s = self.stages
        v = self.entries.values
        return [v[i * s:(i + 1) * s] for i in range(s)]

    @property
    def b(self) -> list[Any]:
        """b's polynomials: the last of the entries (a kernel family's, the only ones)."""
        return self.entries.values[-self.stages:]

    @property
    def consistency_note(self) -> str | None:
        """What a Σb that is not identically 1 says of the members (None when it is): a
        member is consistent only where it is 1 — what ``solve`` finds when asked, so its
        reports leave the note to ``verify``'s."""
        total = sum(self.b, self.b[0] * 0)
        defect = total - 1
        if defect.is_zero():
            return None
        shown = "Σb = " + str(total).replace(" ", "")
        if defect.is_constant():
            return f"{shown} ≠ 1 for every parameter value: no member is consistent (not even order 1)"
        return (f"{shown} is not identically 1: a member is consistent only where it is 1 "
                f"(rkcheck solve {self.info.source or 'FILE'} --classical-order 1 says where)")

    def equation(self, text: str) -> Any:
        """``"lhs = rhs"`` (or an expression meaning ``= 0``) over the family's ring."""
        sides = text.split("=")
        # an option's text, not the file's: OptionError names --where, not the file
        if len(sides) > 2:
            raise OptionError(f"cannot read the equation {text!r}: it has more than one '='", "--where")
        if len(sides) == 2 and not all(side.strip() for side in sides):
            raise OptionError(f"cannot read the equation {text!r}: '=' needs an expression on each side", "--where")
        nodes = []
        for side, where in zip(sides, ("", "right of '=': ") if len(sides) == 2 else ("",)):
            try:  # each side parsed as written, so that a column counts in what the user typed
                nodes.append(ex.parse(side))
            except UserError as err:
                raise OptionError(f"cannot read the equation {text!r}: {where}{err.message}", "--where") from None
        node = nodes[0] if len(nodes) == 1 else ex.Binary("-", nodes[0], nodes[1], len(sides[0]) + 1)
        unknown = {n.name for n in xp.names(node)} - set(self.parameters) - set(self.entries.constants)
        if unknown:
            raise OptionError(f"unknown name {sorted(unknown)[0]!r} in {text!r} (the parameters are "
                              f"{', '.join(self.parameters)})", "--where")
        try:
            return self.entries.polynomial_of(node, "--where")
        except UserError as err:
            raise OptionError(f"cannot read the equation {text!r}: {err.message}", "--where") from None

    def at(self, values: Mapping[str, Any], name: str | None = None) -> Any:
        """The method at the given values of every parameter: a :class:`Tableau`, or for
        a family of kernels its :class:`~rkcheck.methods.continuous.ContinuousMethod`.  A
        value is a rational (an int, a Fraction, a Decimal, a finite float taken exactly,
        numpy's too, a text ``"1/3"``), an exact real number written as an entry is
        (``"1/2 - sqrt(3)/6"``, ``"root(x^3 - x - 1, 1)"``, a sympy number), or a real
        value :func:`rkcheck.solve` found (a solution's ``values`` may be passed whole).
        The member has the family file's ``[check]`` and claims."""
        if not isinstance(values, Mapping):
            raise UserError(f"expected a mapping of the parameters to their values, got {type(values).__name__}",
                            "values")
        missing = [p for p in self.parameters if p not in values]
        if missing:
            raise UserError(f"no value for the parameter {missing[0]}")
        unknown = [k for k in values if k not in self.parameters]
        if unknown:
            raise UserError(f"{unknown[0]!r} is not a parameter (the parameters are {', '.join(self.parameters)})")
        # on the expressions, where a root's polynomial keeps its own x
        subst = {p: _value_node(values[p], p) for p in self.parameters}
        texts = list(self.kernel) if self.kernel else [x for row in self.A_text for x in row] + list(self.b_text)
        out = [xp.to_text(xp.substituted(ex.parse(t), subst)) for t in texts]
        constants = {k: xp.to_text(xp.substituted(v, subst)) for k, v in self.entries.constants.items()}
        if self.kernel:
            return _kernel_from_texts(out[0], out[1], constants, name or self.name, self.info)
        s = self.stages
        return _tableau_from_texts([out[i * s:(i + 1) * s] for i in range(s)], out[s * s:], constants,
                                   name or self.name, self.info)


def _value_text(q: Fraction) -> str:
    """A parameter's value as an entry's text (of any length: str() stops at 4 300 digits)."""
    return f"({ex.fraction_text(q)})"


def _value_node(value: Any, name: str) -> ex.Expr:
    """A parameter's value (:meth:`Family.at`) as an expression to put in its place."""
    from rkcheck.numbers.coordinates import AlgebraicValue

    if isinstance(value, AlgebraicValue):
        text = value.expression()
        if text is None:
            raise UserError(f"{value.text} is not a real number: a method's entries are real", name)
    elif type(value).__module__.startswith("sympy"):  # its text, as a family's entries take it
        text = str(value)
    elif isinstance(value, str) and not _is_rational(value):
        text = value
    else:
        return ex.parse(_value_text(_rational(value, name)))
    return _exact_real(text, name)


def _is_rational(text: str) -> bool:
    """Whether ``text`` is a rational as Python writes one (``"1/3"``, ``"0.25"``): taken
    exactly, where a decimal in an entry of six or more digits stands for an interval."""
    try:
        Fraction(text)
    except (ValueError, ZeroDivisionError):
        return False
    return True


def _exact_real(text: str, name: str) -> ex.Expr:
    """The expression ``text``, which must name nothing and be an exact real number."""
    from rkcheck.numbers.algebraic import NotAlgebraic
    from rkcheck.numbers.field_builder import field_of

    try:
        node = ex.parse(text)
    except UserError as err:
        raise err.located(name) from None
    used = xp.names(node)
    if used:
        raise UserError(f"unknown name {used[0].name!r} at column {used[0].column}: a parameter's value is a "
                        "number", name)
    try:
        field_of([node])
    except NotAlgebraic as err:
        raise UserError(f"cannot be used exactly: {err}", name) from None
    except UserError as err:
        raise err.located(name) from None
    return ex.parse(f"({text})")


def _rational(value: Any, name: str) -> Fraction:
    """A rational parameter value: an integer or a Fraction (numpy's too), a Decimal, a
    text ``"1/3"``, or a finite float (taken exactly, as the binary number it is)."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, Decimal, str)):
        raise UserError("expected a number (an int, a Fraction, a text such as '1/2 - sqrt(3)/6', or a value "
                        f"from solve), got {type(value).__name__}", name)
    try:
        if isinstance(value, numbers.Rational):  # numpy's integers too: their parts as Python ints
            q = Fraction(int(value.numerator), int(value.denominator))
        else:
            q = Fraction(value) if isinstance(value, (Decimal, str)) else Fraction(float(value))
    except (ValueError, OverflowError, ZeroDivisionError):
        raise UserError(f"expected a finite rational number, got {str(value)[:40]!r}", name) from None
    bits = max(q.numerator.bit_length(), q.denominator.bit_length())
    if bits > ex.MAX_BITS:
        raise UserError(ex.too_large("value", f"{count_text(bits)} bits"), name)
    return q


def entry_text(value: Any, place: str) -> str:
    """An entry of a family given in Python: a string, an int, a Fraction, or a sympy
    expression (its text: ``beta**2/2``, ``sqrt(3)``)."""
    if isinstance(value, bool):
        raise UserError("expected a number, a string or a sympy expression, got a boolean", place)
    if isinstance(value, str):
        return value
    if isinstance(value, (int, Fraction)):
        return ex.fraction_text(value)  # at any length
    if type(value).__module__.startswith("sympy"):
        return str(value)
    raise UserError(f"expected a number, a string or a sympy expression, got {type(value).__name__} (floats are "
                    "not exact: write them as strings)", place)


def family_from_arrays(A: Sequence[Sequence[Any]], b: Sequence[Any], parameters: Sequence[Any],
                       constants: Mapping[str, Any] | None = None, name: str = "unnamed family") -> Family:
    """A family from Python values (see :func:`entry_text`); ``parameters``: names or
    sympy symbols; ``constants``: name → value, like a file's ``[constants]``."""
    if constants is not None and not isinstance(constants, Mapping):
        raise UserError(f"expected a mapping of names to values, got {type(constants).__name__}", "constants")
    if isinstance(parameters, str) or not isinstance(parameters, (list, tuple)):
        raise UserError(f"expected a list of parameter names, got {parameters!r}", "parameters")
    params = tuple(str(p) for p in parameters)
    if len(set(params)) != len(params):
        raise UserError(f"a parameter is named twice in {list(params)}", "parameters")
    parse_parameters({p: "free" for p in params}, constants or {})
    if not isinstance(name, str):
        raise UserError(f"expected a string, got {type(name).__name__}", "name")
    from rkcheck.methods.arrays import as_list, as_vector

    b = as_vector(b, "b")
    A = [as_list(row, f"A[{i}]") for i, row in enumerate(as_list(A, "A"), start=1)]
    s = len(b)
    if len(A) != s or any(len(row) != s for row in A):
        raise UserError(f"A must be {s}×{s} (one row and one column per entry of b)", "A")
    A_text = [[entry_text(x, f"A[{i + 1}][{j + 1}]") for j, x in enumerate(row)] for i, row in enumerate(A)]
    b_text = [entry_text(x, f"b[{i + 1}]") for i, x in enumerate(b)]
    consts = {}
    for k, v in (constants or {}).items():
        try:
            consts[k] = ex.parse(entry_text(v, f"constants.{k}"))
        except UserError as err:
            raise err.located(f"constants.{k}") from None
    return build_family(name, params, A_text, b_text, consts, MethodInfo(source="<memory>"))


def _tableau_from_texts(A: Sequence[Sequence[str]], b: Sequence[str], constants: Mapping[str, str],
                        name: str, info: MethodInfo) -> Tableau:
    from rkcheck.numbers.entries import Constants, Entry

    consts = Constants({k: ex.parse(v) for k, v in constants.items()})
    A_ = tuple(tuple(Entry.parse(x, consts) for x in row) for row in A)
    b_ = tuple(Entry.parse(x, consts) for x in b)
    return Tableau(A=A_, b=b_, c=None, name=name, info=info.replace(constants=consts))


def _kernel_from_texts(A: str, b: str, constants: Mapping[str, str], name: str, info: MethodInfo) -> Any:
    from rkcheck.methods.continuous import ContinuousMethod
    from rkcheck.numbers.entries import Constants

    consts = Constants({k: ex.parse(v) for k, v in constants.items()})
    return ContinuousMethod(A, b, name, info.replace(constants=consts))


def parse_parameters(table: Mapping[str, Any], constants: Mapping[str, Any]) -> tuple[str, ...]:
    """The ``[parameters]`` table: each name an identifier, declared ``"free"``."""
    names = []
    for name, kind in table.items():
        place = f"parameters.{name}"
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name) or name in ex.FUNCTIONS or name.startswith("__"):
            raise UserError("a parameter's name must be an identifier (letters, digits, _; not starting with __) "
                            "other than a function name (sqrt, root)", place)
        if name in constants:
            raise UserError("a parameter and a constant have the same name", place)
        if kind not in PARAMETER_KINDS:
            raise UserError(f"expected {' or '.join(repr(k) for k in PARAMETER_KINDS)}, got {kind!r}", place)
        names.append(name)
    if not names:
        raise UserError("the [parameters] table names no parameter", "parameters")
    return tuple(names)


class KernelMatrix(Sequence[list[Any]]):
    """The rows of a kernel family's surrogate A (a sequence of rows, as any family's A),
    formed from ``factors = (V, C, W)`` with ``A = V C Wᵀ`` when asked for, never held
    together: ``V[i][a] = x_iᵃ``, ``W[j][c] = w_j x_jᶜ`` (constants) and ``C[a][c]`` the
    kernel's coefficient of ``τᵃσᶜ`` (a polynomial in the parameters).  The n² entries
    of a surrogate of a few hundred nodes, rationals of hundreds of digits, took
    hundreds of megabytes and seconds to form, and a computation reads A through the
    factors: a product ``x Aᵀ`` costs ``n(p + q + 2)`` products of polynomials by
    constants and ``(p+1)(q+1)`` of polynomials, where ``x Aᵀ`` itself costs ``n²`` (n
    nodes, p and q the degrees in τ and σ): the surrogate's nodes grow with the trees,
    the kernel's degrees do not."""

    def __init__(self, factors: tuple[Any, Any, Any]):
        self.factors = factors

    def __len__(self) -> int:
        return len(self.factors[0])

    @overload
    def __getitem__(self, i: int) -> list[Any]: ...

    @overload
    def __getitem__(self, i: slice) -> list[list[Any]]: ...

    def __getitem__(self, i: int | slice) -> list[Any] | list[list[Any]]:
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        V, C, W = self.factors
        return list((V[i] @ C) @ W.T)

    def row_sums(self) -> list[Any]:
        """``A·1`` (the nodes c), through the factors: ``V (C (Wᵀ 1))``."""
        V, C, W = self.factors
        return list(V @ (C @ W.sum(axis=0)))


def build_family(name: str, parameters: tuple[str, ...], A: Sequence[Sequence[str]], b: Sequence[str],
                 constants: Mapping[str, ex.Expr], info: MethodInfo,
                 parsed: Sequence[ex.Expr] | None = None) -> Family:
    """A family from its entry texts (validated shape), parameters and constants;
    ``parsed``: the texts' expressions (A by rows, then b) when the caller built them,
    names checked, so that generated entries are not parsed back."""
    s = len(b)
    texts = [x for row in A for x in row] + list(b)
    places = [f"A[{i + 1}][{j + 1}]" for i in range(s) for j in range(s)] + [f"b[{i + 1}]" for i in range(s)]
    if parsed is not None:
        entries = ParametricEntries(list(parsed), places, parameters, constants)
        return _with_warnings(Family(name, parameters, tuple(tuple(r) for r in A), tuple(b), entries, info))
    nodes = []
    known = set(parameters) | set(constants)
    for text, place in zip(texts, places):
        try:
            node = ex.parse(text)
        except UserError as err:
            raise err.located(place) from None
        unknown = [n for n in xp.names(node) if n.name not in known]
        if unknown:
            raise UserError(f"unknown name {unknown[0].name!r} at column {unknown[0].column} (parameters: "
                            f"{', '.join(parameters)})", place)
        nodes.append(node)
    entries = ParametricEntries(nodes, places, parameters, constants)
    return _with_warnings(Family(name, parameters, tuple(tuple(r) for r in A), tuple(b), entries, info))


def _with_warnings(family: Family) -> Family:
    """``family`` with a warning for the parameters no entry uses (every value of them
    gives the same method)."""
    values = family.entries.values
    ring_names = list(family.ring.ctx.names())
    unused = [p for p in family.parameters
              if not any(v.degrees()[ring_names.index(p)] for v in values if not v.is_zero())]
    if not unused:
        return family
    many = len(unused) > 1
    note = (f"parameter{'s' if many else ''} {', '.join(unused)} appear{'' if many else 's'} in no entry: "
            f"every value of {'them' if many else 'it'} gives the same method")
    return dataclasses.replace(family, notes=(*family.notes, note))
