"""Table cells shared by the text reports: a verdict's words, a residual for people, and
user text that rich must not read as markup."""

from __future__ import annotations

from fractions import Fraction

from rich.text import Text

from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.formatting import ball_strings, decimal_string, radius_string
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS, Verdict

STYLE = {HOLDS: "green", HOLDS_TO_DIGITS: "yellow", FAILS: "bold red"}


def state_text(v: Verdict) -> Text:
    return Text(v.label(), style=STYLE[v.state])


def enclosure_text(enc: Enclosure, verdict: Verdict, sig: int = 12, value=None) -> str:
    """A residual for people: exact value, or mid ± radius, or a certified bound.  An
    exact algebraic ``value`` (number-field element) is shown exactly and numerically."""
    if value is not None and hasattr(value, "rational"):
        r = value.rational()
        if r is None:
            return f"{value.text()} ≈ {decimal_string(enc.mid, sig)}"
        enc = Enclosure.of(r)
    if enc.exact:
        if enc.mid == 0:
            return "0"
        frac = str(enc.mid)
        approx = decimal_string(enc.mid, sig)
        if frac == approx:
            return frac
        return f"{frac} = {approx}" if Fraction(approx) == enc.mid else f"{frac} ≈ {approx}"
    if verdict.state == FAILS:
        return "{} ± {}".format(*ball_strings(enc.mid, enc.rad, sig))
    return f"|R| ≤ {radius_string(enc.magnitude() + enc.rad)}"


def plain(*values) -> list:
    """Table cells as plain Text: user strings and brackets like [τ] are not rich markup."""
    return [v if isinstance(v, Text) else Text(str(v)) for v in values]
