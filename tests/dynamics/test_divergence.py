"""NaN/Inf in a simulation is an error naming the step, never a column of nan and a zero
energy error; hostile step sizes and problem sizes are refused in one line."""

from __future__ import annotations

from support.clirun import run_cli
from support.paths import TABLEAUX

RK4 = str(TABLEAUX / "explicit" / "rk4.toml")
GAUSS2 = str(TABLEAUX / "collocation" / "gauss-2.toml")


def one_line(r) -> str:
    assert r.code == 2, (r.code, r.out, r.err)
    assert "Traceback" not in r.err and len(r.err.splitlines()) == 1, r.err
    assert "nan" not in r.out
    return r.err.strip()


def test_an_explicit_method_that_blows_up_is_an_error_not_zero(capsys):
    # harmonic oscillator: RK4 is stable only for h < 2.78 (|R(ih)| <= 1); h = 1e300
    # overflows float64 at the first step
    err = one_line(run_cli(capsys, "simulate", RK4, "--problem", "harmonic", "--h", "1e300", "--steps", "10"))
    assert err.startswith(f"rkcheck: error: {RK4}: --h: the solution diverged at step 1")
    # h = 3: R(3i) = 1 - 9/2 + 81/24 + i(3 - 27/6) = -1/8 - 3i/2, |R| = sqrt(145)/8 ≈ 1.5052;
    # H = |y|²/2 (y0 = (1, 0)) grows like |R|^(2n) and overflows float64 (≈ 1.8e308) once
    # |R|^(2n) > 2·1.8e308, at n ≈ 868; H is evaluated every steps/200 = 25 steps, so the
    # divergence is seen at the first multiple of 25 from there
    import math

    first = math.ceil((math.log(2) + math.log(1.7976931348623157e308)) / (2 * math.log(math.sqrt(145) / 8)))
    err = one_line(run_cli(capsys, "simulate", RK4, "--problem", "harmonic", "--h", "3", "--steps", "5000"))
    step = int(err.split("diverged at step ")[1].split()[0])
    assert step == 25 * math.ceil(first / 25), (step, first)


def test_implicit_methods_fail_the_same_way(capsys):
    err = one_line(run_cli(capsys, "simulate", GAUSS2, "--problem", "quartic", "--h", "1e300", "--steps", "3"))
    assert "Newton's method did not converge" in err or "diverged" in err


def test_a_step_size_that_underflows_is_refused(capsys):
    err = one_line(run_cli(capsys, "simulate", RK4, "--problem", "harmonic", "--h", "1e-1000", "--steps", "3"))
    assert err.endswith("--h: the step size is 0 in float64 (it underflows); use a larger --h, or --dps")


def test_random_problems_are_bounded_by_their_monomial_count(capsys):
    # C(2d + m, m) - 1 monomials: degree 12, dim 6 -> C(24, 12) - 1 = 2 704 155
    err = one_line(run_cli(capsys, "simulate", RK4, "--problem", "random:degree=12,dim=6"))
    assert err == ("rkcheck: error: --problem: random:degree=12,dim=6 has 2,704,155 monomials; the limit is "
                   "20,000 (lower the degree or dim)")
