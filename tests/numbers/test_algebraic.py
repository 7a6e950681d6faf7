"""Exact number fields (rkcheck.numbers.algebraic) against sympy's exact algebra."""

from fractions import Fraction

import pytest
import sympy as sp

from rkcheck.errors import UserError
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.algebraic import NotAlgebraic
from rkcheck.numbers.field_builder import field_of
from rkcheck.numbers.minimal import minimal_polynomial


def _values(*texts, constants=None):
    return field_of([ex.parse(t) for t in texts], {k: ex.parse(v) for k, v in (constants or {}).items()})


def _same(v, expr):
    """v is a root of sympy's minimal polynomial of ``expr`` (exactly, in v's field); with
    the 40-digit agreement of the enclosures this pins v to expr."""
    y = sp.Symbol("y")
    mp = sp.Poly(sp.minimal_polynomial(expr, y), y)
    acc = v * 0
    for c in mp.all_coeffs():
        acc = acc * v + Fraction(int(sp.Rational(c).p), int(sp.Rational(c).q))
    return acc.is_zero()


def test_rationals_stay_rational():
    r = _values("1/3", "sqrt(9/4)", "2^-2", "root(x^2 - 4, 2)")
    assert r.field is None
    assert r.values == [Fraction(1, 3), Fraction(3, 2), Fraction(1, 4), Fraction(2)]


def test_one_square_root_is_named_and_printed():
    r = _values("1/4 - sqrt(3)/6", "sqrt(12)", "1/(2 + sqrt(3))")
    assert r.field.name == "sqrt(3)" and r.field.degree == 2
    assert r.values[0].text() == "1/4 - sqrt(3)/6"
    assert r.values[1].text() == "2*sqrt(3)"
    assert r.values[2].text() == "2 - sqrt(3)"  # (2+√3)(2−√3) = 1


def test_gauss3_entry_text():
    r = _values("5/36 - sqrt(15)/30", "2/9 - sqrt(15)/15")
    assert [v.text() for v in r.values] == ["5/36 - sqrt(15)/30", "2/9 - sqrt(15)/15"]


@pytest.mark.parametrize("texts, sympy_exprs", [
    (["sqrt(3)", "sqrt(15)", "sqrt(5)", "sqrt(3)*sqrt(5) - sqrt(15)"],
     [sp.sqrt(3), sp.sqrt(15), sp.sqrt(5), 0]),
    (["sqrt(5/36 + sqrt(70)/126)", "sqrt(5/36 - sqrt(70)/126)", "sqrt(70)"],
     [sp.sqrt(sp.Rational(5, 36) + sp.sqrt(70) / 126), sp.sqrt(sp.Rational(5, 36) - sp.sqrt(70) / 126), sp.sqrt(70)]),
    (["root(x^3 - 3*x + 1, 2)", "root(x^3 - 3*x + 1, 1)^2", "sqrt(2)/(1 + sqrt(2))"],
     [sp.CRootOf(sp.Symbol("x")**3 - 3 * sp.Symbol("x") + 1, 1), sp.CRootOf(sp.Symbol("x")**3 - 3 * sp.Symbol("x") + 1, 0)**2,
      sp.sqrt(2) / (1 + sp.sqrt(2))]),
])
def test_compositum_values_agree_with_sympy(texts, sympy_exprs):
    r = _values(*texts)
    for v, e in zip(r.values, sympy_exprs):
        if isinstance(v, Fraction):
            assert sp.Rational(v.numerator, v.denominator) == sp.nsimplify(e)
            continue
        enc = v.enclosure(80)
        assert enc.lo <= sp.Rational(str(sp.N(e, 60))) + sp.Rational(1, 10**40)
        assert sp.Rational(str(sp.N(e, 60))) - sp.Rational(1, 10**40) <= enc.hi
        assert _same(v, e)


def test_field_degree_is_the_compositum_degree():
    # Q(√3, √5) has degree 4 although three square roots appear
    assert _values("sqrt(3)", "sqrt(15)", "sqrt(5)").field.degree == 4
    # Gauss-5's nodes: the splitting field of 63x^4 − 70x^2 + 15 (dihedral, degree 8)
    assert _values("sqrt(5/36 + sqrt(70)/126)", "sqrt(5/36 - sqrt(70)/126)").field.degree == 8


def test_conjugates_of_huge_size_are_told_apart():
    # sqrt(1e155) = 10^77·√10: conjugate sums of size 10^38 that fixed-precision balls
    # could not separate; √5 = √10/√2 is already in the field, so the degree is 2·2·2·2
    texts = ["sqrt(sqrt(1e155) + sqrt(2))", "sqrt(7)", "sqrt(5)"]
    exprs = [sp.sqrt(sp.sqrt(sp.Integer(10)**155) + sp.sqrt(2)), sp.sqrt(7), sp.sqrt(5)]
    r = _values(*texts)
    assert r.field.degree == 16
    for v, e in zip(r.values, exprs):
        enc, ref = v.enclosure(400), sp.Rational(str(sp.N(e, 120)))
        assert enc.lo - sp.Rational(1, 10**60) <= ref <= enc.hi + sp.Rational(1, 10**60)
        assert _same(v, e)


def test_arithmetic_identities_exactly():
    r = _values("sqrt(2)", "sqrt(3)")
    a, b = r.values
    assert (a * a) == 2 and (b * b) == 3
    assert ((a + b) * (a - b)) == -1
    assert ((a + b) / (a + b)) == 1
    assert (a + b).inverse() * (a + b) == 1
    assert (a - b).sign() == -1 and (a * b - 2).sign() == 1
    assert ((a + b) ** 2 - 5 - 2 * a * b).is_zero()


def test_constants_and_zero_division():
    r = _values("c1*c1", constants={"c1": "1/2 - sqrt(3)/6"})
    assert r.values[0].text() == "1/3 - sqrt(3)/6"  # (1/2 − √3/6)² = 1/4 + 1/12 − √3/6
    with pytest.raises(UserError, match="division by zero"):
        _values("1/(sqrt(2)*sqrt(2) - 2)")
    with pytest.raises(UserError, match="negative"):
        _values("sqrt(1 - sqrt(2))")


def test_degree_cap_is_a_clear_refusal():
    with pytest.raises(NotAlgebraic, match="degree"):
        field_of([ex.parse(f"sqrt({p})") for p in (2, 3, 5, 7, 11, 13)], max_degree=16)


def test_enclosure_width_and_sign_of_tiny_differences():
    # 99/70 − √2 ≈ 7.2e-5 > 0 and (99/70 − √2)^8 ≈ 7e-34: signs and widths decided exactly
    r = _values("(99/70 - sqrt(2))^8")
    v = r.values[0]
    assert v.sign() == 1
    iv = v.enclosure(200)
    assert iv.hi - iv.lo <= Fraction(1, 2**200)
    truth = sp.Rational(str(sp.N((sp.Rational(99, 70) - sp.sqrt(2)) ** 8, 120)))
    value, margin = Fraction(int(truth.p), int(truth.q)), Fraction(1, 10**110)  # truth to 120 digits
    assert iv.lo - margin <= value <= iv.hi + margin


@pytest.mark.parametrize("refined", [True, False])
def test_theta_is_enclosed_refined_alone_or_by_the_isolation(refined, monkeypatch):
    # √2 + √3 (θ of degree 4) against sympy to 700 digits, by Newton's bracket or, when
    # that proves nothing, by isolating every root at the width asked
    import rkcheck.numbers.algebraic as algebraic

    found = []
    refine = algebraic.refine_root if refined else (lambda coeffs, start, bits: None)
    monkeypatch.setattr(algebraic, "refine_root", lambda *args: found.append(refine(*args)) or found[-1])
    K = _values("sqrt(2) + sqrt(3)").values[0].field
    theta = K.theta_enclosure(2000)
    assert found and (found[-1] is not None) == refined  # the route the case names was taken
    assert theta.hi - theta.lo <= Fraction(1, 2**2000)
    root = sp.Poly([sp.Rational(c.numerator, c.denominator) for c in reversed(K.minpoly)], sp.Symbol("x"))
    value = sorted(r for r in sp.real_roots(root))[K.index - 1]
    truth = sp.Rational(str(sp.N(value, 700)))
    margin = Fraction(1, 10**690)
    assert theta.lo - margin <= Fraction(int(truth.p), int(truth.q)) <= theta.hi + margin


def _galois_order(text):
    x = sp.Symbol("x")
    group, _ = sp.polys.numberfields.galois_group(sp.Poly(sp.sympify(text.replace("^", "**")), x))
    return group.order()


GAUSS4 = "70*x^4 - 140*x^3 + 90*x^2 - 20*x + 1"  # the shifted Legendre P4 (Gauss-4's nodes)
GAUSS6 = "924*x^6 - 2772*x^5 + 3150*x^4 - 1680*x^3 + 420*x^2 - 42*x + 1"


def test_mirrored_roots_of_a_symmetric_polynomial_are_not_adjoined_again(monkeypatch):
    # P4(1 − x) = P4(x): the largest node is 1 − the smallest, already in Q(c1); with the
    # compositum's characteristic polynomial out of reach only the mirror can place it
    import rkcheck.numbers.field_builder as alg

    def no_compositum(*args):
        raise AssertionError("the compositum was built")

    with monkeypatch.context() as m:
        m.setattr(alg, "charpoly_sum", no_compositum)
        r = field_of([ex.parse(f"root({GAUSS4}, {k})") for k in (1, 4)])
    assert r.field.degree == 4
    c1, c4 = r.values
    assert c4 == 1 - c1
    # all four nodes: the splitting field, of the degree of the Galois group (sympy)
    r = _values(*[f"root({GAUSS4}, {k})" for k in range(1, 5)])
    assert r.field.degree == _galois_order(GAUSS4) == 8
    assert r.values[2] == 1 - r.values[1] and r.values[3] == 1 - r.values[0]


def test_the_six_gauss_6_nodes_generate_a_field_of_the_galois_groups_order():
    # three nodes generate the splitting field (degree |Gal| = 48, by sympy); the other
    # three are their mirrors, so the builder stops at 48 instead of asking for 48·6
    r = field_of([ex.parse(f"root({GAUSS6}, {k})") for k in range(1, 7)], max_degree=48)
    assert r.field.degree == _galois_order(GAUSS6) == 48
    assert all(r.values[5 - i] == 1 - r.values[i] for i in range(3))
    # below the field's degree the cap is a clear refusal
    with pytest.raises(NotAlgebraic, match="more than 32"):
        field_of([ex.parse(f"root({GAUSS6}, {k})") for k in range(1, 7)], max_degree=32)


# ------------------------------------------------ minimal polynomials, enclosures

MINPOLY_CASES = [
    ("sqrt(2) + sqrt(3)", sp.sqrt(2) + sp.sqrt(3)),
    ("(1 + sqrt(5))/2 - 3/7", (1 + sp.sqrt(5)) / 2 - sp.Rational(3, 7)),
    ("root(x^3 - 3*x + 1, 2)^2 + 1/3", sp.CRootOf(sp.Symbol("x")**3 - 3 * sp.Symbol("x") + 1, 1)**2 + sp.Rational(1, 3)),
    ("sqrt(5/36 + sqrt(70)/126)/7", sp.sqrt(sp.Rational(5, 36) + sp.sqrt(70) / 126) / 7),
]


def _sympy_minpoly(expr):
    X = sp.Symbol("X")
    coeffs = sp.Poly(sp.minimal_polynomial(expr, X), X).monic().all_coeffs()[::-1]
    return [Fraction(int(sp.Rational(c).p), int(sp.Rational(c).q)) for c in coeffs]


@pytest.mark.parametrize("text, expr", MINPOLY_CASES, ids=[t for t, _ in MINPOLY_CASES])
def test_minimal_polynomial_agrees_with_sympy(text, expr):
    # the element sits in a larger field (with sqrt(11) and a Gauss-4 node adjoined), so
    # its minimal polynomial is a proper factor of its characteristic polynomial
    r = _values(text, "sqrt(11)", f"root({GAUSS4}, 1)")
    assert r.field.degree > len(_sympy_minpoly(expr)) - 1
    assert minimal_polynomial(r.values[0]) == _sympy_minpoly(expr)


def test_minimal_polynomial_without_the_numerics_is_the_same(monkeypatch):
    # the exact route (factoring the characteristic polynomial) where the numerical
    # candidate is unavailable gives the same answer
    from rkcheck.numbers import minimal

    r = _values("sqrt(2) + sqrt(3)/5", f"root({GAUSS4}, 2)")
    fast = minimal_polynomial(r.values[0])
    monkeypatch.setattr(minimal, "candidate", lambda x, prec: None)
    assert minimal_polynomial(r.values[0]) == fast == _sympy_minpoly(sp.sqrt(2) + sp.sqrt(3) / 5)


def test_a_wrong_numerical_candidate_is_never_returned(monkeypatch):
    # the numerics only propose: a candidate that is not a root is refused, exactly
    from rkcheck.numbers import minimal

    r = _values("sqrt(2) + sqrt(3)")
    monkeypatch.setattr(minimal, "candidate", lambda x, prec: [Fraction(-1), Fraction(0), Fraction(1)])
    assert minimal_polynomial(r.values[0]) == _sympy_minpoly(sp.sqrt(2) + sp.sqrt(3))


@pytest.mark.parametrize("text, expr", MINPOLY_CASES, ids=[t for t, _ in MINPOLY_CASES])
def test_enclosure_contains_the_value_in_a_larger_field(text, expr):
    r = _values(text, "sqrt(11)", f"root({GAUSS4}, 3)")
    iv = r.values[0].enclosure(300)
    assert iv.hi - iv.lo <= Fraction(1, 2**300)
    # the enclosure contains the value (sympy's, to 150 digits: its own error is far below
    # the width); its midpoint is only as close as the width, which cached enclosures of
    # the field's generator may make narrower than asked
    truth = sp.Rational(str(sp.N(expr, 150)))
    slack = Fraction(1, 10**145)
    assert iv.lo - slack <= Fraction(int(truth.p), int(truth.q)) <= iv.hi + slack


def test_a_dot_product_reduced_once_is_the_sum_of_the_products():
    # one reduction modulo g for the whole sum against sympy's exact value of the sum
    from rkcheck.numbers.algebraic import dot

    texts = ["sqrt(2) + sqrt(3)", "1/3 - sqrt(6)", f"root({GAUSS4}, 2)", "7/5", "sqrt(3)/2", f"root({GAUSS4}, 2)^2 - 1"]
    r = _values(*texts)
    xs, ys = r.values[:3], r.values[3:]
    xs = [v if hasattr(v, "field") else r.field(v) for v in xs]
    ys = [v if hasattr(v, "field") else r.field(v) for v in ys]
    node = sp.CRootOf(sp.Poly([int(c) for c in sp.Poly(sp.sympify(GAUSS4.replace("^", "**")), sp.Symbol("x")).all_coeffs()], sp.Symbol("x")), 1)
    exact = (sp.sqrt(2) + sp.sqrt(3)) * sp.Rational(7, 5) + (sp.Rational(1, 3) - sp.sqrt(6)) * sp.sqrt(3) / 2 + node * (node**2 - 1)
    assert _same(dot(xs, ys), exact)
    assert dot(xs, ys) == xs[0] * ys[0] + xs[1] * ys[1] + xs[2] * ys[2]
    # anything but elements of one field: no fast path
    assert dot(xs, [Fraction(1)] * 3) is None and dot([], []) is None


def test_inverses_in_a_field_of_degree_16_are_those_of_the_extended_gcd():
    # above degree 8 an inverse solves the system of multiplication by α; the slower
    # extended gcd of α's polynomial with g gives the same element, and α·α⁻¹ = 1
    r = _values("sqrt(sqrt(1e155) + sqrt(2))", "sqrt(7)", "sqrt(5)")
    x, y, z = r.values
    assert r.field.degree == 16
    g = r.field.g
    for alpha in (x, x + y * z, x * y - 3 * z + 1, (x + 1) * (y - 2) * (z + Fraction(1, 3))):
        inv = alpha.inverse()
        assert inv * alpha == 1
        d, s, _ = alpha.poly.xgcd(g)
        assert inv.poly == (s / d) % g


@pytest.mark.parametrize("texts, constants", [
    (["1/3 + 2/7*x", "x^3 - 1/x", "(-2)^-3", "-(x - y)^2/5"], {"x": "3/4", "y": "x^2 + 1/2"}),
    (["0.125 * 8e-3", "2^(3 - 1)", "-x"], {"x": "-(1/9)"}),
    (["x / (y - y)"], {"x": "1", "y": "2"}),
    (["0^(-2)"], {}),
    (["2^(1/2)"], {}),
    (["(1/0)^(1/2)"], {}),
    (["z + 1"], {}),
])
def test_rational_expressions_take_the_builders_values_and_errors(texts, constants):
    # field_of evaluates root-free expressions in plain rationals; the builder, run
    # directly, evaluates them in a field of degree 1: the same values, the same errors
    from rkcheck.numbers import field_builder as fb

    nodes = [ex.parse(t) for t in texts]
    defs = {k: ex.parse(v) for k, v in constants.items()}

    def outcome(run):
        try:
            return run().values
        except (UserError, NotAlgebraic) as err:
            return type(err).__name__, str(err)

    assert outcome(lambda: field_of(nodes, defs)) == outcome(lambda: fb._field_of(nodes, defs, 48))
