"""`rkcheck new` writes exact entries in their number field, checked against
published tableaux (Hairer–Wanner, Solving ODEs II, Tables 5.5, 5.6, 7.4, IV.5.2)."""

from fractions import Fraction

import pytest

from rkcheck.io.writers import render_toml
from rkcheck.methods.families import parse_spec


def _tableau_lines(text: str) -> str:
    return text[text.index("[tableau]"):]


PUBLISHED = {
    ("gauss", 2): ['["1/4", "1/4 - sqrt(3)/6"]', '["1/4 + sqrt(3)/6", "1/4"]', 'b = ["1/2", "1/2"]'],
    ("gauss", 3): ['["5/36", "2/9 - sqrt(15)/15", "5/36 - sqrt(15)/30"]',
                   '["5/36 + sqrt(15)/24", "2/9", "5/36 - sqrt(15)/24"]',
                   '["5/36 + sqrt(15)/30", "2/9 + sqrt(15)/15", "5/36"]', 'b = ["5/18", "4/9", "5/18"]'],
    # (88 − 7√6)/360, (296 − 169√6)/1800, (−2 + 3√6)/225; (16 − √6)/36, 1/9
    ("radau-iia", 3): ['["11/45 - 7*sqrt(6)/360", "37/225 - 169*sqrt(6)/1800", "-2/225 + sqrt(6)/75"]',
                       'b = ["4/9 - sqrt(6)/36", "4/9 + sqrt(6)/36", "1/9"]'],
    # Lobatto IIIA 4, row 2: (11 + √5)/120, (25 − √5)/120, (25 − 13√5)/120, (−1 + √5)/120
    ("lobatto-iiia", 4): ['["11/120 + sqrt(5)/120", "5/24 - sqrt(5)/120", "5/24 - 13*sqrt(5)/120", "-1/120 + sqrt(5)/120"]'],
}


@pytest.mark.parametrize("family, s", list(PUBLISHED))
def test_new_prints_published_exact_entries(family, s):
    text = _tableau_lines(render_toml(parse_spec({"name": family, "s": s})))
    assert "[constants]" not in text
    for piece in PUBLISHED[(family, s)]:
        assert piece in text, piece


def test_higher_degree_fields_keep_exact_node_constants():
    # Gauss-4's nodes need nested roots (a degree-8 field): the file keeps the node
    # constants and Lagrange forms, which load as exact algebraic entries
    from rkcheck.io.loader import loads

    text = render_toml(parse_spec({"name": "gauss", "s": 4}))
    assert "[constants]" in text and "sqrt(30)" in text
    tab = loads(text, "gauss4.toml")
    values = tab.exact_values()
    assert values.field.degree == 8
    # Gauss s = 4: quadrature order 2s = 8 exactly (published), Σ b = 1, A·1 = c
    for k in range(1, 10):
        r = sum((bi * ci ** (k - 1) for bi, ci in zip(values.b, values.c)), values.b[0] * 0) - Fraction(1, k)
        assert r.is_zero() == (k <= 8), k
    for row, ci in zip(values.A, values.c):
        assert (sum(row, ci * 0) - ci).is_zero()
