"""Exact ranks of the double-bush map at algebraic rules (numerical ranks can be
wrong at low precision), against the seed's theorems:

* Gauss, m = 2s: rank M = s² − 1, kernel spanned by (1 − c)bᵀ (seed Lemma "DBmono");
* nodes the zeros of P_s − ζP_{s−1}, m = 2s − 1: rank s² − 3 for ζ ≠ −1 (Gauss ζ = 0,
  Radau II ζ = 1) and s² − s − 1 for ζ = −1 (Radau I);
* the zero-row-sum part of the kernel is one-dimensional for m = 2s − 1 ("onedim").
"""

import pytest

from rkcheck.energy.double_bush import kernel_of, rule_values


@pytest.mark.parametrize("s", [2, 3, 4])
def test_gauss_m_2s_rank_and_kernel_exactly(s):
    b, c, exact = rule_values("gauss", s, 30)
    assert exact  # sqrt(3), sqrt(15), nested roots for s = 4: all exact now
    k = kernel_of(b, c, 2 * s, True)
    assert k.rank == s * s - 1
    (N,) = k.basis
    # N ∝ (1 − c)bᵀ: every 2×2 minor of N against (1 − c)bᵀ vanishes exactly
    K = [[(1 - ci) * bj for bj in b] for ci in c]
    flat_n = [x for row in N for x in row]
    flat_k = [x for row in K for x in row]
    i0 = next(i for i, x in enumerate(flat_k) if x != 0)
    for x, y in zip(flat_n, flat_k):
        assert (x * flat_k[i0] - y * flat_n[i0]) == 0


@pytest.mark.parametrize("rule_name, s, rank", [
    ("gauss", 3, 6), ("radau-ii", 3, 6), ("radau-i", 3, 5), ("gauss", 4, 13), ("radau-i", 4, 11),
])
def test_m_2s_minus_1_ranks_exactly(rule_name, s, rank):
    b, c, exact = rule_values(rule_name, s, 30)
    assert exact
    k = kernel_of(b, c, 2 * s - 1, True)
    assert k.rank == rank  # s² − 3, or s² − s − 1 for Radau I
    if rule_name != "radau-i":
        assert len(k.zero_row_sum) == 1


def test_perturb_along_the_exact_kernel_direction_is_quadratic_to_1e_30(capsys):
    # the kernel direction of an algebraic AVF tableau must not be rounded through str()
    # at 15 digits and the fitted slope fell to 1.55; exact now, so max|R| = C·ε² for
    # every ε (seed: the failure along the kernel is quadratic), the slope is 2
    import json

    from support.clirun import run_cli
    from support.paths import TABLEAUX

    r = run_cli(capsys, "perturb", str(TABLEAUX / "avf" / "avf-gauss-2.toml"), "--direction", "kernel",
                "--degree", "3", "--format", "json")
    assert r.code == 0, r.err
    doc = json.loads(r.out)
    assert "exact" in doc["direction"]
    assert abs(doc["slope"] - 2) < 1e-6
    rows = doc["rows"]
    from fractions import Fraction
    ratios = {round(float(row["max_residual"]) / float(Fraction(row["eps"])) ** 2, 6) for row in rows[-10:]}
    assert len(ratios) == 1  # the same constant C at ε = 1e-21 … 1e-30
