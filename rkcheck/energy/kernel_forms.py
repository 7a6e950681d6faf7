"""A kernel over the box of its decimals as exact polynomials in its literals.

Each number of the kernel that stands for an interval ``[m − r, m + r]`` — a rounded
decimal, an enclosed root, the reciprocal of such a divisor — becomes ``m + r·u`` with a
variable ``u ∈ [−1, 1]`` of its own, and ``A(τ, σ)``, ``B(τ)`` become polynomials with
rational coefficients in ``τ, σ`` and those variables (FLINT's ``fmpq_mpoly``).  A
literal is one variable however often the kernel uses it: a constant's literals are
shared by every use of the constant, and a Miyatake–Butcher entry is one literal in
``A`` and in ``B`` (the kernel's nodes share it).  A kernel identity computed on these
polynomials then cancels what cancels for every kernel of the box, exactly; interval
coefficients (:mod:`rkcheck.energy.kernel_box`) would let two uses of one literal take
two values.

A coefficient of ``τ^i σ^j`` is a polynomial ``c(u)``; over the box it lies within
``c(0) ± Σ|c_α|`` (the sum over its nonconstant terms), since every ``|u^α| ≤ 1``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Iterator

from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode

#: a kernel identity whose polynomials would pass this many terms is judged on interval
#: coefficients instead (sound, less sharp); a product is refused by its terms' count
#: before it is formed
FORM_TERMS = 200_000


class NoForm(Exception):
    """The polynomials of an identity would pass :data:`FORM_TERMS` terms, or a divisor
    of the kernel is not bounded away from 0 on the box: it is judged on intervals."""


class Form:
    """A polynomial in τ, σ and the box's variables ``u``."""

    __slots__ = ("p",)

    def __init__(self, p: Any):
        self.p = p

    @property
    def ctx(self) -> Any:
        return self.p.context()

    def __add__(self, other: "Form") -> "Form":
        return Form(self.p + other.p)

    def __sub__(self, other: "Form") -> "Form":
        return Form(self.p - other.p)

    def __neg__(self) -> "Form":
        return Form(-self.p)

    def __mul__(self, other: "Form") -> "Form":
        if len(self.p) * len(other.p) > FORM_TERMS:
            raise NoForm
        return Form(self.p * other.p)

    def scaled(self, q: Fraction) -> "Form":
        from flint import fmpq

        return Form(self.p * fmpq(q.numerator, q.denominator))

    def constant(self, q: Fraction) -> "Form":
        from flint import fmpq

        return Form(self.ctx.from_dict({}) + fmpq(q.numerator, q.denominator))

    def _gens(self) -> tuple[Any, ...]:
        return tuple(self.ctx.gens())

    def at_tau(self, value: int) -> "Form":
        """``p(value, σ)``."""
        return Form(self.p.subs({"t": value}))

    def reflected(self, tau: bool, sigma: bool) -> "Form":
        """τ → 1 − τ and/or σ → 1 − σ."""
        t, s, *u = self._gens()
        return Form(self.p.compose(1 - t if tau else t, 1 - s if sigma else s, *u))

    def swapped(self) -> "Form":
        t, s, *u = self._gens()
        return Form(self.p.compose(s, t, *u))

    def in_sigma(self) -> "Form":
        """``p(τ)`` written in σ."""
        t, s, *u = self._gens()
        return Form(self.p.compose(s, s, *u))

    def d_tau(self) -> "Form":
        return Form(self.p.derivative("t"))

    def integral(self, var: str) -> "Form":
        """``∫₀¹ p d(var)``."""
        q = self.p.integral(var)
        return Form(q.subs({var: 1}) - q.subs({var: 0}))

    def spans(self) -> Iterator[tuple[Fraction, Fraction]]:
        """Per monomial ``τ^i σ^j``: its coefficient's value at the box's centre (u = 0) and how
        far the box moves it at most."""
        centre: dict[tuple[int, int], Fraction] = {}
        spread: dict[tuple[int, int], Fraction] = {}
        for exps, c in self.p.terms():
            key = (exps[0], exps[1])
            q = Fraction(int(c.p), int(c.q))
            if any(exps[2:]):
                spread[key] = spread.get(key, Fraction(0)) + abs(q)
            else:
                centre[key] = q
        for key in centre.keys() | spread.keys():
            yield centre.get(key, Fraction(0)), spread.get(key, Fraction(0))


def kernel_forms(method: Any, decimals: DecimalsMode, bits: int) -> tuple[Form, Form]:
    """``A(τ, σ)`` and ``B(τ)`` of ``method`` as :class:`Form` s under ``decimals``."""
    from flint import fmpq_mpoly_ctx

    mode = DecimalsMode(decimals)
    constants = method.info.constants
    enclosures = constants.enclosures(bits, mode)
    nodes = [*method.nodes, *(constants.definitions[name] for name in constants.order)]
    slots = sum(1 for node in nodes for n in xp.walk(node)
                if isinstance(n, ex.Call) or (isinstance(n, ex.Num) and n.interval(mode) is not None)
                or (isinstance(n, ex.Binary) and n.op == "/"))
    ctx = fmpq_mpoly_ctx.get(("t", "s") + tuple(f"u{k}" for k in range(slots)), "lex")
    builder = _Builder(ctx, mode, bits, enclosures)
    for name in constants.order:
        builder.names[name] = builder.form(constants.definitions[name])
    A, B = (builder.form(node) for node in method.nodes)
    return A, B


class _Builder:
    """Folds a kernel's expressions into forms, a variable per interval number met."""

    def __init__(self, ctx: Any, mode: DecimalsMode, bits: int, enclosures: dict[str, Interval]):
        self.ctx, self.mode, self.bits, self.enclosures = ctx, mode, bits, enclosures
        self.gens = ctx.gens()
        self.names: dict[str, Form] = {}
        self.literals: dict[int, Form] = {}  # by node: one variable per literal, however often met
        self.used = 0

    def _number(self, box: Interval) -> Form:
        """A number of the box: exact, or ``m + r·u`` for a new variable u."""
        zero = Form(self.ctx.from_dict({}))
        if box.is_point:
            return zero.constant(box.lo)
        u = self.gens[2 + self.used]
        self.used += 1
        return zero.constant(box.mid) + Form(u).scaled(box.rad)

    def _literal(self, n: ex.Num | ex.Call) -> Form:
        if id(n) not in self.literals:
            box = n.interval(self.mode) if isinstance(n, ex.Num) else None
            if isinstance(n, ex.Call):
                self.literals[id(n)] = self._number(xp.enclose(n, self.bits, self.mode, self.enclosures))
            else:
                self.literals[id(n)] = self._number(Interval(*box) if box is not None else Interval.point(n.value))
        return self.literals[id(n)]

    def form(self, node: ex.Expr) -> Form:
        def combine(n: ex.Expr, vals: list[Form]) -> Form:
            if isinstance(n, ex.Name):
                if n.name in ("tau", "sigma"):
                    return Form(self.gens[0 if n.name == "tau" else 1])
                return self.names[n.name]
            if isinstance(n, (ex.Num, ex.Call)):
                return self._literal(n)
            if isinstance(n, ex.Unary):
                return -vals[0]
            if isinstance(n, ex.Power):
                k = xp.evaluate_exact(n.exponent, {})
                assert k is not None and k.denominator == 1 and k >= 0  # checked when the kernel was read
                out = vals[0].constant(Fraction(1))
                for _ in range(int(k)):
                    out = out * vals[0]
                return out
            left, right = vals
            if n.op in "+-":
                return left + right if n.op == "+" else left - right
            if n.op == "*":
                return left * right
            return left * self._reciprocal(right)

        form: Form = xp.fold(node, combine, xp.polynomial_operands)
        return form

    def _reciprocal(self, divisor: Form) -> Form:
        """``1/divisor`` (a number: checked when the kernel was read): exact, or a new
        variable over the reciprocal of the divisor's range."""
        (centre, spread), = list(divisor.spans()) or [(Fraction(0), Fraction(0))]
        if spread == 0 and centre != 0:
            return divisor.constant(1 / centre)
        if abs(centre) <= spread:
            raise NoForm
        return self._number(Interval(centre - spread, centre + spread).reciprocal())
