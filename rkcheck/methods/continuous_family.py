"""A continuous-stage kernel with free ``[parameters]`` as a family
(:class:`~rkcheck.methods.parametric.Family`): its exact surrogate tableau
(:mod:`rkcheck.methods.continuous`) on rational nodes keeps every entry a polynomial in
the parameters, so the family machinery (conditions as polynomials, ``rkcheck solve``)
applies unchanged.  The surrogate is built for the trees a computation reads
(:meth:`~rkcheck.methods.parametric.Family.covering`): its size grows with them, and a
file is loaded with the smallest (:data:`FIRST_VERTICES`)."""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Mapping, Sequence

import numpy as np

from rkcheck.errors import UserError
from rkcheck.methods.continuous import MAX_SURROGATE_NODES
from rkcheck.methods.kernel import VARIABLES, b_in_tau
from rkcheck.methods.quadrature import rational_rule
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
    widen = partial(kernel_family, name, parameters, A, b, constants, info)
    family = _factored_family(name, parameters, info, poly, x, w, (p, q, dB))
    return dataclasses.replace(family, kernel=(A, b), reach=vertices, widen=widen)


def _factored_family(name: str, parameters: tuple[str, ...], info: MethodInfo, kernel: Any, x: list[Fraction],
                     w: list[Fraction], degrees: tuple[int, int, int]) -> Any:
    """The family of the surrogate on the nodes ``x`` with weights ``w``, its entries
    ``A_ij = w_j K(x_i, x_j)`` and ``b_i = w_i B(x_i)`` over the ring of the parameters
    (in the kernel's field, if its constants need one); A as ``V C Wᵀ`` from the
    kernel's coefficients (:class:`~rkcheck.methods.parametric.KernelMatrix`), its
    entries formed as read — never n² expressions folded one by one, nor held
    together."""
    from rkcheck.methods.parametric import Family
    from rkcheck.numbers.parametric import object_array

    p, q, dB = degrees
    entries = kernel.over(parameters)  # the ring, and the constants for --where
    ring = entries.ring
    A_poly, B_poly = kernel.values
    C = _coefficients(A_poly, kernel.ring.variables, ring, (p, q))
    D = _coefficients(B_poly, kernel.ring.variables, ring, (dB, 0))
    top = max(p, dB)
    V = object_array([ring.constant(xi ** a) for xi in x for a in range(top + 1)], (len(x), top + 1))
    W = object_array([ring.constant(wj * xj ** c) for xj, wj in zip(x, w) for c in range(q + 1)], (len(x), q + 1))
    b_values = (V[:, :dB + 1] @ D)[:, 0] * object_array([ring.constant(wj) for wj in w], (len(w),))
    entries.values = list(b_values)
    return Family(name, parameters, (), tuple(str(v) for v in b_values), entries, info,
                  factors=(np.ascontiguousarray(V[:, :p + 1]), C, W))


def _coefficients(poly: Any, names: Sequence[str], ring: Any, degrees: tuple[int, int]) -> Any:
    """The coefficients of ``τᵃσᶜ`` (a ≤ degrees[0], c ≤ degrees[1]) in ``poly`` (over
    the variables ``names``: tau, sigma and the parameters) as an array of polynomials
    in the parameters over ``ring``."""
    from rkcheck.numbers.parametric import object_array

    at_tau, at_sigma = names.index("tau"), names.index("sigma")
    rest = [i for i in range(len(names)) if i not in (at_tau, at_sigma)]
    found: dict[tuple[int, int], dict[tuple[int, ...], Any]] = {}
    for exps, c in poly.terms():
        found.setdefault((int(exps[at_tau]), int(exps[at_sigma])), {})[tuple(int(exps[i]) for i in rest)] = c
    zero = ring.constant(0)
    a_max, c_max = degrees
    return object_array([ring.ctx.from_dict(found[(a, c)]) if (a, c) in found else zero
                         for a in range(a_max + 1) for c in range(c_max + 1)], (a_max + 1, c_max + 1))

