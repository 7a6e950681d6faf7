"""Families with free parameters: conditions as polynomials and their exact solution
sets, checked against the seed's Theorem 1 and against rkcheck's own numeric engine at
points (an independent route: modular exact evaluation of one tableau)."""

from __future__ import annotations

import json
import random
import re
import subprocess
import sys
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

import rkcheck
from rkcheck.errors import UserError

FAMILIES = TABLEAUX / "families"


def tableau_of(solution, A_names, b):
    """The tableau of a solution, its values written as entries (closed forms parse)."""
    A = [[solution.values[name].text for name in row] for row in A_names]
    return rkcheck.from_arrays(A, b)


A2 = [["a11", "a12"], ["a21", "a22"]]
A3 = [["a11", "a12", "a13"], ["a21", "a22", "a23"], ["a31", "a32", "a33"]]


def test_theorem1_s2_m3_two_avf_solutions():
    res = rkcheck.solve(FAMILIES / "theorem1-s2-m3.toml", degree=3, order=6)
    assert res.dimension == 0 and len(res.solutions) == 2 and all(s.real for s in res.solutions)
    b = [Fraction(3, 4), Fraction(1, 4)]
    nodes = set()
    for s in res.solutions:
        A = [[Fraction(s.values[n].text) for n in row] for row in A2]
        c = [sum(row) for row in A]
        # A = c bᵀ: AVF over the rule (b, c), and the rule integrates up to degree 2
        assert A == [[ci * bj for bj in b] for ci in c]
        assert all(sum(bi * ci ** k for bi, ci in zip(b, c)) == Fraction(1, k + 1) for k in range(3))
        nodes.add(tuple(c))
        assert rkcheck.verify(tableau_of(s, A2, ["3/4", "1/4"]), degree=3, order=6).verdict == "holds"
    assert nodes == {(Fraction(1, 3), Fraction(1)), (Fraction(2, 3), Fraction(0))}


def test_theorem1_s2_m4_gauss_nodes_in_either_order():
    res = rkcheck.solve(FAMILIES / "theorem1-s2-m4.toml", degree=4, order=6)
    assert res.dimension == 0 and len(res.solutions) == 2
    gauss = rkcheck.load("@gauss-2")
    want = sorted(float(gauss.A[i][0].enclosure(64).mid + gauss.A[i][1].enclosure(64).mid) for i in range(2))
    for s in res.solutions:
        tab = tableau_of(s, A2, ["1/2", "1/2"])
        c = sorted(float(sum(e.enclosure(64).mid for e in row)) for row in tab.A)
        assert c == pytest.approx(want, abs=1e-15)
        assert rkcheck.verify(tab, degree=4, order=6).verdict == "holds"  # exact, in Q(√3)


def test_seed_kernel_family_first_condition_is_beta_squared_over_72():
    fc = rkcheck.family_conditions(FAMILIES / "seed-kernel-zeta-0.toml", degree=3, order=6)
    assert fc.energy_order == 4
    (first,) = fc.exceptional
    beta = fc.family.ring.parameter("beta")
    assert first.polynomial == beta ** 2 / 72 and first.id == "1,2,3,2,3,2"
    res = rkcheck.solve(FAMILIES / "seed-kernel-zeta-0.toml", degree=3, order=6)
    assert [s.values["beta"].text for s in res.solutions] == ["0"]


def test_theorem1_s3_m6_two_gauss_avf_solutions():
    res = rkcheck.solve(FAMILIES / "theorem1-s3-m6.toml", degree=6, order=7)
    assert res.dimension == 0 and len(res.solutions) == 2
    for s in res.solutions:
        assert s.values["a22"].text == "2/9" and s.values["a21"].text == "5/36"  # middle node 1/2: row (1/2)·b
        tab = tableau_of(s, A3, ["5/18", "4/9", "5/18"])
        assert rkcheck.verify(tab, degree=6, order=7).verdict == "holds"


@pytest.mark.parametrize("seed", range(3))
def test_polynomials_agree_with_the_exact_engine_at_rational_points(seed):
    fam = rkcheck.load_family(FAMILIES / "theorem1-s2-m3.toml")
    fc = rkcheck.family_conditions(fam, degree=None, order=5)
    rng = random.Random(seed)
    point = {p: Fraction(rng.randint(-9, 9), rng.randint(1, 7)) for p in fam.parameters}
    tab = fam.at(point)
    want = {c.id: c.residual for c in rkcheck.verify(tab, degree=None, order=5).conditions}
    names = fam.ring.variables
    for c in fc.energy:
        from flint import fmpq

        got = c.polynomial.subs({n: fmpq(point[n].numerator, point[n].denominator) for n in names})
        assert Fraction(str(got)) == want[c.id], c.id


def test_where_adds_an_equation():
    res = rkcheck.solve(FAMILIES / "theorem1-s2-m3.toml", degree=3, order=6, where=["a22 = 0"])
    assert [s.values["a11"].text for s in res.solutions] == ["1/2"]


def test_cli_solve_json_has_the_documented_keys(capsys):
    import json

    r = run_cli(capsys, "solve", str(FAMILIES / "theorem1-s2-m3.toml"), "--degree", "3", "--order", "6",
                "--format", "json")
    assert r.code == 0, r.err
    doc = json.loads(r.out)
    assert set(doc) >= {"parameters", "equations", "groebner", "dimension", "solutions"}
    assert doc["parameters"] == ["a11", "a12", "a21", "a22"] and doc["dimension"] == 0
    assert {tuple(sorted(s["values"].items())) for s in doc["solutions"]} == {
        (("a11", "1/4"), ("a12", "1/12"), ("a21", "3/4"), ("a22", "1/4")),
        (("a11", "1/2"), ("a12", "1/6"), ("a21", "0"), ("a22", "0"))}


@pytest.mark.parametrize(("entry", "message"), [
    ("sqrt(beta)", "a parameter under sqrt"),
    ("2^beta", "a parameter in an exponent"),
    ("1/beta", "a parameter in a denominator"),
    ("gamma", "unknown name 'gamma'"),
])
def test_non_polynomial_entries_are_one_line_errors(tmp_path, capsys, entry, message):
    path = tmp_path / "bad.toml"
    path.write_text(f'[parameters]\nbeta = "free"\n[tableau]\nA = [["{entry}"]]\nb = ["1"]\n', encoding="utf-8")
    r = run_cli(capsys, "solve", str(path), "--degree", "2", "--order", "3")
    assert r.code == 2 and r.err.count("\n") == 1 and message in r.err and "A[1][1]" in r.err, r.err
    with pytest.raises(UserError, match=message):
        rkcheck.load_family(path)


def test_a_family_is_not_loaded_as_one_tableau():
    with pytest.raises(UserError, match="free \\[parameters\\]"):
        rkcheck.load(FAMILIES / "theorem1-s2-m3.toml")


def test_the_time_limit_is_a_one_line_error(tmp_path, capsys):
    # A and b free, s = 3, m = 5: beyond a plain Buchberger in 1 s
    names = [f"a{i}{j}" for i in range(1, 4) for j in range(1, 4)] + ["b1", "b2", "b3"]
    params = "\n".join(f'{n} = "free"' for n in names)
    path = tmp_path / "hard.toml"
    path.write_text(f"[parameters]\n{params}\n[tableau]\nA = [[\"a11\", \"a12\", \"a13\"], [\"a21\", \"a22\", \"a23\"], "
                    f"[\"a31\", \"a32\", \"a33\"]]\nb = [\"b1\", \"b2\", \"b3\"]\n", encoding="utf-8")
    r = run_cli(capsys, "solve", str(path), "--degree", "5", "--order", "6", "--where", "b1 + b2 + b3 = 1",
                "--max-seconds", "1")
    assert r.code == 2 and "time limit" in r.err and r.err.count("\n") == 1, r.err


def test_a_family_from_sympy_values_is_the_file_family():
    sp = pytest.importorskip("sympy")
    beta = sp.Symbol("beta")
    c = [sp.Rational(1, 2) - sp.sqrt(3) / 6, sp.Rational(1, 2) + sp.sqrt(3) / 6]
    b = [sp.Rational(1, 2)] * 2
    A = [[c[i] * b[j] - beta * (1 - 2 * c[j]) * b[j] for j in range(2)] for i in range(2)]
    mine = rkcheck.family_conditions(rkcheck.family_from_arrays(A, b, parameters=[beta]), degree=3, order=6)
    theirs = rkcheck.family_conditions(FAMILIES / "seed-kernel-zeta-0.toml", degree=3, order=6)
    assert [str(c.polynomial) for c in mine.energy] == [str(c.polynomial) for c in theirs.energy]
    with pytest.raises(UserError, match="floats are not exact"):
        rkcheck.family_from_arrays([[0.5]], [1], parameters=["beta"])


def test_verify_json_on_a_family_gives_each_condition_as_a_polynomial(capsys):
    import json

    r = run_cli(capsys, "verify", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--format", "json")
    assert r.code == 0, r.err
    doc = json.loads(r.out)
    assert doc["energy_order_generic"] == 4 and doc["exceptional"] == ["1,2,3,2,3,2"]
    (first,) = [c for c in doc["conditions"] if c["kind"] == "energy" and c["id"] == "1,2,3,2,3,2"]
    assert (first["polynomial"], first["degree"], first["vanishes"]) == ("1/72*beta^2", 2, False)
    # the conditions below order 5 hold for every β (the seed's kernel direction)
    assert all(c["vanishes"] for c in doc["conditions"] if c["kind"] == "energy" and c["order"] <= 4)


def test_the_api_reads_a_family_files_check_table_as_the_cli_does():
    # seed-kernel-zeta-0.toml has [check] degree = 3, order = 6: left out, they apply
    # (api.md); at β = 0 the family is energy-preserving to order ≥ 6 for cubic
    # Hamiltonians (the seed's Theorem 1), while without a degree bound β = 0 reaches 4
    path = TABLEAUX / "families" / "seed-kernel-zeta-0.toml"
    conds = rkcheck.family_conditions(path)
    assert (conds.degree, conds.order) == (3, 6)
    unbounded = rkcheck.family_conditions(path, degree=None)
    assert unbounded.degree is None and len(unbounded.energy) > len(conds.energy)
    orders = dict(zip((p["beta"] for p in rkcheck.sweep(path, ["beta=0:1:2"]).points()),
                      rkcheck.sweep(path, ["beta=0:1:2"]).orders))
    assert orders[0] == 6
    cli = subprocess.run([sys.executable, "-m", "rkcheck", "conditions", str(path), "--order", "6", "--format",
                          "json"], capture_output=True, text=True)
    assert cli.returncode == 0 and json.loads(cli.stdout)["degree"] == 3, cli.stderr


def test_a_solution_in_a_quadratic_subfield_prints_its_closed_form(capsys, tmp_path):
    # the solution x lies in Q(√2) while the family's numbers span Q(√2, √3) (degree 4):
    # it prints as 1/4 − √2/4, read through its own minimal polynomial, not as a cubic in
    # a generator of the quartic field; substituted into the tableau, the conditions hold
    text = ('[parameters]\nx = "free"\n[tableau]\nA = [["sqrt(2)/4 + x", "1/4 - sqrt(3)/6"], '
            '["1/4 + sqrt(3)/6", "1/4"]]\nb = ["1/2", "1/2"]\n')
    path = tmp_path / "nf2.toml"
    path.write_text(text, encoding="utf-8")
    r = run_cli(capsys, "solve", str(path), "--degree", "2", "--order", "2")
    assert r.code == 0 and "x = 1/4 - 1/4*sqrt(2)" in r.out and "at z =" not in r.out, r.out
    tableau = "[tableau]\n" + text.split("[tableau]\n")[1].replace("x", "(1/4 - sqrt(2)/4)")
    assert rkcheck.verify(rkcheck.loads(tableau), degree=2, order=2).all_hold


def test_a_parameter_named_x_leaves_roots_polynomial_variable_alone(tmp_path):
    # x in root(x^3 - 2, 1) is the polynomial's own variable: a parameter called x made
    # it "a parameter under root(...)"; named x or y, the family's conditions are the same
    texts = {}
    for name in ("x", "y"):
        path = tmp_path / f"{name}.toml"
        path.write_text(f'[parameters]\n{name} = "free"\n[tableau]\nA = [["{name}", "root(x^3 - 2, 1)/4"], '
                        '["0", "1/4"]]\nb = ["1/2", "1/2"]\n', encoding="utf-8")
        conds = rkcheck.family_conditions(path, degree=None, order=3)
        texts[name] = [str(c.polynomial).replace(name, "P") for c in conds.energy]
    assert texts["x"] == texts["y"] and texts["x"]


def test_a_member_keeps_roots_own_x_when_a_parameter_is_called_x():
    """``x·root(x³ − 2, 1)`` at x = 2 is 2·∛2: the root's x is its polynomial's own, only
    the outer x is the parameter."""
    fam = rkcheck.family_from_arrays([["x*root(x^3 - 2, 1)"]], ["1"], ["x"])
    box = fam.at({"x": 2}).A[0][0].enclosure(30)
    assert (box.lo / 2) ** 3 <= 2 <= (box.hi / 2) ** 3 and box.hi - box.lo < Fraction(1, 10**20)


def test_order_1_has_no_condition_and_every_parameter_value_solves_it():
    """Energy conditions start at order 2 (3 vertices): at order 1 nothing constrains the
    six free entries of a 2-stage method, a set of dimension 6."""
    res = rkcheck.solve(TABLEAUX / "families" / "design-s2-m3.toml", degree=None, order=1)
    assert res.equations == 0 and res.dimension == 6


def test_a_solution_past_the_range_of_floats_is_exact():
    res = rkcheck.solve(TABLEAUX / "families" / "continuous-collocation-kappa.toml", degree=None, order=2,
                        where=["kappa = 10^400"])
    (solution,) = res.solutions
    assert Fraction(solution.values["kappa"].text) == 10**400


@pytest.mark.parametrize("definition, name", [('"zz"', "zz"), ('"tau^2"', "tau")])
def test_a_constant_that_is_not_a_number_is_named_at_its_place(tmp_path, definition, name):
    f = tmp_path / "c.toml"
    f.write_text(f'[parameters]\nk = "free"\n[constants]\nc = {definition}\n[tableau]\nA = [["k*c"]]\nb = ["1"]\n')
    with pytest.raises(UserError) as err:
        rkcheck.load_family(f)
    assert err.value.place == "constants.c" and f"unknown name '{name}'" in err.value.message


@pytest.mark.parametrize("where, message", [
    ("= 3", "'=' needs an expression on each side"),
    ("kappa =", "'=' needs an expression on each side"),
    ("kappa = 3 = 3", "more than one '='"),
    ("kappa = 3x", "right of '=': unexpected 'x' at column 3"),
])
def test_a_where_equation_that_cannot_be_read_says_why_in_its_own_text(where, message):
    from rkcheck.errors import OptionError

    with pytest.raises(OptionError, match=re.escape(message)) as err:
        rkcheck.solve(TABLEAUX / "families" / "continuous-collocation-kappa.toml", degree=None, order=2,
                      where=[where])
    assert err.value.place == "--where"


@pytest.mark.parametrize("check", ["[check]\ndegree = 3\norder = 3\n", ""])
def test_solve_without_degree_and_order_reads_the_check_table_as_verify_does(tmp_path, capsys, check):
    # the same family solved with the options written out is the reference: the file's
    # [check] when it has one, else no degree bound and order 6 (the conditions verify uses)
    path = tmp_path / "fam.toml"
    path.write_text('[parameters]\nx = "free"\n[tableau]\nA = [["x*x*x/2 - x/2", "0"], ["0", "1/2"]]\n'
                    f'b = ["1/2", "1/2"]\n{check}', encoding="utf-8")
    given = ("--degree", "3", "--order", "3") if check else ("--degree", "none", "--order", "6")
    implicit = run_cli(capsys, "solve", str(path), "--format", "json")
    explicit = run_cli(capsys, "solve", str(path), *given, "--format", "json")
    assert implicit.code == explicit.code == 0, implicit.err
    doc, reference = json.loads(implicit.out), json.loads(explicit.out)
    del doc["seconds"], reference["seconds"]  # the time taken
    assert doc == reference
    assert (doc["options"]["degree"], doc["options"]["order"]) == ((3, 3) if check else (None, 6))
    text = run_cli(capsys, "solve", str(path))
    source = "(the file's [check])" if check else "(the default)"
    assert f"energy conditions to order {3 if check else 6} {source}" in text.out, text.out
    assert "energy conditions to order" not in run_cli(capsys, "solve", str(path), *given).out
    api = rkcheck.solve(path)
    assert [s.values["x"].text for s in api.solutions] == [s["values"]["x"] for s in doc["solutions"]]


def test_a_nonzero_constant_condition_fixes_the_order_of_every_member(tmp_path, capsys):
    # stage 3 has weight 0 and feeds no stage: p changes no condition, and [τ³] is
    # Σb c² − 1/3 (×1/4, its 1/σ·…) = 1/2 − 1/3 ≠ 0 for every p: order 2 everywhere, by hand
    path = tmp_path / "fc.toml"
    path.write_text('[parameters]\np = "free"\n[tableau]\nA = [["0","0","0"],["1","0","0"],["p","0","0"]]\n'
                    'b = ["1/2","1/2","0"]\n', encoding="utf-8")
    for value in (0, 5, Fraction(-7, 3)):
        assert rkcheck.verify(rkcheck.load_family(path).at({"p": value}), order=4).energy_order == 2
    r = run_cli(capsys, "verify", str(path), "-N", "4")
    assert "energy order for every parameter value: 2" in r.out and "rkcheck solve" not in r.out, r.out
    doc = json.loads(run_cli(capsys, "verify", str(path), "-N", "4", "--format", "json").out)
    assert doc["energy_order_generic"] == 2 and doc["energy_order_everywhere"] is True
    seed = json.loads(run_cli(capsys, "verify", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--format", "json").out)
    assert seed["energy_order_everywhere"] is False  # β²/72: zero at β = 0


def test_conditions_of_a_family_reads_its_check_order_as_verify_does(capsys):
    # seed-kernel-zeta-0.toml: [check] degree = 3, order = 6; `conditions FAMILY` with
    # neither option reads both; the reference is the same with both typed
    path = str(FAMILIES / "seed-kernel-zeta-0.toml")
    implicit = json.loads(run_cli(capsys, "conditions", path, "--format", "json").out)
    explicit = json.loads(run_cli(capsys, "conditions", path, "-N", "6", "-m", "3", "--format", "json").out)
    assert implicit == explicit and implicit["order_checked"] == 6
    r = run_cli(capsys, "conditions", path, "--emit", "python", "--format", "json")
    assert r.code == 2 and "--format json and --emit do not go together" in r.err
    assert "Missing option '--order'" in run_cli(capsys, "conditions", "--degree", "3").err


def test_a_family_whose_condition_is_a_nonzero_constant_fails(tmp_path, capsys):
    # every member is the midpoint rule (a = 1/2, b = 1 whatever p): its condition [τ³]
    # is a nonzero constant, so no value of p gives energy order 3 — the tableau engine,
    # on the midpoint rule itself, finds that condition failing (below)
    path = tmp_path / "f.toml"
    path.write_text('[parameters]\np = "free"\n[tableau]\nA = [["1/2 + 0*p"]]\nb = ["1"]\n', encoding="utf-8")
    quiet = run_cli(capsys, "verify", str(path), "-q")
    assert quiet.code == 1 and quiet.out.strip().splitlines() == [
        "FAIL: condition 1,2,2,2 of order 3 is a nonzero constant: no parameter value gives energy order 3"]
    assert run_cli(capsys, "verify", str(path), "--fail-on", "never").code == 0
    doc = json.loads(run_cli(capsys, "verify", str(path), "--format", "json").out)
    assert doc["fails_everywhere"] == "1,2,2,2"
    midpoint = rkcheck.verify(rkcheck.from_arrays([["1/2"]], ["1"]), degree=None, order=3)
    assert midpoint.energy_order == 2 and midpoint.failures[0].id == "1,2,2,2"  # the member, checked as a tableau
    free = FAMILIES / "theorem1-s2-m3.toml"  # its conditions are polynomials that vanish somewhere
    assert run_cli(capsys, "verify", str(free), "-q").code == 0


def test_a_parameter_named_i_is_not_confused_with_the_imaginary_unit(tmp_path, capsys):
    # two stages, weights (2, −1), A free with a11 called i: the solutions are complex; their
    # values, read back by sympy with sqrt(-1) as the unit, are AVF over a rule exact to
    # degree 2 (A = c bᵀ, Σ b c^(k−1) = 1/k for k ≤ 3) — which they could not be were the
    # unit read as the parameter
    sympy = pytest.importorskip("sympy")
    path = tmp_path / "fi.toml"
    path.write_text('[parameters]\ni = "free"\na12 = "free"\na21 = "free"\na22 = "free"\n[tableau]\n'
                    'A = [["i", "a12"], ["a21", "a22"]]\nb = ["2", "-1"]\n', encoding="utf-8")
    doc = json.loads(run_cli(capsys, "solve", str(path), "--degree", "3", "--order", "5", "--format", "json").out)
    assert doc["solutions"]
    for s in doc["solutions"]:
        assert not any(re.search(r"(?<![\w.])i(?![\w(])", t) for t in s["values"].values())
        v = {k: sympy.sympify(t) for k, t in s["values"].items()}
        A = sympy.Matrix([[v["i"], v["a12"]], [v["a21"], v["a22"]]])
        b = sympy.Matrix([2, -1])
        c = A * sympy.Matrix([1, 1])
        assert sympy.simplify(A - c * b.T) == sympy.zeros(2, 2)
        assert all(sympy.simplify(sum(b[j] * c[j] ** (k - 1) for j in range(2)) - sympy.Rational(1, k)) == 0
                   for k in (1, 2, 3))


@pytest.mark.parametrize("limit", [3, 32])
def test_the_pieces_of_a_solution_set_never_pass_max_pieces(monkeypatch, limit):
    # every 2-stage method with energy order 5 for cubic H: a set of dimension 4 whose
    # basis factors again and again (34 pieces, were every split made)
    import rkcheck.numbers.decompose as decompose

    monkeypatch.setattr(decompose, "MAX_PIECES", limit)
    family = rkcheck.load_family(str(FAMILIES / "design-s2-m3.toml"))
    result = rkcheck.solve(family, degree=3, order=5, route="plain")
    assert result.dimension == 4 and 1 < len(result.pieces) <= limit
    assert any(p.whole for p in result.pieces)


CUBIC_FIELD = """[parameters]
p = "free"
q = "free"
[constants]
k = "{k}"
[tableau]
A = [["p*k", "p"], ["k^2 - p", "1/3"]]
b = ["1/2 + q*k", "1/2 - q"]
"""


def test_solutions_over_a_cubic_field_are_read_from_the_quotient_ring(tmp_path, capsys):
    # two conditions in p, q over Q(k), k³ = k + 1, where a lexicographic basis takes minutes.
    # sympy, independently: the resultant in p of the two residuals (k numerical, 60
    # digits) has as many distinct roots q as rkcheck has solutions, and every solution
    # makes both residuals vanish
    sympy = pytest.importorskip("sympy")
    path = tmp_path / "cubic.toml"
    path.write_text(CUBIC_FIELD.format(k="root(x^3 - x - 1, 1)"), encoding="utf-8")
    result = rkcheck.solve(path, degree=3, order=3, max_seconds=30)
    code = run_cli(capsys, "conditions", str(path), "--order", "3", "--degree", "3", "--emit", "sympy").out
    space: dict = {}
    exec(code, space)  # the code rkcheck wrote for this family, not file content
    p, q = sympy.symbols("p q")
    f1, f2 = (sympy.expand(r) for r in space["residuals"](p, q))
    k = sympy.N(sympy.CRootOf(sympy.Symbol("x") ** 3 - sympy.Symbol("x") - 1, 0), 60)
    t = sympy.Symbol("t")  # k as a symbol: the resultant exact, then k put in
    exact = sympy.resultant(f1.subs(space["theta"], t), f2.subs(space["theta"], t), p)
    roots = sympy.Poly(sympy.expand(exact.subs(t, k)), q).nroots(n=30)
    distinct = [r for i, r in enumerate(roots) if all(abs(r - s) > 1e-12 for s in roots[:i])]
    assert len(result.solutions) == len(distinct) > 0
    for s in result.solutions:
        at = {p: s.values["p"].approx, q: s.values["q"].approx, space["theta"]: complex(k)}
        assert all(abs(complex(f.subs(at))) < 1e-9 for f in (f1, f2))
    # every digit of a value shown "≈" is right: mpmath's roots of its minimal polynomial
    import mpmath

    shown = [v for s in result.solutions for v in s.values.values() if "≈" in v.text]
    assert shown
    for v in shown:
        real = float(re.search(r"≈ (-?[0-9.e+-]+)", v.text).group(1))
        with mpmath.workdps(40):
            roots = mpmath.polyroots([mpmath.mpf(c.numerator) / c.denominator for c in reversed(v.minpoly)],
                                     maxsteps=400, extraprec=400)
        assert min(abs(float(mpmath.re(r)) - real) for r in roots) <= 6e-10 * max(1.0, abs(real)), v.text


def test_the_quotient_ring_and_the_lexicographic_route_agree(tmp_path, monkeypatch):
    # over Q(√5) both routes finish: the same solutions, exactly
    import rkcheck.numbers.quotient as quotient

    path = tmp_path / "quad.toml"
    path.write_text(CUBIC_FIELD.format(k="sqrt(5)"), encoding="utf-8")
    read = sorted(tuple(sorted((n, v.text) for n, v in s.values.items())) for s in
                  rkcheck.solve(path, degree=3, order=3).solutions)
    monkeypatch.setattr(quotient, "MAX_QUOTIENT_DIMENSION", 0)  # the quotient ring refused: the lex route
    lex = sorted(tuple(sorted((n, v.text) for n, v in s.values.items())) for s in
                 rkcheck.solve(path, degree=3, order=3).solutions)
    assert read == lex and len(read) > 0


def test_a_family_says_what_its_entries_say_beside_the_conditions(capsys, tmp_path):
    # Σb = 1/2 + p (by hand) is 1 only at p = 1/2; r appears in no entry; 0.5 is a bare float;
    # c is ignored (a family's nodes are its row sums)
    path = tmp_path / "f.toml"
    path.write_text('[parameters]\np = "free"\nr = "free"\n[tableau]\nA = [["p", 0.5], ["1/2", "0"]]\n'
                    'b = ["1/2", "p"]\nc = ["1", "1/2"]\n', encoding="utf-8")
    text = " ".join(run_cli(capsys, "verify", str(path)).out.split())
    assert "parameter r appears in no entry" in text
    assert "Σb = p+1/2 is not identically 1" in text
    assert "1 entry is a bare float (0.5)" in text and "tableau.c ignored" in text
    solved = json.loads(run_cli(capsys, "solve", str(path), "--format", "json").out)
    # solve says the same, but where Σb = 1 is its own answer to give
    assert any("tableau.c ignored" in w for w in solved["warnings"])
    assert any("bare float" in w for w in solved["warnings"]) and not any("Σb" in w for w in solved["warnings"])
    text = " ".join(run_cli(capsys, "solve", str(path)).out.split())
    assert "warning: tableau.c ignored" in text and "warning: parameter r appears in no entry" in text
    consistent = tmp_path / "g.toml"
    consistent.write_text('[parameters]\np = "free"\n[tableau]\nA = [["p", "0"], ["1/2", "0"]]\n'
                          'b = ["1 - p", "p"]\n', encoding="utf-8")
    assert "warning" not in run_cli(capsys, "verify", str(consistent)).out
