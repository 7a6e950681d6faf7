"""How the numbers of a method are read: the decimals mode and the working precision.

A :class:`Reading` is decided once, where the options are resolved, and passed down
unchanged to everything that reads entries, encloses them or evaluates conditions
(docs: "Verdicts and numbers").  It is the one place that says what a decimal literal
stands for and how many digits a certified ball carries — like an mpmath context that
owns its precision, so that no function below the options takes a loose ``decimals``
string or ``dps`` integer.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from rkcheck.numbers.precision import bits_for_dps, entry_bits


class DecimalsMode(StrEnum):
    """What a decimal literal such as ``0.2113248654051871`` stands for.

    * ``AUTO`` — as ``ROUNDED``, widened to the binary64 double's rounding interval when
      the literal, as written, is the shortest representation of a double (what Python,
      numpy and Julia print);
    * ``ROUNDED`` — a decimal with enough significant digits
      (:data:`rkcheck.numbers.grammar.ROUNDED_MIN_DIGITS`) is any number within half a
      unit of its last digit;
    * ``FLOAT64`` — every nonzero decimal is the double nearest to it, and stands for
      that double's rounding interval;
    * ``EXACT`` — every literal at face value.

    A ``StrEnum``: its members are the strings of the CLI, the ``[check]`` table and
    the JSON output, so ``DecimalsMode.AUTO == "auto"``.
    """

    AUTO = "auto"
    ROUNDED = "rounded"
    FLOAT64 = "float64"
    EXACT = "exact"

    @property
    def rounds(self) -> bool:
        """Long decimals stand for their rounding interval (``auto`` and ``rounded``)."""
        return self in (DecimalsMode.AUTO, DecimalsMode.ROUNDED)


class Arithmetic(StrEnum):
    """Which arithmetic evaluates the conditions: ``AUTO`` (exact when the entries are
    exact numbers, certified balls otherwise), ``EXACT`` (refuse data that is not
    exact) or ``BALL`` (certified balls even for exact data)."""

    AUTO = "auto"
    EXACT = "exact"
    BALL = "ball"


#: The working precision (decimal digits) of certified balls when nothing else is said.
DEFAULT_DPS = 50


@dataclass(frozen=True)
class Reading:
    """The decimals mode, the working precision and the arithmetic of one check, as one
    value."""

    decimals: DecimalsMode = DecimalsMode.AUTO
    dps: int = DEFAULT_DPS
    arithmetic: Arithmetic = Arithmetic.AUTO

    def __post_init__(self) -> None:
        # accept the modes' strings (the API and the files speak strings); store enums
        object.__setattr__(self, "decimals", DecimalsMode(self.decimals))
        object.__setattr__(self, "arithmetic", Arithmetic(self.arithmetic))

    @property
    def entry_bits(self) -> int:
        """Bits of the entries' enclosures (a few guard bits above the balls' precision)."""
        return entry_bits(self.dps)

    @property
    def ball_bits(self) -> int:
        """Bits of the certified balls' mid-points."""
        return bits_for_dps(self.dps)

    def at(self, dps: int) -> "Reading":
        """The same reading at another working precision."""
        return Reading(self.decimals, dps, self.arithmetic)

    def using(self, arithmetic: Arithmetic | str) -> "Reading":
        """The same reading in another arithmetic."""
        return Reading(self.decimals, self.dps, Arithmetic(arithmetic))

#: The default reading of every check.
DEFAULT_READING = Reading()
