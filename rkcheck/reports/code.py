"""Conditions as code: the energy conditions (and the classical order conditions) written
as functions of A and b for optimisers and computer algebra (``rkcheck conditions --emit``).

Every language gets the same two pieces:

* the elementary weights ``a(t) = bᵀΦ(t)`` of the rooted trees the conditions use, with
  ``Φ(τ) = 1`` and ``Φ([t₁ … t_k]) = AΦ(t₁) ⊙ … ⊙ AΦ(t_k)`` (definitions §2);
* the residuals, in rkcheck's order (the ``conditions`` listing): for the energy
  condition of a free tree ``R = (1/L) Σ_u m_u Π_{t ∈ B₋(u)} a(t)`` with integer
  ``m_u = ±L/σ(u)`` and ``L = lcm σ(u)`` (definitions §3), and for a rooted tree t of the
  classical order conditions ``a(t) − 1/γ(t) = (γ a(t) − 1)/γ``.

Integer multipliers and one division per residual keep the output exact for exact inputs
(Python: ``Fraction``; sympy: ``Rational``; Julia: ``Rational``), and plain floating point
otherwise.  A residual vector is what an optimiser wants: ``scipy.optimize.least_squares``
minimises its squares, ``minimize(..., constraints={"type": "eq", "fun": ...})`` imposes it.

LaTeX uses index notation (``Σ_{i,j} b_i a_ij c_j``, ``c_i = Σ_j a_ij``), one equation per
condition, every term written ``± m\\,`` followed by its weights, so that it can be read
back mechanically.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from rkcheck.numbers.formatting import counted
from rkcheck.trees.rooted import (
    bracket,
    canonical_level_sequence,
    children_of_level_sequence,
)
from rkcheck.version import __version__

LANGUAGES = ("python", "sympy", "julia", "matlab", "latex")
_LETTERS = "ijklmnpqruvwxyzefgh"  # summation indices (no a, b, c, s, t, o: they mean something)


@dataclass(frozen=True)
class Residual:
    label: str  # id and bracket, for comments
    denominator: int  # L
    terms: tuple[tuple[int, tuple[int, ...]], ...]  # (m_u, positions of the weights in the product)


@dataclass
class ConditionCode:
    """The trees (canonical level sequences, children before parents) and the residuals."""

    trees: list[tuple[int, ...]]
    energy: list[Residual]
    classical: list[Residual]
    order: int
    degree: int | None
    stages: int | None
    explicit: bool

    @cached_property
    def positions(self) -> dict[tuple[int, ...], int]:
        """Each tree's place in :attr:`trees`, built once (built per tree, emitting the
        conditions would be quadratic in their number)."""
        return {s: k for k, s in enumerate(self.trees)}

    def description(self) -> str:
        deg = "all Hamiltonians" if self.degree is None else f"degree ≤ {self.degree}"
        out = f"{counted(len(self.energy), 'energy condition')} up to order {self.order} ({deg})"
        if self.classical:
            out += f" and {counted(len(self.classical), 'classical order condition')} up to order {self.order}"
        return out


def condition_code(listing, classical: bool = False, stages: int | None = None,
                   explicit: bool = False) -> ConditionCode:
    """Collect the trees and residuals of a :class:`~rkcheck.trees.listing.ConditionListing`
    (conditions in its order: by order, then canonical id)."""
    import math

    import numpy as np

    from rkcheck.trees.table import TreeTable

    index: dict[tuple[int, ...], int] = {}

    def need(seq: tuple[int, ...]) -> None:
        seq = canonical_level_sequence(seq)
        if seq in index:
            return
        for child in children_of_level_sequence(seq):
            need(child)
        index[seq] = -1

    energy_terms = []
    for n, k, rec in listing.sorted_conditions():
        forests = listing.term_forests(n, k)
        L = math.lcm(*(sigma for _, sigma, _ in forests))
        terms = []
        for sign, sigma, seqs in forests:
            for q in seqs:
                need(q)
            terms.append((sign * (L // sigma), seqs))
        energy_terms.append((f"{rec.id}  {rec.bracket}  order {rec.order}", L, terms))
    classical_trees: list[tuple[tuple[int, ...], int]] = []
    if classical:
        full = TreeTable(listing.order)
        for n in range(1, listing.order + 1):
            ids = np.asarray(full.ids_of_order(n))
            for t, gamma in zip(ids.tolist(), full.gamma(ids).tolist()):
                seq = full.level_sequence(t)
                need(seq)
                classical_trees.append((canonical_level_sequence(seq), int(gamma)))
    trees = sorted(index, key=lambda q: (len(q), tuple(-x for x in q)))
    for k, seq in enumerate(trees):
        index[seq] = k
    energy = [
        Residual(label, den, tuple((m, tuple(sorted(index[canonical_level_sequence(s)] for s in seqs))) for m, seqs in terms))
        for label, den, terms in energy_terms
    ]
    classical_res = [
        Residual(f"{','.join(map(str, seq))}  {bracket(seq)}  γ = {gamma}", gamma,
                 ((gamma, (index[seq],)), (-1, ())))
        for seq, gamma in classical_trees
    ]
    return ConditionCode(trees, energy, classical_res, listing.order, listing.degree, stages, explicit)


def _children_positions(code: ConditionCode, seq: tuple[int, ...]) -> list[int]:
    return [code.positions[canonical_level_sequence(c)] for c in children_of_level_sequence(seq)]


def _product(factors: list[str], op: str = "*") -> str:
    return op.join(factors) if factors else "1"


def _residual_text(r: Residual, weight, op: str, div) -> str:
    """``(m1*w..*w.. - m2*w.. ) / L`` in a language (``weight(k)`` names weight k)."""
    parts = []
    for m, positions in r.terms:
        factors = [weight(k) for k in positions]
        mag = abs(m)
        body = _product(factors, op)
        if factors and mag != 1:
            body = f"{mag}{op}{body}"
        elif not factors:
            body = str(mag)
        sign = "-" if m < 0 else "+"
        parts.append((sign, body))
    text = ("-" if parts[0][0] == "-" else "") + parts[0][1]
    for sign, body in parts[1:]:
        text += f" {sign} {body}"
    if r.denominator == 1:
        return text
    return f"({text}){div(r.denominator)}"


# ---------------------------------------------------------------------- Python


def _python_like(code: ConditionCode, sym: bool) -> str:
    lines = _python_header(code, sym) + _python_weights(code)
    lines += _python_residual_functions(code, "sympy.Rational" if sym else "Fraction")
    if code.stages is not None:
        lines += _python_stages(code, code.stages, sym)
    return "\n".join(lines) + "\n"


def _python_header(code: ConditionCode, sym: bool) -> list[str]:
    """The module docstring and imports of the emitted Python or sympy code."""
    title = "sympy" if sym else "Python"
    lines = [
        f'"""{code.description()}, as {title} functions of A and b.',
        "",
        f"Generated by rkcheck {__version__} (`rkcheck conditions --emit {'sympy' if sym else 'python'}`): every residual",
        "is zero exactly when the condition holds. A is a list of rows (or a sympy Matrix), b a list.",
        "Exact inputs (ints, Fractions, sympy numbers and symbols) give exact residuals; floats give floats.",
    ]
    if not sym:
        lines += [
            "",
            "With scipy.optimize (x = the free entries of the tableau, see unpack):",
            "    least_squares(residuals, x0)                       # sum of squares to 0",
            "    minimize(f, x0, constraints={'type': 'eq', 'fun': residuals})",
        ]
    return lines + ['"""', "", "from fractions import Fraction" if not sym else "import sympy", ""]


def _python_weights(code: ConditionCode) -> list[str]:
    """``elementary_weights(A, b)``: Φ tree by tree, ``AΦ`` only for the trees that are
    some tree's child."""
    lines = [
        "",
        "def elementary_weights(A, b):",
        '    """a(t) = bᵀΦ(t), Φ(τ) = 1, Φ([t1 … tk]) = AΦ(t1) ⊙ … ⊙ AΦ(tk), for the trees listed."""',
        "    if hasattr(A, 'tolist'):",
        "        A = A.tolist()",
        "    b = list(b)",
        "    s = len(b)",
        "",
        "    def image(v):  # A v",
        "        return [sum(A[i][j] * v[j] for j in range(s)) for i in range(s)]",
        "",
    ]
    children_of = [_children_positions(code, seq) for seq in code.trees]
    images = {c for children in children_of for c in children}
    for k, seq in enumerate(code.trees):
        children = children_of[k]
        comment = f"  # {bracket(seq)}"
        if not children:
            lines.append(f"    phi{k} = [1] * s{comment}")
        else:
            names = [f"Aphi{c}" for c in children]
            if len(names) == 1:
                lines.append(f"    phi{k} = {names[0]}{comment}")
            else:
                lines.append(f"    phi{k} = [{' * '.join(f'x{n}' for n in range(len(names)))} for "
                             f"{', '.join(f'x{n}' for n in range(len(names)))} in zip({', '.join(names)})]{comment}")
        if k in images:
            lines.append(f"    Aphi{k} = image(phi{k})")
    lines.append("    return [" + ", ".join(f"sum(x * y for x, y in zip(b, phi{k}))" for k in range(len(code.trees))) + "]")
    return lines


def _python_residual_functions(code: ConditionCode, num: str) -> list[str]:
    """``energy_conditions(A, b)`` and (when asked for) ``order_conditions(A, b)``."""

    def div(L: int) -> str:
        return f" / {num}({L})"

    lines: list[str] = []
    for name, residuals, what in (("energy_conditions", code.energy, "energy conditions"),
                                  ("order_conditions", code.classical, "classical order conditions")):
        if name == "order_conditions" and not code.classical:
            continue
        lines += ["", "", f"def {name}(A, b):",
                  f'    """The {counted(len(residuals), "residual")} of the {what}, in rkcheck\'s order."""',
                  "    w = elementary_weights(A, b)", "    return ["]
        for r in residuals:
            lines.append(f"        {_residual_text(r, lambda k: f'w[{k}]', '*', div)},  # {r.label}")
        lines.append("    ]")
    return lines


def _free_entries(code: ConditionCode) -> list[tuple[int, int]]:
    s = code.stages or 0
    return [(i, j) for i in range(s) for j in range(s) if not code.explicit or j < i]


def _python_stages(code: ConditionCode, s: int, sym: bool) -> list[str]:
    free = _free_entries(code)
    shape = "strictly lower triangular A (explicit), " if code.explicit else ""
    out = ["", "", f"STAGES = {s}", f"FREE_A = {free}  # (row, column) of the free entries of A, 0-based", ""]
    out += [
        "",
        "def unpack(x):",
        f'    """The tableau from the vector of its free entries: {shape}row by row, then b ({len(free) + s} numbers)."""',
        f"    A = [[0] * {s} for _ in range({s})]",
        "    for (i, j), v in zip(FREE_A, x):",
        "        A[i][j] = v",
        f"    return A, list(x[{len(free)}:{len(free) + s}])",
        "",
        "",
        "def pack(A, b):",
        '    """The inverse of unpack."""',
        "    return [A[i][j] for i, j in FREE_A] + list(b)",
        "",
        "",
        "def residuals(x):",
        '    """Every residual as one list: the function to hand to an optimiser."""',
        "    A, b = unpack(x)",
        "    return energy_conditions(A, b)" + (" + order_conditions(A, b)" if code.classical else ""),
    ]
    if sym:
        names = " ".join(f"a{i + 1}_{j + 1}" for i, j in free)
        out += [
            "",
            "",
            f"a_symbols = sympy.symbols({names!r}, seq=True)",
            f"b_symbols = sympy.symbols({' '.join(f'b{i + 1}' for i in range(s))!r}, seq=True)",
            "A, b = unpack(list(a_symbols) + list(b_symbols))",
            "energy = [sympy.expand(r) for r in energy_conditions(A, b)]  # polynomials in the a_ij, b_i",
        ]
        if code.classical:
            out.append("order = [sympy.expand(r) for r in order_conditions(A, b)]")
    return out


# ------------------------------------------------------------------ Julia, MATLAB


def _weight_lines(code: ConditionCode, ones: str, end: str, comment: str, indent: str) -> list[str]:
    """``φ`` (and ``Aφ`` where a parent needs it) of every tree, children before parents,
    in the array syntax Julia and MATLAB share (``.*``, ``A * x``)."""
    lines = []
    images = {c for seq in code.trees for c in _children_positions(code, seq)}
    for k, seq in enumerate(code.trees):
        children = _children_positions(code, seq)
        value = " .* ".join(f"Aphi{c}" for c in children) if children else ones
        lines.append(f"{indent}phi{k} = {value}{end}  {comment} {bracket(seq)}")
        if k in images:
            lines.append(f"{indent}Aphi{k} = A * phi{k}{end}")
    return lines


def _julia(code: ConditionCode) -> str:
    lines = [
        f"# {code.description()}, as Julia functions of A and b.",
        f"# Generated by rkcheck {__version__} (`rkcheck conditions --emit julia`). Rational inputs give exact",
        "# residuals; floats give floats. For Optim.jl / NLsolve.jl hand them `x -> energy_conditions(unpack(x)...)`.",
        "",
        "function elementary_weights(A, b)",
        "    s = length(b)",
    ]
    lines += _weight_lines(code, "ones(eltype(b), s)", end="", comment="#", indent="    ")
    lines.append("    return [" + ", ".join(f"sum(b .* phi{k})" for k in range(len(code.trees))) + "]")
    lines.append("end")
    for name, residuals in (("energy_conditions", code.energy), ("order_conditions", code.classical)):
        if name == "order_conditions" and not code.classical:
            continue
        lines += ["", f"function {name}(A, b)", "    w = elementary_weights(A, b)", "    return ["]
        for r in residuals:
            lines.append(f"        {_residual_text(r, lambda k: f'w[{k + 1}]', '*', lambda L: f' / {L}')},  # {r.label}")
        lines += ["    ]", "end"]
    if code.stages is not None:
        free = _free_entries(code)
        s = code.stages
        lines += ["", f"# free entries of A (row, column), 1-based{', strictly lower triangular' if code.explicit else ''}",
                  f"const FREE_A = [{', '.join(f'({i + 1}, {j + 1})' for i, j in free)}]",
                  "function unpack(x)",
                  f"    A = zeros(eltype(x), {s}, {s})",
                  "    for (k, (i, j)) in enumerate(FREE_A)",
                  "        A[i, j] = x[k]",
                  "    end",
                  f"    return A, x[{len(free) + 1}:{len(free) + s}]",
                  "end"]
    return "\n".join(lines) + "\n"


def _matlab(code: ConditionCode) -> str:
    lines = [
        "function [energy, order] = rkcheck_conditions(A, b)",
        f"% {code.description()}.",
        f"% Generated by rkcheck {__version__} (`rkcheck conditions --emit matlab`): energy(k) = 0 exactly when",
        "% condition k holds (order: the classical order conditions, empty unless --classical).",
        "% With fmincon / lsqnonlin: residuals of x are rkcheck_conditions(A(x), b(x)).",
        "b = b(:);",
        "s = numel(b);",
    ]
    lines += _weight_lines(code, "ones(s, 1)", end=";", comment="%", indent="")
    lines.append("w = [" + "; ".join(f"b.' * phi{k}" for k in range(len(code.trees))) + "];")
    for name, residuals in (("energy", code.energy), ("order", code.classical)):
        if not residuals:
            lines.append(f"{name} = [];")
            continue
        lines.append(f"{name} = [ ...")
        for r in residuals:
            lines.append(f"    {_residual_text(r, lambda k: f'w({k + 1})', '*', lambda L: f' / {L}')}; ...  % {r.label}")
        lines.append("];")
    lines.append("end")
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------- LaTeX


def latex_weight(seq: tuple[int, ...]) -> str:
    """``\\sum_{i,j} b_{i} a_{ij} c_{j}^{2}``: a(t) in index notation."""
    letters = iter(_LETTERS)
    root = next(letters)
    indices = [root]
    factors = [f"b_{{{root}}}"]

    def visit(sub: tuple[int, ...], idx: str) -> None:
        children = children_of_level_sequence(sub)
        leaves = sum(1 for ch in children if len(ch) == 1)
        if leaves:
            factors.append(f"c_{{{idx}}}" + (f"^{{{leaves}}}" if leaves > 1 else ""))
        for ch in children:
            if len(ch) > 1:
                j = next(letters)
                indices.append(j)
                factors.append(f"a_{{{idx}{j}}}")
                visit(ch, j)

    visit(seq, root)
    return f"\\sum_{{{','.join(indices)}}} " + " ".join(factors)


def _latex(code: ConditionCode) -> str:
    lines = [
        f"% {code.description()}.",
        f"% Generated by rkcheck {__version__} (`rkcheck conditions --emit latex`). Index notation: every sum",
        "% runs over the stages 1..s, c_i = \\sum_j a_{ij}"
        + ("; explicit methods: a_{ij} = 0 for j \\ge i." if code.explicit else "."),
        "% Each condition is R = (1/L) \\sum_u m_u \\prod_{t \\in B_-(u)} a(t) = 0 (one term per rooting u).",
        "\\begin{align*}",
    ]

    def weight(k: int) -> str:
        return f"\\Big({latex_weight(code.trees[k])}\\Big)"

    def residual(r: Residual, name: str) -> str:
        body = ""
        for m, positions in r.terms:
            sign = "-" if m < 0 else "+"
            counts: dict[int, int] = {}
            for p in positions:
                counts[p] = counts.get(p, 0) + 1
            factors = " ".join(weight(p) + (f"^{{{n}}}" if n > 1 else "") for p, n in counts.items())
            body += f" {sign} {abs(m)}\\," + (f" {factors}" if factors else "")
        head = f"\\tfrac{{1}}{{{r.denominator}}}\\Big[" if r.denominator != 1 else "\\Big["
        return f"{name} &= {head}{body} \\Big] = 0"

    rows = [residual(r, f"R_{{{r.label.split()[0]}}}") for r in code.energy]
    rows += [residual(r, f"\\Phi_{{{r.label.split()[0]}}}") for r in code.classical]
    for k, row in enumerate(rows):
        lines.append(row + (" \\\\" if k < len(rows) - 1 else ""))
    lines.append("\\end{align*}")
    return "\n".join(lines) + "\n"


def emit(listing, language: str, classical: bool = False, stages: int | None = None, explicit: bool = False) -> str:
    """The conditions of ``listing`` (and, with ``classical``, the classical order conditions
    up to the same order) as source text in ``language`` (one of :data:`LANGUAGES`)."""
    code = condition_code(listing, classical, stages, explicit)
    if language == "python":
        return _python_like(code, sym=False)
    if language == "sympy":
        return _python_like(code, sym=True)
    if language == "julia":
        return _julia(code)
    if language == "matlab":
        return _matlab(code)
    if language == "latex":
        return _latex(code)
    raise ValueError(f"unknown language {language!r}")

