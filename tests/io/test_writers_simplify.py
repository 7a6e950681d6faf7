"""The code writers (LaTeX, Julia, Python: ``show --format``, ``rkcheck.write``) write each
entry as its exact value with like terms combined and constants folded: as many terms as
sympy's own expansion of the entry has, and the same value."""

from __future__ import annotations

import re

import pytest
import sympy as sp
from support.paths import TABLEAUX

from rkcheck.io.formats import to_julia, to_latex, to_python
from rkcheck.io.loader import load, loads
from rkcheck.numbers.expressions import to_text

CASES = {
    # the two the issue quotes: c = A·1 of a row (-1/3, 1) and of a row (1, -1, 1)
    "row-sum": '[tableau]\nA = [["-1/3", "1"], ["1", "-1"]]\nb = ["1/2", "1/2"]\n',
    "cancel": '[tableau]\nA = [["1", "-1", "1"], [0, 0, 0], [0, 0, 0]]\nb = ["1/2", "1/4", "1/4"]\n',
    "roots": '[tableau]\nA = [["1 - 1/3", "sqrt(12)/4 + 1 - 1/2"], ["sqrt(3) + 1 - sqrt(3)", "(1 + sqrt(3))^2"]]\n'
             'b = ["1/2 + 1/2 - 1/2", "1/2"]\n',
    "constants": '[constants]\nr = "sqrt(3)"\nh = "1/2"\n[tableau]\nA = [["h - r/6 + r/6", "h*r*r"], ["r*r", "r - h"]]\n'
                 'b = ["h", "h"]\n',
}


def sympy_entries(tab):
    """A, b and c = A·1 (when not given) in sympy, from the entry texts as written."""
    loc: dict = {}
    for k, v in tab.info.constants.definitions.items():
        loc[k] = sp.sympify(to_text(v).replace("^", "**"), locals=dict(loc))

    def value(e):
        # denominators made rational: p + q·sqrt(n) when the value lies in Q(sqrt(n))
        return sp.expand(sp.radsimp(sp.together(sp.sympify(e.text.replace("^", "**"), locals=loc))))

    A = [[value(e) for e in row] for row in tab.A]
    c = [value(e) for e in tab.c] if tab.c is not None else [sp.expand(sum(row)) for row in A]
    return [x for row in A for x in row] + [value(e) for e in tab.b] + c


def terms(value) -> int:
    return len(sp.Add.make_args(sp.expand(value)))


def written_terms(text: str) -> int:
    """Additive terms of one written entry (canonical forms have no parentheses around sums)."""
    return len(re.split(r"(?<=\S) [+-] ", text.strip()))


def python_cells(tab):
    ns: dict = {}
    exec(to_python(tab), ns)  # our own output, not file content
    cells = [x for row in ns["A"] for x in row] + list(ns["b"]) + list(ns["c"])
    body = to_python(tab)
    texts = []
    for name in ("A", "b", "c"):
        block = re.search(rf"^{name} = \[(.*?)\]$" if name != "A" else r"^A = \[\n(.*?)\n\]$", body, re.M | re.S).group(1)
        rows = [r.strip().strip(",").strip("[]") for r in block.splitlines()] if name == "A" else [block]
        for row in rows:
            texts += _split_top(row)
    return cells, texts


def _split_top(row: str) -> list[str]:
    """Cells of a row written ``x, y, z`` (commas inside parentheses belong to a cell)."""
    out, depth, cur = [], 0, ""
    for ch in row:
        depth += ch == "("
        depth -= ch == ")"
        if ch == "," and depth == 0:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    return out + [cur.strip()] if cur.strip() else out


@pytest.mark.parametrize("name", list(CASES))
def test_python_writes_each_entry_exactly_with_like_terms_combined(name):
    tab = loads(CASES[name], f"{name}.toml")
    want = sympy_entries(tab)
    cells, texts = python_cells(tab)
    assert len(cells) == len(want) == len(texts)
    for got, w, text in zip(cells, want, texts):
        assert sp.simplify(sp.sympify(got) - w) == 0, (text, w)
        assert written_terms(text) == terms(w), (text, w)
        assert "r" not in re.sub(r"Fraction|sympy\.sqrt", "", text)  # constants folded in


def latex_cells(tab):
    lines = to_latex(tab).splitlines()
    body = lines[lines.index(next(x for x in lines if x.startswith(r"\begin{array}"))) + 1:lines.index(r"\end{array}")]
    rows = [line.rstrip().removesuffix(r" \\").split(" & ") for line in body if line.strip() != r"\hline"]
    s = len(rows[-1]) - 1
    A = [cell.strip() for row in rows[:s] for cell in row[1:]]
    return A + [cell.strip() for cell in rows[s][1:]] + [row[0].strip() for row in rows[:s]]


@pytest.mark.parametrize("name", list(CASES))
def test_latex_and_julia_write_as_many_terms_as_the_value_has(name):
    tab = loads(CASES[name], f"{name}.toml")
    want = sympy_entries(tab)
    for text, w in zip(latex_cells(tab), want):
        assert written_terms(text) == terms(w), (text, w)
    julia = to_julia(tab)
    c_line = next(line for line in julia.splitlines() if line.startswith("c = "))
    for text, w in zip(_split_top(c_line[5:-1]), want[-len(tab.b):]):
        assert written_terms(text) == terms(w), (text, w)


def test_the_quoted_cases_read_plainly():
    # c = A·1: -1/3 + 1 = 2/3 and 1 + (-1) + 1 = 1, written as such
    assert r"\frac{2}{3} & -\frac{1}{3} & 1" in to_latex(loads(CASES["row-sum"], "r.toml"))
    assert "c = [Fraction(1), Fraction(0), Fraction(0)]" in to_python(loads(CASES["cancel"], "c.toml"))


def test_a_shipped_tableau_with_lagrange_constants_is_written_in_its_field():
    # Gauss-3's file defines b and A through Lagrange integrals over its nodes; each entry
    # is p + q·sqrt(15) with rational p, q: at most two terms, and the same value
    tab = load(str(TABLEAUX / "collocation" / "gauss-3.toml"))
    want = sympy_entries(tab)
    for text, w in zip(latex_cells(tab), want):
        assert written_terms(text) == terms(w) <= 2, (text, w)
    cells, _ = python_cells(tab)
    assert all(sp.simplify(sp.sympify(g) - w) == 0 for g, w in zip(cells, want))
