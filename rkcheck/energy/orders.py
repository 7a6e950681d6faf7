"""Quadrature order and classical order (definitions §2, §4).

* quadrature order: the largest ``k`` with ``Σ b_i c_i^(j-1) = 1/j`` for ``j = 1..k``
  (``c = A·1``); at most ``2s`` for ``s`` nodes.
* classical order: the largest ``p`` with ``a(t) = 1/γ(t)`` for every rooted tree with
  at most ``p`` vertices.  It is checked order by order on a growable, unbounded tree
  table and stops at the first failing order, so it costs what the method's order
  costs, whatever the energy-check order.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache

from rkcheck.energy.verdicts import FAILS, Verdict, classify, classify_interval, combine
from rkcheck.evaluation.backends import Backend
from rkcheck.methods.quadrature import quadrature_residual
from rkcheck.numbers.intervals import Interval, interval_sum
from rkcheck.trees.rooted import RootedTreeTable


@dataclass(frozen=True)
class OrderResult:
    order: int  # the largest order whose conditions all hold (capped at ``checked``)
    checked: int  # the highest order examined
    verdict: Verdict  # of the conditions up to ``order``: holds or holds_to_digits
    first_failure: str | None = None  # e.g. "Σ b_i c_i^3 = 1/4" or a tree


def row_sums(A: list[list[Interval]]) -> list[Interval]:
    """``A·1``: the nodes ``c`` every B-series quantity uses (definitions §1)."""
    return [interval_sum(row) for row in A]


def quadrature_order(A: list[list[Interval]], b: list[Interval], exact: bool) -> OrderResult:
    """Quadrature order of the rule ``(b, A·1)`` (checked up to ``2s``, its maximum)."""
    c = row_sums(A)
    top = 2 * len(b)
    verdicts = []
    for k in range(1, top + 1):
        v = classify_interval(quadrature_residual(b, c, k), exact)
        if v.state == FAILS:
            power = "" if k == 1 else ("_i" if k == 2 else f"_i^{k - 1}")
            label = "Σ b_i = 1" if k == 1 else f"Σ b_i c{power} = 1/{k}"
            return OrderResult(k - 1, k, combine(verdicts), label)
        verdicts.append(v)
    return OrderResult(top, top, combine(verdicts))


@lru_cache(maxsize=1)
def unbounded_table() -> RootedTreeTable:
    """The process-wide growable table of all rooted trees (for classical orders)."""
    return RootedTreeTable(1, None, growable=True)


def classical_order(backend: Backend, max_order: int) -> OrderResult:
    """Classical order (capped at ``max_order``), stopping at the first failing order."""
    table = unbounded_table()
    verdicts: list[Verdict] = []
    for p in range(1, max_order + 1):
        table.grow_to(p)
        backend.tree_weights(table, p)
        for t in table.ids_of_order(p):
            v = classify(backend.weight_minus(table, t, Fraction(1, table.gamma[t])))
            if v.state == FAILS:
                return OrderResult(p - 1, p, combine(verdicts), f"a({table.bracket(t)}) = 1/{table.gamma[t]}")
            verdicts.append(v)
    return OrderResult(max_order, max_order, combine(verdicts))
