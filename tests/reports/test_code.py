"""Conditions as code (`rkcheck conditions --emit`): the emitted Python and sympy are run,
and the emitted LaTeX is read back and evaluated by brute-force index sums; all must give
the engine's residuals exactly on random rational tableaux.  The classical order
conditions are compared with the reference implementation's a(t) − 1/γ(t).  Julia and
MATLAB (not installed here) are checked structurally."""

from __future__ import annotations

import itertools
import random
import re
from fractions import Fraction as F

import pytest
import sympy
from support import reference as ref
from support.clirun import run_cli

from rkcheck.energy.check import CheckOptions, check
from rkcheck.methods.tableau import Tableau
from rkcheck.reports.code import emit
from rkcheck.trees.listing import condition_listing as condition_table

CASES = [(6, None), (5, 3), (6, 2), (4, 4)]


def random_tableau(rng, s, explicit=False):
    A = [[F(rng.randint(-5, 5), rng.randint(1, 5)) if (not explicit or j < i) else F(0) for j in range(s)]
         for i in range(s)]
    b = [F(rng.randint(-5, 5), rng.randint(1, 5)) for _ in range(s)]
    return A, b


def engine_residuals(A, b, order, degree):
    res = check(Tableau.from_values(A, b), CheckOptions(degree=degree, order=order))
    assert res.backend == "exact"
    return [r.enclosure.mid for r in res.conditions]


def load_module(text: str) -> dict:
    namespace: dict = {}
    exec(compile(text, "<emitted>", "exec"), namespace)  # our own generated code, never file content
    return namespace


@pytest.mark.parametrize("order, degree", CASES)
def test_emitted_python_gives_the_engine_residuals(order, degree):
    mod = load_module(emit(condition_table(order, degree), "python", classical=True))
    rng = random.Random(order * 10 + (degree or 0))
    for _ in range(4):
        A, b = random_tableau(rng, rng.randint(1, 4))
        got = mod["energy_conditions"](A, b)
        assert got == engine_residuals(A, b, order, degree)
        assert all(isinstance(x, (F, int)) for x in got)
        # classical order conditions against the reference: a(t) − 1/γ(t), in the emitted order
        text = emit(condition_table(order, degree), "python", classical=True)
        seqs = [tuple(map(int, m.group(1).split(","))) for m in re.finditer(r"# ([\d,]+)  \S+  γ = ", text)]
        expected = [ref.elementary_weight(t, A, b) - F(1, ref.gamma(t)) for t in seqs]
        assert mod["order_conditions"](A, b) == expected
        assert len(seqs) == sum(len(ref.rooted_trees(n)) for n in range(1, order + 1))


def test_emitted_python_with_stages_packs_the_free_entries():
    mod = load_module(emit(condition_table(4, None), "python", classical=True, stages=3, explicit=True))
    rng = random.Random(5)
    A, b = random_tableau(rng, 3, explicit=True)
    x = mod["pack"](A, b)
    assert len(x) == 3 + 3 and mod["unpack"](x) == (A, b)
    r = mod["residuals"](x)
    assert r[: len(condition_table(4, None))] == engine_residuals(A, b, 4, None)
    # floats in, floats out: what scipy.optimize passes
    assert all(isinstance(v, float) for v in mod["residuals"]([float(v) for v in x]))


@pytest.mark.parametrize("order, degree", CASES[:2])
def test_emitted_sympy_gives_the_engine_residuals(order, degree):
    mod = load_module(emit(condition_table(order, degree), "sympy"))
    rng = random.Random(3)
    A, b = random_tableau(rng, 3)
    got = mod["energy_conditions"](sympy.Matrix(A), [sympy.Rational(x.numerator, x.denominator) for x in b])
    assert [F(int(g.p), int(g.q)) for g in got] == engine_residuals(A, b, order, degree)


def test_emitted_sympy_symbols_are_the_polynomials_of_the_conditions():
    mod = load_module(emit(condition_table(5, 3), "sympy", stages=2, explicit=True))
    a21, = mod["a_symbols"]
    b1, b2 = mod["b_symbols"]
    # by hand: the first condition [τ²] is (Σb)²/2 − Σ b c = (b1 + b2)²/2 − b2 a21
    assert sympy.expand(mod["energy"][0] - ((b1 + b2) ** 2 / 2 - b2 * a21)) == 0
    rng = random.Random(11)
    A, b = random_tableau(rng, 2, explicit=True)
    values = {a21: A[1][0], b1: b[0], b2: b[1]}
    got = [F(str(sympy.nsimplify(e.subs(values)))) for e in mod["energy"]]
    assert got == engine_residuals(A, b, 5, 3)


# ---------------------------------------------------------------- LaTeX read back

TERM = re.compile(r" ([+-]) (\d+)\\,((?: \\Big\(\\sum_\{[a-z,]+\}[^()]*?\\Big\)(?:\^\{\d+\})?)*)")
WEIGHT = re.compile(r"\\Big\(\\sum_\{([a-z,]+)\} ([^()]*?)\\Big\)(?:\^\{(\d+)\})?")
FACTOR = re.compile(r"([abc])_\{([a-z]+)\}(?:\^\{(\d+)\})?")


def latex_weight_value(indices: str, factors: str, A, b) -> F:
    """Σ over all index values of the product of b_i, a_ij, c_j^k (brute force)."""
    names = indices.split(",")
    s = len(b)
    c = [sum(row, F(0)) for row in A]
    parsed = [(m.group(1), m.group(2), int(m.group(3) or 1)) for m in FACTOR.finditer(factors)]
    assert " ".join(x for x in factors.split()) == factors.strip() and parsed
    total = F(0)
    for values in itertools.product(range(s), repeat=len(names)):
        env = dict(zip(names, values))
        term = F(1)
        for kind, idx, power in parsed:
            if kind == "b":
                term *= b[env[idx]]
            elif kind == "c":
                term *= c[env[idx]] ** power
            else:
                term *= A[env[idx[0]]][env[idx[1]]]
        total += term
    return total


def latex_residuals(text: str, A, b) -> list[F]:
    out = []
    for line in text.splitlines():
        m = re.match(r"R_\{[\d,]+\} &= (?:\\tfrac\{1\}\{(\d+)\})?\\Big\[(.*) \\Big\] = 0(?: \\\\)?$", line)
        if not m:
            continue
        den, body = int(m.group(1) or 1), m.group(2)
        assert "".join(t.group(0) for t in TERM.finditer(body)) == body, "every part of the line is a term"
        total = F(0)
        for t in TERM.finditer(body):
            value = F(int(t.group(2))) * (-1 if t.group(1) == "-" else 1)
            for w in WEIGHT.finditer(t.group(3)):
                value *= latex_weight_value(w.group(1), w.group(2), A, b) ** int(w.group(3) or 1)
            total += value
        out.append(total / den)
    return out


@pytest.mark.parametrize("order, degree", [(5, None), (6, 3)])
def test_emitted_latex_read_back_gives_the_engine_residuals(order, degree):
    text = emit(condition_table(order, degree), "latex")
    assert text.count("\\begin{align*}") == 1 and text.count("\\end{align*}") == 1
    assert text.count("{") == text.count("}")
    rng = random.Random(order)
    for _ in range(2):
        A, b = random_tableau(rng, rng.randint(1, 3))
        got = latex_residuals(text, A, b)
        assert len(got) == len(condition_table(order, degree))
        assert got == engine_residuals(A, b, order, degree)


# ------------------------------------------------------- Julia, MATLAB: structure


@pytest.mark.parametrize("language, comment", [("julia", "#"), ("matlab", "%")])
def test_julia_and_matlab_are_well_formed(language, comment):
    table = condition_table(6, 4)
    text = emit(table, language, classical=True, stages=3)
    residual_lines = [line for line in text.splitlines() if re.search(rf"{comment} [\d,]+  \S+  (order|γ)", line)]
    n_classical = sum(len(ref.rooted_trees(n)) for n in range(1, 7))
    assert len(residual_lines) == len(table) + n_classical
    code_lines = [line.split(comment)[0] for line in text.splitlines()]
    for code in code_lines:
        assert code.count("(") == code.count(")"), code  # parentheses close on their line
    whole = "\n".join(code_lines)
    assert whole.count("[") == whole.count("]")  # brackets span lines ([ ... ])
    opened = len(re.findall(r"^\s*(function|for)\b", text, re.M))
    assert opened == len(re.findall(r"^\s*end\b", text, re.M))


def test_cli_emit_and_its_option_errors(capsys, tmp_path):
    out = tmp_path / "c.py"
    r = run_cli(capsys, "conditions", "--emit", "python", "--order", "4", "--degree", "3", "-o", str(out))
    assert r.code == 0 and "def energy_conditions(A, b):" in out.read_text(encoding="utf-8")
    for args, message in [(["--explicit"], "--explicit needs --stages"),
                          (["--stages", "2"], "go with --emit")]:
        extra = [] if "--emit" in args or message == "go with --emit" else ["--emit", "python"]
        r = run_cli(capsys, "conditions", "--order", "4", *extra, *args)
        assert r.code == 2 and message in r.err and len(r.err.strip().splitlines()) == 1


@pytest.mark.parametrize("language, weight", [("python", r"w\[(\d+)\]"), ("julia", r"w\[(\d+)\]"),
                                               ("matlab", r"w\((\d+)\)")])
def test_emitted_residuals_have_their_like_terms_combined(language, weight):
    # each residual is written with as many terms as sympy's expansion of it has: no two
    # terms with the same weights, no constant written twice
    import re

    import sympy as sp

    from rkcheck.api.trees import conditions as listing_of

    text = emit(listing_of(6, None).listing, language, classical=True)
    lines = [line for line in text.splitlines() if re.match(r"\s+\(?[-\w\[\]()* +]+\)? / (Fraction\()?\d+", line)
             or re.match(r"\s+\d\*w[\[(]", line)]
    assert len(lines) > 20
    for line in lines:
        body = re.split(r"\s*(?:,|; \.\.\.)\s*(?:#|%)", line)[0].strip()
        whole = re.match(r"\((.*)\) / (?:Fraction\()?\d+\)?$", body)
        body = whole.group(1) if whole else body
        expr = sp.sympify(re.sub(weight, r"w\1", body), locals={f"w{k}": sp.Symbol(f"w{k}") for k in range(60)})
        written = len(re.split(r"(?<=\S) [+-] ", body))
        assert written == len(sp.Add.make_args(sp.expand(expr))), line
