"""A rounded decimal that several entries share is one number (definitions §5.2): the
tableaux a file allows are those of its literals' box, and a condition that is nonzero
for every value of the literals fails.

The oracle is exact and independent of the engine: with entries polynomial in one
literal ``a``, each condition's residual is a polynomial P(a) of degree at most 2n, got
by interpolating the brute-force reference (``reference``: exact Fractions) at 2n + 1
rational points; sympy then counts its real roots in any rational interval.  A kernel's
decimal coefficient κ is checked the same way, with the engine's exact route (itself
cross-checked against the reference elsewhere) giving P(κ) at rational κ.
"""

from __future__ import annotations

import functools
import math
from fractions import Fraction

import numpy as np
import pytest
import sympy
from support import reference as ref

import rkcheck
from rkcheck.energy.check import check
from rkcheck.energy.explain import explain
from rkcheck.evaluation import box as box_module
from rkcheck.evaluation.box import judge_box
from rkcheck.evaluation.values import TableauValues
from rkcheck.io.loader import loads
from rkcheck.methods.continuous import ContinuousMethod
from rkcheck.numbers.entries import Constants, Entry
from rkcheck.numbers.grammar import parse
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.literals import literal_box
from rkcheck.numbers.reading import Reading
from rkcheck.options import CheckOptions
from rkcheck.trees.listing import ConditionListing
from rkcheck.verdicts import FAILS, HOLDS_TO_DIGITS

#: tableaux in one constant a, entries polynomials in a and 1/a, as the file writes them
#: and as the oracle computes them (Fractions): the 3-stage one has Σb = 1 for every a;
#: Ralston's family (c₂ = a) has Σb = 1 and bᵀc = 1/2 for every a
FAMILIES = {
    "polynomial": (([["0", "0", "0"], ["a", "0", "0"], ["a*a", "1 - a", "0"]], ["1 - a - a*a/2", "a", "a*a/2"]),
                   lambda a: ([[0, 0, 0], [a, 0, 0], [a * a, 1 - a, 0]], [1 - a - a * a / 2, a, a * a / 2])),
    "ralston": (([["0", "0"], ["a", "0"]], ["1 - 1/(2*a)", "1/(2*a)"]),
                lambda a: ([[0, 0], [a, 0]], [1 - 1 / (2 * a), 1 / (2 * a)])),
}


@functools.lru_cache(maxsize=None)
def _entries_at(family: str, a: Fraction) -> tuple[list[list[Fraction]], list[Fraction]]:
    return FAMILIES[family][1](a)


def _polynomial(values: dict[Fraction, Fraction]) -> sympy.Poly:
    """The interpolating polynomial through exact points, by Newton's divided
    differences in Fractions (a polynomial of lower degree than the number of points is
    recovered exactly)."""
    xs = list(values)
    coef = [values[x] for x in xs]
    for j in range(1, len(xs)):
        for i in range(len(xs) - 1, j - 1, -1):
            coef[i] = (coef[i] - coef[i - 1]) / (xs[i] - xs[i - j])
    poly = [Fraction(0)]  # coefficients, constant first: Horner on the Newton form
    for i in range(len(xs) - 1, -1, -1):
        shifted = [Fraction(0)] + poly
        for k, p in enumerate(poly):
            shifted[k] -= xs[i] * p
        shifted[0] += coef[i]
        poly = shifted
    x = sympy.Symbol("x")
    return sympy.Poly([sympy.Rational(c.numerator, c.denominator) for c in reversed(poly)], x, domain="QQ")


@functools.lru_cache(maxsize=None)
def _reference_conditions(n: int) -> list[tuple[frozenset, dict]]:
    return [(frozenset(ref.canonicalize(u) for u, *_ in c["terms"]), c) for c in ref.energy_conditions(n)]


def _roots_within(P: sympy.Poly, lo: Fraction, hi: Fraction) -> int:
    return int(P.count_roots(sympy.Rational(lo.numerator, lo.denominator), sympy.Rational(hi.numerator, hi.denominator)))


def _toml(family: str, literal: str) -> str:
    A_texts, b_texts = FAMILIES[family][0]
    rows = ", ".join("[" + ", ".join(f'"{t}"' for t in row) + "]" for row in A_texts)
    return (f'[method]\nname = "shared literal"\n[constants]\na = "{literal}"\n'
            f'[tableau]\nA = [{rows}]\nb = [{", ".join(chr(34) + t + chr(34) for t in b_texts)}]\n')


def _judge_against_polynomial(result, P: sympy.Poly, residual_at, face: Fraction, radius: Fraction) -> bool:
    """The verdict of one condition against the polynomial ``P`` whose roots near the
    literal are the residual's, and the residual itself (``residual_at(a)``, exact);
    whether the residual vanishes somewhere on the literal's box."""
    state, digits, enclosure, name = result.verdict.state, result.verdict.digits, result.enclosure, result.id
    lo, hi = face - radius, face + radius
    if P.is_zero:
        assert state == HOLDS_TO_DIGITS, name
        return False
    inside = _roots_within(P, lo, hi) > 0
    if inside:
        assert state != FAILS, name  # never a false failure
    elif not _roots_within(P, face - 3 * radius, face + 3 * radius):
        assert state == FAILS, name  # nonzero with a margin: first order decides it
    for a in (lo, face, hi):
        v = residual_at(a)
        if state == FAILS:  # the enclosure holds the residual at every point of the box
            assert abs(v - Fraction(enclosure.mid)) <= Fraction(enclosure.rad), name
        else:
            assert abs(v) <= Fraction(1, 10**digits), name
    return inside


#: literals rounded from a root of a condition's residual (polynomial family:
#: x⁴ − x³ + 3x² − 1 and x⁵ − 2x⁴ + 7x³ − 6x² + 13x − 4, roots 0.601887712… and
#: 0.341860781…; Ralston's family: 1/6 − a/4 at 2/3): their boxes hold it
HOLDING_A_ROOT = [("polynomial", "0.6018877"), ("polynomial", "0.3418608"), ("ralston", "0.6666667")]

#: ... and literals 4 to 5 half-units from those roots: the conditions fail on the whole
#: box, by a residual a few times its variation along the literal
NEAR_A_ROOT = [("polynomial", "0.6018879"), ("polynomial", "0.6018875"), ("polynomial", "0.3418610"),
               ("polynomial", "0.3418606"), ("ralston", "0.6666669"), ("ralston", "0.6666665")]

ELSEWHERE = [("polynomial", "0.6666669"), ("polynomial", "1.4142136"), ("polynomial", "0.2113249"),
             ("ralston", "0.5773503"), ("ralston", "1.4142136")]


@pytest.mark.parametrize("family, literal", ELSEWHERE + HOLDING_A_ROOT + NEAR_A_ROOT)
def test_a_constant_shared_by_entries_is_judged_over_its_own_interval(family, literal):
    face = Fraction(literal)
    radius = Fraction(1, 2 * 10**7)  # half a unit of the seventh decimal
    res = check(loads(_toml(family, literal), "shared.toml"), CheckOptions(degree=None, order=6))
    states, inside = set(), 0
    for r in res.conditions:
        cond = next(c for keys, c in _reference_conditions(r.vertices) if ref.canonicalize(r.level_sequence) in keys)

        def residual_at(a: Fraction, cond=cond) -> Fraction:
            return ref.energy_residual(cond, *_entries_at(family, a))
        # the polynomial family's entries have degree ≤ 2 in a, so R has degree ≤ 2n (2n + 3
        # points recover it exactly); Ralston's b has 1/a, and a^(2n)·R(a) has degree ≤ 4n
        n = r.vertices
        power, half = (0, n + 1) if family == "polynomial" else (2 * n, 2 * n + 2)
        P = _polynomial({a: a ** power * residual_at(a) for a in (face + k for k in range(-half, half + 1))})
        states.add(r.verdict.state)
        inside += _judge_against_polynomial(r, P, residual_at, face, radius)
    assert FAILS in states
    assert (inside > 0) == ((family, literal) in HOLDING_A_ROOT)


def test_an_identity_in_the_shared_literal_holds_beyond_the_literals_digits():
    # Ralston's family: by hand bᵀc = b₂a = 1/2 for every a, so the condition with 3
    # vertices, 1/2 − bᵀc (Σb = 1), is 0 on the whole box; along the literal its variation
    # is second order, and it holds far beyond the literal's 7 digits (over the entries'
    # own box, each b_i ± 6e−8 on its own, it held to 6)
    res = check(loads(_toml("ralston", "0.6666669"), "ralston.toml"), CheckOptions(degree=None, order=4))
    first = next(r for r in res.conditions if r.vertices == 3)
    assert first.verdict.state == HOLDS_TO_DIGITS and first.verdict.digits >= 12


# ------------------------------------------------------------------ a kernel's decimal

KERNEL = "tau + {k}*tau*(sigma - 1/2)"


def test_a_kernels_decimal_is_one_number_in_every_surrogate_entry():
    literal, order = "0.0000100000", 6
    face, radius = Fraction(literal), Fraction(1, 2 * 10**11)
    res = rkcheck.verify(ContinuousMethod.from_kernel(KERNEL.format(k=literal)), degree=None, order=order)
    exact: dict[str, dict[Fraction, Fraction]] = {}
    for k in range(-order - 1, order + 2):  # degree ≤ n − 1 ≤ order in κ
        kappa = face + Fraction(k, 10**6)
        text = KERNEL.format(k=f"({kappa.numerator}/{kappa.denominator})")
        for r in rkcheck.verify(ContinuousMethod.from_kernel(text), degree=None, order=order).conditions:
            exact.setdefault(r.id, {})[kappa] = r.residual
    failing = 0
    for r in res.conditions:
        P = _polynomial(exact[r.id])
        failing += r.verdict.state == FAILS
        _judge_against_polynomial(r, P, lambda kappa: Fraction(str(P.eval(sympy.Rational(kappa.numerator,
                                                                                         kappa.denominator)))),
                                  face, radius)
    assert failing == sum(1 for pts in exact.values() if pts[face] != 0)


def test_a_miyatake_butcher_entry_is_one_number_in_a_and_in_b():
    # M = [[κ]]: A = κτ, B = κ, AVF with step κh, so by hand every energy condition is 0
    # for every κ: along its one literal it holds far beyond its 7 digits (with A's κ
    # and B's varying apart, to 6)
    method = ContinuousMethod.from_matrix([["1.000001"]])
    res = rkcheck.verify(method, degree=None, order=5)
    assert res.conditions and all(r.verdict.state == HOLDS_TO_DIGITS and r.verdict.digits >= 10
                                  for r in res.conditions)


# ------------------------------------------------------------------ the Jacobian itself


def test_the_jacobian_encloses_the_derivatives_by_hand():
    consts = Constants({"a": parse("0.6666669"), "q": parse("sqrt(a) + 0.1234567")})
    entries = [Entry.parse(t, consts) for t in ("1/(2*a)", "q*q", "a^3 - 0.5000001*a", "7")]
    box = literal_box(entries, 200, "auto")
    assert box is not None and len(box.radii) == 3 and all(r == Fraction(1, 2 * 10**7) for r in box.radii)
    a0, p0 = Fraction("0.6666669"), Fraction("0.5000001")
    for a in (a0 - box.radii[0], a0, a0 + box.radii[0]):
        s = sympy.sqrt(sympy.Rational(a.numerator, a.denominator))
        q = s + sympy.Rational(1234567, 10**7)
        by_hand = [  # ∂/∂a, ∂/∂(0.1234567), ∂/∂(0.5000001) of each entry
            (-1 / (2 * a * a), 0, 0),
            (q / s, 2 * q, 0),
            (3 * a * a - p0, 0, -a),
            (0, 0, 0),
        ]
        for row, expected in zip(box.rows, by_hand):
            for iv, d in zip([row.get(lit, Interval.point(0)) for lit in range(3)], expected):
                d = sympy.sympify(d) if not isinstance(d, Fraction) else sympy.Rational(d.numerator, d.denominator)
                assert sympy.Rational(iv.lo.numerator, iv.lo.denominator) <= d <= sympy.Rational(iv.hi.numerator,
                                                                                               iv.hi.denominator)


def test_literals_written_once_are_not_shared():
    entries = [Entry.parse(t) for t in ("0.6666669", "1 - 0.3333331", "0.6666669*2")]
    assert literal_box(entries, 200, "auto") is None


def test_entries_built_from_one_parse_are_two_numbers_unless_they_share_their_literals():
    # a reader may build entries of equal text from one parse (the file loader does):
    # definitions §5 still reads two written literals as two numbers
    node = parse("0.6666669")
    assert literal_box([Entry.from_node("0.6666669", node), Entry.from_node("0.6666669", node)], 200, "auto") is None
    one = literal_box([Entry.from_node("0.6666669", node, shares_literals=True),
                       Entry.from_node("0.6666669", node, shares_literals=True)], 200, "auto")
    assert one is not None and len(one.radii) == 1


def test_a_kernels_surrogate_shares_its_literal():
    method = ContinuousMethod.from_kernel(KERNEL.format(k="0.0000100000"))
    tab = method.surrogate(5)
    box = literal_box([e for row in tab.A for e in row if not e.enclosure(200, "auto").is_point], 200, "auto")
    assert box is not None and len(box.radii) == 1


# ------------------------------------------------------------------ every route of the box

GAUSS3 = """
[constants]
r = "3.872983346207417"
[tableau]
A = [["5/36", "2/9 - r/15", "5/36 - r/30"], ["5/36 + r/24", "2/9", "5/36 - r/24"],
     ["5/36 + r/30", "2/9 + r/15", "5/36"]]
b = ["5/18", "4/9", "5/18"]
"""


def test_the_majorant_route_judges_along_the_literals_as_every_direction_does(monkeypatch):
    # Gauss-3 with √15 written once, to 16 digits (its box holds √15): from 15 vertices
    # the majorant decides first and the others get every direction, along the literal

    tab = loads(GAUSS3, "gauss3.toml")
    values = TableauValues(tab, Reading())
    chain = values.literal_chain
    assert chain is not None and chain.radii.shape == (1,)
    listing = ConditionListing(14, None)
    wanted = sorted(listing.orders)
    new = judge_box(listing, values.A, values.b, tab.exact_A(), tab.exact_b(), wanted, None, chain)
    with monkeypatch.context() as m:
        m.setattr(box_module, "MAJORANT_MIN_VERTICES", 10**6)
        old = judge_box(listing, values.A, values.b, tab.exact_A(), tab.exact_b(), wanted, None, chain)
    exact = check(loads(GAUSS3.replace('"3.872983346207417"', '"sqrt(15)"'), "g.toml"),
                  CheckOptions(degree=None, order=14))
    held = {r.id for r in exact.conditions if r.verdict.state != FAILS}
    decided = 0
    for n in wanted:
        a, b = new[n], old[n]
        assert a.refined is not None
        decided += int(a.refined[2].sum())
        assert np.array_equal(a.excludes_zero(), b.excludes_zero()), n
        for k in range(len(b)):
            ea, eb = a.enclosure(k), b.enclosure(k)
            assert ea.mid == eb.mid
            assert math.isclose(float(ea.rad), float(eb.rad), rel_tol=1e-5), n
    assert decided
    # the conditions √15's Gauss-3 satisfies exactly never fail on the box that holds it
    res = check(tab, CheckOptions(degree=None, order=14))
    assert held and all(r.verdict.state != FAILS for r in res.conditions if r.id in held)


# ------------------------------------------------------------------ irrational face values

def _sympy_residual(cond, A, b):
    """R for sympy entries, by the definitions' recursion (the reference's, written again
    over sympy numbers: Φ(τ) = 1, Φ([t₁…t_q]) = Π (AΦ(t_k)), a(t) = bᵀΦ(t))."""
    s = len(b)

    def phi(t):
        out = [sympy.Integer(1)] * s
        for child in ref.split_children(t):
            v = phi(child)
            out = [out[i] * sum(A[i][j] * v[j] for j in range(s)) for i in range(s)]
        return out

    total = sympy.Integer(0)
    for _, sign, sig, forest in cond["terms"]:
        term = sympy.Rational(sign, sig)
        for t in forest:
            term *= sum(b[i] * w for i, w in enumerate(phi(t)))
        total += term
    return sympy.expand(total)


@pytest.mark.parametrize("literal", ["0.5000002", "0.5000000", "0.4999998", "0.7320508"])
def test_exact_roots_beside_a_shared_decimal_are_judged_over_the_literals_box(literal):
    # Gauss-2 (√3 exact) with b = (h, 1 − h), h one decimal: every residual is a
    # polynomial in h over Q(√3); its sign at the box's ends is decided exactly by sympy
    text = ('[constants]\nh = "%s"\nr3 = "sqrt(3)"\n[tableau]\nA = [["1/4", "1/4 - r3/6"], ["1/4 + r3/6", "1/4"]]\n'
            'b = ["h", "1 - h"]\n' % literal)
    res = check(loads(text, "g2h.toml"), CheckOptions(degree=None, order=5))
    h, r3 = sympy.Symbol("h"), sympy.sqrt(3)
    A = [[sympy.Rational(1, 4), sympy.Rational(1, 4) - r3 / 6], [sympy.Rational(1, 4) + r3 / 6, sympy.Rational(1, 4)]]
    face, radius = sympy.Rational(literal), sympy.Rational(1, 2 * 10**7)
    decided = 0
    for r in res.conditions:
        cond = next(c for keys, c in _reference_conditions(r.vertices) if ref.canonicalize(r.level_sequence) in keys)
        R = _sympy_residual(cond, A, [h, 1 - h])
        state, ends = r.verdict.state, [R.subs(h, face - radius), R.subs(h, face + radius)]
        if R == 0:
            assert state == HOLDS_TO_DIGITS, r.id
            continue
        # R·R̄ (√3 → −√3) has rational coefficients and the roots of R among its own
        norm = sympy.Poly(sympy.expand(R * R.subs(r3, -r3)), h, domain="QQ")
        if sympy.sign(ends[0]) != sympy.sign(ends[1]) or 0 in ends:
            assert state != FAILS, r.id  # a root in the box: never a false failure
        elif not norm.count_roots(face - 3 * radius, face + 3 * radius):
            assert state == FAILS, r.id
            decided += 1
        for v in ends + [R.subs(h, face)]:
            if state == FAILS:
                assert abs(v - sympy.Rational(Fraction(r.enclosure.mid))) <= sympy.Rational(Fraction(r.enclosure.rad))
            else:
                assert abs(v) <= sympy.Rational(1, 10**r.verdict.digits)
    assert decided or literal == "0.5000000"


def test_a_square_root_of_a_shared_decimal_is_one_number():
    # Ralston's family at c₂ = q = √a, a = "0.4444448": by hand the condition with 4
    # vertices is 1/6 − q/4, zero only at a = 4/9 = 0.444444…, outside 0.4444448 ± 5e−8
    # (it fails on the whole box), and bᵀc = 1/2 for every a
    text = ('[constants]\na = "0.4444448"\nq = "sqrt(a)"\n[tableau]\nA = [["0", "0"], ["q", "0"]]\n'
            'b = ["1 - 1/(2*q)", "1/(2*q)"]\n')
    res = check(loads(text, "sqrt.toml"), CheckOptions(degree=None, order=3))
    by_vertices = {r.vertices: r for r in res.conditions}
    assert by_vertices[4].verdict.state == FAILS
    a_lo, a_hi = sympy.Rational("0.44444475"), sympy.Rational("0.44444485")
    for a in (a_lo, a_hi):
        value = sympy.Rational(1, 6) - sympy.sqrt(a) / 4
        enc = by_vertices[4].enclosure
        assert abs(value - sympy.Rational(Fraction(enc.mid))) <= sympy.Rational(Fraction(enc.rad))
    assert by_vertices[3].verdict.state == HOLDS_TO_DIGITS and by_vertices[3].verdict.digits >= 12


# ------------------------------------------------------------------ explain

@pytest.mark.parametrize("text", [
    _toml("ralston", "0.6666669"),
    '[tableau]\nA = [["1/2"]]\nb = ["0.9999999999"]\n',
    '[constants]\nh = "0.5000002"\nr3 = "sqrt(3)"\n[tableau]\nA = [["1/4", "1/4 - r3/6"], ["1/4 + r3/6", "1/4"]]\n'
    'b = ["h", "1 - h"]\n',
])
def test_explain_on_a_box_gives_the_verdict_and_enclosure_of_the_check(text):
    # explain's terms are intervals over the box each; its R is the condition judged
    # over the box jointly, as the check judges it — the same verdict (the enclosure may
    # come from another pass: the same mid-point, a radius within rounding)
    tab = loads(text, "box.toml")
    values = TableauValues(tab, Reading())
    res = check(tab, CheckOptions(degree=None, order=4))
    assert res.conditions
    for r in res.conditions:
        shown = explain(r.level_sequence, values)
        assert shown.verdict == r.verdict, r.id
        assert Fraction(shown.enclosure.mid) == Fraction(r.enclosure.mid), r.id
        assert math.isclose(float(shown.enclosure.rad), float(r.enclosure.rad), rel_tol=1e-9), r.id


def test_exact_roots_are_one_number_not_directions_of_the_box_at_any_precision():
    # Gauss-2 (√3 exact) with decimal weights: the box has 2 directions (b's), whatever
    # --dps makes of √3's enclosure.  By hand, with b₁ = 1/2 + u, b₂ = 1/2 + v and
    # c = (1/2 − √3/6, 1/2 + √3/6), R(1,2,2) = (Σb)²/2 − bᵀc = (1/2 + √3/6)u + (1/2 −
    # √3/6)v + (u + v)²/2: affine but for a 10⁻¹⁴ term, so its least value on the box
    # (u ∈ [5, 15]·10⁻⁸, v ∈ [−15, −5]·10⁻⁸) is at a corner, where sympy finds it
    # positive: it fails at 50 digits and at 300 alike (past about 290 digits √3's
    # enclosure is below float64's range, yet √3 is one number, not a direction)
    from rkcheck.energy.judging import box_directions

    text = ('[constants]\nr3 = "sqrt(3)"\n[tableau]\nA = [["1/4", "1/4 - r3/6"], ["1/4 + r3/6", "1/4"]]\n'
            'b = ["0.5000001", "0.4999999"]\n')
    tab = loads(text, "g2p.toml")
    r3, half = sympy.sqrt(3), sympy.Rational(1, 20_000_000)
    c = [sympy.Rational(1, 2) - r3 / 6, sympy.Rational(1, 2) + r3 / 6]
    for b1 in (sympy.Rational("0.5000001") - half, sympy.Rational("0.5000001") + half):
        for b2 in (sympy.Rational("0.4999999") - half, sympy.Rational("0.4999999") + half):
            assert sympy.simplify((b1 + b2) ** 2 / 2 - (b1 * c[0] + b2 * c[1])) > 0
    for dps in (50, 300):
        values = TableauValues(tab, Reading(dps=dps))
        assert box_directions(values) == 2
        first = next(r for r in check(tab, CheckOptions(degree=4, order=3, dps=dps)).conditions if r.vertices == 3)
        assert first.verdict.state == FAILS, dps
