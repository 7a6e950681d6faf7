"""A decimal box's conditions of one order as judged (definitions §5.2): the centre
``R(x̃)`` — certified balls or exact — beside the variation ``V`` over the box and the
screen's own enclosure over it, each decisive where it is sharper
(:func:`~rkcheck.evaluation.box.judge_box` computes them)."""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Iterable, Protocol

import numpy as np

from rkcheck.evaluation.balls import ETA, INFLATE, BallSums, FloatSums, U
from rkcheck.numbers.enclosure import Enclosure


class Variations(Protocol):
    """What gives the variation ``V`` of every condition of an order along every
    direction, on demand (:class:`~rkcheck.evaluation.box.Refiner`)."""

    def variation(self, n: int) -> np.ndarray: ...

class BallCentre:
    """``R(x̃)`` of one order's conditions in balls: ``M/(f·2^P) ± ρ/(f·2^S)``
    (:class:`~rkcheck.evaluation.balls.BallSums`), decided without a Fraction per
    condition."""

    def __init__(self, sums: BallSums):
        self.sums = sums

    def spread(self) -> np.ndarray:
        """The balls' radii (floats, about: only for choosing the exact route)."""
        s = self.sums
        result: np.ndarray = np.ldexp(np.asarray(s.rads, dtype=float), -s.shift) / float(s.factorial)
        return result

    def beyond(self, variation: np.ndarray) -> np.ndarray:
        """``|R(x̃)| > V`` for every value in the ball: ``|M| > 2^P·(f·V + ρ·2^−S)``, the
        right side rounded up (a float compared with a Python integer exactly; an
        overflow to inf claims nothing)."""
        s = self.sums
        f = float(s.factorial)
        if f < s.factorial:
            f = math.nextafter(f, math.inf)
        with np.errstate(over="ignore", invalid="ignore"):
            t = (f * variation + np.ldexp(np.asarray(s.rads, dtype=float), -s.shift)) * (1 + 8 * U) + ETA
        return s.exceeds(t)

    def bound(self, variation: np.ndarray) -> np.ndarray:
        """An upper bound of ``|R(x̃)| + ε + V`` (floats, rounded up)."""
        with np.errstate(over="ignore"):
            result: np.ndarray = (self.sums.magnitude_bound() + variation) * INFLATE + ETA
            return result

    def enclosure(self, k: int, variation: float) -> Enclosure:
        e = self.sums.enclosure(k)
        return Enclosure(e.mid, e.rad + Fraction(variation), False)


class ExactCentre:
    """``R(x̃) = integers[k] / scale`` exactly (residues modulo primes), decided with
    integer comparisons: a Fraction per condition (a gcd each) costs more than the
    evaluation."""

    def __init__(self, integers: list[int], scale: int):
        self.integers, self.scale = integers, scale
        self._c: np.ndarray | None = None

    def beyond(self, variation: np.ndarray) -> np.ndarray:
        """``|R(x̃)| > V``, exactly.  Rounding to nearest is monotone and V is a float, so
        the correctly rounded ``c = |N|/scale`` above V proves ``|R(x̃)| > V`` and below V
        disproves it; only ``c = V`` is decided in integers: ``|N|·2^k > m·scale`` for
        ``V = m/2^k``."""
        c = self._magnitudes()
        if c is None:
            return self._beyond_exactly(variation, range(len(self.integers)))
        out = c > variation
        tie = np.flatnonzero(c == variation)
        if len(tie):
            out[tie] = self._beyond_exactly(variation, tie.tolist())[tie]
        return out

    def _beyond_exactly(self, variation: np.ndarray, indices: Iterable[int]) -> np.ndarray:
        out = np.zeros(len(self.integers), dtype=bool)
        for i in indices:
            x = self.integers[i]
            if x and math.isfinite(variation[i]):
                m, k = float(variation[i]).as_integer_ratio()
                out[i] = abs(x) * k > m * self.scale
        return out

    def _magnitudes(self) -> np.ndarray | None:
        """``|N|/scale`` correctly rounded (integer true division, as ``float(Fraction)``),
        element by element in numpy's loop; None past float64's range."""
        if self._c is None:
            try:
                self._c = (np.abs(np.array(self.integers, dtype=object)) / self.scale).astype(float) \
                    if len(self.integers) else np.zeros(0)
            except OverflowError:
                return None
        return self._c

    def bound(self, variation: np.ndarray) -> np.ndarray:
        """An upper bound of ``|R(x̃)| + V``: floats, rounded up."""
        c = self._magnitudes()
        if c is None:  # the integer division raises past float64's range, as float(Fraction) does
            c = np.array([_float_or_inf(abs(x), self.scale) for x in self.integers], dtype=float)
        result: np.ndarray = (c * (1 + 4 * U) + variation) * INFLATE + ETA
        return result

    def enclosure(self, k: int, variation: float) -> Enclosure:
        return Enclosure(Fraction(self.integers[k], self.scale), Fraction(variation), False)


def _float_or_inf(x: int, q: int) -> float:
    try:
        return x / q
    except OverflowError:
        return math.inf


class BoxSums:
    """The conditions of one order judged over the box (the representative's sign):
    the mean value form ``R(x̃) ± V`` and the screen's enclosure over the box, each
    decisive where it is sharper.  What :func:`~rkcheck.energy.results.order_verdicts`
    reads: ``excludes_zero``, ``magnitude_bound``, ``enclosure``."""

    def __init__(self, centre: BallCentre | ExactCentre, screen: "FloatSums | OpenScreen", variation: np.ndarray,
                 refined: "tuple[Variations, int, np.ndarray] | None" = None):
        """``refined``: where ``variation`` is the majorant's bound ``V̄`` (a mask), the
        order ``n`` and what computes its ``V`` when a report shows such a condition."""
        self.centre, self.screen, self.variation = centre, screen, variation
        self.refined = refined
        self._fails = centre.beyond(variation)
        self._screen_fails = np.asarray(screen.excludes_zero(), dtype=bool)
        self._bound = centre.bound(variation)
        self._screen_bound = np.asarray(screen.magnitude_bound(), dtype=float)

    def around(self, centre: BallCentre | ExactCentre) -> "BoxSums":
        """The same order judged around another centre."""
        return BoxSums(centre, self.screen, self.variation, self.refined)

    def _shown_variation(self, k: int) -> float:
        """``V`` of condition ``k``: the majorant's ``V̄`` decided it (it fails either way),
        the enclosure a report shows has the ``V`` of every direction."""
        if self.refined is None or not self.refined[2][k]:
            return float(self.variation[k])
        refiner, n, _ = self.refined
        return float(refiner.variation(n)[k])

    def __len__(self) -> int:
        return len(self.variation)

    def excludes_zero(self) -> np.ndarray:
        result: np.ndarray = self._fails | self._screen_fails
        return result

    def magnitude_bound(self) -> np.ndarray:
        result: np.ndarray = np.minimum(self._bound, self._screen_bound)
        return result

    def enclosure(self, k: int) -> Enclosure:
        """The enclosure that decides: the mean value form's where it fails or bounds
        ``|R|`` at least as tightly, else the screen's."""
        if self._fails[k] or not (self._screen_fails[k] or self._screen_bound[k] < self._bound[k]):
            return self.centre.enclosure(k, self._shown_variation(k))
        return self.screen.enclosure(k)


class OpenScreen:
    """The screen's enclosures over the box of the conditions the majorant left open
    (``opened``, their sums from a :class:`~rkcheck.evaluation.subset.Subset`); the
    others, which the majorant decided, have none: they exclude nothing and bound
    nothing."""

    def __init__(self, k: int, opened: np.ndarray | None = None, sums: FloatSums | None = None):
        self._fails, self._bound = np.zeros(k, dtype=bool), np.full(k, np.inf)
        self._sums, self._position = sums, np.full(k, -1, dtype=np.intp)
        if opened is not None and sums is not None:
            self._fails[opened] = np.asarray(sums.excludes_zero(), dtype=bool)
            self._bound[opened] = np.asarray(sums.magnitude_bound(), dtype=float)
            self._position[opened] = np.arange(len(opened))

    def excludes_zero(self) -> np.ndarray:
        return self._fails

    def magnitude_bound(self) -> np.ndarray:
        return self._bound

    def enclosure(self, k: int) -> Enclosure:
        assert self._sums is not None and self._position[k] >= 0, "no screen for a decided condition"
        return self._sums.enclosure(int(self._position[k]))
