"""Accuracy against speed: the seed's ranks and kernels, perturbation slopes and
detection thresholds, and backend agreement."""

from __future__ import annotations

import sys
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX  # noqa: E402

from rkcheck.energy.double_bush import kernel_of, rule_values
from rkcheck.errors import UserError
from rkcheck.io.loader import load
from rkcheck.studies.accuracy import (
    bench_backends,
    direction,
    direction_dps,
    mpf_fraction,
    parse_eps,
    perturb_sweep,
)


def seed_N(zeta, b, c):
    """The seed's s = 2, m = 3 direction N = ((ζ−1)1 − 2ζc) bᵀ(I − 2C)."""
    if isinstance(zeta, Fraction) and not isinstance(b[0], Fraction) and not hasattr(b[0], "field"):
        import mpmath

        zeta = mpmath.mpf(zeta.numerator) / zeta.denominator
    return [[((zeta - 1) - 2 * zeta * c[i]) * b[j] * (1 - 2 * c[j]) for j in range(len(b))] for i in range(len(b))]


def proportional(X, Y, tol) -> bool:
    """X = λY for some λ ≠ 0, entrywise within tol (after scaling by the largest entry);
    evaluated at 80 digits when the entries are mpmath numbers."""
    import mpmath

    with mpmath.workdps(80):
        fx = [x for row in X for x in row]
        fy = [y for row in Y for y in row]
        k = max(range(len(fy)), key=lambda i: abs(fy[i]))
        lam = fx[k] / fy[k]
        return lam != 0 and all(abs(x - lam * y) <= tol for x, y in zip(fx, fy))


@pytest.mark.parametrize("s", [2, 3, 4, 5])
def test_gauss_even_case_rank_and_kernel(s):
    # seed §3: m = 2s, Gauss rule: rank M = s² − 1, ker M spanned by (1 − c)bᵀ
    b, c, exact = rule_values("gauss", s, 50)
    k = kernel_of(b, c, 2 * s, exact, 50)
    assert k.rank == s * s - 1 and len(k.basis) == 1
    import mpmath

    with mpmath.workdps(80):
        expected = [[(1 - ci) * bj for bj in b] for ci in c]
    assert proportional(k.basis[0], expected, 1e-40)
    if not exact:  # the gap: a clear cut between O(1e-6..1e-1) and O(1e-50)
        (_, last_nonzero), (_, first_zero) = k.singular_values[-2], k.singular_values[-1]
        assert last_nonzero > 1e-8 and first_zero < 1e-45


@pytest.mark.parametrize("s", [2, 3, 4, 5])
@pytest.mark.parametrize("zeta", ["0", "1", "1/2", "-1/3", "-1"])
def test_odd_case_ranks_and_one_dimensional_zero_row_sum_kernel(s, zeta):
    # seed §4: m = 2s − 1, nodes the zeros of P_s − ζP_{s−1}:
    # rank s² − 3 for ζ ≠ −1, s² − s − 1 for ζ = −1; ker M ∩ {N·1 = 0} is 1-dimensional
    b, c, exact = rule_values(f"zeta:{zeta}", s, 50)
    k = kernel_of(b, c, 2 * s - 1, exact, 50)
    expected = s * s - s - 1 if zeta == "-1" else s * s - 3
    assert k.rank == expected
    assert len(k.zero_row_sum) == 1


@pytest.mark.parametrize("zeta", [Fraction(0), Fraction(1, 3), Fraction(1), Fraction(-1, 2)])
def test_s2_m3_kernel_direction_is_the_seeds_N(zeta):
    # seed §2.4: the zero-row-sum kernel direction is ((ζ−1)1 − 2ζc) bᵀ(I − 2C)
    b, c, exact = rule_values(f"zeta:{zeta}", 2, 60)
    k = kernel_of(b, c, 3, exact, 60)
    assert len(k.zero_row_sum) == 1
    import mpmath

    tol = 0 if exact else 1e-50
    with mpmath.workdps(80):
        N = seed_N(zeta, b, c)
    assert proportional(k.zero_row_sum[0], N, tol)


# ------------------------------------------------------------------ perturbation slopes
#
# The model (seed §2.4): along a direction N with M(N) = 0 and N·1 = 0 every condition
# linear in A holds, and max|R|(ε) = K ε² (1 + ρ(ε)) with ρ(ε) = O(ε); along a generic
# direction max|R|(ε) = K ε (1 + ρ(ε)).  We allow |ρ| ≤ RHO = 10 % over the sweep
# (ε ≤ 10^-2, so a cubic coefficient up to 10 K) and check that directly: R/ε^p varies by
# at most that factor.  Then every point lies within δ = log10(1 + RHO) of the line
# log R = p log ε + log K, and the least-squares slope is off by at most
#     |Σ (x_k − x̄) δ_k| / Σ (x_k − x̄)²  ≤  δ · Σ|x_k − x̄| / Σ (x_k − x̄)²,
# the tolerance below (0.0041 for the 15 decades 10^-2 … 10^-30).  The rounding of the
# kernel direction to 15 digits gave slopes 1.44–1.55 on these tableaux.

RHO = Fraction(1, 10)
SWEEP = "1e-2..1e-30:2"


def slope_tolerance(eps) -> float:
    import math

    xs = [math.log10(e) for e in eps]
    mean = sum(xs) / len(xs)
    delta = math.log10(1 + float(RHO))
    return delta * sum(abs(x - mean) for x in xs) / sum((x - mean) ** 2 for x in xs)


def assert_power_law(result, power: int, eps) -> None:
    ratios = [r.max_residual / r.eps ** power for r in result.rows]
    assert all(x is not None and x > 0 for x in [r.max_residual for r in result.rows])  # every ε certified
    assert max(ratios) <= (1 + RHO) * min(ratios), [float(x) for x in ratios]
    assert abs(result.slope - power) <= slope_tolerance(eps), (result.slope, slope_tolerance(eps))


def sweep(name: str, kind: str, degree: int, order: int = 8, dps_list=(50,)):
    tab = load(str(TABLEAUX / name))
    eps = parse_eps(SWEEP)
    D, desc = direction(tab, kind, degree, dps=direction_dps(eps, dps_list))
    return tab, D, eps, perturb_sweep(tab, D, desc, eps, degree, order, dps_list)


def double_bush_defect(D, b, c, m: int):
    """max over 1 ≤ p < q ≤ m−1 of |Σ_ij D_ij (p b_i c_i^(p−1) c_j^q − q b_i c_i^(q−1) c_j^p)| (seed
    Lemma DBmono), with b, c sympy numbers, evaluated to 300 digits."""
    import sympy

    def rational(x):  # exact field elements enter through a 1200-bit enclosure
        return x if isinstance(x, Fraction) else x.enclosure(1200).mid

    D = [[rational(x) for x in row] for row in D]
    worst = 0
    for q in range(2, m):
        for p in range(1, q):
            expr = sum(sympy.Rational(D[i][j].numerator, D[i][j].denominator)
                       * (p * b[i] * c[i] ** (p - 1) * c[j] ** q - q * b[i] * c[i] ** (q - 1) * c[j] ** p)
                       for i in range(len(b)) for j in range(len(b)))
            worst = max(worst, abs(sympy.N(expr, 300)))
    return worst


@pytest.mark.parametrize("name, s", [("avf/avf-gauss-2.toml", 2), ("avf/avf-gauss-3.toml", 3)])
def test_kernel_direction_of_an_algebraic_tableau_is_in_the_kernel_far_beyond_15_digits(name, s):
    # the kernel is computed exactly in the rule's field (Q(sqrt(3)), Q(sqrt(15))); checked
    # against sympy's own Gauss rule to 300 digits
    import sympy

    tab = load(str(TABLEAUX / name))
    D, desc = direction(tab, "kernel", 3, dps=140)
    assert "(exact;" in desc
    assert all(sum(row) == 0 for row in D)  # zero row sums exactly
    assert max(abs(x) for row in D for x in row) == 1
    # the s-point Gauss rule: c = roots of the shifted Legendre polynomial, b by sympy
    x = sympy.Symbol("x")
    c = sorted(sympy.Poly(sympy.legendre(s, 2 * x - 1), x).all_roots(), key=lambda r: sympy.N(r, 50))
    b = [sympy.integrate(sympy.prod([(x - cj) / (ci - cj) for cj in c if cj != ci]), (x, 0, 1)) for ci in c]
    assert double_bush_defect(D, b, c, 3) < sympy.Float("1e-120")


@pytest.mark.parametrize("name", ["avf/avf-gauss-2.toml", "avf/avf-gauss-3.toml", "avf/avf-lobatto-3.toml"])
def test_kernel_direction_fails_quadratically_down_to_1e_30(name):
    # Gauss-2/3: algebraic (√3, √15) entries; Lobatto-3: rational; every kernel exact
    tab, D, eps, kern = sweep(name, "kernel", 3)
    assert kern.warnings == []
    assert_power_law(kern, 2, eps)
    # float64 cannot see ε = 1e-9 along the kernel (residual ~1e-19 < its radius) ...
    assert kern.thresholds["float64"] is not None and kern.thresholds["float64"] > Fraction(1, 10**9)
    # ... while 50 digits certify the failure at ε = 1e-20 (residual ~1e-41)
    row20 = next(r for r in kern.rows if r.eps == Fraction(1, 10**20))
    assert row20.detected["dps:50"]


def test_kernel_direction_on_gauss_2_first_fails_at_six_vertices():
    # seed §2.4 (s = 2, m = 3, ζ = 0): along N every condition with ≤ 5 vertices holds to
    # second order too; the first failure is at 6 vertices (order 5).  A direction rounded
    # to its working precision would fail the linear conditions at order 3 or 4 already.
    _, _, _, kern = sweep("avf/avf-gauss-2.toml", "kernel", 3)
    assert {r.first_failing_order for r in kern.rows} == {5}


@pytest.mark.parametrize("name", ["avf/avf-gauss-2.toml", "avf/avf-lobatto-3.toml"])
def test_generic_direction_fails_linearly(name):
    _, _, eps, rand = sweep(name, "random", 3)
    assert rand.warnings == []
    assert_power_law(rand, 1, eps)


def test_mpf_fraction_keeps_every_bit_at_any_global_precision():
    import mpmath

    with mpmath.workdps(200):
        third = mpmath.mpf(1) / 3
        minus = -mpmath.sqrt(2)
    assert mpmath.mp.dps == 15  # converted outside the working precision, as perturb does
    f = mpf_fraction(third)
    assert abs(f - Fraction(1, 3)) < Fraction(1, 10**199)
    assert abs(Fraction(str(third)) - Fraction(1, 3)) > Fraction(1, 10**17)  # what str() kept
    g = mpf_fraction(minus)
    assert g < 0 and abs(g * g - 2) < Fraction(1, 10**198)
    assert type(f.numerator) is int and mpf_fraction(mpmath.mpf(0)) == 0


def test_warns_when_the_unperturbed_tableau_already_fails():
    # AVF over 3-point Lobatto (Simpson, quadrature order 4) is AVF only up to degree 4:
    # at degree 5 its conditions fail at ε = 0.  The failing conditions, by the
    # brute-force reference: every free tree with ≤ 7 vertices and maximum degree ≤ 5.
    from support import reference as ref

    c, b = [Fraction(0), Fraction(1, 2), Fraction(1)], [Fraction(1, 6), Fraction(2, 3), Fraction(1, 6)]
    A = [[ci * bj for bj in b] for ci in c]
    failing, total = [], 0
    for n in range(3, 8):
        for cond in ref.energy_conditions(n, 5):
            total += 1
            if ref.energy_residual(cond, A, b) != 0:
                failing.append(n - 1)
    assert failing  # the premise: the base tableau fails
    tab = load(str(TABLEAUX / "avf" / "avf-lobatto-3.toml"))
    eps = parse_eps("1e-2..1e-6")
    D, desc = direction(tab, "random", 5)
    res = perturb_sweep(tab, D, desc, eps, 5, 6, (15,))
    assert len(res.warnings) == 1
    assert (f"already fails {len(failing)} of {total} conditions at degree 5, order 6 (the first at order "
            f"{min(failing)})") in res.warnings[0]
    assert "slope means nothing" in res.warnings[0]


def test_bench_backends_agree_with_exact_and_digits_grow_with_dps():
    tab = load(str(TABLEAUX / "explicit" / "rk4.toml"))
    rows, _ = bench_backends(tab, None, 7, (15, 30, 50, 100))
    assert rows[-1].backend == "exact"
    assert all(r.agrees for r in rows)  # no false `fails`, no missed failure
    digits = [r.min_digits for r in rows if r.backend.startswith("dps:")]
    assert digits == sorted(digits) and digits[0] < digits[-1]
    assert rows[0].backend == "float64" and 13 <= rows[0].min_digits <= 16


def test_commands_run_and_chart_needs_matplotlib(tmp_path, capsys, monkeypatch):
    path = str(TABLEAUX / "avf" / "avf-radau-ii-2.toml")
    r = run_cli(capsys, "kernel", "-m", "3", "--tableau", path)
    assert r.code == 0 and "rank M = 1" in r.out and "dimension 1" in r.out
    r = run_cli(capsys, "perturb", path, "--direction", "entry:1,2", "--eps", "1e-2..1e-6")
    assert r.code == 0 and "slope" in r.out
    r = run_cli(capsys, "bench", path, "--dps", "15,50", "--repeat", "1", "--format", "json")
    assert r.code == 0 and '"agrees": true' in r.out
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # as if the plot extra were missing
    r = run_cli(capsys, "bench", path, "--dps", "15", "--repeat", "1", "--chart", str(tmp_path / "c.png"))
    assert r.code == 2 and "pip install 'rkcheck[plot]'" in r.err


def test_chart_files_are_written_when_matplotlib_is_there(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    path = str(TABLEAUX / "avf" / "avf-radau-ii-2.toml")
    out = tmp_path / "perturb.png"
    r = run_cli(capsys, "perturb", path, "--direction", "kernel", "--eps", "1e-2..1e-10:2", "--chart", str(out))
    assert r.code == 0 and out.stat().st_size > 1000


def test_bad_inputs_are_one_line_errors(capsys):
    path = str(TABLEAUX / "avf" / "avf-radau-ii-2.toml")
    r = run_cli(capsys, "perturb", path, "--direction", "sideways")
    assert r.code == 2 and "unknown direction" in r.err
    r = run_cli(capsys, "perturb", path, "--direction", "kernel", "--degree", "2")
    assert r.code == 2 and "needs --degree m >= 3" in r.err
    r = run_cli(capsys, "perturb", path, "--direction", "random", "--eps", "1e-1..banana")
    assert r.code == 2 and "--eps" in r.err


def test_perturb_command_reports_the_base_failure_in_text_and_json(capsys):
    import json

    path = str(TABLEAUX / "avf" / "avf-lobatto-3.toml")
    args = ("perturb", path, "--direction", "random", "--degree", "5", "--order", "6", "--eps", "1e-2,1e-4", "--dps", "15")
    r = run_cli(capsys, *args)
    assert r.code == 0 and "warning: the unperturbed tableau already fails" in r.out
    r = run_cli(capsys, *args, "--format", "json")
    doc = json.loads(r.out)
    assert len(doc["warnings"]) == 1 and "slope means nothing" in doc["warnings"][0]
    r = run_cli(capsys, "perturb", path, "--direction", "random", "--degree", "3", "--order", "6",
                "--eps", "1e-2,1e-4", "--dps", "15", "--format", "json")
    assert json.loads(r.out)["warnings"] == []  # Simpson: AVF for degree 3, nothing fails at ε = 0


def test_eps_values_are_exact_and_their_exponents_bounded():
    # a range far past float64 (1e-330 underflows to 0 as a float) is every decade exactly;
    # an exponent past an entry's bound is refused at once, before any value is built
    values = parse_eps("1e-1..1e-330")
    assert values == [Fraction(1, 10**k) for k in range(1, 331)]
    assert parse_eps("1e-3, 1/1000, 10^-3") == [Fraction(1, 1000)] * 3
    for text, message in (("1e-100000000", "out of range"), ("2e-3..1e-5", "ends are powers of ten"),
                          ("x", "cannot read"), ("1e-1..1e-5:0", "cannot read")):
        with pytest.raises(UserError, match=message) as err:
            parse_eps(text)
        assert str(err.value).startswith("--eps: ")


def test_balls_certify_digits_past_float64s_range():
    # Gauss-3 is exact: the conditions that hold are 0, so any certified digits are sound;
    # at 1000 digits the balls certify about that many, past a float's 2^−1074 (323 digits)
    import rkcheck

    result = rkcheck.bench("@gauss-3", degree=3, order=6, dps=[400, 1000], repeat=1)
    digits = {row.backend: row.min_digits for row in result.rows}
    assert digits["dps:400"] > 390 and digits["dps:1000"] > 990, digits
