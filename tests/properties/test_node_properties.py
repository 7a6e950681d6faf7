"""A family's properties decided in its node algebra ``Q[x, y]/(P(x), P(y))``, against the
same properties computed entry by entry over the nodes' number field.

Independent routes: the field's own values of the entries (each evaluated in the field
from its text, :func:`rkcheck.methods.closed_forms.family_exact_values`) run through the
generic functions of :mod:`rkcheck.properties.tableau`; an entry the node route names is
checked by evaluating its minimal polynomial at the field's value of it, exactly, and by
reading its ``root(f, k)`` text back with the entry parser.
"""

from __future__ import annotations

import pickle
import re
from fractions import Fraction

import pytest

from rkcheck.methods.closed_forms import family_exact_values
from rkcheck.methods.family_spec import parse_spec
from rkcheck.methods.node_algebra import _square_root_field, node_algebra
from rkcheck.methods.node_form import node_form
from rkcheck.numbers.entries import Entry
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.reading import DecimalsMode
from rkcheck.properties.from_nodes import node_properties, node_quadrature_order
from rkcheck.properties.orders import quadrature_order
from rkcheck.properties.scalars import certainly_larger, values_from_enclosures
from rkcheck.properties.tableau import properties_of_values

FAMILIES = [
    {"name": "gauss", "s": 4}, {"name": "gauss", "s": 5}, {"name": "radau-iia", "s": 4},
    {"name": "radau-ia", "s": 4}, {"name": "lobatto-iiia", "s": 6}, {"name": "lobatto-iiib", "s": 6},
    {"name": "avf", "s": 4}, {"name": "hbvm", "k": 4, "s": 2}, {"name": "hbvm", "k": 4, "s": 3},
    {"name": "hbvm", "k": 5, "s": 2},
]


def _routes(table):
    spec = parse_spec(table)
    form = node_form(spec)
    algebra = node_algebra(spec, form)
    assert algebra is not None, "a family beyond square roots, consistent, with nonzero weights"
    found, reason = family_exact_values(spec)
    assert reason is None
    n = algebra.n
    v = found.values
    A, b = [v[i * n:(i + 1) * n] for i in range(n)], v[n * n:n * n + n]
    return algebra, form, found.field, A, b


def _at(K, f, alpha):
    total = K(0)
    for c in reversed(f):
        total = total * alpha + K(c)
    return total


def _same_value(node_value, K, alpha):
    """The node route's value is the field's: its minimal polynomial vanishes there, and
    the two enclosures meet."""
    assert _at(K, node_value.minimal, alpha).is_zero()
    a, b = node_value.enclosure(200), alpha.enclosure(200)
    assert not (a.hi < b.lo or b.hi < a.lo)


def _without_value(reason: str) -> str:
    return reason.split(": largest entry")[0].split(" of the tableau:")[0]


@pytest.mark.parametrize("table", FAMILIES)
def test_properties_match_the_field_route(table):
    algebra, form, K, A, b = _routes(table)
    mine = node_properties(algebra)
    want = properties_of_values(A, b)
    assert mine.exact and want.exact
    assert mine.reduction.reduced_stages == want.reduction.reduced_stages == algebra.n
    assert mine.reduction.classes == want.reduction.classes
    assert mine.stability.text() == want.stability.text()
    assert mine.symmetric == want.symmetric
    s_mine, s_want = mine.symplectic, want.symplectic
    assert s_mine.verdict == s_want.verdict and s_mine.defect_entry == s_want.defect_entry
    assert _without_value(s_mine.reason) == _without_value(s_want.reason)
    if s_mine.defect is not None:
        i, j = s_want.defect_entry
        _same_value(s_mine.defect, K, s_want.defect)
    for degree in range(2, 7):
        (avf_m, cert_m), (avf_w, cert_w) = mine.certificates(degree), want.certificates(degree)
        assert avf_m.verdict == avf_w.verdict
        assert _without_value(avf_m.reason) == _without_value(avf_w.reason)
        assert re.findall(r"≈ (\S+)$", avf_m.reason) == re.findall(r"≈ (\S+)$", avf_w.reason)
        assert cert_m == cert_w


@pytest.mark.parametrize("table", FAMILIES)
def test_quadrature_order_matches_the_field_route(table):
    algebra, _, _, A, b = _routes(table)
    assert node_quadrature_order(algebra) == quadrature_order(A, b)


@pytest.mark.parametrize("table", [FAMILIES[0], FAMILIES[2], FAMILIES[7]])
def test_every_entry_value_is_the_fields(table):
    """Zero, rational or ``root(f, k)``: every entry of A − (A·1)bᵀ and of M, read in the
    node algebra, is the field's entry (its text read back by the entry parser)."""
    algebra, _, K, A, b = _routes(table)
    n = algebra.n
    F, W_x, W_y, x = algebra.F, algebra.W_x, algebra.W_y, algebra.x
    c = [sum(row, K(0)) for row in A]
    D = F - x * W_y
    M = W_x * F + W_y * algebra.swap(F) - W_x * W_y
    for i in range(n):
        for j in range(n):
            for g, want in ((D, A[i][j] - c[i] * b[j]), (M, b[i] * A[i][j] + b[j] * A[j][i] - b[i] * b[j])):
                v = algebra.value(g, i, j)
                assert v.is_zero() == want.is_zero()
                q = want.rational()
                assert v.rational() == q
                _same_value(v, K, want)
                if q is None:
                    read = Entry.parse(v.text()).enclosure(200, DecimalsMode.EXACT)
                    field = want.enclosure(200)
                    assert not (read.hi < field.lo or field.hi < read.lo)


def test_a_value_travels_as_a_worker_sends_it():
    algebra, _, K, A, b = _routes(FAMILIES[7])
    v = algebra.value(algebra.F - algebra.x * algebra.W_y, 0, 1)
    back = pickle.loads(pickle.dumps(v))
    assert back.minimal == v.minimal and back.text() == v.text()
    assert back.enclosure(100) == v.enclosure(100)


def test_a_square_root_field_keeps_the_field_route():
    """Nodes in one ``Q(√d)`` (Gauss-3, Lobatto-5) keep the field: it is cheap, and writes
    values in √d."""
    for table in ({"name": "gauss", "s": 3}, {"name": "lobatto-iiia", "s": 5}, {"name": "gauss", "s": 2}):
        spec = parse_spec(table)
        assert node_algebra(spec, node_form(spec)) is None
    x2 = [Fraction(-2), 0, 1]
    assert _square_root_field([Fraction(16), 0, Fraction(-10), 0, 1])  # (x² − 2)(x² − 8)
    assert not _square_root_field([Fraction(6), 0, Fraction(-5), 0, 1])  # (x² − 2)(x² − 3)
    assert not _square_root_field([Fraction(-2), 0, 0, 1])  # x³ − 2
    assert _square_root_field(x2) and _square_root_field([Fraction(-1), 1])


def test_certainly_larger_leaves_ties_to_the_first():
    third = Fraction(1, 3)
    assert certainly_larger(Fraction(-1, 2), third) and not certainly_larger(third, Fraction(-1, 3))
    close = Interval(third - Fraction(1, 10**50), third + Fraction(1, 10**50))
    assert not certainly_larger(close, third) and not certainly_larger(third, close)
    assert certainly_larger(Interval(Fraction(1, 2), Fraction(3, 5)), third)


def test_a_family_beyond_the_field_limit_is_exact_and_agrees_with_balls():
    """Radau IIA with six stages generates a field of degree 60, over the limit: its
    conditions and properties are now exact over Q.  Every exact residual lies in the
    enclosure certified balls give it, and every verdict agrees with theirs."""
    from rkcheck.energy.check import check
    from rkcheck.methods.families import family_tableau
    from rkcheck.options import CheckOptions
    from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS

    spec = parse_spec({"name": "radau-iia", "s": 6})
    reason = family_exact_values(spec)[1]
    assert reason is not None and "degree at least 60" in reason
    tableau = family_tableau(spec)
    exact = check(tableau, CheckOptions(order=9, degree=4))
    balls = check(tableau, CheckOptions(order=9, degree=4, arithmetic="ball", dps=60))
    assert exact.backend.value == "exact" and balls.backend.value == "ball"
    mine, theirs = list(exact.conditions), list(balls.conditions)
    assert [c.id for c in mine] == [c.id for c in theirs] and len(mine) > 100
    for a, b in zip(mine, theirs):
        assert isinstance(a.residual, Fraction)
        assert a.verdict.state in (HOLDS, FAILS)
        assert {HOLDS: HOLDS_TO_DIGITS, FAILS: FAILS}[a.verdict.state] == b.verdict.state
        assert abs(Fraction(a.residual) - Fraction(b.enclosure.mid)) <= Fraction(b.enclosure.rad)
    assert exact.quadrature.order == 11 and exact.classical.order == balls.classical.to_digits
    # the properties from the entries' enclosures alone (no node form)
    A, b = values_from_enclosures(*tableau.enclosures(400, DecimalsMode.EXACT), False)
    enclosed = properties_of_values(A, b)
    assert quadrature_order(A, b).to_digits == 11
    for name in ("symplectic", "symmetric"):
        mine_p, theirs_p = getattr(exact.properties, name), getattr(enclosed, name)
        assert mine_p.verdict.state == FAILS == theirs_p.verdict.state
    defect = exact.properties.symplectic.defect.enclosure(100)
    ball = enclosed.symplectic.defect
    assert exact.properties.symplectic.defect_entry == enclosed.symplectic.defect_entry
    assert not (defect.hi < ball.lo or ball.hi < defect.lo)
