"""A continuous-stage kernel with free ``[parameters]`` as a family
(:class:`~rkcheck.methods.parametric.Family`): its exact surrogate tableau
(:mod:`rkcheck.methods.continuous`) on rational nodes keeps every entry a polynomial in
the parameters, so the family machinery (conditions as polynomials, ``rkcheck solve``)
applies unchanged.  The surrogate is built for the trees a computation reads
(:meth:`~rkcheck.methods.parametric.Family.covering`): its size grows with them, and a
file is loaded with the smallest (:data:`FIRST_VERTICES`)."""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Mapping

from rkcheck.errors import UserError
from rkcheck.methods.continuous import (
    MAX_SURROGATE_NODES,
    VARIABLES,
    _literal,
    b_in_tau,
    rational_rule,
)
from rkcheck.methods.tableau import MethodInfo
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex

#: the surrogate a kernel family is loaded with (trees of up to 2 vertices): enough to
#: validate the file; each computation widens it to the trees it reads
FIRST_VERTICES = 2


def kernel_family(name: str, parameters: tuple[str, ...], A: str, b: str, constants: Mapping[str, ex.Expr],
                  info: MethodInfo, vertices: int = FIRST_VERTICES) -> Any:
    """The family of the kernel ``A``, ``b`` (texts in tau, sigma and the parameters), its
    entries a surrogate exact for trees of up to ``vertices`` vertices."""
    import dataclasses
    from functools import partial

    from rkcheck.methods.parametric import build_family
    from rkcheck.numbers.parametric import ParametricEntries

    clash = sorted(set(parameters) & set(VARIABLES))
    if clash:
        raise UserError(f"{clash[0]} is a kernel variable, not a parameter", f"parameters.{clash[0]}")
    nodes = []
    for place, text in (("continuous.A", A), ("continuous.b", b)):
        try:
            node = ex.parse(text)
        except UserError as err:
            raise err.located(place) from None
        for used in xp.names(node):
            if used.name not in VARIABLES and used.name not in parameters and used.name not in constants:
                raise UserError(f"unknown name {used.name!r} at column {used.column}: a kernel is a polynomial in "
                                "tau and sigma (and the [parameters] and [constants])", place)
        nodes.append(node)
    nodes[1] = b_in_tau(nodes[1], "continuous.b")
    poly = ParametricEntries(nodes, ["continuous.A", "continuous.b"], (*VARIABLES, *parameters), constants,
                             noun="tau, sigma or a parameter")
    ring = poly.ring

    def deg(p: Any, v: str) -> int:
        return max((int(m[ring.variables.index(v)]) for m in p.monoms()), default=0)

    A_poly, B_poly = poly.values
    p, q, dB = deg(A_poly, "tau"), deg(A_poly, "sigma"), deg(B_poly, "tau")
    n_nodes = max(q + (vertices - 2) * p, dB + (vertices - 1) * p) + 1
    if n_nodes > MAX_SURROGATE_NODES:
        raise UserError(f"the kernel needs {n_nodes} quadrature nodes, more than MAX_SURROGATE_NODES = "
                        f"{MAX_SURROGATE_NODES}", "continuous")
    x, w = rational_rule(n_nodes)
    A_at = [[_at(nodes[0], w[j], x[i], x[j]) for j in range(n_nodes)] for i in range(n_nodes)]
    b_at = [_at(nodes[1], w[i], x[i], Fraction(0)) for i in range(n_nodes)]
    A_text = [[text for text, _ in row] for row in A_at]
    b_text = [text for text, _ in b_at]
    parsed = [node for row in A_at for _, node in row] + [node for _, node in b_at]
    widen = partial(kernel_family, name, parameters, A, b, constants, info)
    family = build_family(name, parameters, A_text, b_text, constants, info, parsed)
    return dataclasses.replace(family, kernel=(A, b), reach=vertices, widen=widen)


def _at(node: ex.Expr, weight: Fraction, tau: Fraction, sigma: Fraction) -> tuple[str, ex.Expr]:
    """The surrogate's entry ``weight·node(tau, sigma)``: its text (shown, written out)
    and its expression (what the text parses to, built without parsing n² texts)."""
    value = xp.substituted(node, {"tau": _literal(tau), "sigma": _literal(sigma)})
    text = f"{weight.numerator}/{weight.denominator}*({xp.to_text(value)})"
    return text, ex.Binary("*", _literal(weight), value, 1)
