"""Quadrature rules: orders (seed §2.4) and nodes/weights against closed forms by hand."""

from __future__ import annotations

from fractions import Fraction

import pytest

from rkcheck.errors import UserError
from rkcheck.methods.quadrature import closed_forms, rule
from rkcheck.numbers.entries import Entry

# Closed forms from the literature (Hairer–Wanner II, Table IV.5.x; Abramowitz–Stegun 25.4):
HAND = {
    ("gauss", 1): (["1/2"], ["1"]),
    ("gauss", 2): (["(3 - sqrt(3))/6", "(3 + sqrt(3))/6"], ["1/2", "1/2"]),
    ("gauss", 3): (["1/2 - sqrt(15)/10", "1/2", "1/2 + sqrt(15)/10"], ["5/18", "4/9", "5/18"]),
    ("radau-ii", 2): (["1/3", "1"], ["3/4", "1/4"]),
    ("radau-ii", 3): (["(4 - sqrt(6))/10", "(4 + sqrt(6))/10", "1"], ["(16 - sqrt(6))/36", "(16 + sqrt(6))/36", "1/9"]),
    ("radau-i", 2): (["0", "2/3"], ["1/4", "3/4"]),
    ("radau-i", 3): (["0", "(6 - sqrt(6))/10", "(6 + sqrt(6))/10"], ["1/9", "(16 + sqrt(6))/36", "(16 - sqrt(6))/36"]),
    ("lobatto", 2): (["0", "1"], ["1/2", "1/2"]),
    ("lobatto", 3): (["0", "1/2", "1"], ["1/6", "2/3", "1/6"]),
    ("lobatto", 4): (["0", "(5 - sqrt(5))/10", "(5 + sqrt(5))/10", "1"], ["1/12", "5/12", "5/12", "1/12"]),
}


@pytest.mark.parametrize("name, s", list(HAND), ids=[f"{n}-{s}" for n, s in HAND])
@pytest.mark.parametrize("dps", [50, 100])
def test_nodes_and_weights_agree_with_closed_forms(name, s, dps):
    bits = int(dps * 3.33) + 10
    c, b = rule(name, s).enclosures(bits)
    nodes, weights = HAND[(name, s)]
    for got, text in list(zip(c, nodes)) + list(zip(b, weights)):
        want = Entry.parse(text).enclosure(bits + 20)
        assert got.lo <= want.hi and want.lo <= got.hi, (text, float(got.mid))  # both contain the value
        assert got.hi - got.lo < Fraction(1, 10**dps)


@pytest.mark.parametrize("s", [1, 2, 3, 4, 5, 6])
def test_orders_follow_the_seed(s):
    # seed §2.4: Gauss (ζ=0) has quadrature order 2s; every other ζ gives 2s−1;
    # Lobatto has 2s−2 (its 2 end points are fixed).
    assert rule("gauss", s).order() == 2 * s
    for name in ("radau-i", "radau-ii", "zeta:1/2", "zeta:-1/3", "zeta:1"):
        assert rule(name, s).order() == 2 * s - 1
    if s >= 2:
        assert rule("lobatto", s).order() == 2 * s - 2


def test_rational_rules_are_exact():
    c, b = rule("radau-ii", 2).exact_nodes_weights()
    assert c == [Fraction(1, 3), Fraction(1)] and b == [Fraction(3, 4), Fraction(1, 4)]
    assert rule("lobatto", 3).is_rational and not rule("gauss", 2).is_rational


@pytest.mark.parametrize("name, s", [("gauss", 4), ("gauss", 5), ("lobatto", 5), ("lobatto", 6), ("radau-ii", 3), ("zeta:1/2", 2)])
def test_closed_forms_evaluate_inside_the_certified_nodes(name, s):
    r = rule(name, s)
    texts = closed_forms(r.nodes)
    assert texts is not None and len(texts) == s
    for node, text in zip(r.nodes, texts):
        enc = node.enclosure(180)
        val = Entry.parse(text).enclosure(220)
        assert enc.lo <= val.hi and val.lo <= enc.hi, text


def test_no_closed_form_for_an_irreducible_cubic():
    # Radau IIA 4: after removing the node 1 a cubic with three irrational zeros remains
    assert closed_forms(rule("radau-ii", 4).nodes) is None


@pytest.mark.parametrize("value, shown", [("2e6", "2000000"), ("1000001", "1000001"), ("-2000001/2", "-1000000.5"),
                                          ("1e400", "1e400"), ("-7e1000", "-7e1000")])
def test_a_zeta_out_of_range_is_refused_with_its_exact_value(value, shown):
    # past float64's range too, and never rounded into the range it lies outside
    with pytest.raises(UserError) as err:
        rule(f"zeta:{value}", 2)
    assert str(err.value) == f"zeta must lie in [-1,000,000, 1,000,000], got {shown}"


@pytest.mark.parametrize("method, s", [("gauss", 20), ("radau-ia", 12)])
def test_decimal_collocation_entries_against_mpmath(method, s):
    # past 8 nodes `new` writes 60-digit decimals; each is the entry to its last digit:
    # a_ij = ∫_0^{c_i} ℓ_j (Gauss) or b_j/b_i ∫_{c_j}^1 ℓ_i (Radau IA), the nodes and
    # weights from mpmath's own root finding at 120 digits — an independent route
    import tomllib

    import mpmath

    import rkcheck

    doc = tomllib.loads(rkcheck.new_toml(method, stages=s))["tableau"]
    with mpmath.workdps(120):
        if method == "gauss":
            nodes = sorted((1 + mpmath.mpf(x)) / 2 for x in mpmath.polyroots(
                mpmath.taylor(lambda t: mpmath.legendre(s, t), 0, s)[::-1], maxsteps=200, extraprec=400))
        else:  # Radau I: zeros of P_s(2x−1) + P_{s−1}(2x−1), 0 among them
            nodes = sorted((1 + mpmath.mpf(x)) / 2 for x in mpmath.polyroots(
                [a + b for a, b in zip(mpmath.taylor(lambda t: mpmath.legendre(s, t), 0, s)[::-1],
                                       [0] + mpmath.taylor(lambda t: mpmath.legendre(s - 1, t), 0, s - 1)[::-1])],
                maxsteps=200, extraprec=400))

        def integral(j, lo, hi):  # ∫ ℓ_j from lo to hi: ℓ_j expanded, integrated term by term
            coeffs = [mpmath.mpf(1)]
            for k in range(s):
                if k != j:
                    coeffs = [(coeffs[m - 1] if m else 0) - nodes[k] * (coeffs[m] if m < len(coeffs) else 0)
                              for m in range(len(coeffs) + 1)]
            scale = mpmath.fprod(nodes[j] - nodes[k] for k in range(s) if k != j)
            return mpmath.fsum(a * (hi ** (m + 1) - lo ** (m + 1)) / (m + 1) for m, a in enumerate(coeffs)) / scale

        weights = [integral(j, 0, 1) for j in range(s)]
        for i in range(s):
            for j in range(s):
                if method == "gauss":
                    want = integral(j, 0, nodes[i])
                else:
                    want = weights[j] / weights[i] * integral(i, nodes[j], 1)
                got = mpmath.mpf(doc["A"][i][j])
                assert abs(got - want) <= mpmath.mpf(10) ** -58 * max(abs(want), mpmath.mpf(10) ** -40), (i, j)
        if method == "radau-ia":
            assert doc["c"][0] == "0"  # exactly the node 0, not the noise of an enclosure about it
