"""The exact solver (rkcheck.numbers.solving) on systems whose solutions are known by
construction, cross-checked with sympy where a second opinion helps."""

from __future__ import annotations

import random
import subprocess
import sys
from fractions import Fraction

import pytest
from flint import fmpq, fmpq_mpoly_ctx

from rkcheck.numbers.groebner import dimension
from rkcheck.numbers.solving import solve_system


def ring(*names):
    ctx = fmpq_mpoly_ctx.get(names, "lex")
    return ctx, ctx.gens()


def q(x):
    x = Fraction(x)
    return fmpq(x.numerator, x.denominator)


@pytest.mark.parametrize("seed", range(4))
def test_rational_points_are_found_exactly(seed):
    # the ideal of a few rational points: products of linear forms vanish exactly there
    rng = random.Random(seed)
    ctx, (x, y) = ring("x", "y")
    pts = {(Fraction(rng.randint(-5, 5), rng.randint(1, 4)), Fraction(rng.randint(-5, 5), rng.randint(1, 4)))
           for _ in range(3)}
    xs = sorted({p[0] for p in pts})
    assert len(xs) == len(pts) == 3  # these seeds give three points with distinct x
    f = ctx.constant(1)
    g = ctx.constant(0)
    for px, py in pts:
        f = f * (x - q(px))
    # y = interpolant of the points' y over their x (Lagrange), when the x are distinct
    # the points' ideal is <Π(x − xᵢ), y − interpolant(x)>
    for px, py in pts:
        term = ctx.constant(q(py))
        for ox, _ in pts:
            if ox != px:
                term = term * (x - q(ox)) / q(px - ox)
        g = g + term
    res = solve_system([f, y - g], None, None)
    got = {(Fraction(s.values["x"].text), Fraction(s.values["y"].text)) for s in res.solutions}
    assert res.dimension == 0 and got == pts


def test_quadratic_solutions_are_closed_forms_that_satisfy_the_system():
    sp = pytest.importorskip("sympy")
    ctx, (x, y) = ring("x", "y")
    eqs = [x * x - 2 * x - 1, y - x * x]  # x = 1 ± √2, y = x²
    res = solve_system(eqs, None, None)
    assert res.dimension == 0 and len(res.solutions) == 2 and all(s.real for s in res.solutions)
    X, Y = sp.symbols("x y")
    for s in res.solutions:
        vx = sp.sympify(s.values["x"].text.replace("^", "**"))
        vy = sp.sympify(s.values["y"].text.replace("^", "**"))
        assert sp.simplify(vx**2 - 2 * vx - 1) == 0 and sp.simplify(vy - vx**2) == 0
    assert {s.values["x"].text for s in res.solutions} == {"1 + sqrt(2)", "1 - sqrt(2)"}


def test_complex_solutions_are_marked_not_real():
    ctx, (x,) = ring("x")
    res = solve_system([x * x + 1], None, None)
    assert len(res.solutions) == 2 and not any(s.real for s in res.solutions)


def test_inconsistent_and_positive_dimensional_sets():
    ctx, (x, y, z) = ring("x", "y", "z")
    assert solve_system([x - 1, x - 2], None, None).dimension == -1
    assert solve_system([x * y - 1, z], None, None).dimension == 1  # a hyperbola in the plane z = 0
    assert solve_system([x - y * z], None, None).dimension == 2  # a surface


def test_dimension_from_leading_monomials_by_hand():
    # <x²> in 2 variables: {y} avoids every leading monomial → dimension 1; <1> → -1
    assert dimension([(2, 0)], 2) == 1
    assert dimension([(0, 0)], 2) == -1
    assert dimension([(1, 0, 0), (0, 1, 0), (0, 0, 3)], 3) == 0


def test_split_along_factors_gives_each_line_of_a_cross():
    import time

    from rkcheck.numbers.decompose import contains, split
    from rkcheck.numbers.groebner import groebner

    names = ("x", "y", "z")
    # V(x·y, z): the two lines x = z = 0 and y = z = 0
    basis = groebner([{(1, 1, 0): 1}, {(0, 0, 1): 1}], names, "degrevlex", time.monotonic() + 30)
    pieces = split(basis, names, time.monotonic() + 30)
    assert sorted(sorted(map(lambda d: tuple(sorted(d.items())), p.basis)) for p in pieces) == [
        [(((0, 0, 1), 1),), (((0, 1, 0), 1),)], [(((0, 0, 1), 1),), (((1, 0, 0), 1),)]]
    assert all(p.dimension == 1 for p in pieces)
    assert contains(pieces[0], {(1, 1, 0): 1}, names, time.monotonic() + 30)


def test_a_real_quadratic_coordinate_at_complex_roots_takes_its_own_conjugate():
    # ψ = z⁴ − 8z² + 36 has the roots ±√5 ± i; the coordinate p(z) = (z² + 6)/(2z) (mod ψ)
    # is Re z = ±√5, real at every root: its closed form must carry the sign of that
    # root's real part (it was −√5 at all four: the ball's imaginary part straddles 0)
    from flint import fmpq, fmpq_poly

    from rkcheck.numbers.coordinates import coordinate_value as _value

    psi = fmpq_poly([36, 0, -8, 0, 1])
    z = fmpq_poly([0, 1])
    inverse = -(z**3 - 8 * z) * fmpq(1, 36)  # 1/z mod ψ
    p = ((z**2 + 6) * inverse * fmpq(1, 2)) % psi
    assert (p * p - 5) % psi == 0  # p is a square root of 5 in Q[z]/ψ
    minimal: dict = {}
    for k, (root, _) in enumerate(psi.complex_roots()):
        v = _value(p, psi, root, k, minimal, "a")
        sign = 1 if float(root.real.mid()) > 0 else -1
        assert v.real and v.text == ("sqrt(5)" if sign > 0 else "-sqrt(5)"), (k, v.text)
        assert abs(v.approx - sign * 5 ** 0.5) < 1e-12


def test_a_cubic_coordinate_is_shown_as_a_root_of_a_polynomial_in_its_own_name():
    # y = x² at the roots of x³ − x − 1: y's minimal polynomial (sympy's, independently)
    # is the one shown, written in y — an x there would read as the other parameter
    sp = pytest.importorskip("sympy")
    ctx, (x, y) = ring("x", "y")
    res = solve_system([x**3 - x - 1, y - x * x], None, None)
    assert res.dimension == 0 and len(res.solutions) == 3
    X, Y = sp.symbols("x y")
    want = sp.Poly(sp.minimal_polynomial(sp.CRootOf(X**3 - X - 1, 0) ** 2, Y), Y).monic()
    for s in res.solutions:
        text = s.values["y"].text
        assert " of " in text and "x" not in text.split(" of ")[1], text
        shown = sp.Poly(sp.sympify(text.split(" of ")[1].split(" (")[0].replace("^", "**")), Y).monic()
        assert shown == want and "1*" not in text
        assert abs(complex(want.as_expr().subs(Y, s.values["y"].approx))) < 1e-9


def test_a_square_root_of_a_large_prime_is_written_without_factoring_it():
    # bounded trial division: √p would be 10^15 steps; the closed forms are checked by
    # sympy: each squared is the discriminant's root, exactly
    sp = pytest.importorskip("sympy")
    code = ("from flint import fmpq_mpoly_ctx\nfrom rkcheck.numbers.solving import solve_system\n"
            "ctx = fmpq_mpoly_ctx.get(('x',), 'lex'); (x,) = ctx.gens()\n"
            "for eq in (x*x - 1000000000000000000000000000057, x*x - 3*1000000000000000000000000000057**2,"
            " 16*x*x - 24*x + 13, x*x + 1):\n"
            "    print(';'.join(s.values['x'].text for s in solve_system([eq], None, None).solutions))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    p = 1000000000000000000000000000057
    X = sp.Symbol("x")
    for line, poly in zip(out.stdout.splitlines(), (X**2 - p, X**2 - 3 * p * p, 16 * X**2 - 24 * X + 13, X**2 + 1)):
        texts = line.split(";")
        assert len(texts) == 2 and "sqrt(1)" not in line, line
        for t in texts:
            assert sp.expand(poly.subs(X, sp.sympify(t.replace("^", "**").replace("i", "I")))) == 0, t


def test_the_square_part_of_a_discriminant_by_hand_and_by_sympy():
    # D = square²·d exactly; d square-free (sympy factors it) below the trial limit's
    # square, and the square of a large prime beside a small factor still taken out
    sp = pytest.importorskip("sympy")
    from rkcheck.numbers.coordinates import _squarefree_part

    rng = random.Random(7)
    for _ in range(300):
        D = Fraction(rng.randint(-10**8, 10**8) or 1, rng.randint(1, 10**4))
        d, square = _squarefree_part(D)
        assert square * square * d == D
        assert all(e == 1 for e in sp.factorint(abs(d)).values()), (D, d)
    p = 1000000000000000000000000000057
    assert _squarefree_part(Fraction(2 * p * p)) == (2, Fraction(p))
    assert _squarefree_part(Fraction(-3 * 8 * p * p)) == (-6, Fraction(2 * p))
