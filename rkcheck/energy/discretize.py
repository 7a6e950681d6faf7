"""A continuous-stage method discretised by a quadrature rule (definitions §6):
``a_ij = b_j A(c_i, c_j)``, ``b_i = b_i B(c_i)``, written exactly.

**The degree it keeps** (the line-integral argument of HBVMs, Brugnano–Iavernaro–
Trigiante 2010): let the kernel have the certificate of :mod:`rkcheck.energy.continuous`
(``A(0,σ) = 0``, ``A(1,σ) = B(σ)``, ``∂τA`` symmetric) and τ-degree p, and let the rule
have quadrature order q (exact for polynomials of degree < q).  The discrete method's
stage path ``u(τ) = y₀ + h Σ_j b_j A(τ, c_j) f(Y_j)`` is a polynomial of degree p with
``u(c_i) = Y_i``, ``u(0) = y₀``, ``u(1) = y₁``.  For f = J∇H with H of degree m,
``H(y₁) − H(y₀) = ∫₀¹ ∇H(u)ᵀu' dτ = h Σ_j b_j ∫₀¹ ∂τA(τ, c_j) ∇H(u(τ))ᵀ J ∇H(Y_j) dτ``;
the integrand has τ-degree ``(p − 1) + (m − 1)p = mp − 1``, so when ``mp ≤ q`` the rule
integrates it exactly and ``ΔH = h Σ_ij b_i b_j ∂τA(c_i, c_j) ∇H(Y_i)ᵀJ∇H(Y_j) = 0``
(∂τA symmetric, J skew).  Every energy condition for degree ≤ ``⌊q/p⌋`` then holds.
For HBVM(k, s) (Gauss-k, p = s, q = 2k) this is Brugnano–Iavernaro–Trigiante's 2k/s.
"""

from __future__ import annotations

import dataclasses
import re
from typing import Any

from rkcheck.errors import UserError
from rkcheck.methods.closed_forms import MAX_EXACT_NODES
from rkcheck.methods.continuous import ContinuousMethod
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Entry
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.precision import bits_for_digits
from rkcheck.numbers.reading import DecimalsMode

#: rule names: gauss-k, radau-i-k, radau-ii-k, lobatto-k, newton-cotes-k
RULE_PATTERN = re.compile(r"(gauss|radau-i|radau-ii|lobatto|newton-cotes)-(\d+)")
MAX_RULE_NODES = 20
#: significant digits of the decimals written for a rule with more than
#: :data:`~rkcheck.methods.closed_forms.MAX_EXACT_NODES` irrational nodes (as ``rkcheck new``)
DECIMAL_DIGITS = 60


@dataclasses.dataclass(frozen=True)
class Discretisation:
    """The written tableau's pieces and what the discretisation keeps."""

    constants: dict[str, str]
    A: list[list[str]]
    b: list[str]
    c: list[str]
    rule: str
    quadrature_order: int
    kept_degree: int | None  # None: no kernel certificate, no degree guaranteed
    reason: str


def _rule_texts(spec: Any) -> tuple[list[str], list[str], dict[str, str], int, str]:
    """Node and weight texts (possibly naming constants), those constants, the rule's
    quadrature order and its name, for a rule name or a tableau (its b and c)."""
    if not isinstance(spec, str):
        return _tableau_rule(spec)
    m = RULE_PATTERN.fullmatch(spec.strip().lower())
    if m is None:
        raise UserError(f"unknown rule {spec!r}: gauss-K, radau-i-K, radau-ii-K, lobatto-K, newton-cotes-K, "
                        "or a tableau file", "rule")
    name, k = m.group(1), int(m.group(2))
    if not 1 <= k <= MAX_RULE_NODES:
        raise UserError(f"{k} nodes: a rule has 1 to {MAX_RULE_NODES} (MAX_RULE_NODES)", "rule")
    if name == "newton-cotes":
        if k < 2:  # equispaced with both ends (as lobatto-K): one node cannot be both
            raise UserError("newton-cotes needs at least 2 nodes (both ends of [0, 1])", "rule")
        from rkcheck.methods.quadrature import rational_rule

        x, w = rational_rule(k)
        order = k + 1 if k % 2 == 1 else k  # symmetric: an odd count gains one degree
        return [str(v) for v in x], [str(v) for v in w], {}, order, f"newton-cotes-{k}"
    from rkcheck.methods.closed_forms import lagrange_integral_text
    from rkcheck.methods.quadrature import rule

    r = rule(name, k)
    order = r.order()
    if r.is_rational:
        x, w = r.exact_nodes_weights()
        return [str(v) for v in x], [str(v) for v in w], {}, order, f"{name}-{k}"
    forms = r.node_closed_forms()
    if forms is None:  # every named rule's nodes have root(p, k) forms; kept for the type
        raise UserError(f"the nodes of {name}-{k} have no exact form", "rule")
    cn = [f"c{i + 1}" for i in range(k)]
    consts = {cn[i]: forms[i] for i in range(k)} | {f"w{j + 1}": lagrange_integral_text(cn, j, "0", "1")
                                                    for j in range(k)}
    return cn, [f"w{j + 1}" for j in range(k)], consts, order, f"{name}-{k}"


def _tableau_rule(tab: Any) -> tuple[list[str], list[str], dict[str, str], int, str]:
    """The rule (b, c) of a tableau (c = A·1 when it gives none)."""
    from rkcheck.evaluation.values import TableauValues
    from rkcheck.numbers.reading import Reading
    from rkcheck.properties import scalars as sc
    from rkcheck.properties.orders import quadrature_order

    consts = {f"r_{k}": xp.to_text(v) for k, v in tab.info.constants.definitions.items()}
    rename: dict[str, ex.Expr] = {k: ex.Name(f"r_{k}", 1) for k in tab.info.constants.definitions}

    def text(e: Any) -> str:
        return xp.to_text(xp.substituted(e.node, rename))

    c = [text(e) for e in tab.c] if tab.c is not None else [
        " + ".join(f"({text(e)})" for e in row) for row in tab.A]
    b = [text(e) for e in tab.b]
    # the quadrature order of the nodes the tableau is built on: the file's c where it
    # gives one (which may differ from A·1), through a tableau whose row sums are c
    if tab.c is not None:
        zero = Entry.of(0)
        tab = dataclasses.replace(tab, A=tuple((ci, *[zero] * (len(tab.c) - 1)) for ci in tab.c), c=None)
    values = TableauValues(tab, Reading(DecimalsMode.EXACT))
    order = quadrature_order(*sc.tableau_values(values)).order
    return c, b, consts, order, tab.info.source


def discretize(method: ContinuousMethod, rule_spec: Any) -> Discretisation:
    """The tableau of ``method`` on the rule ``rule_spec`` (a name such as ``gauss-3``,
    or a :class:`~rkcheck.methods.tableau.Tableau` whose b and c are the rule), as exact
    entry texts, and the degree it keeps (module docstring)."""
    from rkcheck.energy.continuous import kernel_facts

    decimal = _decimal_rule(rule_spec)
    if decimal is None:
        c, w, consts, order, name = _rule_texts(rule_spec)
    else:
        nodes, weights, bits, order, name = decimal
        c, w, consts = [], [], {}
    own = {k: xp.to_text(v) for k, v in method.info.constants.definitions.items()}
    clash = sorted(set(own) & set(consts))
    if clash:
        raise UserError(f"the kernel's constants {', '.join(clash)} clash with the rule's names; rename them",
                        "constants")
    consts = own | consts
    A_node, B_node = method.nodes
    k = len(c)

    def node(t: str) -> ex.Expr:
        return ex.parse(f"({t})")

    if decimal is not None:
        consts, A, b, c_out = _decimals(method, nodes, weights, bits)
    else:
        A = [[f"{_par(w[j])}*({xp.to_text(xp.substituted(A_node, {'tau': node(c[i]), 'sigma': node(c[j])}))})"
              for j in range(k)] for i in range(k)]
        b = [f"{_par(w[i])}*({xp.to_text(xp.substituted(B_node, {'tau': node(c[i])}))})" for i in range(k)]
        consts, A, b, c_out = _simplified(A, b, c, consts)
    facts = kernel_facts(method, None)
    p = method.kernel.deg_tau
    if facts.certificate.certified and 0 < p and order // p >= 2:
        kept = order // p
        reason = (f"every energy condition holds for Hamiltonians of degree ≤ {kept} = ⌊q/p⌋ (quadrature order "
                  f"q = {order}, kernel degree p = {p} in τ; line-integral argument)")
    elif facts.certificate.certified and p > 0:  # ⌊q/p⌋ ≤ 1: not even quadratic Hamiltonians
        # degree 1 has no energy condition (definitions §3): every method preserves linear H
        kept, reason = None, (f"the quadrature order q = {order} is below twice the kernel's degree p = {p} in τ "
                              f"(⌊q/p⌋ = {order // p}): no degree with an energy condition is guaranteed")
    elif facts.certificate.certified:
        kept, reason = None, "the kernel is constant in τ: energy is preserved for every degree"
    else:
        kept, reason = None, f"{facts.certificate.reason}: no degree is guaranteed"
    if method.is_box(DecimalsMode.AUTO):  # the rule's entries fold the decimals into exact numbers
        reason += (f"; the kernel's decimals (as few as {method.rounded_digits} significant digits) are taken at "
                   "face value: the tableau is exact, the centre of the box they stand for")
    if decimal is not None:
        reason += (f"; the nodes of {name} have no short exact form (more than {MAX_EXACT_NODES} nodes): the entries "
                   f"are written as {DECIMAL_DIGITS}-digit decimals of the exact ones, read back as rounded to their "
                   "last digit")
    return Discretisation(consts, A, b, c_out, name, order, kept, reason)


def _decimal_rule(spec: Any) -> tuple[list[Interval], list[Interval], int, int, str] | None:
    """The enclosed nodes and weights of a named rule with more than MAX_EXACT_NODES
    irrational nodes, whose exact entries (Lagrange integrals of root(p, k) nodes) run to
    megabytes, the bits they hold, its quadrature order and name (None: the rule is
    written exactly)."""
    if not isinstance(spec, str):
        return None
    from rkcheck.methods.quadrature import rule

    m = RULE_PATTERN.fullmatch(spec.strip().lower())
    if m is None or m.group(1) == "newton-cotes" or not MAX_EXACT_NODES < int(m.group(2)) <= MAX_RULE_NODES:
        return None  # _rule_texts reads it, or refuses it
    name, k = m.group(1), int(m.group(2))
    r = rule(name, k)
    if r.is_rational:
        return None
    bits = bits_for_digits(DECIMAL_DIGITS, 64)
    c, w = r.enclosures(bits)
    return c, w, bits, r.order(), f"{name}-{k}"


def _decimals(method: ContinuousMethod, c: list[Interval], w: list[Interval], bits: int) -> Any:
    """The tableau's entries as decimals of DECIMAL_DIGITS digits (the kernel's own
    constants folded in at face value)."""
    from rkcheck.numbers.formatting import decimal_string

    A_node, B_node = method.nodes
    consts = method.info.constants.enclosures(bits, DecimalsMode.EXACT)

    def text(x: Interval) -> str:
        # an enclosure of 0 has no digit to print: its mid-point is noise
        return str(x.lo) if x.is_point else "0" if x.contains_zero() else decimal_string(
            x.mid, DECIMAL_DIGITS, keep_zeros=True)

    def at(node: ex.Expr, tau: Interval, sigma: Interval | None = None) -> Interval:
        where = consts | {"tau": tau} | ({"sigma": sigma} if sigma is not None else {})
        return xp.enclose(node, bits, DecimalsMode.EXACT, where)

    k = len(c)
    A = [[text(w[j] * at(A_node, c[i], c[j])) for j in range(k)] for i in range(k)]
    b = [text(w[i] * at(B_node, c[i])) for i in range(k)]
    return {}, A, b, [text(x) for x in c]


def _par(text: str) -> str:
    return text if re.fullmatch(r"[A-Za-z0-9_/]+", text) else f"({text})"


def _simplified(A: list[list[str]], b: list[str], c: list[str], consts: dict[str, str]) -> Any:
    """Exact values in place of the expressions when they are rational or need one square
    root (:func:`~rkcheck.methods.closed_forms.simplified_texts`)."""
    from rkcheck.methods.closed_forms import simplified_texts

    try:
        return simplified_texts(consts, A, b, c)
    except UserError:
        return consts, A, b, c
