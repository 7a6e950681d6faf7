"""The three states of a condition (definitions §5), and nothing else: the vocabulary
every stage that judges (:mod:`rkcheck.properties`, :mod:`rkcheck.energy`) and every
report shares.  May import: :mod:`rkcheck.numbers`.

=================== =====================================================================
``holds``           the residual is exactly zero (exact arithmetic on exact data)
``holds_to_digits`` a rigorous enclosure of the residual contains 0; ``digits`` = D, the
                    certain decimal digits: ``|R| <= 10^-D`` certified when D >= 1, and
                    D = 0 when not even the first digit is (however wide the enclosure)
``fails``           a rigorous enclosure of the residual excludes 0: certainly violated
=================== =====================================================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from fractions import Fraction
from typing import Any

from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.formatting import digits_text
from rkcheck.numbers.intervals import Interval


class State(StrEnum):
    """The state of a condition.  Its value is the JSON spelling; :attr:`code` is the
    small integer arrays of millions of verdicts store (int8)."""

    HOLDS = "holds"
    HOLDS_TO_DIGITS = "holds_to_digits"
    FAILS = "fails"
    #: a yes/no property of a method that nothing computed decides either way (a
    #: continuous method's kernel form does not show it, and no tree refutes it); never
    #: the state of a condition
    UNDECIDED = "undecided"

    def __repr__(self) -> str:
        # shown as the string it equals (``'fails'``): results print as they serialise
        return repr(self.value)

    @property
    def code(self) -> int:
        return _CODES[self]

    @staticmethod
    def of_code(code: int) -> "State":
        return _STATES[code]


_STATES = (State.HOLDS, State.HOLDS_TO_DIGITS, State.FAILS, State.UNDECIDED)
_CODES = {state: k for k, state in enumerate(_STATES)}

HOLDS = State.HOLDS
HOLDS_TO_DIGITS = State.HOLDS_TO_DIGITS
FAILS = State.FAILS
UNDECIDED = State.UNDECIDED

#: the fewest certain digits a ``holds to D digits`` needs to count as an answer: with
#: none, its enclosure contains 0 and says nothing more (definitions §5)
DECIDING_DIGITS = 1
#: what a statement held to 0 digits concludes
UNDECIDED_TEXT = "not decided, no digit being certain"


@dataclass(frozen=True, slots=True)
class Verdict:
    """holds, holds to ``digits`` digits, or fails (definitions §5.3).

    ``digits`` counts certain digits, so it is never negative: an enclosure that contains
    0 and is wider than 1 certifies no digit, and is ``holds to 0 digits`` whatever its
    width (the enclosure itself says how wide).  Such a verdict decides nothing, and no
    ``--require`` gate passes it (:data:`DECIDING_DIGITS`)."""

    state: State
    digits: int | None = None  # only for holds_to_digits

    def __post_init__(self) -> None:
        if self.digits is not None and self.digits < 0:
            object.__setattr__(self, "digits", 0)

    @property
    def shown(self) -> bool:
        """Holds exactly, or to at least one certain digit: what a certificate, an AVF
        verdict or a claim counts as shown."""
        return self.holds and self.decided

    def how(self) -> str:
        """``exactly``, or ``to D digits``: how a statement that holds holds."""
        return "exactly" if self.state == HOLDS else f"to {digits_text(self.digits)}"

    @property
    def decided(self) -> bool:
        """Whether the verdict says anything: not ``undecided``, and a holds to digits
        certifies at least one digit."""
        if self.state == HOLDS_TO_DIGITS:
            return (self.digits or 0) >= DECIDING_DIGITS
        return self.state != UNDECIDED

    @property
    def holds(self) -> bool:
        return self.state in (HOLDS, HOLDS_TO_DIGITS)

    def label(self) -> str:
        if self.state == HOLDS_TO_DIGITS:
            return f"holds to {digits_text(self.digits)}"
        return self.state

    def answer(self) -> str:
        """The verdict as the answer to a yes/no property: ``yes``, ``yes, to D digits``
        (not a proof), ``no`` or ``not decided``."""
        if self.state == FAILS:
            return "no"
        if not self.decided:
            return "not decided"
        return "yes" if self.state == HOLDS else f"yes, to {digits_text(self.digits)}"


def certified_digits(bound: Fraction | float) -> int:
    """The largest integer D with ``bound <= 10^-D`` (bound > 0), exactly; negative for a
    bound above 10 (a :class:`Verdict` counts that as 0 certain digits)."""
    if bound <= 0:
        raise ValueError("bound must be positive")
    p, q = bound.as_integer_ratio()

    def within(d: int) -> bool:  # bound <= 10^-d, in integers
        return bool(p * 10**d <= q) if d >= 0 else bool(p <= q * 10 ** (-d))

    d = math.floor(math.log10(q) - math.log10(p))  # math.log10 takes big ints
    while within(d + 1):
        d += 1
    while not within(d):
        d -= 1
    return d


def classify(enc: Enclosure) -> Verdict:
    """The state of a residual from its enclosure (definitions §5)."""
    if enc.exact:
        return Verdict(HOLDS) if enc.mid == 0 else Verdict(FAILS)
    if not enc.contains_zero():
        return Verdict(FAILS)
    bound = enc.magnitude() + enc.rad
    if bound == 0:
        return Verdict(HOLDS)
    if isinstance(bound, float):
        bound = bound * (1 + 2.0**-51) + 2.0**-1074  # the float addition rounded up
    return Verdict(HOLDS_TO_DIGITS, certified_digits(bound))


def classify_many(encs: list[Enclosure]) -> list[Verdict]:
    """The states of many residuals at once (the same rule as :func:`classify`).

    When the enclosures come from the float64 screen (float mid-points and radii) the
    rule runs vectorised: ``fails`` iff |mid| > rad; otherwise D = ⌊−log10(bound)⌋ on the
    bound rounded up, lowered by one when log10's own rounding could make it overstate (a
    margin of 1e-9 in the exponent: conservative, never optimistic)."""
    if not encs or not all(isinstance(e.mid, float) for e in encs):
        return [classify(e) for e in encs]
    import numpy as np

    mid = np.array([e.mid for e in encs])
    rad = np.array([e.rad for e in encs])
    fails = np.abs(mid) > rad
    bound = (np.abs(mid) + rad) * (1 + 2.0**-51) + 2.0**-1074
    with np.errstate(divide="ignore"):
        digits = np.floor(-np.log10(bound) - 1e-9)
    digits = np.maximum(np.where(np.isfinite(digits), digits, 0), 0).astype(np.int64)  # certain digits
    cache: dict[int, Verdict] = {}
    fail, hold = Verdict(FAILS), Verdict(HOLDS)
    verdicts = []
    for f, d, bz in zip(fails.tolist(), digits.tolist(), (bound == 0).tolist()):
        if f:
            verdicts.append(fail)
        elif bz:
            verdicts.append(hold)
        else:
            v = cache.get(d)
            if v is None:
                v = cache[d] = Verdict(HOLDS_TO_DIGITS, d)
            verdicts.append(v)
    return verdicts


def classify_bounds(excludes_zero: Any, bound: Any, exponent: int = 0) -> tuple[Any, Any]:
    """The states of many certified values at once, given for each whether its
    enclosure excludes 0 (exactly) and a float upper bound of its magnitude (|mid| + rad)
    in units of ``2^−exponent``: ``fails`` where 0 is excluded, else ``holds to D
    digits`` with D = ⌊−log10(bound) + exponent·log10(2)⌋, lowered by one when log10's own
    rounding could make it overstate (a margin of 1e-9 in the exponent, far above the
    rounding of both terms: conservative, never optimistic).  Returns (state codes
    0/1/2, digits) as numpy arrays."""
    import numpy as np

    fails = np.asarray(excludes_zero, dtype=bool)
    bound = np.asarray(bound, dtype=float)
    with np.errstate(divide="ignore"):
        digits = np.floor(-np.log10(bound) + exponent * math.log10(2) - 1e-9)
    # certain digits, never negative (as :class:`Verdict` counts them); on point data the
    # check raises the precision instead (energy.judging.sharpen_weak_holds)
    digits = np.maximum(np.where(np.isfinite(digits), digits, 0), 0).astype(np.int32)
    state = np.where(fails, FAILS.code, HOLDS_TO_DIGITS.code).astype(np.int8)
    return state, np.where(fails, -1, digits).astype(np.int32)


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
