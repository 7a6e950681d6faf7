"""One energy condition taken apart: its rootings, signs, σ and elementary weights.

``explain(level_sequence)`` accepts *any* rooting of a free tree, finds its canonical
centre (definitions §3) and lists the terms of

    R(t̄) = Σ_u (−1)^κ(t,u) / σ(u) · a(B₋(u)),

writing each ``a(t)`` in the usual Σ-notation over ``b``, ``A`` and ``c``
(``a([[τ²]τ]) = Σ b_i c_i a_ij c_j²``).  With a tableau it also evaluates every term.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from rkcheck.energy.verdicts import Verdict, classify
from rkcheck.evaluation.backends import make_backend
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.trees.conditions import EnergyCondition, condition_from_free_tree
from rkcheck.trees.free import FreeTreeGenerator, table_for
from rkcheck.trees.rooted import bracket, children_of_level_sequence

_INDICES = "ijklmnpqrsuvwxyz"
_SUPERSCRIPTS = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


def sigma_notation(seq: tuple[int, ...]) -> str:
    """``a(t) = bᵀΦ(t)`` in Σ-notation (definitions §2), e.g. ``Σ b_i c_i a_ij c_j²``.

    Leaves hanging from a vertex with index x give ``c_x`` (``c = A·1``); every other
    child gets a new index y and the factor ``a_xy`` followed by its own factors.
    """
    counter = iter(_INDICES)

    def factors(sub: tuple[int, ...], x: str) -> list[str]:
        kids = children_of_level_sequence(sub)
        leaves = sum(1 for k in kids if len(k) == 1)
        out = []
        if leaves:
            out.append(f"c_{x}" + (str(leaves).translate(_SUPERSCRIPTS) if leaves > 1 else ""))
        for k in sorted((k for k in kids if len(k) > 1), reverse=True):
            y = next(counter)
            out.append(f"a_{x}{y}")
            out.extend(factors(k, y))
        return out

    root = next(counter)
    return "Σ " + " ".join([f"b_{root}"] + factors(tuple(seq), root))


@dataclass(frozen=True)
class ExplainedTerm:
    level_sequence: tuple[int, ...]
    bracket: str
    sign: int
    sigma: int
    forest: list[tuple[tuple[int, ...], str, str]]  # (level sequence, bracket, Σ-notation)
    value: Enclosure | None = None  # sign/σ · a(B₋(u)) when a tableau is given


@dataclass
class Explanation:
    given: tuple[int, ...]
    condition: EnergyCondition | None  # None when superfluous
    superfluous: bool
    vertices: int
    max_degree: int
    terms: list[ExplainedTerm] = field(default_factory=list)
    residual: Enclosure | None = None
    verdict: Verdict | None = None

    @property
    def id(self) -> str:
        return self.condition.id if self.condition else ",".join(map(str, self.given))


def explain(seq: tuple[int, ...], tableau=None, dps: int = 50, decimals: str = "rounded") -> Explanation:
    """Take the free tree underlying the rooted tree ``seq`` apart (and evaluate it)."""
    n = len(seq)
    if n < 3:
        return Explanation(seq, None, n == 2, n, n - 1)
    degree = _max_degree(seq)
    table = table_for(n - 1, degree)
    gen = FreeTreeGenerator(table, degree)
    tree = gen.from_level_sequence(seq)
    if tree.superfluous:
        return Explanation(seq, None, True, n, tree.max_degree)
    cond = condition_from_free_tree(-1, tree, table)
    backend = None
    if tableau is not None:
        backend = make_backend(tableau, dps, decimals)
        backend.tree_weights(table)
    terms = []
    for term in cond.terms:
        forest = [
            (table.level_sequence(b), table.bracket(b), sigma_notation(table.level_sequence(b)))
            for b in term.branches
        ]
        value = None
        if backend is not None:
            value = backend.enclose_terms(table, [term], term.sigma)
        terms.append(
            ExplainedTerm(cond.term_level_sequence(term), cond.term_bracket(term), term.sign, term.sigma, forest, value)
        )
    out = Explanation(seq, cond, False, n, cond.max_degree, terms)
    if backend is not None:
        out.residual = backend.enclose_terms(table, cond.terms, cond.denominator)
        out.verdict = classify(out.residual)
    return out


def _max_degree(seq: tuple[int, ...]) -> int:
    degree = [0] * len(seq)
    last: dict[int, int] = {}
    for v, d in enumerate(seq):
        if d > 1:
            p = last[d - 1]
            degree[p] += 1
            degree[v] += 1
        last[d] = v
    return max(degree)


__all__ = ["explain", "sigma_notation", "Explanation", "ExplainedTerm", "bracket"]
