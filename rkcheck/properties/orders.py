"""Quadrature order and classical order (definitions §2, §4).

* quadrature order: the largest ``k`` with ``Σ b_i c_i^(j-1) = 1/j`` for ``j = 1..k``
  (``c = A·1``); at most ``2s`` for ``s`` nodes.
* classical order: the largest ``p`` with ``a(t) = 1/γ(t)`` for every rooted tree with
  at most ``p`` vertices.  It is checked order by order on a growing, unbounded tree
  table and stops at the first failing order, so it costs what the method's order
  costs, whatever the energy-check order.

An order counts proven conditions only (definitions §5): a condition that holds to D
digits is not proven, so an order whose conditions hold only to digits is reported as
"holds to D digits beyond order N" (:attr:`OrderResult.to_digits`), never as held.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import Any, Iterator

import numpy as np

from rkcheck.errors import UserError
from rkcheck.evaluation.backends import ball_context
from rkcheck.evaluation.channels import PrimeChannels, channels_per_image_pass
from rkcheck.evaluation.protocols import EnclosingContext, WeightContext
from rkcheck.evaluation.scaled import ScaledTableau, scaled_rational
from rkcheck.evaluation.values import Backend, TableauValues
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.intervals import Interval
from rkcheck.properties import scalars as sc
from rkcheck.trees.rooted import bracket_of_forest
from rkcheck.trees.table import TreeTable
from rkcheck.verdicts import (
    FAILS,
    HOLDS,
    Verdict,
    classify,
    combine,
)


@dataclass(frozen=True)
class OrderResult:
    """A classical or quadrature order, how far it was checked, and its first failing
    condition.  ``order`` is proven: every condition up to it holds exactly; the
    conditions from there up to ``to_digits`` hold only to digits (the weakest:
    :attr:`digits`)."""

    order: int  # the largest order whose conditions all hold exactly (capped at ``checked``)
    checked: int  # the highest order examined
    verdict: Verdict  # of the conditions up to ``to_digits``: holds or holds_to_digits
    first_failure: str | None = None  # e.g. "Σ b_i c_i^3 = 1/4" or a tree
    # the largest order whose conditions all hold, exactly or to digits (None: ``order``)
    to_digits: int | None = None

    def __post_init__(self) -> None:
        if self.to_digits is None:
            object.__setattr__(self, "to_digits", self.order)

    @property
    def digits(self) -> int | None:
        """The digits to which the conditions beyond :attr:`order` (up to
        :attr:`to_digits`) hold; None when there are none."""
        return self.verdict.digits if self.to_digits != self.order else None


def _order_result(per_order: list[Verdict], checked: int, first_failure: str | None = None) -> OrderResult:
    """From the combined verdict of each order 1, 2, … that holds (exactly or to digits):
    the proven order is the run of exact ones."""
    proven = next((k for k, v in enumerate(per_order) if v.state != HOLDS), len(per_order))
    return OrderResult(proven, checked, combine(per_order), first_failure, len(per_order))


def quadrature_order(A: list[list[Any]], b: list[Any]) -> OrderResult:
    """Quadrature order of the rule ``(b, A·1)`` (checked up to ``2s``, its maximum).

    ``A``, ``b`` are scalars of :mod:`rkcheck.properties.scalars` (Fractions, field elements
    or intervals), so an algebraic rule such as Gauss's gets an exact order."""
    c = sc.row_sums(A, sc.sample(A, b))
    return quadrature_order_of(sc.quadrature_residuals(b, c), len(b))


def quadrature_order_of(residuals: Iterator[Any], stages: int) -> OrderResult:
    """The quadrature order from the residuals ``Σ b_i c_i^(k−1) − 1/k``, k = 1, 2, …,
    of an s-stage rule (checked up to 2s)."""
    top = 2 * stages
    verdicts: list[Verdict] = []
    for k, residual in zip(range(1, top + 1), residuals):
        v = sc.verdict(residual)
        if v.state == FAILS:
            power = "" if k == 1 else ("_i" if k == 2 else f"_i^{k - 1}")
            label = "Σ b_i = 1" if k == 1 else f"Σ b_i c{power} = 1/{k}"
            return _order_result(verdicts, k, label)
        verdicts.append(v)
    return _order_result(verdicts, top)


@lru_cache(maxsize=1)
def unbounded_table() -> TreeTable:
    """The process-wide table of all rooted trees (no degree bound), grown as far as
    classical orders have needed."""
    return TreeTable(1)


class TreeWeights:
    """Φ, ψ and a of every tree of a growing table, in one number context (for the
    classical order conditions ``a(t) = 1/γ(t)``).  Trees run along the first axis of
    the context's arrays, or the second of :class:`PrimeChannels` (channels first)."""

    def __init__(self, ctx: WeightContext, s: int):
        self.ctx, self.s, self.done = ctx, s, 1
        self.axis = 1 if isinstance(ctx, PrimeChannels) else 0
        self.phi, self.psi, self.a = ctx.vectors(1, s), ctx.vectors(1, s), ctx.scalars(1)
        one = ctx.ones(1, s)
        ctx.put(self.phi, 0, one)
        ctx.put(self.psi, 0, ctx.matvec(one))
        ctx.put(self.a, 0, ctx.dot(one))

    def extend(self, table: TreeTable, p: int) -> Any:
        """The weights a(t) of the trees with p vertices (orders below are done)."""
        ctx = self.ctx
        for n in range(self.done + 1, p + 1):
            lo, hi = table.first[n], table.first[n + 1]
            grow = hi - self._rows(self.a)
            if grow > 0:
                self.phi = self._append(self.phi, ctx.vectors(grow, self.s))
                self.psi = self._append(self.psi, ctx.vectors(grow, self.s))
                self.a = self._append(self.a, ctx.scalars(grow))
            phi_n = ctx.mul(ctx.take(self.phi, table.left[lo:hi]), ctx.take(self.psi, table.right[lo:hi]))
            ctx.put(self.phi, lo, phi_n)
            ctx.put(self.psi, lo, ctx.matvec(phi_n))
            ctx.put(self.a, lo, ctx.dot(phi_n))
            self.done = n
        lo, hi = table.first[p], table.first[p + 1]
        return ctx.take(self.a, np.arange(lo, hi))

    def _rows(self, x: Any) -> int:
        return len(x[0]) if isinstance(x, tuple) else x.shape[self.axis]

    def _append(self, x: Any, y: Any) -> Any:
        if isinstance(x, tuple):
            return tuple(np.concatenate([xa, ya]) for xa, ya in zip(x, y))
        return np.concatenate([x, y], axis=self.axis)


def _first_failure(table: TreeTable, ids: np.ndarray) -> str:
    """The classical condition of the failing tree with the smallest level sequence
    (the one-vertex tree τ as what it says: ``Σ b_i = 1``)."""
    best = min((int(t) for t in ids), key=table.level_sequence)
    gamma = int(table.gamma(np.array([best]))[0])
    forest = [table.level_sequence(c) for c in table.children(best)]
    if not forest:
        return "Σ b_i = 1"
    return f"a({bracket_of_forest(forest)}) = 1/{gamma}"


def classical_order(values: TableauValues, max_order: int) -> OrderResult:
    """Classical order (definitions §2: ``a(t) = 1/γ(t)`` for every tree with ≤ p vertices),
    capped at ``max_order``, stopping at the first order with a certain failure.

    Exact data — also when the energy conditions were asked in balls: like the
    quadrature order, this is a property of the tableau's own numbers —: residues of
    ``γ(t)·â(t) − d^|t|`` (``â = d^|t| a``) modulo primes; a nonzero one proves the
    failure, zero at enough primes (the size bound of :mod:`rkcheck.evaluation.modular`)
    proves the condition.  Otherwise certified balls, except for the trees whose weight
    involves no entry known only as an interval (:class:`Dependence`): those are exact."""
    if values.backend is Backend.EXACT:
        return _exact_classical_order(values.scaled, values.stages, max_order)
    if values.kind.is_exact:  # balls asked for: exact where the primes the field needs are found
        try:
            return _exact_classical_order(values.scaled, values.stages, max_order)
        except UserError:  # beyond MAX_PRIMES_SCANNED: the balls, as asked
            pass
    return _ball_classical_order(values, max_order)


class ExactWeights:
    """The classical conditions of each order decided exactly, from residues modulo the
    primes the order's size bound needs; a channel opened for a lower order carries on
    to the higher ones."""

    def __init__(self, scaled: ScaledTableau, s: int):
        self.scaled, self.s = scaled, s
        # the channels opened for one order, run together (one array operation for all
        # of them per step, not one per channel): their primes as a column, and their weights
        self.groups: list[tuple[np.ndarray, TreeWeights]] = []
        self.opened: list[int] = []

    def failing(self, table: TreeTable, p: int) -> np.ndarray:
        """Which trees with ``p`` vertices (orders below done) fail ``a(t) = 1/γ(t)``."""
        scaled = self.scaled
        ids = np.arange(table.first[p], table.first[p + 1])
        gamma = table.gamma(ids)
        # γ(t)·e^p·a(t) − e^p is an algebraic integer (e the integrality denominator,
        # = d over Q), in embedding j at most p!·M_j^p + e^p (M_j with e in place of
        # d) <= 2^(log2 B_j + p·log2 e + 1) (B_j >= 1): zero residues over
        # Π q > 2^bits prove it zero (the norm argument of rkcheck.evaluation.modular;
        # over Q its one embedding).  With d instead of e the bound would grow with
        # log2 d per vertex (1236 bits for HBVM(6, σ), against 19 for e)
        e = scaled.integral_d or scaled.d
        bits = scaled.decision_bits(p + 1, 1) + math.ceil(p * math.log2(e)) + 1
        primes = scaled.primes_for(bits)
        # one channel per (prime, root); the primes already open are the first ones
        # (counted, not searched: thousands of primes for entries of thousands of digits).
        # A root whose images are a stage permutation of an earlier root's has the same
        # a(t) = bᵀΦ(t) (ScaledTableau.channel_sources): it is not evaluated again
        pairs: list[tuple[int, int]] = []
        for q, roots in primes[len(self.opened):]:
            self.opened.append(q)
            sources = scaled.channel_sources(q)
            pairs.extend((q, r) for j, r in enumerate(roots) if sources[j] == j)
        # in groups whose images fit (a surrogate's are large: channels_per_image_pass)
        width = channels_per_image_pass(self.s)
        for k in range(0, len(pairs), width):
            group = pairs[k:k + width]
            self.groups.append((np.array([q for q, _ in group], dtype=np.int64)[:, None],
                                TreeWeights(scaled.channels(group), self.s)))
        failing = np.zeros(len(ids), dtype=bool)
        for P, weights in self.groups:
            a = weights.extend(table, p)  # (channels, trees)
            target = np.array([pow(scaled.d, p, q) for q in P[:, 0].tolist()], dtype=np.int64)[:, None]
            failing |= np.any(a * _residues(gamma, P, math.factorial(p)) % P != target, axis=0)
        return failing


def _exact_classical_order(scaled: ScaledTableau, s: int, max_order: int) -> OrderResult:
    table = unbounded_table()
    exact = ExactWeights(scaled, s)
    verdicts: list[Verdict] = []
    for p in range(1, max_order + 1):
        table.grow_to(p)
        failing = exact.failing(table, p)
        if failing.any():
            ids = np.arange(table.first[p], table.first[p + 1])
            return _order_result(verdicts, p, _first_failure(table, ids[failing]))
        verdicts.append(Verdict(HOLDS))
    return _order_result(verdicts, max_order)


def _residues(values: np.ndarray, P: np.ndarray, largest: int) -> np.ndarray:
    """``values`` (exact ints, ``|value| <= largest``) modulo each prime of the column
    ``P``: (primes, values)."""
    if largest < 1 << 62:  # the densities γ(t) <= p! of trees with up to 20 vertices
        out: np.ndarray = np.asarray(values, dtype=np.int64).reshape(1, -1) % P
        return out
    return np.array([[int(x) % q for x in values] for q in P[:, 0].tolist()], dtype=np.int64).reshape(len(P), -1)


def _ball_classical_order(values: TableauValues, max_order: int) -> OrderResult:
    """Each order's conditions decided on certified balls — a ball without 1/γ(t)
    fails —, but exactly for the trees whose weight involves no interval entry (the
    same number on the whole box: ``Σ b_i = 1`` with b exact and A in decimals)."""
    table = unbounded_table()
    s = values.stages
    verdicts: list[Verdict] = []
    balls: EnclosingContext = ball_context(values)
    weights = TreeWeights(balls, s)
    dependence = TreeWeights(Dependence(values.A, values.b), s)
    exact: ExactWeights | None = ExactWeights(scaled_rational(*_points(values.A, values.b)), s)
    for p in range(1, max_order + 1):
        table.grow_to(p)
        ids = np.arange(table.first[p], table.first[p + 1])
        enclosures = balls.enclosures(weights.extend(table, p))
        depends = dependence.extend(table, p)
        fails_exactly = None
        if exact is not None and not depends.all():
            try:
                fails_exactly = exact.failing(table, p)
            except UserError:  # no primes within MAX_PRIMES_SCANNED: every condition in balls
                exact = None
        gamma = table.gamma(ids)
        order_verdicts = []
        failed: list[int] = []
        for k, (t, enc, g) in enumerate(zip(ids, enclosures, gamma)):
            if fails_exactly is not None and not depends[k]:
                v = Verdict(FAILS) if fails_exactly[k] else Verdict(HOLDS)
            else:
                v = classify(Enclosure(enc.mid - Fraction(1, int(g)), enc.rad, False))
            if v.state == FAILS:
                failed.append(int(t))
            order_verdicts.append(v)
        if failed:
            return _order_result(verdicts, p, _first_failure(table, np.array(failed)))
        verdicts.append(combine(order_verdicts))
    return _order_result(verdicts, max_order)


def _points(A: list[list[Interval]], b: list[Interval]) -> tuple[list[list[Fraction]], list[Fraction]]:
    """The exact entries, and 0 for the others: what the weights that involve no interval
    entry are computed from (they are the same whatever stands for the others)."""
    def point(x: Interval) -> Fraction:
        return Fraction(x.lo) if x.is_point else Fraction(0)

    return [[point(x) for x in row] for row in A], [point(x) for x in b]


class Dependence:
    """Which weights may involve an entry that is an interval (not a point): booleans in
    the shape of the weights, through the same kernel (:class:`TreeWeights`).  An entry
    that is exactly zero contributes nothing; every other one may, so a weight marked
    False is the same number wherever the interval entries lie in their intervals."""

    def __init__(self, A: list[list[Interval]], b: list[Interval]):
        self._nonzero = np.array([[not (x.is_point and x.lo == 0) for x in row] for row in A], dtype=np.int64)
        self._interval_row = np.array([any(not x.is_point for x in row) for row in A], dtype=bool)
        self._b_nonzero = np.array([not (x.is_point and x.lo == 0) for x in b], dtype=np.int64)
        self._b_interval = any(not x.is_point for x in b)

    def vectors(self, n: int, s: int) -> np.ndarray:
        return np.zeros((n, s), dtype=bool)

    def scalars(self, n: int) -> np.ndarray:
        return np.zeros(n, dtype=bool)

    def ones(self, k: int, s: int) -> np.ndarray:
        return np.zeros((k, s), dtype=bool)

    def one(self, k: int) -> np.ndarray:
        return np.zeros(k, dtype=bool)

    def take(self, x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        result: np.ndarray = x[idx]
        return result

    def put(self, store: np.ndarray, lo: int, x: np.ndarray) -> None:
        store[lo:lo + len(x)] = x

    def mul(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        result: np.ndarray = x | y
        return result

    def matvec(self, x: np.ndarray) -> np.ndarray:
        """``(Ax)_i`` involves an interval entry if a row entry is one, or if it is not
        zero and meets an ``x_j`` that involves one."""
        result: np.ndarray = ((x.astype(np.int64) @ self._nonzero.T) > 0) | self._interval_row
        return result

    def dot(self, x: np.ndarray) -> np.ndarray:
        result: np.ndarray = ((x.astype(np.int64) @ self._b_nonzero) > 0) | self._b_interval
        return result
