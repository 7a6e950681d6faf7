"""The coefficient weight W = n of an order (OrderTerms.coefficient_weight), which replaces
``(n−1)!`` times the terms in the bound that decides zero residues, against the
reference's conditions (support.reference.energy_conditions: networkx free trees, their
rootings and σ(u), nothing from rkcheck): ``W = max_k Σ_u c_u / gcd_u c_u`` with
``c_u = (n−1)!/σ(u)`` over the terms u of condition k."""

from __future__ import annotations

import math
from functools import reduce

import pytest
from support import reference as ref

from rkcheck.trees.listing import ConditionListing


def reference_weight(n: int, degree: int | None) -> int:
    best = 1
    for cond in ref.energy_conditions(n, degree):
        coefficients = [math.factorial(n - 1) // sigma for _, _, sigma, _ in cond["terms"]]
        g = reduce(math.gcd, coefficients)
        best = max(best, sum(c // g for c in coefficients))
    return best


@pytest.mark.parametrize("degree", [None, 3])
def test_the_weight_bounds_every_conditions_coefficients_and_is_reached(degree):
    # the bound W = n (the orbit argument of OrderTerms.coefficient_weight) against the
    # reference's coefficients by brute force: never exceeded, and reached (no prime lost)
    listing = ConditionListing(9, degree)
    for n, terms in listing.orders.items():
        assert terms.coefficient_weight == n == reference_weight(n, degree), n


def test_the_weight_is_far_below_the_old_bound():
    listing = ConditionListing(13, None)
    for n, terms in listing.orders.items():
        assert terms.coefficient_weight < math.factorial(n - 1) * terms.max_terms or n <= 3


RK4 = ([["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]],
       ["1/6", "1/3", "1/3", "1/6"])
# AVF over Simpson's rule (A = c bᵀ, quadrature order 4): every condition of a free tree
# of maximum degree ≤ 4 holds (seed §1), others need not
AVF_SIMPSON = ([["0", "0", "0"], ["1/12", "1/3", "1/12"], ["1/6", "2/3", "1/6"]], ["1/6", "2/3", "1/6"])


@pytest.mark.parametrize("tableau", [RK4, AVF_SIMPSON], ids=["rk4", "avf-simpson"])
def test_decision_with_the_weight_still_decides_every_condition_as_the_reference(tableau):
    # the exact check to order 9 with the weight's fewer primes: every condition is
    # proven zero exactly where the reference's Fraction residual is zero
    from fractions import Fraction as F

    from rkcheck.evaluation.modular import exact_condition_sums
    from rkcheck.evaluation.scaled import scaled_rational

    A = [[F(x) for x in row] for row in tableau[0]]
    b = [F(x) for x in tableau[1]]
    scaled = scaled_rational(A, b)
    listing = ConditionListing(9, None)
    sums = exact_condition_sums(scaled, listing)
    seen = set()
    for n in listing.orders:
        t = listing.orders[n]
        assert (scaled.decision_bits(n, t.max_terms, t.coefficient_weight)
                < scaled.decision_bits(n, t.max_terms)) or n <= 3
        expected = {c["id"]: ref.energy_residual(c, A, b) for c in ref.energy_conditions(n)}
        zero = sums[n].is_zero()
        for k in range(len(t)):
            key = listing.record(n, k).level_sequence
            assert bool(zero[k]) == (expected[key] == 0), (n, key)
            seen.add(bool(zero[k]))
    assert seen == {True, False}  # both verdicts occur: the comparison is not vacuous
