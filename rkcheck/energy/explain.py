"""One energy condition taken apart: its rootings, signs, σ and elementary weights.

``explain(level_sequence)`` accepts *any* rooting of a free tree, finds its canonical
centre (definitions §3) and lists the terms of

    R(t̄) = Σ_u (−1)^κ(t,u) / σ(u) · a(B₋(u)),

writing each ``a(t)`` in the usual Σ-notation over ``b``, ``A`` and ``c``
(``a([[τ²]τ]) = Σ b_i c_i a_ij c_j²``).  With a tableau it also evaluates every term.

The tree is small (at most 21 vertices), so everything is computed directly on it: the
rooting at every vertex, its canonical level sequence, the distance to the designated
centre — a second route to the conditions, independent of the bulk listing of
:mod:`rkcheck.trees.listing` (the tests compare the two).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Callable

from rkcheck.energy.judging import box_order, judged_over_box
from rkcheck.energy.results import ConditionResults
from rkcheck.evaluation.values import TableauValues
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.intervals import Interval
from rkcheck.trees.free import FreeTree
from rkcheck.trees.graph import adjacency, centres, distances, rooted_at
from rkcheck.trees.listing import ConditionListing
from rkcheck.trees.rooted import (
    bracket,
    bracket_of_forest,
    children_of_level_sequence,
)
from rkcheck.verdicts import Verdict, classify

_INDICES = "ijklmnpqrsuvwxyz"
_SUPERSCRIPTS = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


def sigma_notation(seq: tuple[int, ...]) -> str:
    """``a(t) = bᵀΦ(t)`` in Σ-notation (definitions §2), e.g. ``Σ b_i c_i a_ij c_j²``.

    Leaves hanging from a vertex with index x give ``c_x`` (``c = A·1``); every other
    child gets a new index y and the factor ``a_xy`` followed by its own factors.
    """
    # 16 letters, then i17, i18, ...: a tree may have up to 31 vertices
    counter = itertools.chain(_INDICES, (f"i{n}" for n in itertools.count(len(_INDICES) + 1)))

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
class RootingTerm:
    """One term ``(−1)^κ(t,u) / σ(u) · a(B₋(u))`` of a condition: the rooting ``u``
    (canonical level sequence and bracket), the sign, σ(u), the forest B₋(u) as
    brackets, its elementary weights in Σ-notation (``Σ b_i a_ij``), and — when a
    tableau was given — a certified enclosure of the term's value (exact for exact data)."""

    level_sequence: tuple[int, ...]
    bracket: str
    sign: int
    sigma: int
    forest: tuple[str, ...]
    weights: tuple[str, ...]
    value: Enclosure | None = None


@dataclass(frozen=True)
class EnergyCondition:
    """The energy condition of one free tree, taken apart (definitions §3):
    ``R(t̄) = Σ_u (−1)^κ(t,u) / σ(u) · a(B₋(u))`` over the distinct rootings u, with the
    sign of the designated rooting.  ``tree`` is None when the tree gives no condition
    (superfluous, or fewer than 3 vertices).  With a tableau, ``enclosure`` holds R
    (exact for exact data) and ``verdict`` its state (definitions §5)."""

    given: tuple[int, ...]  # the rooting asked about
    tree: FreeTree | None
    superfluous: bool
    vertices: int
    max_degree: int
    terms: tuple[RootingTerm, ...] = ()
    enclosure: Enclosure | None = None
    verdict: Verdict | None = None
    tableau: Any = field(default=None, repr=False, compare=False)  # what the terms were evaluated on

    @property
    def id(self) -> str | None:
        """The free tree's id (its canonical level sequence); None when it gives no condition."""
        return self.tree.id if self.tree else None

    @property
    def is_condition(self) -> bool:
        """Whether the tree gives a condition (3 or more vertices, not superfluous)."""
        return self.tree is not None

    @property
    def level_sequence(self) -> tuple[int, ...] | None:
        return None if self.tree is None else self.tree.level_sequence

    @property
    def bracket(self) -> str | None:
        return None if self.tree is None else self.tree.bracket

    @property
    def residual(self) -> Fraction | None:
        """R exactly, when it is a rational computed exactly."""
        e = self.enclosure
        return Fraction(e.mid) if e is not None and e.exact else None

    @property
    def state(self) -> str | None:
        return None if self.verdict is None else self.verdict.state

    @property
    def digits(self) -> int | None:
        return None if self.verdict is None else self.verdict.digits


# ------------------------------------------------------------------ the free tree


def sigma_of(seq: tuple[int, ...]) -> int:
    """σ (definitions §2) of a canonical level sequence: Π r_i! σ(t_i)^r_i."""
    import math

    subs = children_of_level_sequence(seq)
    out = 1
    for sub in set(subs):
        r = subs.count(sub)
        out *= math.factorial(r) * sigma_of(sub) ** r
    return out


# ------------------------------------------------------------------ weights


def _weights(A: list[list[Any]], b: list[Any], one: Any) -> Callable[[tuple[int, ...]], Any]:
    """a(t) for a level sequence, memoised (Φ(τ) = 1, Φ([t…]) = ⊙ AΦ(t_i))."""
    s = len(b)
    cache: dict[tuple[int, ...], list[Any]] = {}

    def phi(seq: tuple[int, ...]) -> list[Any]:
        if seq not in cache:
            out = [one] * s
            for sub in children_of_level_sequence(seq):
                p = phi(sub)
                Ap = [sum((A[i][j] * p[j] for j in range(1, s)), A[i][0] * p[0]) for i in range(s)]
                out = [x * y for x, y in zip(out, Ap)]
            cache[seq] = out
        return cache[seq]

    def a(seq: tuple[int, ...]) -> Any:
        p = phi(seq)
        return sum((b[i] * p[i] for i in range(1, s)), b[0] * p[0])

    return a


def _enclosure(x: Any) -> Enclosure:
    if isinstance(x, Interval):
        return Enclosure(x.mid, x.rad, False)
    if isinstance(x, (Fraction, int)):
        return Enclosure.of(x)
    # an element of a number field (sqrt, root entries): exact when rational, else a
    # nonzero algebraic number, enclosed tightly enough to show it
    rational = x.rational()
    if rational is not None:
        return Enclosure.of(rational)
    enc = x.enclosure(256)
    return Enclosure(enc.mid, enc.rad, False)


def _terms(rootings: dict[tuple[int, ...], int], values: TableauValues | None) -> tuple[list[RootingTerm], Any]:
    """Each rooting's term (sign, σ, forest, weights) and, with a tableau, its value and
    their sum: exactly when the values are exact, else on their enclosures."""
    weight = None
    unit: Fraction | Interval = Fraction(1)
    if values is not None:
        if values.exact is not None and values.exact.entries() is not None:
            A, b, unit = values.exact.A, values.exact.b, Fraction(1)
        else:
            A, b, unit = values.A, values.b, Interval.point(1)
        weight = _weights(A, b, unit)
    terms, total = [], None
    for u, parity in rootings.items():
        forest_seqs = sorted(children_of_level_sequence(u), reverse=True)
        forest = tuple(bracket(f) for f in forest_seqs)
        weights = tuple(sigma_notation(f) for f in forest_seqs)
        sign, sigma = (-1 if parity else 1), sigma_of(u)
        value = None
        if weight is not None:
            product: Any = unit
            for f in forest_seqs:
                product = product * weight(f)
            term = product * (Fraction(sign, sigma) if isinstance(unit, Fraction) else Interval.point(Fraction(sign, sigma)))
            total = term if total is None else total + term
            value = _enclosure(term)
        terms.append(RootingTerm(u, bracket_of_forest(forest_seqs), sign, sigma, forest, weights, value))
    return terms, total


def _over_the_box(condition: FreeTree, values: TableauValues) -> tuple[Enclosure, Verdict]:
    """The enclosure and verdict of ``condition`` judged jointly over a decimal box (its
    order with the check's machinery, :mod:`rkcheck.energy.judging`)."""
    n = condition.vertices
    listing = ConditionListing(n - 1, None)
    results = ConditionResults(listing, box_order(listing, values, n))
    found = next(c for c in results if c.tree.id == condition.id)
    return found.enclosure, found.verdict


def explain(seq: tuple[int, ...], values: TableauValues | None = None) -> EnergyCondition:
    """Take the free tree underlying the rooted tree ``seq`` apart (and evaluate it on a
    tableau's values: exactly when they are exact, else on their enclosures)."""
    seq = tuple(seq)
    n = len(seq)
    adj = adjacency(seq)
    max_degree = max((len(a) for a in adj), default=0)
    if n < 3:
        return EnergyCondition(seq, None, n == 2, n, max_degree)
    cs = centres(adj)
    if len(cs) == 2:  # two centres: superfluous when the halves across the edge are equal
        x, y = cs
        halves = []
        for keep, cut in ((x, y), (y, x)):
            sub = [[w for w in nb if not (v == keep and w == cut)] for v, nb in enumerate(adj)]
            halves.append(rooted_at(sub, keep))
        if halves[0] == halves[1]:
            return EnergyCondition(seq, None, True, n, max_degree)
    designated = max(cs, key=lambda c: rooted_at(adj, c))
    dist = distances(adj, designated)
    rootings: dict[tuple[int, ...], int] = {}
    for v in sorted(range(n), key=lambda v: (dist[v], rooted_at(adj, v))):
        rootings.setdefault(rooted_at(adj, v), dist[v] % 2)
    id_seq = rooted_at(adj, designated)
    condition = FreeTree(id_seq, bracket(id_seq), max_degree, len(rootings))
    terms, total = _terms(rootings, values)
    residual = None if total is None else _enclosure(total)
    verdict = None if residual is None else classify(residual)
    if values is not None and judged_over_box(values):
        # the terms evaluated above are each an interval over the box; the condition's
        # own verdict and enclosure are the joint box's, as verify gives them
        residual, verdict = _over_the_box(condition, values)
    tableau = None if values is None else values.tableau
    return EnergyCondition(seq, condition, False, n, max_degree, tuple(terms), residual, verdict, tableau)
