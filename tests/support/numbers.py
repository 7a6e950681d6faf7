"""How a tableau's numbers read, for tests: the check's own reading (rkcheck.numbers.reading)."""

from __future__ import annotations

from rkcheck.evaluation.values import TableauValues
from rkcheck.numbers.reading import Reading


def exact_under(tab, decimals: str = "auto") -> bool:
    """Whether a check with this decimals mode runs on exact values (rational or a number field)."""
    return TableauValues(tab, Reading(decimals)).kind.is_exact
