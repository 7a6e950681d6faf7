"""Entries with free parameters, as exact polynomials.

A family's entries (``[parameters]`` in a file) are polynomials in the parameters whose
coefficients lie in Q or in the number field K = Q(θ) of the entries' parameter-free
parts (square roots, ``root(P, k)``: :mod:`rkcheck.numbers.algebraic`).  They are
represented over Q in the variables ``(θ, p₁, …, p_k)`` — θ only when K ≠ Q — and kept
reduced modulo the minimal polynomial g(θ): with the lexicographic order and θ first,
g's leading monomial is θ^D, so the remainder of a division by g is the unique
representative of degree < D in θ, and a polynomial vanishes identically over K exactly
when its reduced form is zero.

Parameters may appear wherever a polynomial can: sums, products, integer powers and
division by a parameter-free number.  Under ``sqrt``/``root``, in an exponent or in a
denominator they would make the entries non-polynomial; each is a one-line error naming
the place.  Decimal literals are read at face value (exactly): a family is a statement
about exact coefficients.
"""

from __future__ import annotations

import copy
from fractions import Fraction
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

from rkcheck.errors import ResourceError, UserError
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.algebraic import NotAlgebraic, NumberField
from rkcheck.numbers.field_builder import field_of
from rkcheck.numbers.room import each_watched

#: The name of the field generator among the variables (parameter names may not start
#: with two underscores, so it never clashes with one); shown as θ.
THETA = "__theta"

#: At most this many parameters in one family (the solver's cost grows quickly with it).
MAX_PARAMETERS = 32

#: Terms of one entry expanded (``(p0 + … + p9)^64`` would have 10^11): an entry is what
#: a person writes, and every condition multiplies entries together.
MAX_ENTRY_TERMS = 100_000

#: Products of terms one step may take — expanding one entry, or one array operation
#: on the conditions' polynomials — (about its cost: a few seconds; FLINT's C loops are
#: not interrupted by Ctrl-C or SIGTERM until they return).
MAX_PRODUCT_WORK = 200_000_000

_ENTRIES, _FEWER = "the family's entries", "use fewer or smaller entries"


def fresh_name(base: str, taken: Iterable[str]) -> str:
    """``base``, or ``base_``, ``base__``… — the first not in ``taken``: a name rkcheck
    adds beside the family's parameters (a node ``z``, ``c1``) never equals one of them."""
    taken = set(taken)
    name = base
    while name in taken:
        name += "_"
    return name


def object_array(values: Sequence[Any], shape: tuple[int, ...]) -> np.ndarray:
    """A numpy object array holding the polynomials themselves (numpy would otherwise try
    to iterate them): numpy's products then call the polynomials' own arithmetic."""
    out = np.empty(shape, dtype=object)
    flat = out.reshape(-1)
    for i, v in enumerate(values):
        flat[i] = v
    return out


class ParameterRing:
    """Polynomials in the parameters over Q or over K = Q(θ) (module docstring)."""

    def __init__(self, parameters: Sequence[str], field: NumberField | None = None):
        from flint import fmpq_mpoly_ctx

        self.parameters = tuple(parameters)
        self.field = field
        names = ((THETA,) if field is not None else ()) + self.parameters
        self.ctx = fmpq_mpoly_ctx.get(names, "lex")
        gens = self.ctx.gens()
        self.theta: Any = gens[0] if field is not None else None
        self._params = dict(zip(self.parameters, gens[1:] if field is not None else gens))
        self.minpoly: Any = None
        if field is not None:
            theta = gens[0]
            g = [Fraction(c) for c in field.minpoly]  # ascending, monic
            self.minpoly = sum((self.constant(c) * theta ** k for k, c in enumerate(g)), self.constant(0))

    @property
    def variables(self) -> tuple[str, ...]:
        """Every variable, θ first when there is one."""
        return tuple(self.ctx.names())

    def constant(self, value: Fraction | int) -> Any:
        from flint import fmpq

        value = Fraction(value)
        return self.ctx.constant(fmpq(value.numerator, value.denominator))

    def parameter(self, name: str) -> Any:
        return self._params[name]

    def element(self, value: Any) -> Any:
        """A Fraction or a field element of K as a polynomial in θ."""
        if isinstance(value, (Fraction, int)):
            return self.constant(value)
        if self.field is None or value.field is not self.field:
            raise ValueError("a number outside the family's field")
        out = self.constant(0)
        for k, c in enumerate(value.coeffs):
            if c:
                out = out + self.constant(c) * self.theta ** k
        return out

    def reduce(self, p: Any) -> Any:
        """The representative of degree < D in θ (unchanged over Q)."""
        return p if self.minpoly is None else p % self.minpoly

    def is_zero(self, p: Any) -> bool:
        return bool(self.reduce(p).is_zero())


def uses(node: ex.Expr, names: set[str]) -> bool:
    """Whether the expression uses one of ``names`` — also inside a root's polynomial,
    whose names the grammar keeps apart (its x is bound), so that ``root(x^2 - beta, 2)``
    counts as using beta."""
    for n in xp.walk(node):
        if isinstance(n, ex.Name) and n.name in names:
            return True
        # x is the polynomial's own variable, whatever a parameter is called
        if isinstance(n, ex.Call) and n.func == "root" and n.args and uses(n.args[0], names - {"x"}):
            return True
    return False


def parameter_closure(constants: Mapping[str, ex.Expr], parameters: Sequence[str]) -> set[str]:
    """The parameters and every constant that uses one, directly or through others."""
    found = set(parameters)
    changed = True
    while changed:
        changed = False
        for name, node in constants.items():
            if name not in found and uses(node, found):
                found.add(name)
                changed = True
    return found


class ParametricEntries:
    """The entries of a family as polynomials over one :class:`ParameterRing`.

    ``nodes``: the parsed entries; ``constants``: the ``[constants]`` definitions (a
    constant may use parameters); ``places``: each entry's place for error messages."""

    def __init__(self, nodes: Sequence[ex.Expr], places: Sequence[str], parameters: Sequence[str],
                 constants: Mapping[str, ex.Expr], noun: str = "a parameter"):
        if len(parameters) > MAX_PARAMETERS:
            raise UserError(f"{len(parameters)} parameters exceed the limit MAX_PARAMETERS = {MAX_PARAMETERS}",
                            "parameters")
        self.constants = dict(constants)
        self.noun = noun  # what the names are called in messages (a kernel's are tau, sigma and parameters)
        self.dependent = parameter_closure(self.constants, parameters)
        fixed_constants = {k: v for k, v in self.constants.items() if k not in self.dependent}
        self._expanded: dict[str, Any] = {}
        leaves = self._fixed_leaves(nodes, places)
        try:
            found = field_of([node for node, _ in leaves], fixed_constants)
        except NotAlgebraic as err:
            place = _failing_place(leaves, fixed_constants, (NotAlgebraic,)) or "parameters"
            raise UserError(f"not an exact algebraic number: {err}", place) from None
        except ResourceError:  # the memory, not an entry: no place to look for
            raise
        except UserError as err:
            if err.place:
                raise
            raise err.located(_failing_place(leaves, fixed_constants) or "parameters") from None
        self.ring = ParameterRing(parameters, found.field)
        # keyed by node identity: the nodes are kept alive with their values, so that an id
        # is never reused by another node while the map holds it
        # thousands of entries over a number field, each of hundreds of digits, are formed
        # one by one: the memory left is read between them
        self._fixed = {id(node): (node, self.ring.element(v))
                       for (node, _), v in each_watched(zip(leaves, found.values), _ENTRIES, _FEWER)}
        self.values = [self._entry(node, place) for node, place in each_watched(zip(nodes, places), _ENTRIES, _FEWER)]

    def over(self, parameters: Sequence[str]) -> "ParametricEntries":
        """These constants and parameter-free parts, in the same field, over the ring of
        ``parameters`` alone, with no entries of their own: a kernel read in τ, σ and
        the parameters gives its family, whose entries are formed from the kernel's
        coefficients in the parameters (τ and σ gone once the nodes are put in)."""
        out = copy.copy(self)
        out.ring = ParameterRing(parameters, self.ring.field)
        out.dependent = parameter_closure(self.constants, parameters)
        out.noun = "a parameter"
        out._expanded = {}
        out._fixed = {key: (node, out.ring.element(self.number(value))) for key, (node, value) in self._fixed.items()}
        out.values = []
        return out

    def number(self, value: Any) -> Any:
        """A parameter-free value of the ring as the number it is: a Fraction, or an
        element of the field."""
        if self.ring.field is not None:
            return self._field_element(value)
        coeffs = value.coeffs()
        return Fraction(int(coeffs[0].p), int(coeffs[0].q)) if coeffs else Fraction(0)

    def polynomial_of(self, node: ex.Expr, place: str) -> Any:
        """Another expression over the same ring (an extra equation): its parameter-free
        parts (numbers, the family's constants, roots) must lie in the entries' field."""
        for leaf, _ in self._fixed_leaves([node], [place]):
            if id(leaf) not in self._fixed:
                self._fixed[id(leaf)] = (leaf, self._in_field(leaf, place))
        return self._entry(node, place)

    def _in_field(self, leaf: ex.Expr, place: str) -> Any:
        """A parameter-free part of an extra equation as a number of the entries' field:
        built with the entries' own parts, then carried into the field as the entries
        have it (built again, its generator may differ: ``sqrt(12)`` for ``sqrt(3)``)."""
        from rkcheck.numbers.same_field import carried

        fixed_constants = {k: v for k, v in self.constants.items() if k not in self.dependent}
        parts = list(self._fixed.values())
        try:
            found = field_of([n for n, _ in parts] + [leaf], fixed_constants)
        except NotAlgebraic as err:
            raise UserError(f"not an exact algebraic number: {err}", place) from None
        value = found.values[-1]
        rational = value if found.field is None else value.rational()
        if rational is not None:
            return self.ring.constant(rational)
        field = self.ring.field
        number = None if field is None else \
            carried(value, [(found.values[i], self.number(v)) for i, (_, v) in enumerate(parts)], field)
        if number is None:
            from rkcheck.numbers.minimal import minimal_polynomial
            from rkcheck.numbers.polynomials import poly_text

            # the equation the number satisfies has coefficients in Q, which any field holds
            raise UserError(f"{xp.to_text(leaf)} is not a number of the entries' field, "
                            f"{'the rationals' if field is None else f'Q({field.name})'}; write the polynomial "
                            f"equation it is a root of instead: {poly_text(minimal_polynomial(value))} = 0 "
                            f"for x = {xp.to_text(leaf)}", place)
        return self.ring.element(number)

    def _entry(self, node: ex.Expr, place: str) -> Any:
        self._work = 0  # products of terms spent on this entry (MAX_PRODUCT_WORK), its constants included
        return self.ring.reduce(self._polynomial(node, place))

    # ------------------------------------------------------------------ parameter-free parts

    def _fixed_leaves(self, nodes: Sequence[ex.Expr], places: Sequence[str]) -> list[tuple[ex.Expr, str]]:
        """The maximal parameter-free sub-expressions of every entry and of the
        parameter-dependent constants (one field holds them all)."""
        out: list[tuple[ex.Expr, str]] = []
        todo = list(zip(nodes, places)) + [(self.constants[n], f"constants.{n}") for n in sorted(self.dependent)
                                           if n in self.constants]
        for node, place in todo:
            stack = [node]
            while stack:
                n = stack.pop()
                if not uses(n, self.dependent):
                    out.append((n, place))
                    continue
                self._check_polynomial(n, place)
                stack.extend(xp.polynomial_operands(n))
        return out

    def _check_polynomial(self, n: ex.Expr, place: str) -> None:
        """A node that uses a parameter must keep the entry polynomial in it."""
        if isinstance(n, ex.Call):
            raise UserError(f"{self.noun} under {n.func}(...) (column {n.column}): entries must be polynomials "
                            f"in {self._names}", place)
        if isinstance(n, ex.Power) and uses(n.exponent, self.dependent):
            raise UserError(f"{self.noun} in an exponent (column {n.column}): entries must be polynomials "
                            f"in {self._names}", place)
        if isinstance(n, ex.Binary) and n.op == "/" and uses(n.right, self.dependent):
            raise UserError(f"{self.noun} in a denominator (column {n.column}): entries must be polynomials "
                            f"in {self._names}", place)

    @property
    def _names(self) -> str:
        return "them" if self.noun != "a parameter" else "the parameters"

    # ------------------------------------------------------------------ polynomials

    def _polynomial(self, node: ex.Expr, place: str) -> Any:
        def operands(n: ex.Expr) -> tuple[ex.Expr, ...]:
            return () if id(n) in self._fixed else xp.polynomial_operands(n)

        def combine(n: ex.Expr, vals: list[Any]) -> Any:
            if id(n) in self._fixed:
                return self._fixed[id(n)][1]
            if isinstance(n, ex.Name):
                return self._name(n.name, place)
            if isinstance(n, ex.Unary):
                return -vals[0]
            if isinstance(n, ex.Binary):
                left, right = vals
                if n.op == "+":
                    return left + right
                if n.op == "-":
                    return left - right
                if n.op == "*":
                    return self._product(left, right, n, place)
                return self._product(left, self._inverse(right, n, place), n, place)
            if isinstance(n, ex.Power):
                return self._power(vals[0], n, place)
            raise UserError(f"cannot read this part of the entry as a polynomial (column {getattr(n, 'column', 1)})",
                            place)

        return xp.fold(node, combine, operands)

    def _name(self, name: str, place: str) -> Any:
        if name in self.ring.parameters:
            return self.ring.parameter(name)
        if name not in self._expanded:
            self._expanded[name] = self.ring.reduce(self._polynomial(self.constants[name], f"constants.{name}"))
        return self._expanded[name]

    def _inverse(self, value: Any, n: ex.Binary, place: str) -> Any:
        """1/value for a parameter-free value (a number of K)."""
        if value.is_zero() or (self.ring.minpoly is not None and self.ring.is_zero(value)):
            raise UserError(f"division by zero (column {n.column})", place)
        if self.ring.field is None:
            (c,) = value.coeffs()
            return self.ring.constant(1 / Fraction(int(c.p), int(c.q)))
        return self.ring.element(self._field_element(value).inverse())

    def _field_element(self, value: Any) -> Any:
        field = self.ring.field
        assert field is not None
        coeffs = [Fraction(0)] * field.degree
        for (k, *_), c in value.to_dict().items():
            coeffs[k] = Fraction(int(c.p), int(c.q))
        return field(coeffs)

    def _power(self, base: Any, n: ex.Power, place: str) -> Any:
        exponent = xp.evaluate_exact(n.exponent, {})
        if exponent is None or exponent.denominator != 1 or not 0 <= exponent <= 64:
            raise UserError(f"a power of {self.noun} needs a whole exponent from 0 to 64 (column {n.column})", place)
        out = self.ring.constant(1)
        for _ in range(int(exponent)):
            out = self._product(out, base, n, place)
        return out

    def _product(self, left: Any, right: Any, n: ex.Expr, place: str) -> Any:
        """``left·right``, reduced, within :data:`MAX_PRODUCT_WORK` and :data:`MAX_ENTRY_TERMS`."""
        column = getattr(n, "column", 1)
        self._work += len(left) * len(right)
        if self._work > MAX_PRODUCT_WORK:
            raise UserError(f"expanding the entry takes more than {MAX_PRODUCT_WORK:,} products of terms at column "
                            f"{column}, {len(left):,} × {len(right):,} terms there (the limit MAX_PRODUCT_WORK)", place)
        out = self.ring.reduce(left * right)
        if len(out) > MAX_ENTRY_TERMS:
            raise UserError(f"the entry expands to more than {MAX_ENTRY_TERMS:,} terms at column {column} "
                            f"(the limit MAX_ENTRY_TERMS)", place)
        return out


def _failing_place(leaves: Sequence[tuple[ex.Expr, str]], constants: Mapping[str, ex.Expr],
                   refused: tuple[type[Exception], ...] = (UserError,)) -> str | None:
    """The place of the first constant, then the first parameter-free part, that cannot
    be evaluated on its own (``refused``: the errors that count; read only when the
    field of all of them refused one, to name where)."""
    parts = [(node, f"constants.{name}") for name, node in constants.items()] + list(leaves)
    for node, place in parts:
        try:
            field_of([node], dict(constants))
        except refused:
            return place
        except (UserError, NotAlgebraic):
            continue
    return None
