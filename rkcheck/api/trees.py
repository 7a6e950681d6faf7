"""Free trees and single energy conditions, for people building their own tools.

A free tree is named by its canonical id: the canonical level sequence (the
lexicographically largest, as in RootedTrees.jl) of its rooting at the centre — for two
centres, the larger of the two (definitions §3).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

from rkcheck.errors import OptionError, UserError
from rkcheck.methods.tableau import Tableau
from rkcheck.options import DEFAULT_DPS, MAX_ORDER


@dataclass(frozen=True)
class FreeTree:
    """A non-superfluous free tree: one energy condition (definitions §3)."""

    level_sequence: tuple[int, ...]  # canonical id: the rooting at the (larger) centre
    bracket: str  # Butcher's bracket notation of that rooting
    max_degree: int  # the largest number of edges at a vertex
    rootings: int  # distinct rooted trees in its class π⁻¹(t̄)

    @property
    def id(self) -> str:
        return ",".join(map(str, self.level_sequence))

    @property
    def vertices(self) -> int:
        return len(self.level_sequence)

    @property
    def order(self) -> int:
        """The energy order at which it is a condition: vertices − 1."""
        return self.vertices - 1


def free_trees(n: int, max_degree: int | None = None) -> list[FreeTree]:
    """The energy conditions with ``n`` vertices: every free tree with n vertices that is
    not superfluous (definitions §3) and whose vertices have at most ``max_degree`` edges
    (None: no bound; a bound m gives the conditions for Hamiltonians of degree ≤ m),
    sorted by canonical id.  There are none below 3 vertices; n = 3…12 give 1, 1, 3, 4,
    11, 19, 47, 97, 235, 531 without a bound."""
    from rkcheck.options import parse_degree
    from rkcheck.trees.listing import condition_listing

    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise OptionError(f"expected a positive number of vertices, got {n!r}", "n")
    if n > MAX_ORDER + 1:
        raise OptionError(f"at most {MAX_ORDER + 1} vertices, got {n}", "n")
    try:
        degree = parse_degree(max_degree, "max_degree")
    except UserError as err:
        raise OptionError(err.message, err.place) from None
    if n < 3:
        return []
    listing = condition_listing(n - 1, degree)
    records = sorted(listing.records(n), key=lambda r: r.level_sequence)
    return [FreeTree(tuple(r.level_sequence), r.bracket, r.max_degree, r.rootings) for r in records]


@dataclass(frozen=True)
class RootingTerm:
    """One term ``(−1)^κ(t,u) / σ(u) · a(B₋(u))`` of a condition: the rooting ``u``
    (canonical level sequence), the sign, σ(u), the forest B₋(u) as brackets, the
    elementary weights in Σ-notation, and the term's value when a tableau was given."""

    level_sequence: tuple[int, ...]
    sign: int
    sigma: int
    forest: tuple[str, ...]
    weights: tuple[str, ...]
    value: Any  # Fraction (exact), (mid, radius) Fractions (enclosed), or None


@dataclass(frozen=True)
class EnergyCondition:
    """The energy condition of one free tree, taken apart (definitions §3):
    ``R(t̄) = Σ_u (−1)^κ(t,u) / σ(u) · a(B₋(u))`` over the rootings u, with the sign of
    the designated rooting (the centre).  With a tableau, ``residual`` is R (exact
    Fraction when the tableau is exact, else None), ``enclosure`` (mid, radius) and
    ``state`` its verdict (definitions §5)."""

    given: tuple[int, ...]
    level_sequence: tuple[int, ...] | None  # canonical id; None when superfluous
    bracket: str | None
    superfluous: bool
    vertices: int
    max_degree: int
    terms: tuple[RootingTerm, ...]
    residual: Fraction | None = None
    enclosure: tuple[Fraction, Fraction] | None = None
    state: str | None = None
    digits: int | None = None

    @property
    def id(self) -> str | None:
        return None if self.level_sequence is None else ",".join(map(str, self.level_sequence))

    @property
    def is_condition(self) -> bool:
        """Whether the tree gives a condition (3 or more vertices, not superfluous)."""
        return self.level_sequence is not None


def _level_sequence(tree: Any) -> tuple[int, ...]:
    from rkcheck.trees.rooted import parse_level_sequence

    if isinstance(tree, FreeTree):
        return tree.level_sequence
    if hasattr(tree, "level_sequence"):  # a Condition of a Verification
        return tuple(tree.level_sequence)
    try:
        if isinstance(tree, str):
            return tuple(parse_level_sequence(tree))
        if isinstance(tree, Sequence) and all(isinstance(x, int) and not isinstance(x, bool) for x in tree):
            return tuple(parse_level_sequence(",".join(map(str, tree))))
    except ValueError as err:
        raise OptionError(str(err), "tree") from None
    raise OptionError(f"expected a level sequence (e.g. '1,2,3,2' or (1, 2, 3, 2)), got {tree!r}", "tree")


def energy_condition(tree: Any, tableau: Tableau | None = None, *, dps: int = DEFAULT_DPS,
                     decimals: str = "auto") -> EnergyCondition:
    """The energy condition of the free tree underlying ``tree`` — any rooting of it,
    as a level sequence (``"1,2,3,2"``, ``(1, 2, 3, 2)``), a :class:`FreeTree` or a
    checked :class:`~rkcheck.api.verification.Condition` — with its terms; evaluated on
    ``tableau`` when one is given (exactly for exact tableaux, else a certified
    enclosure at ``dps`` digits).  Computed directly on the tree, independently of the
    bulk listing that :func:`~rkcheck.api.verification.verify` uses."""
    from rkcheck.api.tableaux import as_tableau
    from rkcheck.energy.explain import explain

    seq = _level_sequence(tree)
    if len(seq) > MAX_ORDER + 1:
        raise OptionError(f"at most {MAX_ORDER + 1} vertices", "tree")
    tab = as_tableau(tableau) if tableau is not None else None
    ex = explain(seq, tab, dps, decimals)

    def value(enc: Any) -> Any:
        if enc is None:
            return None
        return Fraction(enc.mid) if enc.exact else (Fraction(enc.mid), Fraction(enc.rad))

    terms = tuple(RootingTerm(tuple(t.level_sequence), t.sign, t.sigma, tuple(f[1] for f in t.forest),
                              tuple(f[2] for f in t.forest), value(t.value)) for t in ex.terms)
    cond = ex.condition
    out = EnergyCondition(seq, None if cond is None else tuple(cond.level_sequence),
                          None if cond is None else cond.bracket, ex.superfluous, ex.vertices, ex.max_degree, terms)
    if ex.residual is not None and ex.verdict is not None:
        enc = ex.residual
        out = EnergyCondition(out.given, out.level_sequence, out.bracket, out.superfluous, out.vertices,
                              out.max_degree, terms, Fraction(enc.mid) if enc.exact else None,
                              (Fraction(enc.mid), Fraction(enc.rad)), ex.verdict.state, ex.verdict.digits)
    return out
