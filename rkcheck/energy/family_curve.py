"""The structured route of ``rkcheck solve`` when the quadrature conditions leave
infinitely many rules: the seed's proof, run over the whole set of rules at once.

The route of :mod:`rkcheck.energy.family_solve` needs finitely many weights and nodes.
With A and b free, the quadrature conditions of a degree-m method with ``m = 2s − 1``
leave a curve — the seed's ζ-family of rules whose nodes are the zeros of
``P_s − ζ P_{s−1}``.  Its ideal Q (in the weights and the nodes x = (b, c)) is not
split into points; instead every step is done once over the ring of functions on the
set of rules, localised at the elements we divide by:

1. **Linear conditions over the rules.**  The row sums and double-bush conditions are
   linear in A with coefficients polynomials in x.  Gaussian elimination runs over
   fractions ``p/q`` of polynomials in x, an entry counting as zero when its numerator
   lies in Q (normal form modulo Q's reduced Gröbner basis).  Each division is recorded:
   where no recorded divisor vanishes, the elimination specialises to every rule of
   V(Q), so there ``A = c bᵀ + Σ k_f D_f N_f`` with polynomial directions ``D_f N_f``
   (``D_f`` clears the denominators of direction f) — when c bᵀ solves the linear
   conditions identically, which is checked.
2. **The rest.**  Every condition on that A is a polynomial in (x, k); reduced modulo
   Q they form, with Q, an ideal J.  If some k_f ≠ 0 at a zero of J, then ``1 − w·k_f``
   has a common zero with J: the polynomials in x alone of the Gröbner basis of
   ``J + (1 − w k_f)`` vanish at its rule.  When they, with Q, have finitely many
   zeros, every rule outside those points and outside the zeros of the divisors has
   exactly one method: A = c bᵀ, the AVF method over that rule.
3. **The exceptional rules** (finitely many, exactly) go through the finite route, one
   Galois orbit at a time; what they add beyond their AVF method is reported as its own
   component — the seed's case analysis (ζ = 0, Radau) found by computation.

Every step is exact; nothing is sampled.  When a step does not apply (the rules are
not a set of AVF methods generically, the exceptional rules are not finitely many, the
entries lie in a number field), the caller falls back to the plain route.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence

from rkcheck.numbers.groebner import (
    Terms,
    dimension,
    groebner,
    integer_dicts,
    leading_monomial,
)
from rkcheck.numbers.parametric import ParameterRing, fresh_name
from rkcheck.numbers.solving import Component


class RuleRing:
    """Polynomials in the weights and nodes modulo the quadrature ideal Q (its reduced
    degrevlex Gröbner basis ``basis`` over ``names``), with the divisors used so far."""

    def __init__(self, basis: list[Terms], names: tuple[str, ...]):
        from flint import fmpq_mpoly_ctx, fmpz_mpoly_ctx, fmpz_mpoly_vec

        self.names = names
        self.ctx = fmpq_mpoly_ctx.get(names, "degrevlex")
        self.zctx = fmpz_mpoly_ctx.get(names, "degrevlex")
        self.basis = basis
        self.vec = fmpz_mpoly_vec([self.zctx.from_dict(d) for d in basis], self.zctx)
        self.divisors: list[Any] = []

    def in_ideal(self, p: Any) -> bool:
        """Whether p (over Q, in this ring's variables) lies in Q."""
        return bool(p.is_zero() or integral(p, self.zctx).reduction_primitive_part(self.vec).is_zero())

    def fraction(self, p: Any) -> "RuleFraction":
        return RuleFraction(self, p, self.ctx.constant(1))


def integral(p: Any, zctx: Any) -> Any:
    """p with its denominators cleared, over Z (the same zeros, the same ideal)."""
    return zctx.from_dict(integer_dicts([p])[0])


class RuleFraction:
    """``num/den`` on the rules of Q: zero when num lies in Q.  Division records its
    divisor (the elimination is valid only where the divisors do not vanish).  The
    attribute ``field`` lets :func:`rkcheck.energy.double_bush.nullspace_exact` take it
    as a field element."""

    __slots__ = ("ring", "num", "den")
    field = "rules"

    def __init__(self, ring: RuleRing, num: Any, den: Any):
        g = num.gcd(den)
        if not g.is_constant():
            num, den = num / g, den / g
        self.ring, self.num, self.den = ring, num, den

    def _lift(self, o: Any) -> "RuleFraction":
        if isinstance(o, RuleFraction):
            return o
        from fractions import Fraction

        from flint import fmpq

        o = Fraction(o)
        return RuleFraction(self.ring, self.ring.ctx.constant(fmpq(o.numerator, o.denominator)), self.ring.ctx.constant(1))

    def __add__(self, o: Any) -> "RuleFraction":
        o = self._lift(o)
        return RuleFraction(self.ring, self.num * o.den + o.num * self.den, self.den * o.den)

    __radd__ = __add__

    def __neg__(self) -> "RuleFraction":
        return RuleFraction(self.ring, -self.num, self.den)

    def __sub__(self, o: Any) -> "RuleFraction":
        return self + (-self._lift(o))

    def __rsub__(self, o: Any) -> "RuleFraction":
        return self._lift(o) - self

    def __mul__(self, o: Any) -> "RuleFraction":
        o = self._lift(o)
        return RuleFraction(self.ring, self.num * o.num, self.den * o.den)

    __rmul__ = __mul__

    def __pow__(self, k: int) -> "RuleFraction":
        return RuleFraction(self.ring, self.num ** k, self.den ** k)

    def __truediv__(self, o: Any) -> "RuleFraction":
        o = self._lift(o)
        if o.is_zero():
            raise ZeroDivisionError("division by zero on the rules")
        if not o.num.is_constant():
            self.ring.divisors.append(o.num)
        return RuleFraction(self.ring, self.num * o.den, self.den * o.num)

    def __rtruediv__(self, o: Any) -> "RuleFraction":
        return self._lift(o) / self

    def is_zero(self) -> bool:
        return self.ring.in_ideal(self.num)

    def __eq__(self, o: object) -> bool:
        return (self - self._lift(o)).is_zero()

    def __ne__(self, o: object) -> bool:
        return not self == o

    __hash__ = None  # type: ignore[assignment]


# ------------------------------------------------------------------ the route


def solve_on_rules(family: Any, layout: Any, degree: int | None, order: int, classical: int | None,
                   extra: Sequence[Any], deadline: float) -> tuple[int, list[Component], list[Any]] | None:
    """``(dimension of the rules, components, Galois orbits of the exceptional rules)``
    when the route applies
    (module docstring), else None.  The first component is the AVF methods over every
    rule of Q outside the exceptional ones (present when c bᵀ solves every condition
    there)."""
    from rkcheck.energy.family_rules import quadrature_system

    if family.ring.field is not None:
        return None
    polys, qctx, nodes = quadrature_system(family, layout, degree, order, extra)
    names = tuple(qctx.names())
    basis = groebner(integer_dicts(polys), names, "degrevlex", deadline)
    dim = dimension([leading_monomial(d, "degrevlex") for d in basis], len(names)) if basis else len(names)
    if dim != 1:  # on a surface of rules the exceptional ones are curves: not this route
        return None
    rules = RuleRing(basis, names)
    directions = _linear_part(family, layout, rules, nodes, degree, order)
    if directions is None:
        return None
    R, A, scales = directions
    kernel_names = R.parameters[len(names):]
    rest, at_avf = _remaining(layout, rules, R, A, degree, order, classical)
    sets = [[p] for p in _irreducible_factors(rules.divisors + scales)]
    sets += [_rules_with_nonzero(rules, rest, kernel_names, f, deadline) for f in range(len(kernel_names))]
    if at_avf:  # c bᵀ fails somewhere: only finitely many rules may keep it
        sets.append(at_avf)
    exceptional = _exceptional_orbits(polys, qctx, sets, deadline)
    if exceptional is None:
        return None
    components: list[Component] = []
    if not at_avf:
        components.append(Component(dim, avf=True, equations=_avf_equations(family, rules, polys, nodes)))
    return dim, components, exceptional


def _linear_part(family: Any, layout: Any, rules: RuleRing, nodes: list[str], degree: int | None,
                 order: int) -> tuple[ParameterRing, list[list[Any]], list[Any]] | None:
    """A over a ring in (x, k): ``c bᵀ + Σ k_f D_f N_f`` (module docstring, step 1), the
    kernel coordinates' names and the D_f; None when c bᵀ does not solve the linear
    conditions on the rules."""
    from rkcheck.energy.double_bush import nullspace_exact
    from rkcheck.energy.family_rules import double_bush_rows, row_sum_rows

    s = family.stages
    gens = dict(zip(rules.names, rules.ctx.gens()))
    b = [rules.fraction(w) for w in _weights(layout, rules)]
    c = [rules.fraction(gens[n]) for n in nodes]
    rows = row_sum_rows(c) + double_bush_rows(b, c, degree, order)
    avf = [c[i] * b[j] for i in range(s) for j in range(s)]
    if not all(sum((r[k] * avf[k] for k in range(s * s)), r[-1]).is_zero() for r in rows):
        return None
    _, basis = nullspace_exact(rows, s * s + 1)
    kernel = [v for v in basis if v[s * s].is_zero()]
    free = [f"__k{f + 1}" for f in range(len(kernel))]
    R = ParameterRing(rules.names + tuple(free))
    up = _embedding(rules, R)
    A = [up(avf[k].num) for k in range(s * s)]
    scales = []
    for name, v in zip(free, kernel):
        D = rules.ctx.constant(1)
        for x in v[:s * s]:
            D = D * (x.den / D.gcd(x.den))
        scales.append(D)
        for k in range(s * s):
            if not v[k].num.is_zero():
                A[k] = A[k] + up((D * v[k].num) / v[k].den) * R.parameter(name)
    return R, [A[i * s:(i + 1) * s] for i in range(s)], scales


def _weights(layout: Any, rules: RuleRing) -> list[Any]:
    """The weights as polynomials on the rules: a weight's own parameter, or its value
    (parameter-free: a constant polynomial of the family's ring)."""
    gens = dict(zip(rules.names, rules.ctx.gens()))
    return [gens[n] if n else rules.ctx.constant(sum(layout.b_fixed[i].to_dict().values(), 0))
            for i, n in enumerate(layout.b)]


def _embedding(rules: RuleRing, R: ParameterRing) -> Callable[[Any], Any]:
    n = len(R.ctx.names()) - len(rules.names)

    def up(p: Any) -> Any:
        return R.ctx.from_dict({tuple(m) + (0,) * n: c for m, c in p.to_dict().items()})

    return up


def _remaining(layout: Any, rules: RuleRing, R: ParameterRing, A: list[list[Any]], degree: int | None,
               order: int, classical: int | None) -> tuple[list[Any], list[Terms]]:
    """The conditions on A reduced modulo Q (integer polynomials over (x, k), degrevlex),
    and those in x alone that are left at k = 0 (empty when c bᵀ solves every condition
    on every rule)."""
    from flint import fmpz_mpoly_ctx, fmpz_mpoly_vec

    from rkcheck.energy.family_conditions import classical_conditions, energy_conditions

    b = [_embedding(rules, R)(w) for w in _weights(layout, rules)]
    conds = [cd.polynomial for cd in energy_conditions(R, A, b, order, degree)]
    if classical is not None:
        conds += [cd.polynomial for cd in classical_conditions(R, A, b, classical)]
    Z = fmpz_mpoly_ctx.get(R.ctx.names(), "degrevlex")
    n = len(R.parameters) - len(rules.names)
    vec = fmpz_mpoly_vec([Z.from_dict({tuple(m) + (0,) * n: c for m, c in d.items()}) for d in rules.basis], Z)
    rest = [q for q in (integral(p, Z).reduction_primitive_part(vec) for p in conds if not p.is_zero())
            if not q.is_zero()]
    origin = list(Z.gens()[:len(rules.names)]) + [Z.constant(0)] * n
    at_avf = []
    for q in rest:
        q0 = q.compose(*origin).reduction_primitive_part(vec)
        if not q0.is_zero():
            at_avf.append({tuple(m)[:len(rules.names)]: int(c) for m, c in q0.to_dict().items()})
    return rest, at_avf


def _rules_with_nonzero(rules: RuleRing, rest: list[Any], free: Sequence[str], f: int, deadline: float) -> list[Terms]:
    """Polynomials in x alone vanishing at every rule where the conditions have a zero
    whose first nonzero kernel coordinate is k_f: those of the Gröbner basis of
    ``Q + rest + (k_1, …, k_(f−1)) + (1 − w·k_f)`` (the earlier coordinates set to 0
    make it far smaller; every zero with k ≠ 0 has a first nonzero coordinate)."""
    x = len(rules.names)
    names = rules.names + tuple(free) + ("__w",)
    dicts = [{tuple(m) + (0,) * (len(free) + 1): c for m, c in d.items()} for d in rules.basis]
    for q in rest:
        kept = {tuple(m) + (0,): int(c) for m, c in q.to_dict().items() if not any(m[x:x + f])}
        if kept:
            dicts.append(kept)
    w = [0] * len(names)
    w[x + f] = w[-1] = 1
    dicts.append({tuple(w): -1, (0,) * len(names): 1})
    basis = groebner(dicts, names, "degrevlex", deadline)
    return [{m[:x]: c for m, c in d.items()} for d in basis if all(not any(m[x:]) for m in d)]


def _irreducible_factors(polys: list[Any]) -> list[Terms]:
    """The distinct irreducible factors of the divisors, as integer dicts."""
    seen: dict[str, Terms] = {}
    for p in polys:
        if p.is_constant():
            continue
        for g, _ in p.factor()[1]:
            d = integer_dicts([g])[0]
            seen.setdefault(str(sorted(d.items())), d)
    return list(seen.values())


def _exceptional_orbits(polys: list[Any], qctx: Any, sets: list[list[Terms]], deadline: float) -> list[Any] | None:
    """The Galois orbits of the rules in the union of the zero sets of ``Q + set`` for
    each set, each orbit once — told apart by the reduced Gröbner basis of its points,
    which is unique (None when one of the sets is infinite)."""
    from rkcheck.energy.family_rules import finite_orbits
    from rkcheck.numbers.points import points_basis

    names = tuple(qctx.names())
    found: dict[str, Any] = {}
    for extra in sets:
        orbits = finite_orbits(list(polys) + [_in_ctx(d, qctx) for d in extra], qctx, None, None, deadline)
        if orbits is None:
            return None
        for o in orbits:
            key = points_basis([(o.phi, [o.coords[n] for n in names])], len(names))
            if not key:
                return None
            found.setdefault(str(sorted(sorted(d.items()) for d in key)), o)
    return list(found.values())


def _in_ctx(d: Terms, ctx: Any) -> Any:
    return ctx.from_dict({m: int(c) for m, c in d.items()})


def _avf_equations(family: Any, rules: RuleRing, polys: list[Any], nodes: list[str]) -> list[Any]:
    """The AVF methods over the rules, as equations in the nodes ``c1 … cs`` and the
    family's parameters: the quadrature system, ``cᵢ = Σⱼ aᵢⱼ`` and ``aᵢⱼ = cᵢ bⱼ``."""
    from flint import fmpq_mpoly_ctx

    ring = family.ring
    shown: list[str] = []
    for i in range(len(nodes)):
        shown.append(fresh_name(f"c{i + 1}", [*ring.parameters, *shown]))
    E = fmpq_mpoly_ctx.get(tuple(shown) + tuple(ring.parameters), "lex")
    g = dict(zip(E.names(), E.gens()))
    params = [g[n] for n in ring.parameters]
    images = [g[shown[nodes.index(n)]] if n in nodes else g[n] for n in rules.names]
    A = [[p.compose(*params, ctx=E) for p in row] for row in family.A]
    b = [p.compose(*params, ctx=E) for p in family.b]
    c = [g[n] for n in shown]
    out = [p.compose(*images, ctx=E) for p in polys]
    out += [ci - sum(row[1:], row[0]) for ci, row in zip(c, A)]
    out += [A[i][j] - c[i] * b[j] for i in range(len(c)) for j in range(len(c))]
    return [p for p in out if not p.is_zero()]
