"""A family's coefficients as exact entry texts, and as exact values in their field.

The nodes of a family's rule are written in closed form (square roots, or ``root(p, k)``
for a root of a named polynomial; :meth:`QuadratureRule.node_closed_forms`), every
weight and coefficient as an exact expression over them (Lagrange integrals written out
with elementary symmetric sums; definitions §1).  :func:`family_exact_values` places them
in one number field (:mod:`rkcheck.numbers.algebraic`), which is what makes ``[family]``
tableaux and ``rkcheck new`` files exact wherever the nodes are algebraic of modest degree.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from itertools import combinations
from typing import TYPE_CHECKING, Any

from rkcheck.methods.quadrature import shifted_legendre
from rkcheck.numbers.polynomials import integral

if TYPE_CHECKING:
    from rkcheck.methods.family_spec import FamilySpec


def _par(text: str) -> str:
    return text if _atomic(text) else f"({text})"


def _atomic(text: str) -> bool:
    depth = 0
    for i, ch in enumerate(text):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif depth == 0 and ch in "+-" and i > 0:
            return False
        elif depth == 0 and ch in "*/" :
            return False
    return not text.startswith("-")


def _esym(names: list[str], k: int) -> str:
    """Elementary symmetric polynomial e_k of the names, as text."""
    if k == 0:
        return "1"
    return " + ".join("*".join(c) for c in combinations(names, k))


def _power(x: str, k: int) -> str:
    if x == "1" or k == 1:
        return x
    return f"{_par(x)}^{k}"


def lagrange_integral_text(names: list[str], i: int, lo: str, hi: str) -> str:
    """``∫_lo^hi ℓ_i(x) dx`` over the nodes ``names`` as an exact expression."""
    others = names[:i] + names[i + 1:]
    n = len(others)
    num = ""
    for k in range(n + 1):  # coefficient of x^k in Π (x − c_j) is (−1)^(n−k) e_(n−k)
        e = _esym(others, n - k)
        if hi == "1" and lo == "0":
            upper = "1"
        elif lo == "0":
            upper = _power(hi, k + 1)
        else:
            upper = f"({_power(hi, k + 1)} - {_power(lo, k + 1)})"
        if e == "1":
            factor = upper
        elif upper == "1":
            factor = _par(e)
        else:
            factor = f"{_par(e)}*{upper}"
        term = factor if k == 0 else f"{factor}/{k + 1}"
        negative = (n - k) % 2 == 1
        if not num:
            num = f"-{term}" if negative else term
        else:
            num = f"{num} {'-' if negative else '+'} {term}"
    factors = [f"({names[i]} - {o})" for o in others]
    if not factors:
        return num
    den = factors[0] if len(factors) == 1 else "(" + "*".join(factors) + ")"
    return f"({num})/{den}"


def _poly_text(p: list[Fraction], x: str) -> str:
    out = ""
    for k, coeff in enumerate(p):
        if coeff == 0:
            continue
        mag = abs(coeff)
        body = _power(x, k) if k else ""
        if not body:
            t = str(mag)
        elif mag == 1:
            t = body
        else:
            t = f"{mag}*{body}"
        if not out:
            out = t if coeff > 0 else f"-{t}"
        else:
            out += f" {'+' if coeff > 0 else '-'} {t}"
    return out or "0"


#: most nodes written as exact Lagrange forms: their texts grow like 2^s (symmetric sums
#: over the other nodes; 19 MB of text at s = 20), and the field of 9 or more nodes is far
#: beyond the degree limit of :mod:`rkcheck.numbers.algebraic` anyway
MAX_EXACT_NODES = 8


def expression_texts(spec: FamilySpec) -> tuple[dict[str, str], list[list[str]], list[str], list[str]] | None:
    """(constants, A, b, c) as exact entry texts, or None without closed-form nodes or
    with more than :data:`MAX_EXACT_NODES` of them."""
    forms = _closed_forms(spec)
    if forms is None:
        return None
    n = len(forms)
    c = [f"c{i + 1}" for i in range(n)]
    bn = [f"b{i + 1}" for i in range(n)]
    consts = {c[i]: forms[i] for i in range(n)}
    for j in range(n):
        consts[bn[j]] = lagrange_integral_text(c, j, "0", "1")
    name = spec.name
    if name == "avf":
        A = [[f"{c[i]}*{bn[j]}" for j in range(n)] for i in range(n)]
    elif name in ("gauss", "lobatto-iiia", "radau-iia"):
        A = [[lagrange_integral_text(c, j, "0", c[i]) for j in range(n)] for i in range(n)]
    elif name in ("lobatto-iiib", "radau-ia"):
        A = [
            [
                (f"{bn[j]}/{bn[i]}*" if i != j else "") + lagrange_integral_text(c, i, c[j], "1")
                for j in range(n)
            ]
            for i in range(n)
        ]
    elif name == "hbvm":
        A = []
        for i in range(n):
            row = []
            for l in range(n):
                parts = []
                for j in range(spec.s):
                    P = shifted_legendre(j)
                    g = _poly_text(integral(P), c[i])
                    p = _poly_text(P, c[l])
                    parts.append(f"{2 * j + 1}*({g})*({p})")
                row.append(f"{bn[l]}*({' + '.join(parts)})")
            A.append(row)
    else:
        z, beta = spec.zeta, spec.beta
        assert z is not None and beta is not None  # the kernel family is given both (parse_spec)
        A = [
            [f"{c[i]}*{bn[j]} + ({beta})*(({z - 1}) - 2*({z})*{c[i]})*{bn[j]}*(1 - 2*{c[j]})" for j in range(n)]
            for i in range(n)
        ]
    return consts, A, bn, c


def _closed_forms(spec: FamilySpec) -> list[str] | None:
    """The texts of the rule's nodes, or None without closed forms or with more than
    :data:`MAX_EXACT_NODES` nodes: the families whose entries are written exactly."""
    r = spec.base_rule()
    return None if r.s > MAX_EXACT_NODES else r.node_closed_forms()


def exact_node_polynomial(spec: FamilySpec) -> list[Fraction] | None:
    """The monic node polynomial (ascending) of a family written exactly, else None."""
    if _closed_forms(spec) is None:
        return None
    P = [Fraction(x) for x in spec.base_rule().nodes[0].poly]
    return [x / P[-1] for x in P]


def lagrange_parts(P: list[Fraction]) -> tuple[list[Any], Any]:
    """``(U, W)`` over the roots c of the monic square-free ``P`` (fmpq_polys reduced
    modulo P): the Lagrange basis polynomial of node j is ``ℓ_j(x) = Σ_k U_k(c_j) x^k`` and
    its integral over [0, 1] is ``W(c_j)`` (see :func:`evaluation_texts`)."""
    from flint import fmpq_poly

    from rkcheck.numbers.polynomials import inverse_mod, to_flint

    n = len(P) - 1
    f = to_flint(list(P))
    V = inverse_mod(f.derivative(), f)
    U = [(to_flint([P[m] for m in range(k + 1, n + 1)]) * V) % f for k in range(n)]
    W = sum((u / (k + 1) for k, u in enumerate(U)), fmpq_poly([])) % f
    return U, W


def simplified_texts(consts: dict[str, str], A: list[list[str]], b: list[str],
                     c: list[str]) -> tuple[dict[str, str], list[list[str]], list[str], list[str]]:
    """The same entries as exact values in their number field
    (:mod:`rkcheck.numbers.algebraic`): ``5/36 - sqrt(15)/30`` when the entries are
    rational or one square root suffices; otherwise (nested roots, ``root(p, k)``) the
    node constants and Lagrange forms, which are exact too."""
    from rkcheck.numbers import grammar as ex
    from rkcheck.numbers.algebraic import NotAlgebraic
    from rkcheck.numbers.field_builder import field_of

    s = len(b)
    flat = [x for row in A for x in row] + list(b) + list(c)
    try:
        found = field_of([ex.parse(x) for x in flat], {k: ex.parse(v) for k, v in consts.items()})
    except NotAlgebraic:
        return consts, A, b, c
    if found.field is None:
        texts = [str(v) for v in found.values]
    elif found.field.sqrt_of:
        texts = [v.text() for v in found.values]
    else:
        # in a field of higher degree the coefficients in a primitive element are long
        # and opaque; the node constants and Lagrange forms say more (and are exact)
        return consts, A, b, c
    A_t = [texts[i * s:(i + 1) * s] for i in range(s)]
    return {}, A_t, texts[s * s:s * s + s], texts[s * s + s:]


@lru_cache(maxsize=16)
def family_exact_values(spec: FamilySpec) -> Any:
    """The family's ``(field, A, b, c)`` exactly (a :class:`~rkcheck.numbers.algebraic.FieldValues`
    with ``field`` None over Q), or None with the reason when the nodes have no closed form
    or their field exceeds the degree limit.  Kept per spec (the values are never mutated),
    and the field of the nodes per set of nodes (:func:`_nodes_field`).

    The entries are evaluated from :func:`evaluation_texts`, polynomials in the nodes,
    not from the Lagrange forms people read: the same values without a division in the
    field (as Lagrange forms the Gauss-6 nodes' weights would cost a third of a second)."""
    from rkcheck.numbers import grammar as ex
    from rkcheck.numbers.algebraic import NotAlgebraic
    from rkcheck.numbers.field_builder import evaluate_in

    texts = expression_texts(spec)
    if texts is None:
        return None, f"the nodes have no closed form in roots, or there are more than {MAX_EXACT_NODES}"
    consts, A, b, c = texts
    nodes = [f"c{i + 1}" for i in range(len(b))]
    order = _adjoining_order(consts, [x for row in A for x in row] + list(b) + list(c), set(nodes))
    try:
        base = _nodes_field(tuple((name, consts[name]) for name in order))
    except NotAlgebraic as err:
        return None, str(err)
    trees = evaluation_trees(spec)
    assert trees is not None  # closed-form nodes, as expression_texts found
    _, definitions, A_e, b_e = trees
    entries = [x for row in A_e for x in row] + list(b_e) + [ex.parse(x) for x in c]
    return evaluate_in(base, order, entries, definitions), None


@lru_cache(maxsize=16)
def evaluation_trees(spec: FamilySpec) -> tuple[list[Fraction], dict[str, Any], list[list[Any]], list[Any]] | None:
    """``(P, definitions, A, b)``: the monic node polynomial and :func:`evaluation_texts`
    parsed, for the field's values; None without closed-form nodes."""
    from rkcheck.numbers import grammar as ex

    texts = expression_texts(spec)
    P = exact_node_polynomial(spec)
    if texts is None or P is None:
        return None
    definitions, A, b = evaluation_texts(spec, P, texts[1])
    return (P, {name: ex.parse(text) for name, text in definitions.items()},
            [[ex.parse(x) for x in row] for row in A], [ex.parse(x) for x in b])


def _adjoining_order(consts: dict[str, str], entries: list[str], nodes: set[str]) -> list[str]:
    """The nodes in the order in which evaluating the Lagrange-form ``entries`` one by one
    (every constant on its first use) first meets them: the order their generators are
    adjoined in, which fixes the primitive element θ that reports write irrational values
    in — the same θ whichever texts the values are then computed from."""
    from rkcheck.numbers import grammar as ex
    from rkcheck.numbers.expressions import walk

    order: dict[str, None] = {}
    seen: set[str] = set()

    def meet(text: str) -> None:
        for node in walk(ex.parse(text)):
            if isinstance(node, ex.Name) and node.name in consts and node.name not in seen:
                seen.add(node.name)
                if node.name in nodes:
                    order[node.name] = None
                else:
                    meet(consts[node.name])

    for text in entries:
        meet(text)
    return list(order) + [name for name in consts if name in nodes and name not in order]


@lru_cache(maxsize=4)
def _nodes_field(consts: tuple[tuple[str, str], ...]) -> Any:
    """The number field of the nodes (``consts``: their names and exact texts, in the
    order their generators are adjoined) and their values in it
    (:func:`rkcheck.numbers.field_builder.field_of`): the field of the six Gauss-6 nodes,
    of degree 48, takes about half a second to build, and a catalogue or a scan meets the
    same nodes in several families (HBVM(6, 2), HBVM(6, 3), Gauss-6)."""
    from rkcheck.numbers import grammar as ex
    from rkcheck.numbers.field_builder import field_of

    names = [name for name, _ in consts]
    return field_of([ex.parse(name) for name in names], {name: ex.parse(text) for name, text in consts})


def evaluation_texts(spec: FamilySpec, P: list[Fraction],
                      A: list[list[str]]) -> tuple[dict[str, str], list[list[str]], list[str]]:
    """``(definitions, A, b)``: the family's weights and coefficients as polynomials in the
    nodes ``c1 … cn``, the roots of the node polynomial ``P`` (all of them, simple); ``A``
    (the texts people read) is kept where it is written over the nodes and weights alone.

    With ``P(x)/(x − c) = Σ_k q_k(c) x^k`` (``q_k(c) = Σ_(m>k) p_m c^(m−k−1)``) and ``V = 1/P'``
    modulo P, the Lagrange basis polynomial of node j is ``ℓ_j(x) = Σ_k U_k(c_j) x^k`` with
    ``U_k = q_k·V mod P``, so ``∫_lo^hi ℓ_j = Σ_k U_k(c_j)(hi^(k+1) − lo^(k+1))/(k + 1)``
    and ``b_j = W(c_j)``, ``W = Σ_k U_k/(k + 1) mod P``; ``1/b_i = (W⁻¹ mod P)(c_i)``.
    Every reduction is modulo P over Q, so each node's values are polynomials of degree
    below n in it: no division in the nodes' field."""
    from rkcheck.numbers.polynomials import from_flint, inverse_mod, to_flint

    n = len(P) - 1
    c = [f"c{i + 1}" for i in range(n)]
    U, W = lagrange_parts(P)
    definitions = {f"b{j + 1}": _poly_text(from_flint(W), c[j]) for j in range(n)}
    bn = list(definitions)
    name = spec.name
    if name in ("gauss", "lobatto-iiia", "radau-iia", "lobatto-iiib", "radau-ia"):
        definitions |= {f"u{k}_{j + 1}": _poly_text(from_flint(U[k]), c[j]) for k in range(n) for j in range(n)}
    if name in ("gauss", "lobatto-iiia", "radau-iia"):  # ∫_0^(c_i) ℓ_j
        A = [[" + ".join(f"{_par(_power(c[i], k + 1))}/{k + 1}*u{k}_{j + 1}" for k in range(n)) for j in range(n)]
             for i in range(n)]
    elif name in ("lobatto-iiib", "radau-ia"):  # b_j/b_i·∫_(c_j)^1 ℓ_i
        inverse = from_flint(inverse_mod(W, to_flint(list(P))))
        definitions |= {f"binv{i + 1}": _poly_text(inverse, c[i]) for i in range(n)}
        A = [[(f"{bn[j]}*binv{i + 1}*" if i != j else "")
              + "(" + " + ".join(f"(1 - {_power(c[j], k + 1)})/{k + 1}*u{k}_{i + 1}" for k in range(n)) + ")"
              for j in range(n)] for i in range(n)]
    return definitions, A, bn
