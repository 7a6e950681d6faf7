"""The vectorised fast paths agree with the straightforward path: bit-identical exact
results, identical verdicts on the shipped tableaux, and a float screen that never says
`fails` where exact arithmetic says `holds` (performance issue)."""

from __future__ import annotations

import random
from fractions import Fraction
from pathlib import Path

import pytest
from support import reference as ref
from support.paths import TABLEAUX  # noqa: E402

from rkcheck.energy.check import evaluate_conditions
from rkcheck.energy.verdicts import FAILS, HOLDS, classify
from rkcheck.evaluation.backends import BallBackend, ExactBackend, make_backend
from rkcheck.evaluation.float_screen import make_float_backend
from rkcheck.io.discovery import find_tableau_files
from rkcheck.io.loader import load
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.precision import bits_for_dps
from rkcheck.studies.accuracy import backend_for
from rkcheck.trees.conditions import ConditionTable, condition_table


def random_tableau(seed: int):
    rng = random.Random(seed)
    s = rng.randint(1, 4)
    A = [[Fraction(rng.randint(-12, 12), rng.randint(1, 12)) for _ in range(s)] for _ in range(s)]
    b = [Fraction(rng.randint(-12, 12), rng.randint(1, 12)) for _ in range(s)]
    if rng.random() < 0.5:  # some with Σb = 1, so that low-order conditions can vanish
        b[-1] = 1 - sum(b[:-1])
    return A, b


def straightforward(table: ConditionTable, backend):
    """The per-condition loop (no vectorisation, no cached term arrays)."""
    backend.tree_weights(table.trees)
    return [backend.enclose_terms(table.trees, c.terms, c.denominator) for c in table.conditions]


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("degree", [None, 3])
def test_exact_fast_path_is_bit_identical_to_the_loop_and_the_reference(seed, degree):
    A, b = random_tableau(seed)
    table = ConditionTable(10 if degree else 8, degree)
    backend = ExactBackend(A, b)
    backend.tree_weights(table.trees)
    fast = backend.enclose_table(table)
    slow = straightforward(table, ExactBackend(A, b))
    assert [e.mid for e in fast] == [e.mid for e in slow]
    assert all(e.exact and e.rad == 0 for e in fast)
    # and against the independent brute force, on the small orders
    for cond, enc in zip(table.conditions, fast):
        if cond.vertices <= 7:
            want = ref.energy_residual({"terms": [
                (None, t.sign, t.sigma, [table.trees.level_sequence(x) for x in t.branches]) for t in cond.terms
            ]}, A, b)
            assert enc.mid == want


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("dps", [15, 50, 400, 1000])
def test_ball_fast_path_has_the_same_mid_points_and_encloses_the_exact_values(seed, dps):
    A, b = random_tableau(seed)
    table = condition_table(9 if dps <= 50 else 7, None)
    exact = ExactBackend(A, b)
    exact.tree_weights(table.trees)
    truth = exact.enclose_table(table)
    bits = bits_for_dps(dps)
    ball = BallBackend([[Interval.point(x) for x in r] for r in A], [Interval.point(x) for x in b], bits)
    ball.tree_weights(table.trees)
    fast = ball.enclose_table(table)
    slow = straightforward(table, BallBackend([[Interval.point(x) for x in r] for r in A],
                                              [Interval.point(x) for x in b], bits))
    assert [e.mid for e in fast] == [e.mid for e in slow]
    for f, t in zip(fast, truth):
        assert abs(f.mid - t.mid) <= f.rad and f.rad < Fraction(1, 10**dps) * max(1, abs(t.mid))


@pytest.mark.parametrize("seed", range(10))
def test_float_screen_never_fails_where_exact_holds(seed):
    A, b = random_tableau(seed)
    tab = Tableau.from_values(A, b)
    table = condition_table(10, None)
    exact = evaluate_conditions(table, ExactBackend(A, b))
    screen = evaluate_conditions(table, make_float_backend(tab))
    for e, f in zip(exact, screen):
        if e.verdict.state == HOLDS:
            assert f.verdict.state != FAILS, e.condition.id
        assert abs(Fraction(f.enclosure.mid) - e.enclosure.mid) <= Fraction(f.enclosure.rad)


FILES = [f for f in find_tableau_files([str(TABLEAUX)])]


@pytest.mark.parametrize("path", FILES, ids=[str(Path(f).relative_to(TABLEAUX)) for f in FILES])
def test_shipped_tableaux_get_identical_verdicts_on_both_paths(path):
    tab = load(path)
    degree = tab.check.get("degree")
    table = condition_table(8, degree)
    fast = evaluate_conditions(table, make_backend(tab, 50, "rounded"))
    slow = straightforward(table, make_backend(tab, 50, "rounded"))
    assert [r.verdict for r in fast] == [classify(e) for e in slow]
    if tab.is_exact("rounded"):  # the float screen against exact arithmetic
        screen = evaluate_conditions(table, backend_for(tab, "float64"))
        for r, s in zip(fast, screen):
            if r.verdict.state == HOLDS:
                assert s.verdict.state != FAILS
