"""A ball printed with fewer digits than it has still holds the value it stands for: the
radius grows by what rounding the mid-point moved it."""

from __future__ import annotations

import random
from fractions import Fraction

from rkcheck.numbers.formatting import ball_strings


def test_printed_balls_enclose_their_mid_points():
    rng = random.Random(28)
    for _ in range(2000):
        mid = Fraction(rng.randint(-10**40, 10**40), rng.randint(1, 10**30))
        rad = Fraction(rng.randint(0, 10**6), 10 ** rng.randint(0, 60))
        sig = rng.randint(1, 40)
        mid_text, rad_text = ball_strings(mid, rad, sig)
        lo, hi = Fraction(mid_text) - Fraction(rad_text), Fraction(mid_text) + Fraction(rad_text)
        assert lo <= mid - rad and mid + rad <= hi, (mid, rad, sig, mid_text, rad_text)


def test_floats_are_taken_exactly_and_nonfinite_balls_say_so():
    mid_text, rad_text = ball_strings(0.1, 1e-30, 40)  # 0.1 is 3602879701896397/2^55
    assert abs(Fraction(mid_text) - Fraction(0.1)) <= Fraction(rad_text)
    assert ball_strings(float("nan"), 1.0, 5) == ("nan", "inf")
