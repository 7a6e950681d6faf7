"""Symplecticity and symmetry of a Runge–Kutta method, certified.

Both are properties of the *method*, so both are decided on its irreducible form
(:mod:`rkcheck.properties.reduction`), which is unique up to a permutation of the stages:

* **symplectic** — ``M = BA + AᵀB − bbᵀ = 0`` with ``B = diag(b)``
  (Lasagni, Sanz-Serna, Suris 1988; Hairer–Lubich–Wanner, *Geometric Numerical
  Integration*, Theorem VI.4.3).  For an irreducible method the condition is also
  necessary (HLW, §VI.7.3), which is why it is tested after the reduction: a symplectic
  method written with a dead stage or a split stage has ``M ≠ 0`` as written, yet is
  the same symplectic map.  Where it fails the report gives the largest entry of M,
  exactly.
* **symmetric** — the adjoint method ``A* = 1bᵀ − A``, ``b* = b`` (HLW, §V.1.3: the
  adjoint of ``(A, b)``, stages taken in reversed order, is ``a*_ij = b_(s+1−j) −
  a_(s+1−i,s+1−j)``) equals the method up to a permutation of its stages.  The
  permutation is searched (nodes ``c*_i = Σb − c_i`` must match), not assumed to be the
  reversal.

Over exact scalars both verdicts are ``holds``/``fails``; over enclosures ``holds to D
digits``/``fails`` (:mod:`rkcheck.properties.scalars`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable

from rkcheck.properties import scalars as sc
from rkcheck.properties.reduction import Reduction
from rkcheck.verdicts import FAILS, HOLDS, Verdict, combine


@dataclass(frozen=True)
class PropertyVerdict:
    """``symplectic`` or ``symmetric``: holds / holds to D digits / fails, and why."""

    name: str
    verdict: Verdict
    reason: str
    defect: object | None = None  # symplectic: the largest entry of M (a scalar)
    defect_entry: tuple[int, int] | None = None  # its place (1-based original stages)
    permutation: tuple[int, ...] | None = None  # symmetric: stage i of the adjoint ↦ stage π(i)

    @property
    def holds(self) -> bool:
        return self.verdict.holds

    def label(self) -> str:
        return self.verdict.answer()


def _after(red: Reduction) -> str:
    return f" (of the reduced {red.reduced_stages}-stage method)" if red.reducible else ""


def symplecticity(red: Reduction) -> PropertyVerdict:
    """``BA + AᵀB − bbᵀ = 0`` on the irreducible form ``red``."""
    A, b = red.A, red.b
    n = len(b)
    entries = ((b[i] * A[i][j] + b[j] * A[j][i] - b[i] * b[j], i, j) for i in range(n) for j in range(i, n))
    return symplectic_verdict(red, entries)


def symplectic_verdict(red: Reduction, entries: Iterable[tuple[sc.Scalar, int, int]]) -> PropertyVerdict:
    """The verdict from the entries ``(M_ij, i, j)``, i ≤ j, of M on the reduced stages
    (those left out are zero exactly).  Where M ≠ 0 the report names its largest entry:
    the first one that no later entry certainly exceeds in size."""
    if red.reduced_stages == 0:
        return PropertyVerdict("symplectic", Verdict(FAILS), "every weight is zero: the method does not move")
    verdicts = list(red.decisions)
    worst = None
    for m, i, j in entries:
        v = sc.verdict(m)
        verdicts.append(v)
        if v.state == FAILS and (worst is None or sc.certainly_larger(m, worst[0])):
            worst = (m, i, j)
    verdict = combine(verdicts)
    if worst is not None:
        m, i, j = worst
        gi, gj = red.kept[i] + 1, red.kept[j] + 1
        q = sc.rational(m)
        if q is not None:
            value = f"|M[{gi}][{gj}]| = {sc.text(abs(q), 12)}"
        elif sc.is_interval(m):
            value = f"M[{gi}][{gj}] ≈ {sc.approx_text(m, 12)}"
        else:
            shown = sc.text(m, 12)  # "≈ …" alone when the exact text is too long to print
            value = f"M[{gi}][{gj}] {shown}" if shown.startswith("≈") else f"M[{gi}][{gj}] = {shown}"
        return PropertyVerdict(
            "symplectic", Verdict(FAILS),
            f"BA + AᵀB − bbᵀ ≠ 0{_after(red)}: largest entry {value}",
            m, (gi, gj),
        )
    return PropertyVerdict("symplectic", verdict, f"BA + AᵀB − bbᵀ = 0 {verdict.how()}{_after(red)}")


def symmetry(red: Reduction) -> PropertyVerdict:
    """Does the adjoint ``(1bᵀ − A, b)`` equal the method up to a stage permutation?"""
    A, b = red.A, red.b
    n = len(b)
    if n == 0:
        return PropertyVerdict("symmetric", Verdict(FAILS), "every weight is zero: the method does not move")
    adjoint = [[b[j] - A[i][j] for j in range(n)] for i in range(n)]
    match = _StageMatch(A, adjoint, b)
    image = match.search()
    if image is None:
        return not_symmetric(red, all(match.candidates))
    verdict = combine(list(red.decisions) + match.decisions)
    return symmetric(red, [image[i] for i in range(n)], verdict)


def not_symmetric(red: Reduction, candidates: bool) -> PropertyVerdict:
    """No stage permutation matches; ``candidates``: every stage had one whose weight,
    node and diagonal entry agree with its adjoint's."""
    return PropertyVerdict(
        "symmetric", Verdict(FAILS),
        f"no stage permutation maps the adjoint method (1bᵀ − A, b){_after(red)} onto it"
        + ("" if candidates else ": the nodes Σb − c_i and weights do not match"),
    )


def symmetric(red: Reduction, image: list[int], verdict: Verdict) -> PropertyVerdict:
    """The adjoint's stage i is the reduced method's stage ``image[i]`` (0-based)."""
    perm = tuple(red.kept[k] + 1 for k in image)
    return PropertyVerdict(
        "symmetric", verdict,
        f"the adjoint (1bᵀ − A, b) equals the method {_permutation_text(red, perm)}, {verdict.how()}{_after(red)}",
        permutation=perm,
    )


class _StageMatch:
    """A stage permutation k = image[i] with ``adjoint[i][j] = A[image i][image j]``,
    by backtracking over the stages whose weight, node and diagonal agree; equalities
    that hold only to digits are kept in ``decisions``."""

    def __init__(self, A: sc.Matrix, adjoint: sc.Matrix, b: sc.Vector):
        self.A, self.adjoint, self.n = A, adjoint, len(b)
        self.decisions: list[Verdict] = []
        like = sc.sample(A, b)
        c, c_adj = sc.row_sums(A, like), sc.row_sums(adjoint, like)
        self.candidates = [
            [k for k in range(self.n)
             if self.equal(b[i], b[k]) and self.equal(c_adj[i], c[k]) and self.equal(adjoint[i][i], A[k][k])]
            for i in range(self.n)
        ]
        self.order = sorted(range(self.n), key=lambda i: len(self.candidates[i]))
        self.image: dict[int, int] = {}
        self.used: set[int] = set()

    def equal(self, x: sc.Scalar, y: sc.Scalar) -> bool:
        v = sc.verdict(x - y)
        if v.state == FAILS:
            return False
        if v.state != HOLDS:
            self.decisions.append(v)
        return True

    def search(self) -> dict[int, int] | None:
        return self.image if self._extend(0) else None

    def _extend(self, pos: int) -> bool:
        if pos == self.n:
            return True
        i, A, adj, image = self.order[pos], self.A, self.adjoint, self.image
        for k in self.candidates[i]:
            if k in self.used:
                continue
            if all(self.equal(adj[i][j], A[k][image[j]]) and self.equal(adj[j][i], A[image[j]][k]) for j in image):
                image[i] = k
                self.used.add(k)
                if self._extend(pos + 1):
                    return True
                del image[i]
                self.used.discard(k)
        return False


def _permutation_text(red: Reduction, perm: tuple[int, ...]) -> str:
    stages = tuple(k + 1 for k in red.kept)
    if perm == tuple(reversed(stages)):
        return "with the stages in reversed order"
    if perm == stages:
        return "with the stages in the same order"
    return "under the stage permutation " + ", ".join(f"{a}→{p}" for a, p in zip(stages, perm))
