"""Accuracy against speed: the seed's ranks and kernels, perturbation slopes and
detection thresholds, and backend agreement (issue: accuracy and stability)."""

from __future__ import annotations

import sys
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX  # noqa: E402

from rkcheck.energy.double_bush import kernel_of, rule_values, seed_N
from rkcheck.io.loader import load
from rkcheck.studies.accuracy import bench_backends, direction, parse_eps, perturb_sweep


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


@pytest.mark.slow
@pytest.mark.parametrize("s", [2, 3, 4, 5])
def test_gauss_even_case_rank_and_kernel(s):
    # seed §3: m = 2s, Gauss rule: rank M = s² − 1, ker M spanned by (1 − c)bᵀ
    b, c, exact = rule_values("gauss", s, 50)
    k = kernel_of(b, c, 2 * s, exact, 50)
    assert k.rank == s * s - 1 and len(k.kernel) == 1
    import mpmath

    with mpmath.workdps(80):
        expected = [[(1 - ci) * bj for bj in b] for ci in c]
    assert proportional(k.kernel[0], expected, 1e-40)
    if not exact:  # the gap: a clear cut between O(1e-6..1e-1) and O(1e-50)
        (_, last_nonzero), (_, first_zero) = k.singular_values[-2], k.singular_values[-1]
        assert last_nonzero > 1e-8 and first_zero < 1e-45


@pytest.mark.slow
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


@pytest.mark.parametrize("name", ["avf/avf-radau-ii-2.toml", "avf/avf-gauss-2.toml"])
def test_perturbation_slopes_and_detection_thresholds(name):
    tab = load(str(TABLEAUX / name))
    eps = parse_eps("1e-2..1e-30:2")
    D, desc = direction(tab, "kernel", 3)
    kern = perturb_sweep(tab, D, desc, eps, 3, 8, (50,))
    assert abs(kern.slope - 2) <= 0.1  # quadratic failure along the kernel (seed)
    # float64 cannot see ε = 1e-9 along the kernel (residual ~1e-18 < its bound)...
    assert kern.thresholds["float64"] is not None and kern.thresholds["float64"] > Fraction(1, 10**9)
    # ... while 50 digits certify the failure at ε = 1e-20 (residual ~1e-40)
    row20 = next(r for r in kern.rows if r.eps == Fraction(1, 10**20))
    assert row20.detected["dps:50"]
    D, desc = direction(tab, "random", 3)
    rand = perturb_sweep(tab, D, desc, eps, 3, 8, (50,))
    assert abs(rand.slope - 1) <= 0.1  # a generic direction fails linearly


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
