"""Stage reduction to the irreducible form, and AVF recognition through disguises.

Independent routes: the disguises of tests/support/disguise.py change the tableau but
not the method; the brute-force reference (tests/support/reference.py) confirms that
every disguised tableau has the elementary weights of the AVF method it hides, and that
a perturbed one breaks an energy condition (so it cannot be AVF, which preserves energy).
"""

from __future__ import annotations

import random
from fractions import Fraction as F

import pytest
from support import reference as ref
from support.disguise import RATIONAL_RULES, avf_tableau, disguise

from rkcheck.energy.check import CheckOptions, check
from rkcheck.methods.tableau import Tableau
from rkcheck.properties.avf import avf_of_reduction, theorem1_remark
from rkcheck.properties.reduction import reduce_tableau

# AVF over Radau IIA-2 in disguise. Stages 1 and 3 have identical
# rows; stage 2's row is 3× theirs once columns 1 and 3 are merged; stages 4 and 5 have
# identical rows and weights 3/8, −3/8 that cancel.
DISGUISED_A = [["17/32", "1/12", "-9/32", "0", "0"], ["51/32", "1/4", "-27/32", "0", "0"],
            ["17/32", "1/12", "-9/32", "0", "0"], ["-1", "4/3", "3/5", "-2/27", "5/27"],
            ["-1", "4/3", "3/5", "-2/27", "5/27"]]
DISGUISED_b = ["4/3", "1/4", "-7/12", "3/8", "-3/8"]


def fr(rows):
    return [[F(x) for x in row] for row in rows]


def test_the_review_example_is_avf_over_radau_iia_2():
    A, b = fr(DISGUISED_A), [F(x) for x in DISGUISED_b]
    red = reduce_tableau(A, b)
    # by hand: merge 1+3 → row (17/32 − 9/32, 1/12) = (1/4, 1/12), weight 4/3 − 7/12 = 3/4;
    # stage 2 → (51/32 − 27/32, 1/4) = (3/4, 1/4), weight 1/4; 4+5 has weight 0, unused.
    assert red.classes == [(0, 2), (1,)]
    assert red.A == [[F(1, 4), F(1, 12)], [F(3, 4), F(1, 4)]] and red.b == [F(3, 4), F(1, 4)]
    assert sorted(red.dropped) == [3, 4] and red.decisions == []
    # AVF over Radau IIA-2: c = (1/3, 1), b = (3/4, 1/4), A = c bᵀ; quadrature order 3
    assert red.A == avf_tableau([F(1, 3), F(1)], [F(3, 4), F(1, 4)])[0]
    for m in (2, 3):
        v = avf_of_reduction(red, m)
        assert v.equals_avf and v.verdict.state == "holds", v.reason
    assert not avf_of_reduction(red, 4).equals_avf  # Σ b c³ = 1/4 fails for Radau-2
    res = check(Tableau.from_values(DISGUISED_A, DISGUISED_b), CheckOptions(degree=2, order=6))
    assert res.avf.equals_avf and res.energy_order_all and res.certificate.kind == "avf"


def _weights_agree(A1, b1, A2, b2, max_vertices=5) -> bool:
    return all(ref.elementary_weight(t, A1, b1) == ref.elementary_weight(t, A2, b2)
               for n in range(1, max_vertices + 1) for t in ref.rooted_trees(n))


def _disguised(seed):
    rng = random.Random(seed)
    name, c, b, q = RATIONAL_RULES[seed % len(RATIONAL_RULES)]
    A0, b0 = avf_tableau(c, b)
    A, bb = disguise(A0, b0, rng, operations=rng.randint(1, 4))
    return name, q, (A0, b0), (A, bb), rng


SEEDS = range(60)


@pytest.mark.parametrize("seed", SEEDS)
def test_every_disguised_avf_tableau_is_recognised(seed):
    name, q, (A0, b0), (A, b), _ = _disguised(seed)
    assert _weights_agree(A0, b0, A, b), "the generator must not change the method"
    red = reduce_tableau(A, b)
    assert red.reduced_stages == len(b0), (name, red.describe())
    assert _weights_agree(A0, b0, red.A, red.b), "the reduction must not change the method"
    for m in range(2, q + 1):
        v = avf_of_reduction(red, m)
        assert v.equals_avf and v.verdict.state == "holds", (name, m, v.reason)


def test_perturbed_disguised_tableaux_are_never_recognised():
    """Change one entry; when the reference finds a failing degree-m energy condition
    the method cannot be AVF (AVF preserves energy), and rkcheck must say so."""
    judged = 0
    for seed in SEEDS:
        name, q, _, (A, b), rng = _disguised(seed)
        m = 2
        A, b = [row[:] for row in A], b[:]
        if rng.random() < 0.8:
            i, j = rng.randrange(len(b)), rng.randrange(len(b))
            A[i][j] += F(rng.choice([-1, 1]), rng.randint(2, 50))
        else:
            j = rng.randrange(len(b))
            b[j] += F(rng.choice([-1, 1]), rng.randint(2, 50))
        fails = any(ref.energy_residual(cond, A, b) != 0
                    for n in range(3, 8) for cond in ref.energy_conditions(n, m))
        v = avf_of_reduction(reduce_tableau(A, b), m)
        if fails:
            judged += 1
            assert not v.equals_avf, (seed, name)
        else:
            # the entry was in a dead stage: the method did not change, it is still AVF
            assert v.equals_avf, (seed, name, v.reason)
    assert judged >= 30  # most perturbations do change the method


def test_dead_chain_and_cancelling_pair_by_hand():
    # implicit midpoint (A = [[1/2]], b = [1]) with a dead chain 2 → 3 and a pair 4, 5
    A = [[F(1, 2), 0, 0, F(1, 7), F(-1, 7)],
         [F(3), 0, 0, 0, 0],
         [F(1), F(2), 0, 0, 0],
         [F(1, 5), F(1), F(1), F(2), F(3)],
         [F(1, 5), F(1), F(1), F(2), F(3)]]
    b = [F(1), 0, 0, F(2), F(-2)]
    red = reduce_tableau([[F(x) for x in row] for row in A], b)
    assert red.A == [[F(1, 2)]] and red.b == [F(1)] and red.classes == [(0,)]
    assert sorted(red.dropped) == [1, 2, 3, 4]


def test_an_irreducible_tableau_is_left_alone():
    A = fr([["5/12", "-1/12"], ["3/4", "1/4"]])  # Radau IIA-2
    red = reduce_tableau(A, [F(3, 4), F(1, 4)])
    assert not red.reducible and red.describe() is None and red.A == A


# ------------------------------------------------------------------ Theorem 1


def test_theorem1_needs_exact_holds_to_conclude_beyond_order_n():
    """The seed kernel family ζ = 1/2, β = 1e-30 (degree 3) holds to ~58 digits
    up to order 7 at 50 digits, but truly fails at order 4 by ≈ β²/36 ≈ 2.8e-62.  The
    report must not conclude "a condition must fail beyond order 7"."""
    from rkcheck.methods.families import family_tableau, parse_spec

    tab = family_tableau(parse_spec({"name": "kernel", "zeta": "1/2", "beta": "1e-30"}))
    res = check(tab, CheckOptions(degree=3, order=7, dps=50, arithmetic="ball"))
    assert res.first_failure is None and res.avf is not None and not res.avf.equals_avf
    assert "beyond order 7" not in res.theorem1 and "hold only to" in res.theorem1
    truth = check(tab, CheckOptions(degree=3, order=4, dps=100, arithmetic="ball"))
    assert truth.first_failure is not None and truth.first_failure.order == 4


def test_the_kernel_family_is_exact_in_its_field_and_fails_by_beta_squared_over_36():
    # the same family checked by default: its nodes (Gauss, sqrt(3)) have a closed form,
    # so the check is exact and finds the order-4 failure at once, of size β²/36
    # (exact: the residual is rational).
    from rkcheck.methods.families import family_tableau, parse_spec

    tab = family_tableau(parse_spec({"name": "kernel", "zeta": "1/2", "beta": "1e-30"}))
    res = check(tab, CheckOptions(degree=3, order=7))
    assert res.backend == "exact"
    first = res.first_failure
    assert first is not None and first.order == 4
    assert abs(first.residual) == F(1, 36) * F(1, 10**30) ** 2
    assert "beyond order" not in res.theorem1


def test_theorem1_concludes_beyond_order_n_from_exact_holds():
    # the kernel family at the Radau II rule (ζ = 1, rational nodes 1/3, 1) with β = 1/10:
    # s = 2 = s_min for m = 3, not AVF; its first failing conditions have order 4, so up
    # to order 3 every condition holds exactly and a failure beyond 3 is certain.
    from support.paths import TABLEAUX

    from rkcheck.io.loader import load

    tab = load(str(TABLEAUX / "counterexamples" / "kernel-radau-beta-0.1.toml"))
    res = check(tab, CheckOptions(degree=3, order=3))
    assert res.backend == "exact" and res.first_failure is None
    assert "must fail beyond order 3" in res.theorem1
    assert check(tab, CheckOptions(degree=3, order=4)).first_failure.order == 4


def test_theorem1_remark_without_exact_holds_names_the_digits():
    from rkcheck.properties.avf import AvfVerdict
    from rkcheck.verdicts import Verdict

    v = AvfVerdict(3, Verdict("fails"), "x", 2, 2, (1, 2), 2)
    assert "must fail beyond order 6" in theorem1_remark(v, None, 6, True)
    text = theorem1_remark(v, None, 6, False, 58)
    assert "beyond order 6" not in text and "58 digits" in text


def test_theorem1_remark_says_when_the_method_is_avf_only_to_digits():
    from rkcheck.properties.avf import AvfVerdict
    from rkcheck.verdicts import Verdict

    exact = theorem1_remark(AvfVerdict(4, Verdict("holds"), "x", 2, 2, (1, 2), 2), None, 8)
    to_digits = theorem1_remark(AvfVerdict(4, Verdict("holds_to_digits", 15), "x", 2, 2, (1, 2), 2), None, 8)
    assert "digits" not in exact and "the minimal-stage energy-preserving method for degree 4" in exact
    assert "AVF to 15 digits (not a proof)" in to_digits
