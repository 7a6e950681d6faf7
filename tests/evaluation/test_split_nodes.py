"""Family tableaux in node form (``A_ij = F(c_i, c_j)``, ``b_j = W(c_j)``) and their
conditions computed over Q at primes that split the node polynomial, against the route
over the nodes' number field.

Independent routes: the field's own values of the entries (every entry evaluated in the
field from its text), its integrality denominator (from each entry's minimal
polynomial), and the field route's exact residuals, whose agreement with sympy and the
reference's conditions ``tests/evaluation/test_field_residuals.py`` checks.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.field_bounds import integrality_denominator
from rkcheck.evaluation.scaled import scaled_field
from rkcheck.evaluation.split_nodes import scaled_nodes
from rkcheck.methods.closed_forms import family_exact_values
from rkcheck.methods.families import family_tableau
from rkcheck.methods.family_spec import parse_spec
from rkcheck.methods.node_form import node_form
from rkcheck.trees.listing import ConditionListing

FAMILIES = [
    {"name": "gauss", "s": 2}, {"name": "gauss", "s": 4}, {"name": "radau-ia", "s": 3},
    {"name": "radau-iia", "s": 3}, {"name": "lobatto-iiia", "s": 4}, {"name": "lobatto-iiib", "s": 4},
    {"name": "avf", "s": 3}, {"name": "hbvm", "k": 4, "s": 2}, {"name": "hbvm", "k": 5, "s": 3},
    {"name": "kernel", "zeta": "1/3", "beta": "1/5"},
]


def _field(table):
    found, reason = family_exact_values(parse_spec(table))
    assert reason is None
    n = int(round((len(found.values) + 1) ** 0.5)) - 1  # A, b, c: n² + 2n values
    v = found.values
    return found.field or Fraction, [v[i * n:(i + 1) * n] for i in range(n)], v[n * n:n * n + n], v[n * n + n:]


def _at(K, terms, *points):
    """``Σ c·Π point^power`` in the field K."""
    total = K(0)
    for powers, c in terms:
        term = K(c)
        for x, k in zip(points, powers if isinstance(powers, tuple) else (powers,)):
            term = term * x**k
        total = total + term
    return total


#: odd Gauss and Lobatto rules have rational nodes, one-stage rules a linear P
MORE = [{"name": "gauss", "s": 1}, {"name": "gauss", "s": 3}, {"name": "radau-ia", "s": 1},
        {"name": "radau-iia", "s": 2}, {"name": "lobatto-iiia", "s": 3}, {"name": "lobatto-iiib", "s": 2},
        {"name": "avf", "s": 1}, {"name": "hbvm", "k": 3, "s": 3}, {"name": "hbvm", "k": 4, "s": 1},
        {"name": "kernel", "zeta": "-2", "beta": "7/3"}]


@pytest.mark.parametrize("table", FAMILIES + MORE)
def test_the_node_form_is_the_tableau(table):
    form = node_form(parse_spec(table))
    assert form is not None
    K, A, b, c = _field(table)
    n = len(b)
    assert form.stages == n
    for i in range(n):
        assert _at(K, form.W, c[i]) == K(b[i])
        for j in range(n):
            assert _at(K, form.F, c[i], c[j]) == K(A[i][j]), (i, j)


@pytest.mark.parametrize("table", FAMILIES[:6] + [{"name": "hbvm", "k": 4, "s": 3}])
def test_the_integrality_scale_is_the_fields_least_denominator(table):
    K, A, b, _ = _field(table)
    want = integrality_denominator([x for row in A for x in row] + list(b), K)
    assert node_form(parse_spec(table)).integrality_scale() == want


@pytest.mark.parametrize("table, top", [(FAMILIES[0], 9), (FAMILIES[2], 8), (FAMILIES[5], 8), (FAMILIES[6], 8),
                                        (FAMILIES[7], 9), (FAMILIES[9], 8)])
def test_conditions_over_split_primes_equal_the_fields(table, top):
    spec = parse_spec(table)
    exact = family_tableau(spec).exact_values()
    assert exact.nodes is not None
    listing = ConditionListing(top, None)
    over_field = exact_condition_sums(scaled_field(exact), listing)
    over_q = exact_condition_sums(scaled_nodes(exact.nodes), listing)
    zeros = failures = 0
    for n, sums in over_field.items():
        assert (over_q[n].is_zero() == sums.is_zero()).all(), n
        for k, value in enumerate(sums.values()):
            rational = value.rational() if hasattr(value, "rational") else Fraction(value)
            assert over_q[n].value(k) == rational, (n, k)
            zeros += rational == 0
            failures += rational != 0
    assert zeros and failures  # both outcomes are compared


def test_every_channel_prime_splits_the_node_polynomial():
    form = node_form(parse_spec({"name": "hbvm", "k": 4, "s": 3}))
    scaled = scaled_nodes(form)
    chosen = scaled.primes_for(400)
    assert sum(p.bit_length() - 1 for p, _ in chosen) >= 400 - len(chosen)
    for p, roots in chosen:
        assert roots == [0]  # one channel per prime
        found = scaled.__dict__["_node_roots"][p]
        assert len(set(found)) == form.stages
        for r in found:
            P = sum(Fraction(c) * r**k for k, c in enumerate(form.P))
            assert P.numerator * pow(P.denominator, -1, p) % p == 0


@pytest.mark.parametrize("table", FAMILIES)
def test_the_stability_series_over_q_is_the_fields(table):
    # r_k = bᵀA^(k−1)1 in the field, product by product, against the traces over Q
    K, A, b, _ = _field(table)
    n = len(b)
    want, v = [Fraction(1)], [K(1)] * n
    for _ in range(2 * n):
        want.append(sum((K(b[i]) * v[i] for i in range(n)), K(0)).rational())
        v = [sum((K(A[i][j]) * v[j] for j in range(n)), K(0)) for i in range(n)]
    assert node_form(parse_spec(table)).stability_series(2 * n) == want


def test_a_tableau_written_out_keeps_the_fields_route():
    # the same Gauss-3 entries as texts in a file: no family, so no node form is assumed
    from support.paths import TABLEAUX

    from rkcheck.evaluation.values import TableauValues
    from rkcheck.io.loader import load
    from rkcheck.numbers.reading import Reading

    tab = load(str(TABLEAUX / "collocation" / "gauss-3.toml"))
    assert tab.exact_values().field is not None and tab.exact_values().nodes is None
    scaled = TableauValues.of(tab, Reading()).scaled
    assert scaled.number_field is not None and scaled.degree == 2


def test_a_familys_error_constant_is_exact(tmp_path):
    # C² = Σ R² over the first failing order, R from the route over the nodes' field
    # (checked against sympy and the reference in test_field_residuals)
    import rkcheck

    path = tmp_path / "gauss2.toml"
    path.write_text('[family]\nname = "gauss"\ns = 2\n', encoding="utf-8")
    exact = family_tableau(parse_spec({"name": "gauss", "s": 2})).exact_values()
    sums = exact_condition_sums(scaled_field(exact), ConditionListing(8, None))
    want = None
    for n in sorted(sums):
        values = [v.rational() if hasattr(v, "rational") else Fraction(v) for v in sums[n].values()]
        if any(values):
            want = sum(v * v for v in values)
            break
    constant = rkcheck.verify(str(path), order=8, degree="none").to_dict()["summary"]["error_constant"]
    assert want is not None and Fraction(constant["squared"]) == want


def test_a_split_node_tableau_travels_by_pickle():
    # a pass sent to a worker (verify --jobs, --scheduler) carries the tableau
    import pickle

    scaled = scaled_nodes(node_form(parse_spec({"name": "gauss", "s": 3})))
    listing = ConditionListing(7, None)
    here = exact_condition_sums(scaled, listing)
    there = exact_condition_sums(pickle.loads(pickle.dumps(scaled)), listing)
    for n, sums in here.items():
        assert [sums.value(k) for k in range(len(sums))] == [there[n].value(k) for k in range(len(sums))]


@pytest.mark.parametrize("table", FAMILIES[:4] + MORE[:2] + MORE[7:])
def test_the_pair_characteristic_polynomial_is_the_multiplication_matrixs(table):
    # the s² × s² matrix of multiplication by g on Q[x, y]/(P(x), P(y)), column by
    # column from the remainders of g·x^a·y^b, and its characteristic polynomial
    from flint import fmpq_mat

    from rkcheck.methods.node_form import pair_charpoly, pair_polynomial, pair_ring, reduce_pair

    form = node_form(parse_spec(table))
    _, x, y = pair_ring()
    n = form.stages
    F = pair_polynomial(form.F)
    for g in (F, F * x - y + 3, F * F - x * y, pair_polynomial([]), pair_polynomial([((0, 0), Fraction(5, 7))])):
        M = fmpq_mat(n * n, n * n)
        for col, (a, b) in enumerate((a, b) for a in range(n) for b in range(n)):
            for (p, q), c in reduce_pair(form.P, g * x**a * y**b).to_dict().items():
                M[int(p) * n + int(q), col] = c
        assert pair_charpoly(form.P, g) == M.charpoly()
