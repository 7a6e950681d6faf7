"""The three states of a condition (SPEC §5), and nothing else.

=================== =====================================================================
``holds``           the residual is exactly zero (exact arithmetic on exact data)
``holds_to_digits`` a rigorous enclosure of the residual contains 0; ``digits`` = D with
                    ``|R| <= 10^-D`` certified
``fails``           a rigorous enclosure of the residual excludes 0: certainly violated
=================== =====================================================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from rkcheck.evaluation.backends import Enclosure
from rkcheck.numbers.intervals import Interval

HOLDS = "holds"
HOLDS_TO_DIGITS = "holds_to_digits"
FAILS = "fails"


@dataclass(frozen=True, slots=True)
class Verdict:
    state: str
    digits: int | None = None  # only for holds_to_digits

    @property
    def holds(self) -> bool:
        return self.state != FAILS

    def label(self) -> str:
        if self.state == HOLDS_TO_DIGITS:
            return f"holds to {self.digits} digits"
        return self.state


def certified_digits(bound: Fraction | float) -> int:
    """The largest integer D with ``bound <= 10^-D`` (bound > 0), exactly."""
    if bound <= 0:
        raise ValueError("bound must be positive")
    p, q = bound.as_integer_ratio()

    def within(d: int) -> bool:  # bound <= 10^-d, in integers
        return p * 10**d <= q if d >= 0 else p <= q * 10 ** (-d)

    d = math.floor(math.log10(q) - math.log10(p))  # math.log10 takes big ints
    while within(d + 1):
        d += 1
    while not within(d):
        d -= 1
    return d


def classify(enc: Enclosure) -> Verdict:
    """The state of a residual from its enclosure (SPEC §5)."""
    if enc.exact:
        return Verdict(HOLDS) if enc.mid == 0 else Verdict(FAILS)
    if not enc.contains_zero():
        return Verdict(FAILS)
    bound = abs(enc.mid) + enc.rad
    if bound == 0:
        return Verdict(HOLDS)
    if isinstance(bound, float):
        bound = bound * (1 + 2.0**-51) + 2.0**-1074  # the float addition rounded up
    return Verdict(HOLDS_TO_DIGITS, certified_digits(bound))


def classify_interval(x: Interval, exact: bool) -> Verdict:
    """The state of a quantity known as an interval; a point interval counts as exact only
    when the data was exact (``exact``), otherwise it is a certified enclosure."""
    return classify(Enclosure(x.mid, x.rad, exact and x.is_point))


def combine(verdicts: list[Verdict]) -> Verdict:
    """All of several conditions: fails if any fails, else the weakest digits."""
    if any(v.state == FAILS for v in verdicts):
        return Verdict(FAILS)
    digits = [v.digits for v in verdicts if v.state == HOLDS_TO_DIGITS]
    if digits:
        return Verdict(HOLDS_TO_DIGITS, min(digits))  # type: ignore[type-var]
    return Verdict(HOLDS)
