"""A free tree as people name it: one energy condition (definitions §3)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property


@dataclass(frozen=True)
class FreeTree:
    """A non-superfluous free tree, named by its designated rooting (the centre; for two
    centres the one with the larger level sequence): its canonical level sequence (the
    condition's id), Butcher's bracket of that rooting, the largest number of edges at
    a vertex, and the number of distinct rooted trees in its class π⁻¹(t̄)."""

    level_sequence: tuple[int, ...]
    bracket: str
    max_degree: int
    rootings: int

    @cached_property
    def id(self) -> str:
        """The level sequence as ``1,2,3,2``: what every report and tool prints."""
        return ",".join(map(str, self.level_sequence))

    @property
    def vertices(self) -> int:
        return len(self.level_sequence)

    @property
    def order(self) -> int:
        """The energy order at which it is a condition: vertices − 1."""
        return self.vertices - 1
