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


# ------------------------------------------------------------------ beyond the field limit
#
# Gauss with 6 and 8 nodes has a field beyond the degree limit; a numerical cut-off once
# printed rank 31 (s = 6, m = 12, 15 digits) and 59 (s = 8, m = 16, 20 digits) where the
# seed's theorem says s² − 1.


def _gauss_float(s):
    """Gauss–Legendre nodes and weights on [0, 1] from numpy (an independent source)."""
    import numpy as np

    x, w = np.polynomial.legendre.leggauss(s)
    return [float(w_ / 2) for w_ in w], [float((x_ + 1) / 2) for x_ in x]


@pytest.mark.parametrize("s, dps", [(6, 15), (8, 20)])
def test_gauss_m_2s_rank_beyond_the_field_limit_is_the_seeds(s, dps):
    import rkcheck

    k = rkcheck.kernel(2 * s, s, dps=dps)
    assert k.rank == s * s - 1 and k.rank_certain and k.rank_bounds == (s * s - 1, s * s - 1)
    assert not k.exact  # the basis is numerical, the rank is not
    (N,) = k.basis
    b, c = _gauss_float(s)
    # N ∝ (1 − c)bᵀ; the largest entry of both scaled to 1
    K = [[(1 - ci) * bj for bj in b] for ci in c]
    big = max(abs(x) for row in K for x in row)
    assert all(abs(float(N[i][j]) - K[i][j] / big) < 1e-12 for i in range(s) for j in range(s))


@pytest.mark.parametrize("rule_name, s", [("gauss", 3), ("gauss", 4), ("radau-i", 3), ("radau-ii", 4),
                                          ("lobatto", 4), ("zeta:1/3", 3), ("zeta:-2", 2)])
def test_node_polynomial_rank_agrees_with_elimination_in_the_field(rule_name, s):
    # the slower obviously-correct route: elimination on M itself over the nodes' field
    from rkcheck.energy.double_bush import node_polynomial_kernel
    from rkcheck.methods.quadrature import rule

    b, c, exact = rule_values(rule_name, s, 30)
    assert exact
    r = rule(rule_name, s)
    cb, bb = r.enclosures(200)
    import mpmath

    with mpmath.workdps(60):
        bf = [mpmath.mpf(x.mid.numerator) / x.mid.denominator for x in bb]
        cf = [mpmath.mpf(x.mid.numerator) / x.mid.denominator for x in cb]
    for m in range(3, 2 * s + 2):
        by_field = kernel_of(b, c, m, True)
        by_poly = node_polynomial_kernel(r.nodes[0].poly, bf, cf, m, 30)
        assert by_poly.rank == by_field.rank, m
        assert len(by_poly.zero_row_sum) == len(by_field.zero_row_sum), m
        assert by_poly.rank_certain and by_poly.zero_row_sum_bounds[0] == by_poly.zero_row_sum_bounds[1]


def test_cli_gauss_6_rank_35_at_15_digits(capsys):
    from support.clirun import run_cli

    r = run_cli(capsys, "kernel", "-s", "6", "-m", "12", "--dps", "15")
    assert r.code == 0, r.err
    line = next(x for x in r.out.splitlines() if x.startswith("rank M"))
    assert line.split()[:4] == ["rank", "M", "=", "35"] and "?" not in line


# An inexact tableau (its entries generate a field of degree 64, beyond the limit) with the
# 3-point Gauss nodes c = A·1 and weights b that are not Gauss's.  The coefficient of a_ij
# in M is b_i times a function of the nodes, so M_b = M_1 ∘ (diag(b) ⊗ I) and, every b_i
# nonzero, rank M_b is the rank at the Gauss weights: s² − 1 = 8 for m = 2s = 6 (seed).
INEXACT_GAUSS_3 = ('{"A": [["1/2 - sqrt(15)/10", "0", "0"], ["0", "1/2", "0"], ["0", "0", "1/2 + sqrt(15)/10"]],'
                   ' "b": ["sqrt(2) + sqrt(3) + sqrt(5) + sqrt(7) + sqrt(11) + sqrt(13)", "1", "1"]}')


def test_numerical_rank_is_bracketed_and_never_claimed(tmp_path, capsys):
    from support.clirun import run_cli

    import rkcheck

    path = tmp_path / "inexact.json"
    path.write_text(INEXACT_GAUSS_3)
    assert rkcheck.load(str(path)).exact_values() is None  # the numerical path, really
    k = rkcheck.kernel(6, tableau=str(path), dps=15)
    lo, hi = k.rank_bounds
    assert lo <= 8 <= hi and not k.rank_certain  # singular values never prove σ_9 = 0
    assert hi == 9  # the matrix size: nothing numerical proves a singular value to be 0
    assert k.rank == 8 and "?" in repr(k)
    r = run_cli(capsys, "kernel", "-m", "6", "--tableau", str(path), "--dps", "15")
    line = next(x for x in r.out.splitlines() if x.startswith("rank M"))
    assert "rank M = 8?" in line and "not determined at this precision" in line and f"{lo} ≤ rank M ≤ 9" in line


def test_numerical_rank_is_certain_when_the_lower_bound_is_full(tmp_path):
    # m = 5, s = 2: six conditions on four unknowns; the rank at the Gauss weights (exact
    # elimination over Q(√3), the same rank by the argument above) is full, and a
    # certified full rank needs no cut
    import rkcheck

    path = tmp_path / "inexact2.json"
    path.write_text('{"A": [["1/2 - sqrt(3)/6", "0"], ["0", "1/2 + sqrt(3)/6"]],'
                    ' "b": ["sqrt(2) + sqrt(3) + sqrt(5) + sqrt(7) + sqrt(11) + sqrt(13)", "1"]}')
    b, c, _ = rule_values("gauss", 2, 30)
    assert kernel_of(b, c, 5, True).rank == 4
    k = rkcheck.kernel(5, tableau=str(path), dps=15)
    assert k.rank_certain and k.rank == 4 and k.basis == []


@pytest.mark.parametrize("rule_name, s, rank", [("radau-i", 6, 29), ("radau-ii", 6, 33), ("zeta:1/3", 7, 46),
                                                ("radau-i", 12, 131)])
def test_m_2s_minus_1_ranks_beyond_the_field_limit(rule_name, s, rank):
    # the seed's theorem: s² − 3 for ζ ≠ −1, s² − s − 1 for ζ = −1 (Radau I), and the
    # zero-row-sum part one-dimensional for ζ ≠ −1
    import rkcheck

    k = rkcheck.kernel(2 * s - 1, s, rule=rule_name, dps=15)
    assert k.rank == rank and k.rank_certain and not k.exact
    if rule_name != "radau-i":
        assert len(k.zero_row_sum) == 1 and k.zero_row_sum_bounds == (1, 1)
        # the numerical direction: M(N) = 0 and N·1 = 0 to the working precision, at the
        # rule's nodes and weights enclosed independently (200 bits)
        import mpmath

        from rkcheck.energy.double_bush import map_rows
        from rkcheck.methods.quadrature import rule

        cb, bb = rule(rule_name, s).enclosures(200)
        with mpmath.workdps(40):
            c = [mpmath.mpf(x.mid.numerator) / x.mid.denominator for x in cb]
            b = [mpmath.mpf(x.mid.numerator) / x.mid.denominator for x in bb]
            flat = [mpmath.mpf(x) for row in k.zero_row_sum[0] for x in row]
            residual = max(abs(sum(r * x for r, x in zip(row, flat))) for row in map_rows(b, c, 2 * s - 1))
            scale = max(abs(r) for row in map_rows(b, c, 2 * s - 1) for r in row)
        assert residual < 1e-12 * scale
        assert all(abs(sum(row)) < 1e-12 for row in k.zero_row_sum[0])


def test_a_decimal_tableau_says_its_rank_is_at_face_value(capsys):
    from support.clirun import run_cli
    from support.paths import TABLEAUX

    out = run_cli(capsys, "kernel", "-m", "4", "--tableau", str(TABLEAUX / "avf" / "avf-gauss-2-decimal16.toml")).out
    assert "decimals taken at face value (16+ significant digits)" in " ".join(out.split())
    exact = run_cli(capsys, "kernel", "-m", "4", "--tableau", str(TABLEAUX / "avf" / "avf-gauss-2.toml")).out
    assert "face value" not in exact
