"""Family tableaux evaluated in the field of their nodes, built once per set of nodes,
from polynomials in the nodes, against the direct route: every Lagrange-form entry text
evaluated by field_of on its own."""

from fractions import Fraction

import pytest

from rkcheck.methods.closed_forms import expression_texts, family_exact_values
from rkcheck.methods.family_spec import parse_spec
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.field_builder import evaluate_in, field_of


def _direct(spec):
    consts, A, b, c = expression_texts(spec)
    flat = [x for row in A for x in row] + list(b) + list(c)
    return field_of([ex.parse(x) for x in flat], {k: ex.parse(v) for k, v in consts.items()})


@pytest.mark.parametrize("table", [
    {"name": "hbvm", "k": 4, "s": 2}, {"name": "hbvm", "k": 4, "s": 3}, {"name": "gauss", "stages": 3},
    {"name": "lobatto-iiib", "stages": 4}, {"name": "avf", "stages": 3}, {"name": "gauss", "stages": 5},
    {"name": "radau-ia", "stages": 3}, {"name": "radau-iia", "stages": 3}, {"name": "lobatto-iiia", "stages": 5},
    {"name": "gauss", "stages": 1},
])
def test_the_shared_nodes_field_gives_the_direct_routes_values_and_field(table):
    spec = parse_spec(table)
    found, reason = family_exact_values(spec)
    assert reason is None
    direct = _direct(spec)
    if direct.field is None:
        assert found.field is None and found.values == direct.values
        return
    # the same primitive element (so reports write irrational values alike) and values
    assert (found.field.minpoly, found.field.index) == (direct.field.minpoly, direct.field.index)
    assert [v.coeffs for v in found.values] == [v.coeffs for v in direct.values]


def test_families_over_the_same_nodes_share_one_field():
    two, _ = family_exact_values(parse_spec({"name": "hbvm", "k": 4, "s": 2}))
    three, _ = family_exact_values(parse_spec({"name": "hbvm", "k": 4, "s": 3}))
    assert two.field is three.field and two.values != three.values


def test_evaluating_in_a_built_field_never_extends_it():
    base = field_of([ex.parse("sqrt(2)")])
    with pytest.raises(ValueError, match="extend the field"):
        evaluate_in(base, ["r2"], [ex.parse("r2 + sqrt(3)")])
    out = evaluate_in(base, ["r2"], [ex.parse("r2^2 - 1/2"), ex.parse("(r2 + 1)*(r2 - 1)")])
    assert out.field is None and out.values == [Fraction(3, 2), Fraction(1)]
