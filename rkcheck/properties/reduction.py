"""Stage reduction: the irreducible method behind a tableau (definitions §4).

Two tableaux define the same method (the same B-series, the same numerical map on
every problem) when one reduces to the other by two operations of Hundsdorfer and
Spijker (IMA J. Numer. Anal. 1 (1981) 293–309; Hairer–Wanner II, §IV.12):

* **DJ-reduction** (Dahlquist–Jeltsch) — drop the stages that cannot influence the
  result: keep the stages with ``b_j ≠ 0`` and, recursively, every stage a kept stage
  uses (``a_ij ≠ 0``); the rest are dead (a dead chain of stages using each other too);
* **S-reduction** — merge stages whose values coincide: take the coarsest partition of
  the stages into classes ``S_1 … S_r`` such that two stages ``i, k`` of one class have
  the same sums ``Σ_{j∈S_m} a_ij = Σ_{j∈S_m} a_kj`` over every class ``S_m`` (found by
  refinement from one class, like colour refinement of a weighted graph).  The merged
  method has ``â_lm = Σ_{j∈S_m} a_ij`` (any ``i ∈ S_l``) and ``b̂_m = Σ_{j∈S_m} b_j``.
  Identical rows are the simplest case; "a row that is 3× another once two columns are
  merged" is found too.

Merging can leave a class whose weights cancel (``b̂_m = 0``) and which nothing uses,
and dropping stages can make classes mergeable: both are repeated to a **fixpoint**.
The result is irreducible, unique up to a permutation of its stages.

Every zero test is a :func:`~rkcheck.properties.scalars.verdict`: exact for exact scalars;
for intervals a test that cannot be decided counts as zero/equal and its verdict
(``holds to D digits``) is recorded, so that every conclusion drawn from the reduced
tableau carries those digits.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from rkcheck.numbers.formatting import counted
from rkcheck.properties import scalars as sc
from rkcheck.verdicts import FAILS, HOLDS, Verdict


@dataclass
class Reduction:
    """The reduced tableau ``(A, b)`` and where its stages come from."""

    A: sc.Matrix
    b: sc.Vector
    classes: list[tuple[int, ...]]  # 0-based original stages merged into each reduced stage
    stages: int  # of the original tableau
    decisions: list[Verdict] = field(default_factory=list)  # zero/equal tests that held only to digits
    dropped: list[int] = field(default_factory=list)  # 0-based original stages dropped
    # the merged stages among them: classes of ≥ 2 original stages merged into one stage
    # that nothing used and whose weights cancel — none of them need be dead by itself
    cancelled: list[tuple[int, ...]] = field(default_factory=list)

    @property
    def kept(self) -> list[int]:
        """A representative (the first original stage) of every reduced stage."""
        return [c[0] for c in self.classes]

    @property
    def reduced_stages(self) -> int:
        return len(self.b)

    @property
    def reducible(self) -> bool:
        return self.reduced_stages < self.stages

    def describe(self) -> str | None:
        """One line saying what the reduction did, or None when nothing was reduced."""
        if not self.reducible:
            return None
        parts = []
        merged = [c for c in self.classes if len(c) > 1]
        if merged:
            parts.append("merged stages " + "; ".join("+".join(str(i + 1) for i in c) for c in merged))
        for c in self.cancelled:
            parts.append(f"merged stages {'+'.join(str(i + 1) for i in c)} into one with weight 0 that nothing "
                         "uses, then dropped it")
        gone = {i for c in self.cancelled for i in c}
        dead = sorted(i for i in self.dropped if i not in gone)
        if dead:
            parts.append(f"dropped dead stage{'s' if len(dead) > 1 else ''} " + ", ".join(str(i + 1) for i in dead))
        return f"reduced from {self.stages} to {counted(self.reduced_stages, 'stage')} ({'; '.join(parts)})"


def reduce_tableau(A: sc.Matrix, b: sc.Vector) -> Reduction:
    """DJ- and S-reduction of ``(A, b)`` repeated to a fixpoint (see the module docstring)."""
    s = len(b)
    decisions: list[Verdict] = []

    def is_zero(x: sc.Scalar) -> bool:
        v = sc.verdict(x)
        if v.state == FAILS:
            return False
        if v.state != HOLDS:
            decisions.append(v)
        return True

    A = [list(row) for row in A]
    b = list(b)
    classes: list[tuple[int, ...]] = [(i,) for i in range(s)]
    dropped: list[int] = []
    cancelled: list[tuple[int, ...]] = []
    while True:
        changed = False
        # DJ: the stages that influence the result
        n = len(b)
        needed = {j for j in range(n) if not is_zero(b[j])}
        frontier = list(needed)
        while frontier:
            i = frontier.pop()
            for j in range(n):
                if j not in needed and not is_zero(A[i][j]):
                    needed.add(j)
                    frontier.append(j)
        if len(needed) < n:
            keep = sorted(needed)
            for j in range(n):
                if j not in needed:
                    dropped.extend(classes[j])
                    if len(classes[j]) > 1:
                        cancelled.append(classes[j])
            A = [[A[i][j] for j in keep] for i in keep]
            b = [b[j] for j in keep]
            classes = [classes[j] for j in keep]
            changed = True
        # S: the coarsest partition with equal class sums within each class
        blocks = _coarsest_partition(A, is_zero)
        if len(blocks) < len(b):
            like = sc.sample(A, b)
            A = [[sc.total([A[blk_l[0]][j] for j in blk_m], like) for blk_m in blocks] for blk_l in blocks]
            b = [sc.total([b[j] for j in blk], like) for blk in blocks]
            classes = [tuple(sorted(i for j in blk for i in classes[j])) for blk in blocks]
            changed = True
        if not changed:
            break
    return Reduction(A, b, classes, s, decisions, dropped, cancelled)


def _coarsest_partition(A: sc.Matrix, is_zero: Callable[[sc.Scalar], bool]) -> list[list[int]]:
    """The coarsest partition of the stages with equal class sums inside each class
    (refinement from one class; blocks ordered by their smallest stage)."""
    n = len(A)
    if n == 0:
        return []
    blocks = [list(range(n))]
    while True:
        like = A[0][0]
        sums = [[sc.total([A[i][j] for j in blk], like) for blk in blocks] for i in range(n)]
        refined: list[list[int]] = []
        for blk in blocks:
            groups: list[list[int]] = []
            for i in blk:
                for g in groups:
                    rep = g[0]
                    if all(is_zero(sums[i][m] - sums[rep][m]) for m in range(len(blocks))):
                        g.append(i)
                        break
                else:
                    groups.append([i])
            refined.extend(groups)
        refined.sort(key=lambda g: g[0])
        if len(refined) == len(blocks):
            return refined
        blocks = refined
