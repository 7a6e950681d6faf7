"""Free trees and single energy conditions, for people building their own tools.

A free tree is named by its canonical id: the canonical level sequence (the
lexicographically largest, as in RootedTrees.jl) of its rooting at the centre — for two
centres, the larger of the two (definitions §3).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Sequence

from rkcheck.api.settings import guard
from rkcheck.energy.explain import EnergyCondition, RootingTerm, explain
from rkcheck.errors import OptionError, UserError, as_option
from rkcheck.evaluation.values import TableauValues
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.reading import DecimalsMode, Reading
from rkcheck.options import (
    DECIMALS_MODES,
    DEFAULT_DPS,
    DEFAULT_MAX_STAGES,
    DPS_RANGE,
    MAX_ORDER,
    ORDER_RANGE,
)
from rkcheck.trees.free import FreeTree

if TYPE_CHECKING:
    from rkcheck.trees.counting import CountOnly
    from rkcheck.trees.listing import ConditionListing


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
    guard(n - 1, degree)  # the resource guard: the listing of n vertices must fit in memory
    listing = condition_listing(n - 1, degree)
    return sorted(listing.records(n), key=lambda r: r.level_sequence)


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


def energy_condition(tree: Any, tableau: "Tableau | str | os.PathLike[str] | None" = None, *,
                     dps: int = DEFAULT_DPS, decimals: str = "auto",
                     max_stages: int = DEFAULT_MAX_STAGES) -> EnergyCondition:
    """The energy condition of the free tree underlying ``tree`` — any rooting of it,
    as a level sequence (``"1,2,3,2"``, ``(1, 2, 3, 2)``), a :class:`FreeTree` or a
    checked :class:`~rkcheck.api.verification.Condition` — with its terms; evaluated on
    ``tableau`` when one is given (a Tableau, or a path or ``"@name"`` loaded with
    ``max_stages``; exactly for exact tableaux, else a certified enclosure at ``dps``
    digits, decimals read as ``decimals`` says: definitions §5).  Computed directly on
    the tree, independently of the bulk listing that
    :func:`~rkcheck.api.verification.verify` uses — ``rkcheck explain ID``."""
    from rkcheck.api.tableaux import as_tableau, load
    from rkcheck.options import parse_choice, parse_int_in

    seq = _level_sequence(tree)
    if len(seq) > MAX_ORDER + 1:
        raise OptionError(f"at most {MAX_ORDER + 1} vertices", "tree")
    dps = _checked(lambda: parse_int_in(dps, DPS_RANGE, "dps"))
    decimals = _checked(lambda: parse_choice(decimals, DECIMALS_MODES, "decimals"))
    if isinstance(tableau, (str, os.PathLike)):
        tab: Tableau | None = load(tableau, max_stages=max_stages)
    else:
        tab = as_tableau(tableau, continuous=True) if tableau is not None else None
    if getattr(tab, "is_continuous", False):  # its weights through a surrogate exact for this tree
        _surrogate_fits(tab, len(seq))
        tab = tab.surrogate(len(seq))  # type: ignore[union-attr]
    return explain(seq, None if tab is None else TableauValues(tab, Reading(DecimalsMode(decimals), dps)))


_checked = as_option


def _surrogate_fits(method: Any, vertices: int) -> None:
    """Refuse (:class:`~rkcheck.errors.ResourceError`) a surrogate whose entries would not
    fit in the memory available, before it is built: hundreds of nodes make n² entries of
    thousands of digits, and GMP, failing to allocate, aborts the process."""
    from rkcheck.api.settings import budget
    from rkcheck.energy.claims import surrogate_bytes
    from rkcheck.errors import ResourceError
    from rkcheck.numbers.formatting import human_bytes

    available = budget().available_bytes
    stages, needed = surrogate_bytes(method, vertices, False)
    if available is not None and needed > available:
        raise ResourceError(f"the surrogate exact for trees of {vertices} vertices ({stages} nodes) needs about "
                            f"{human_bytes(needed)} but {human_bytes(available)} is available; explain a tree of "
                            "fewer vertices", source=method.info.source)


# ------------------------------------------------------------------ the listing


@dataclass(frozen=True)
class ConditionList:
    """What :func:`conditions` gives: the number of energy conditions per energy order
    2 … N (``counts``: order → conditions with order + 1 vertices), their ``total`` and,
    unless only counted, every condition as a :class:`FreeTree` by vertices and then
    canonical id.  ``listing`` is the underlying table (the reports' input)."""

    order: int
    degree: int | None
    listing: "ConditionListing | CountOnly"
    counted_only: bool

    @property
    def total(self) -> int:
        return len(self.listing)

    @property
    def counts(self) -> dict[int, int]:
        return self.listing.counts_by_order()

    @property
    def free_trees(self) -> list[FreeTree]:
        """Every condition (empty when only counted: ``count=True``)."""
        if self.counted_only:
            return []
        return list(self.listing.sorted_records())  # type: ignore[union-attr]

    def __len__(self) -> int:
        return self.total

    def __repr__(self) -> str:
        deg = "no degree bound" if self.degree is None else f"degree ≤ {self.degree}"
        from rkcheck.numbers.formatting import count_text

        return f"<ConditionList: {count_text(self.total)} conditions up to order {self.order}, {deg}>"


def conditions(order: int, degree: int | str | None = None, *, count: bool = False,
               max_conditions: int | None = None, announce: Callable[[str], None] | None = None) -> ConditionList:
    """The energy conditions up to energy order ``order`` — the non-superfluous free trees
    with 3 … order+1 vertices (definitions §3) whose vertices have at most ``degree``
    edges (None or ``"none"``: no bound; a bound m gives the conditions for Hamiltonians
    of degree ≤ m) — as ``rkcheck conditions`` lists them.

    ``count=True`` only counts them, from generating functions (instant at any order);
    otherwise the listing is built, refused (``ResourceError``) when it would not fit in
    memory or exceeds ``max_conditions``; ``announce(text)`` hears the estimate of a
    listing longer than 5 s.  :func:`free_trees` gives the conditions of one size."""
    from rkcheck.options import (
        parse_callback,
        parse_degree,
        parse_flag,
        parse_int_in,
        parse_positive,
    )

    order = _checked(lambda: parse_int_in(order, ORDER_RANGE, "order"))
    bound: int | None = _checked(lambda: parse_degree(degree, "degree"))
    count = _checked(lambda: parse_flag(count, "count"))
    announce = _checked(lambda: parse_callback(announce, "announce"))
    if max_conditions is not None:
        max_conditions = _checked(lambda: parse_positive(max_conditions, "max_conditions"))
    listing: ConditionListing | CountOnly
    if count:
        from rkcheck.trees.counting import CountOnly

        listing = CountOnly(order, bound)
    else:
        from rkcheck.api.settings import budget
        from rkcheck.energy.budget import check_budget, estimate
        from rkcheck.trees.listing import condition_listing

        check_budget(estimate(order, bound, "exact", 0, listing=True), budget(max_conditions, announce), order)
        listing = condition_listing(order, bound)
    return ConditionList(order, bound, listing, count)


__all__ = ["ConditionList", "EnergyCondition", "FreeTree", "RootingTerm", "conditions", "energy_condition", "free_trees"]
