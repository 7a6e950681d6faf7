"""Which number context a tableau is evaluated in, and the evaluation of every condition
of a :class:`~rkcheck.trees.listing.ConditionListing` in it (definitions §5).

* **exact** — the tableau's entries are exact (rationals; number fields): residues
  modulo primes (:mod:`rkcheck.evaluation.modular`), verdicts ``holds``/``fails``;
* **ball** — anything else (rounded decimals, computed family coefficients), or on
  request: certified fixed-point balls at the working precision
  (:class:`~rkcheck.evaluation.balls.BallContext`);
* **float64** — the screen (:class:`~rkcheck.evaluation.balls.FloatContext`), for
  comparisons; never the source of a ``holds``.

This stage returns numbers (residues or enclosures); judging them is the verdict stage's
job (:mod:`rkcheck.energy`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

from rkcheck.errors import UserError
from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.balls import FloatContext, certified_context
from rkcheck.evaluation.modular import (
    ScaledTableau,
    exact_condition_sums,
    scaled_field,
    scaled_rational,
)
from rkcheck.numbers.precision import bits_for_dps, entry_bits

ARITHMETIC_MODES = ("auto", "exact", "ball")


@dataclass
class Evaluation:
    """Per number of vertices: :class:`~rkcheck.evaluation.modular.ExactOrderSums` (exact)
    or a list of :class:`~rkcheck.numbers.enclosure.Enclosure` (balls), each for the
    class representative's rooting (the listing's records give the designated sign)."""

    backend: str
    orders: dict[int, Any] = field(default_factory=dict)
    scaled: ScaledTableau | None = None


def scaled_tableau(tableau, decimals: str) -> ScaledTableau | None:
    """The exact scaled data of the tableau, or None when its entries are not exact
    (definitions §5: rounded decimals are a box of inputs, not numbers)."""
    if tableau.is_exact(decimals):
        if tableau.is_rational:
            return scaled_rational(tableau.exact_A(), tableau.exact_b())
        values = tableau.exact_values(decimals)
        # kept with the values: in a field of high degree the bounds and the integrality
        # denominator take seconds (30 s for HBVM(6, 3), degree 48), and one check asks
        # for them once per pass (classical order, energy conditions, channel estimate);
        # the split primes found so far are kept with them
        scaled = getattr(values, "_scaled", None)
        if scaled is None:
            scaled = scaled_field(values)  # entries in a number field
            values._scaled = scaled
        return scaled
    return None


def ball_context(tableau, dps: int, decimals: str, enclosures=None, vertices: int | None = None) -> Any:
    """The certified ball context (:func:`~rkcheck.evaluation.balls.certified_context`:
    Python-integer or int64-digit mid-points) for trees with up to ``vertices`` vertices."""
    A, b = enclosures or tableau.enclosures(entry_bits(dps), decimals)
    return certified_context(A, b, bits_for_dps(dps), vertices)


def float_context(tableau, decimals: str = "auto") -> FloatContext:
    A, b = tableau.enclosures(128, decimals)
    return FloatContext(A, b)


def choose_backend(tableau, decimals: str, arithmetic: str = "auto") -> str:
    """``exact`` when the entries allow it (and the user did not ask for balls), else
    ``ball``; ``arithmetic = "exact"`` on data that is not exact is a user error."""
    exact = tableau.is_exact(decimals)
    if arithmetic == "exact" and not exact:
        raise UserError("--arithmetic exact: the entries are not exact numbers (rounded decimals or "
                        "coefficients without a closed form); use auto or ball")
    return "exact" if exact and arithmetic != "ball" else "ball"


def evaluate(listing, tableau, dps: int, decimals: str, arithmetic: str = "auto", orders=None,
             enclosures=None, progress: Callable[[int, int], None] | None = None) -> Evaluation:
    """Every condition of ``listing`` (or of the given numbers of vertices);
    ``progress(done, total)`` as the work advances (passes over primes, or orders)."""
    backend = choose_backend(tableau, decimals, arithmetic)
    if backend == "exact":
        scaled = scaled_tableau(tableau, decimals)
        assert scaled is not None  # choose_backend said the entries are exact
        return Evaluation("exact", exact_condition_sums(scaled, listing, orders, progress), scaled)
    wanted = sorted(listing.orders if orders is None else orders)
    ctx = ball_context(tableau, dps, decimals, enclosures, vertices=wanted[-1] if wanted else None)
    on_order = None if progress is None else (lambda n, _: progress(wanted.index(n) + 1, len(wanted)))
    return Evaluation("ball", condition_sums(listing, ctx, tableau.stages, wanted, on_order))


def channels_for(tableau, order: int, decimals: str, arithmetic: str = "auto") -> int:
    """How many channels (prime × root) an exact check to ``order`` needs (for estimates)."""
    if choose_backend(tableau, decimals, arithmetic) != "exact":
        return 0
    scaled = scaled_tableau(tableau, decimals)
    assert scaled is not None  # choose_backend said the entries are exact
    bits = scaled.decision_bits(order + 1, order + 1)
    return len(scaled.primes_for(bits)) * scaled.degree
