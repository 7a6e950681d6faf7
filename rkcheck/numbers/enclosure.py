"""The certified number every backend returns: ``mid ± rad`` (docs/definitions.md §5).

An :class:`Enclosure` is the contract between evaluation and verdicts: the true value
lies in ``[mid − rad, mid + rad]``; ``exact`` says that ``rad == 0`` by construction
(exact arithmetic on exact data), which is what allows the verdict ``holds`` rather
than ``holds to D digits``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import NamedTuple, TypeAlias

Real: TypeAlias = Fraction | float  # an exact rational, or a float (an exact dyadic one)


class Enclosure(NamedTuple):
    """``mid ± rad`` with rational end points; ``exact`` means ``rad == 0`` by construction.

    ``mid`` and ``rad`` are Fractions, or floats on the float64 screen's fast path (a
    float is an exact dyadic rational, so nothing is lost).  A NamedTuple: one is built
    per condition and evaluation, and tuples are much cheaper to build than frozen
    dataclasses."""

    mid: Real
    rad: Real
    exact: bool

    def contains_zero(self) -> bool:
        return self.magnitude() <= self.rad

    def magnitude(self) -> Real:
        """``|mid|``."""
        # abs() of the union: mypy solves abs's type variable to object (the join of
        # Fraction and float), so each branch takes its own abs
        mid = self.mid
        return abs(mid) if isinstance(mid, float) else abs(mid)

    @staticmethod
    def of(x: Fraction | int) -> "Enclosure":
        """The exact enclosure of a rational number."""
        return Enclosure(Fraction(x), Fraction(0), True)
