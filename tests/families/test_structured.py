"""The structured route of ``solve`` (quadrature conditions, then the conditions linear in
A): its formulas against the condition engine, its answers against the plain route, and
the seed's Theorem 1 for four stages (m = 8) against the AVF tableaux of the 4-point
Gauss rule."""

from __future__ import annotations

import itertools
import json
from fractions import Fraction

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

import rkcheck
from rkcheck.energy.family_rules import double_bush_rows
from rkcheck.energy.family_solve import star_constant

FAMILIES = TABLEAUX / "families"


def _proportional(p, q) -> bool:
    """p = r·q for a nonzero rational r."""
    if p.is_zero() or q.is_zero():
        return p.is_zero() and q.is_zero()
    r = p.leading_coefficient() / q.leading_coefficient()
    return p == q * r


def _free_family(s: int):
    A = [[f"a{i}{j}" for j in range(1, s + 1)] for i in range(1, s + 1)]
    b = [f"b{i}" for i in range(1, s + 1)]
    return rkcheck.family_from_arrays(A, b, parameters=[x for row in A for x in row] + b)


def test_star_and_double_bush_formulas_are_the_engines_conditions():
    from flint import fmpq

    fam = _free_family(2)
    fc = rkcheck.family_conditions(fam, degree=3, order=4)
    A, b = fam.A, fam.b
    c = [A[i][0] + A[i][1] for i in range(2)]
    total = b[0] + b[1]
    by_tree = {cd.level_sequence: cd.polynomial for cd in fc.energy}
    # stars with 2 and 3 leaves: the residual is star_constant(k)·(Σbc^(k−1) − (Σb)^k/k)
    for k in (2, 3):
        star = sum(bi * ci ** (k - 1) for bi, ci in zip(b, c)) - total ** k / k
        r = star_constant(k)
        assert by_tree[(1,) + (2,) * k] == star * fmpq(r.numerator, r.denominator)
    # the double bush t_{1,2} (five vertices, degree 3): proportional to the linear row
    (row,) = double_bush_rows(b, c, 3, 4)
    flat = [A[i][j] for i in range(2) for j in range(2)]
    linear = sum((x * a for x, a in zip(row, flat)), row[-1])
    five = [p for ls, p in by_tree.items() if len(ls) == 5]
    assert sum(_proportional(p, linear) for p in five) == 1


@pytest.mark.parametrize(("name", "degree", "order"), [("theorem1-s2-m3", 3, 6), ("theorem1-s2-m4", 4, 6),
                                                       ("theorem1-s3-m6", 6, 7)])
def test_structured_and_plain_routes_find_the_same_solutions(name, degree, order):
    path = FAMILIES / f"{name}.toml"
    plain = rkcheck.solve(path, degree=degree, order=order, route="plain")
    structured = rkcheck.solve(path, degree=degree, order=order, route="structured")
    assert structured.route == "structured" and plain.route == "plain"
    assert structured.dimension == plain.dimension == 0

    def key(res):
        return sorted(tuple(round(v.approx.real, 12) for v in s.values.values()) for s in res.solutions)

    assert key(structured) == key(plain)
    assert len(structured.solutions) == len(plain.solutions)


def test_structured_route_refuses_a_family_it_does_not_fit():
    with pytest.raises(rkcheck.RkcheckError, match="structured route needs A free"):
        rkcheck.solve(FAMILIES / "seed-kernel-zeta-0.toml", degree=3, order=6, route="structured")


def test_a_parameter_no_entry_uses_stays_free_in_every_solution(tmp_path):
    """A = [[x]], b = [1] and a parameter y no entry uses: the energy condition of order 2
    for quadratic H is x − 1/2 (the 1-stage methods: only the midpoint rule preserves
    quadratic energies), and y is free in it — a line, dimension 1, not the point y = 0."""
    path = tmp_path / "unused.toml"
    path.write_text('[parameters]\nx = "free"\ny = "free"\n[tableau]\nA = [["x"]]\nb = ["1"]\n', encoding="utf-8")
    res = rkcheck.solve(path, degree=2, order=2)
    assert res.route == "plain" and res.dimension == 1 and [str(g) for g in res.groebner] == ["x - 1/2"]
    with pytest.raises(rkcheck.RkcheckError, match="no other parameter"):
        rkcheck.solve(path, degree=2, order=2, route="structured")


def _gauss4():
    """The 4-point Gauss rule from its tableau file (exact entries): nodes and weights as
    certified enclosures."""
    tab = rkcheck.load(TABLEAUX / "collocation" / "gauss-4.toml")
    b = [e.enclosure(80) for e in tab.b]
    c = [sum((e.enclosure(80) for e in row[1:]), row[0].enclosure(80)) for row in tab.A]
    return c, b


def test_theorem1_s4_m8_is_avf_over_gauss_in_the_four_compatible_orders():
    res = rkcheck.solve(FAMILIES / "theorem1-s4-m8.toml", degree=8, order=9)
    assert res.dimension == 0 and len(res.solutions) == 4 and all(s.real for s in res.solutions)
    c, b = _gauss4()
    # the file's weights: outer, inner, inner, outer; the nodes may move only within a pair
    outer, inner = (0, 3), (1, 2)
    orders = {(o[0], i[0], i[1], o[1]) for o in itertools.permutations(outer) for i in itertools.permutations(inner)}
    assert len(orders) == 4
    found = set()
    for s in res.solutions:
        got = [[s.values[f"a{i + 1}{j + 1}"].approx.real for j in range(4)] for i in range(4)]
        match = [p for p in orders
                 if all(abs(got[i][j] - float(c[p[i]].mid) * float(b[j].mid)) < 1e-12 for i in range(4) for j in range(4))]
        assert len(match) == 1
        found.add(match[0])
    assert found == orders
    assert all(comp.avf for comp in res.components)


def test_the_s4_m8_avf_tableau_preserves_energy_exactly():
    # the independent engine on one of the four: exact arithmetic in the rule's field
    b = [f"({x})" for x in ("1/4 - sqrt(30)/72", "1/4 + sqrt(30)/72", "1/4 + sqrt(30)/72", "1/4 - sqrt(30)/72")]
    nodes = ["1/2 - sqrt(3/28 + sqrt(30)/70)", "1/2 - sqrt(3/28 - sqrt(30)/70)",
             "1/2 + sqrt(3/28 - sqrt(30)/70)", "1/2 + sqrt(3/28 + sqrt(30)/70)"]
    A = [[f"({ci})*{bj}" for bj in b] for ci in nodes]
    assert rkcheck.verify(rkcheck.from_arrays(A, b), degree=8, order=9).verdict == "holds"


def test_components_report_avf_in_json(capsys):
    import json


    r = run_cli(capsys, "solve", str(FAMILIES / "theorem1-s2-m3.toml"), "--degree", "3", "--order", "6",
                "--format", "json")
    doc = json.loads(r.out)
    assert doc["route"] == "structured" and doc["avf_on_every_component"] is True
    assert sum(c["points"] for c in doc["components"]) == len(doc["solutions"]) == 2
    assert Fraction(doc["solutions"][0]["values"]["a11"]) in {Fraction(1, 4), Fraction(1, 2)}


@pytest.mark.parametrize("lang", ["python", "sympy"])
def test_emitted_family_conditions_agree_with_the_exact_engine(capsys, tmp_path, lang):
    """The emitted code, run at a rational point, gives the residuals that rkcheck's
    exact engine gives for the tableau at that point."""
    from support.clirun import run_cli

    if lang == "sympy":
        pytest.importorskip("sympy")
    path = FAMILIES / "theorem1-s2-m3.toml"
    r = run_cli(capsys, "conditions", str(path), "--order", "5", "--degree", "3", "--emit", lang)
    assert r.code == 0, r.err
    namespace: dict = {}
    exec(compile(r.out, f"<emitted {lang}>", "exec"), namespace)  # our own generated code, not file content
    point = {"a11": Fraction(1, 3), "a12": Fraction(-2, 7), "a21": Fraction(5, 4), "a22": Fraction(0)}
    args = [point[n] for n in ("a11", "a12", "a21", "a22")]
    if lang == "sympy":
        import sympy

        args = [sympy.Rational(x.numerator, x.denominator) for x in args]
    got = [Fraction(str(v)) for v in namespace["residuals"](*args)]
    fam = rkcheck.load_family(path)
    want = {c.id: c.residual for c in rkcheck.verify(fam.at(point), degree=3, order=5).conditions}
    ids = [c.id for c in rkcheck.family_conditions(fam, degree=3, order=5).energy]
    assert got == [want[i] for i in ids]


def test_emitted_latex_names_every_parameter_as_latex_reads_it(capsys, tmp_path):
    # an underscore is a subscript only before braces, else escaped; capital Greek names too
    import re

    path = tmp_path / "f.toml"
    path.write_text('[parameters]\nlambda_ = "free"\nGamma = "free"\nx_a = "free"\nbeta2 = "free"\n'
                    '[tableau]\nA = [["lambda_", "Gamma"], ["x_a", "beta2"]]\nb = ["1/2", "1/2"]\n', encoding="utf-8")
    latex = run_cli(capsys, "conditions", str(path), "--order", "3", "--degree", "3", "--emit", "latex").out
    math = "\n".join(re.split(r"(?<!\\)%", line)[0] for line in latex.splitlines())  # comments aside
    assert not re.search(r"(?<!\\)_(?!\{)", math)
    for name in ("\\mathrm{lambda\\_}", "\\Gamma", "\\mathrm{x\\_a}", "\\beta_{2}"):
        assert name in latex, name


def test_emitted_latex_and_julia_write_every_condition(capsys):
    from support.clirun import run_cli

    path = FAMILIES / "seed-kernel-zeta-0.toml"
    latex = run_cli(capsys, "conditions", str(path), "--order", "6", "--degree", "3", "--emit", "latex").out
    assert "\\tfrac{1}{72} \\beta^{2}" in latex and latex.count("R_{") == 12  # a Greek name as its letter
    free_a = run_cli(capsys, "conditions", str(FAMILIES / "theorem1-s2-m3.toml"), "--emit", "latex").out
    # by hand, R([τ²]) = Σ b_i c_i − 1/2 with b = (3/4, 1/4), c_i = a_i1 + a_i2: its linear
    # terms, with the trailing digits of a name as a subscript
    assert "-\\tfrac{3}{4} a_{11} - \\tfrac{3}{4} a_{12} - \\tfrac{1}{4} a_{21} - \\tfrac{1}{4} a_{22} + \\tfrac{1}{2}" in free_a
    julia = run_cli(capsys, "conditions", str(path), "--order", "6", "--degree", "3", "--emit", "julia").out
    assert "1//72*beta^2" in julia and "theta=sqrt(3)" in julia
    r = run_cli(capsys, "conditions", str(path), "--order", "6", "--emit", "matlab")
    assert r.code == 2 and "python, sympy, julia, latex" in r.err


def test_theorem1_s3_m5_slice_of_the_zeta_family_is_avf():
    """A and b free, m = 5 = 2s − 1: the weights and nodes form a curve (the seed's
    ζ-family); fixing b1 leaves finitely many, each with only its AVF matrix."""
    from flint import acb

    res = rkcheck.solve(FAMILIES / "theorem1-s3-m5.toml", degree=5, order=6, where=["b1 + b2 + b3 = 1", "b1 = 1/4"])
    assert res.route == "structured" and res.dimension == 0 and res.solutions
    assert all(comp.avf for comp in res.components)
    for s in res.solutions:
        b = [s.values[f"b{i}"].ball for i in (1, 2, 3)]
        A = [[s.values[f"a{i}{j}"].ball for j in (1, 2, 3)] for i in (1, 2, 3)]
        c = [sum(row[1:], row[0]) for row in A]
        for i in range(3):  # A = c bᵀ, from the solution's own enclosures
            for j in range(3):
                assert (A[i][j] - c[i] * b[j]).contains(0)
        for k in range(5):  # the rule (b, c) integrates polynomials of degree ≤ 4
            assert (sum(bi * ci ** k for bi, ci in zip(b, c)) - acb(1) / (k + 1)).contains(0)
        assert not (b[0] - acb(1) / 5).contains(0)  # a ball that can exclude: the test can fail


def test_a_surface_of_rules_asks_for_a_slice(capsys, tmp_path):
    """m = 4 with b free: the quadrature conditions leave a surface of rules, beyond the
    route over a curve; the plain route runs out of time and the error says what to fix."""
    from support.clirun import run_cli

    r = run_cli(capsys, "solve", str(FAMILIES / "theorem1-s3-m5.toml"), "--degree", "4", "--order", "5",
                "--where", "b1 + b2 + b3 = 1", "--max-seconds", "1")
    # a --where was given: the hint asks for more of them, not for the one already there
    assert r.code == 2 and r.err.count("\n") == 1 and "fix more weights with --where" in r.err, r.err


RADAU_IIA = (["2/5 - sqrt(6)/10", "2/5 + sqrt(6)/10", "1"], ["4/9 - sqrt(6)/36", "4/9 + sqrt(6)/36", "1/9"])


def test_the_whole_zeta_curve_at_order_7_is_avf_only():
    """A and b free, m = 5, order 7, over the whole curve of rules at once: one component,
    AVF.  Its equations vanish exactly (sympy) at AVF over the Radau IIA rule — a rule of
    the curve in Q(√6) — and not after moving one entry; the exact tableau engine
    confirms that AVF method satisfies every condition to order 8."""
    import sympy

    res = rkcheck.solve(FAMILIES / "theorem1-s3-m5.toml", degree=5, order=7, where=["b1 + b2 + b3 = 1"])
    assert res.route == "structured" and res.rule_dimension == 1 and res.dimension == 1
    assert len(res.components) == 1 and res.components[0].avf is True and res.components[0].dimension == 1
    c = [sympy.sympify(x) for x in RADAU_IIA[0]]
    b = [sympy.sympify(x) for x in RADAU_IIA[1]]
    point = {f"c{i + 1}": c[i] for i in range(3)} | {f"b{j + 1}": b[j] for j in range(3)}
    point |= {f"a{i + 1}{j + 1}": c[i] * b[j] for i in range(3) for j in range(3)}

    def value(e, at):
        names = e.context().names()
        total = sum(sympy.Rational(int(k.p), int(k.q)) * sympy.Mul(*[at[n] ** int(x) for n, x in zip(names, m)])
                    for m, k in e.to_dict().items())
        return sympy.simplify(sympy.expand(total))

    eqs = res.components[0].equations
    assert all(value(e, point) == 0 for e in eqs)
    moved = point | {"a12": point["a12"] + sympy.Rational(1, 100)}
    assert any(value(e, moved) != 0 for e in eqs)
    A = [[f"({RADAU_IIA[0][i]})*({RADAU_IIA[1][j]})" for j in range(3)] for i in range(3)]
    v = rkcheck.verify(rkcheck.from_arrays(A, list(RADAU_IIA[1])), degree=5, order=8)
    assert v.energy_order == 8


def test_the_whole_zeta_curve_at_order_6_has_three_planes_over_gauss():
    """The finding of the slice b1 = 5/18, on the whole curve: besides the AVF curve, three
    planes of non-AVF methods over the Gauss rule, one per position of the weight 4/9; the
    exact engine confirms a point of each (energy order exactly 6, not AVF)."""
    import sympy

    res = rkcheck.solve(FAMILIES / "theorem1-s3-m5.toml", degree=5, order=6, where=["b1 + b2 + b3 = 1"])
    assert res.dimension == 2 and res.rule_dimension == 1
    curve, *planes = res.components
    assert curve.dimension == 1 and curve.avf is True
    assert len(planes) == 3 and all(p.dimension == 2 and p.avf is False for p in planes)
    middle = set()
    for plane in planes:
        A, b = _plane_point(plane)
        middle.add(next(i for i, x in enumerate(b) if sympy.sympify(x) == sympy.Rational(4, 9)))
        v = rkcheck.verify(rkcheck.from_arrays(A, b), degree=5, order=8)
        assert v.energy_order == 6 and v.avf.verdict.state == "fails"
    assert middle == {0, 1, 2}


def _plane_point(plane, s: int = 3, node: tuple[str, str] = ("10*z^2 - 10*z + 1", "1/2 - sqrt(15)/10")):
    """A point of a plane of non-AVF methods over a Gauss rule: z = c1 a Gauss node (its
    minimal polynomial and the root chosen), the free entries chosen, the rest solved
    from the plane's equations; (A, b) as texts."""
    from flint import fmpq

    eqs = plane.equations
    ctx = eqs[0].context()
    assert str(eqs[0]) == node[0]
    free = {n for n in ctx.names() if n != "z"} - {n for e in eqs[1:] for n in [_lead_name(e)]}
    choice = {n: fmpq(k + 1, 10) for k, n in enumerate(sorted(free))}
    values = {}
    for e in eqs[1:]:
        name = _lead_name(e)
        rest = e - ctx.gens()[ctx.names().index(name)]
        values[name] = _text_of(-rest, choice, node[1])
    values.update({n: str(v) for n, v in choice.items()})
    A = [[values[f"a{i}{j}"] for j in range(1, s + 1)] for i in range(1, s + 1)]
    b = [values[f"b{i}"] for i in range(1, s + 1)]
    return A, b


def test_the_curve_route_agrees_with_slices_and_the_engine_for_two_stages():
    """s = 2, A and b free, m = 3, order 4 over the curve of 2-point rules exact for
    quadratics: the AVF curve and, over the Gauss rule only, a line of non-AVF methods
    (the seed's kernel direction at ζ = 0).  Slices through four other rules, solved
    orbit by orbit by the finite route, have AVF methods only; a point of the line is
    checked by the exact engine: energy order exactly 4 (the seed's β²/72 at 6
    vertices), not AVF."""
    res = rkcheck.solve(FAMILIES / "design-s2-m3.toml", degree=3, order=4, where=["b1 + b2 = 1"])
    assert res.rule_dimension == 1 and res.dimension == 1
    curve, line = res.components
    assert curve.avf is True and line.avf is False and line.dimension == 1
    for b1 in ("1/4", "1/3", "2/5", "3/4"):
        piece = rkcheck.solve(FAMILIES / "design-s2-m3.toml", degree=3, order=4, where=["b1 + b2 = 1", f"b1 = {b1}"])
        assert piece.dimension == 0 and piece.solutions and all(c.avf for c in piece.components)
    A, b = _plane_point(line, 2, ("6*z^2 - 6*z + 1", "1/2 - sqrt(3)/6"))
    v = rkcheck.verify(rkcheck.from_arrays(A, b), degree=3, order=7)
    assert v.energy_order == 4 and v.avf.verdict.state == "fails"


def test_design_query_splits_into_avf_and_symmetric_weights():
    """All 2-stage methods with energy order ≥ 4 for cubic H and classical order ≥ 2:
    every point of each piece is checked at rational points of it by the exact engine."""
    res = rkcheck.solve(FAMILIES / "design-s2-m3.toml", degree=3, order=4, classical_order=2)
    assert res.dimension == 1 and len(res.components) == 2
    assert sorted(c.avf is True for c in res.components) == [False, True]
    fam = rkcheck.load_family(FAMILIES / "design-s2-m3.toml")
    # a rational point of the AVF piece: the rule with nodes (0, 2/3), weights (1/4, 3/4)
    # (Radau I, exact for degree ≤ 2) and A = c bᵀ; the exact engine agrees, and the
    # point lies on the AVF piece only
    b = [Fraction(1, 4), Fraction(3, 4)]
    c = [Fraction(0), Fraction(2, 3)]
    point = {"a11": c[0] * b[0], "a12": c[0] * b[1], "a21": c[1] * b[0], "a22": c[1] * b[1], "b1": b[0], "b2": b[1]}
    tab = fam.at(point)
    v = rkcheck.verify(tab, degree=3, order=4)
    assert v.energy_order >= 4
    ctx = fam.ring.ctx
    from flint import fmpq

    values = [fmpq(point[n].numerator, point[n].denominator) for n in ctx.names()]
    avf_piece = next(c for c in res.components if c.avf)
    assert all(e(*values) == 0 for e in avf_piece.equations)
    other = next(c for c in res.components if not c.avf)
    assert any(e(*values) != 0 for e in other.equations)


def test_at_order_6_the_gauss_rule_carries_non_avf_methods():
    """A finding: at order 6 (m = 5, A and b free) the slice b1 = 5/18 through the Gauss
    rule has, besides AVF methods, two planes of non-AVF methods over Gauss (one per
    order of the weights). The exact engine confirms a point of one: energy order 6
    exactly, not AVF. At order 7 the same slice is AVF only."""
    where = ["b1 + b2 + b3 = 1", "b1 = 5/18"]
    res = rkcheck.solve(FAMILIES / "theorem1-s3-m5.toml", degree=5, order=6, where=where)
    planes = [c for c in res.components if c.dimension == 2]
    assert res.dimension == 2 and len(planes) == 2 and all(c.avf is False for c in planes)
    A, b = _plane_point(planes[0])
    v = rkcheck.verify(rkcheck.from_arrays(A, b), degree=5, order=8)
    assert v.energy_order == 6 and v.avf.verdict.state == "fails"
    higher = rkcheck.solve(FAMILIES / "theorem1-s3-m5.toml", degree=5, order=7, where=where)
    assert higher.dimension == 0 and all(c.avf for c in higher.components)


def _lead_name(e) -> str:
    """The parameter an equation of a plane is solved for: its one non-z variable with
    coefficient 1 that no other equation uses first (lex order puts it ahead)."""
    names = e.context().names()
    for m, c in e.to_dict().items():
        used = [names[i] for i, x in enumerate(m) if x]
        if len(used) == 1 and used[0] != "z" and c == 1 and sum(m) == 1:
            return used[0]
    raise AssertionError(str(e))


def _text_of(p, choice, z: str = "1/2 - sqrt(15)/10") -> str:
    """p (linear in z and the chosen parameters) at the choice, as an entry text with z
    the given root (by default a node of the 3-point Gauss rule)."""
    from flint import fmpq

    names = p.context().names()
    q = p.subs({n: v for n, v in choice.items() if n in names})
    z_coeff = fmpq(0)
    const = fmpq(0)
    for m, c in q.to_dict().items():
        if any(m):
            z_coeff += c
        else:
            const += c
    return f"({const}) + ({z_coeff})*({z})"


@pytest.mark.parametrize(("name", "degree", "order"), [("theorem1-s3-m6", 6, 7), ("theorem1-s2-m4", 4, 6)])
def test_the_basis_of_the_points_is_flints_basis_of_the_conditions(name, degree, order):
    """Buchberger–Möller on the structured route's points against FLINT's Buchberger on
    every condition: the same reduced degrevlex basis where the conditions' ideal is
    radical (these two; for s = 2, m = 3 it is not: a double zero)."""
    import time

    from rkcheck.numbers.groebner import groebner, integer_dicts

    path = FAMILIES / f"{name}.toml"
    fam = rkcheck.load_family(path)
    res = rkcheck.solve(path, degree=degree, order=order, route="structured")
    conds = [c.polynomial for c in rkcheck.family_conditions(fam, degree=degree, order=order).energy]
    ring = fam.ring
    if ring.minpoly is not None:
        conds.append(ring.minpoly)
    names = tuple(ring.ctx.names())
    flint_basis = groebner(integer_dicts([p for p in conds if not p.is_zero()]), names, "degrevlex",
                           time.monotonic() + 60)

    def monic(p):
        return p / p.leading_coefficient()

    theirs = {str(monic(ring.ctx.from_dict(d))) for d in flint_basis}
    assert {str(monic(g)) for g in res.groebner} == theirs


def _points(sp, equations, known):
    """Every common zero of ``equations``, found one unknown at a time: an equation with
    a single unknown left is solved (sympy, univariate), each root substituted."""
    left = [e for e in (sp.expand(e.subs(known)) for e in equations) if e != 0]
    if not left:
        return [known]
    single = next((e for e in left if len(e.free_symbols) == 1), None)
    if single is None or any(not e.free_symbols for e in left):
        return []  # a nonzero constant: no zero here (the curves' equations are triangular)
    (x,) = single.free_symbols
    return [p for root in sp.solve(single, x) for p in _points(sp, left, {**known, x: root})]


def test_a_component_over_rational_nodes_is_written_in_the_parameters_alone():
    # 3 stages, A free, Simpson's weights: two curves over nodes of one rational orbit.
    # Their equations use no z (it stood for one number, shown as "2*z + 11 = 0"), and a
    # point of each — a33 = 1/7, the rest solved by sympy — is a tableau rkcheck's exact
    # engine (not the family route) finds energy-preserving to order 6 for quartic H
    sp = pytest.importorskip("sympy")
    names = [f"a{i}{j}" for i in range(1, 4) for j in range(1, 4)]
    weights = ["1/6", "2/3", "1/6"]
    fam = rkcheck.family_from_arrays([names[0:3], names[3:6], names[6:9]], weights, parameters=names)
    result = rkcheck.solve(fam, degree=4, order=6)
    curves = [c for c in result.components if c.dimension == 1]
    assert len(curves) == 2
    symbols = sp.symbols(names)
    local = dict(zip(names, symbols))
    for curve in curves:
        texts = [str(e) for e in curve.equations]
        assert not any("z" in t for t in texts), texts
        equations = [sp.sympify(t.replace("^", "**"), locals=local).subs(symbols[8], sp.Rational(1, 7))
                     for t in texts]
        points = _points(sp, equations, {symbols[8]: sp.Rational(1, 7)})
        assert points
        for point in points:
            entries = [sp.sstr(sp.nsimplify(point[x])).replace("**", "^") for x in symbols]
            tab = rkcheck.Tableau.from_values([entries[0:3], entries[3:6], entries[6:9]], weights)
            assert rkcheck.verify(tab, degree=4, order=6).all_hold, entries


def test_a_family_whose_conditions_all_vanish_is_solved_by_every_value(capsys):
    # the seed's kernel family to order 4 for cubic Hamiltonians: every condition is the
    # zero polynomial (the engine's own, checked first), so every β is a solution — and
    # √3's minimal polynomial, which defines the numbers, is no equation of the set
    path = FAMILIES / "seed-kernel-zeta-0.toml"
    assert all(c.polynomial.is_zero() for c in rkcheck.family_conditions(path, degree=3, order=4).energy)
    result = rkcheck.solve(path, degree=3, order=4)
    assert result.dimension == 1 and all(not c.equations for c in result.components)
    r = run_cli(capsys, "solve", str(path), "-m", "3", "-N", "4")
    assert r.code == 0 and "every value of beta is a solution" in r.out and "sqrt(3)^2" not in r.out, r.out


def test_a_positive_dimensional_set_has_no_solution_list_on_either_route(capsys):
    # solutions[] is null unless finitely many; the plain route (one Gröbner basis, an
    # independent algorithm) agrees on the dimension
    import json

    docs = {route: json.loads(run_cli(capsys, "solve", str(FAMILIES / "design-s2-m3.toml"), "--degree", "3", "--order",
                                      "5", "--where", "b1 + b2 = 1", "--route", route, "--format", "json").out)
            for route in ("plain", "structured")}
    assert docs["plain"]["dimension"] == docs["structured"]["dimension"] == 1
    assert docs["plain"]["solutions"] is None and docs["structured"]["solutions"] is None
    assert docs["structured"]["points_of_finite_components"] == [] and docs["plain"]["points_of_finite_components"] is None
    assert docs["plain"]["rule_dimension"] is None and docs["structured"]["rule_dimension"] == 1


@pytest.mark.parametrize("names", [("z", "z_", "z__", "w"), ("p", "q", "r", "w")])
def test_a_node_is_named_apart_from_every_parameter(capsys, tmp_path, names):
    """A = [[x₁, x₂], [x₃, w]], b = (1/2, 1/2) at degree 3, order 4: by hand the rule is
    2-point Gauss (node n a root of 6n² − 6n + 1), and the rows sum to the nodes, so
    x₁ + x₂ = n, x₃ + w = 1 − n; the remaining conditions leave x₁ + w = 1/2 — a line in w,
    dimension 1.  Parameters named like the node (z, z_, z__) must not change that."""
    import sympy

    x1, x2, x3, w = names
    path = tmp_path / "f.toml"
    path.write_text("[parameters]\n" + "".join(f'{n} = "free"\n' for n in names)
                    + f'[tableau]\nA = [["{x1}", "{x2}"], ["{x3}", "{w}"]]\nb = ["1/2", "1/2"]\n'
                    "[check]\ndegree = 3\norder = 4\n", encoding="utf-8")
    doc = json.loads(run_cli(capsys, "solve", str(path), "--format", "json").out)
    (component,) = doc["components"]
    equations = [sympy.sympify(e) for e in component["equations"]]
    symbols = sorted(set().union(*(e.free_symbols for e in equations)), key=str)
    assert len(symbols) == 5  # the four parameters and one node
    basis = sympy.groebner(equations, *symbols, order="grevlex")
    # dimension 1: every point of the line satisfies them, w free
    solutions = sympy.solve(equations, [s for s in symbols if str(s) != w], dict=True)
    assert component["dimension"] == 1 and len(basis.exprs) == 4 and len(solutions) == 2


def test_avf_nodes_are_named_apart_from_every_parameter(capsys, tmp_path):
    """A = [[c1, c1_], [c2, c2_]], b = (b1, b2), b1 + b2 = 1: AVF over the 2-point Gauss
    rule (nodes (3 ∓ √3)/6, weights 1/2, a_ij = c_i b_j, by hand) preserves every cubic
    energy, so it lies on the AVF component, whatever the names rkcheck gives the nodes."""
    import sympy

    path = tmp_path / "f.toml"
    path.write_text('[parameters]\nc1 = "free"\nc1_ = "free"\nc2 = "free"\nc2_ = "free"\nb1 = "free"\n'
                    'b2 = "free"\n[tableau]\nA = [["c1", "c1_"], ["c2", "c2_"]]\nb = ["b1", "b2"]\n'
                    "[check]\ndegree = 3\norder = 4\n", encoding="utf-8")
    doc = json.loads(run_cli(capsys, "solve", str(path), "--where", "b1+b2=1", "--format", "json").out)
    avf = [c for c in doc["components"] if c["avf"] is True]
    assert avf
    n1, n2 = (3 - sympy.sqrt(3)) / 6, (3 + sympy.sqrt(3)) / 6
    point = {"c1": n1 / 2, "c1_": n1 / 2, "c2": n2 / 2, "c2_": n2 / 2, "b1": sympy.Rational(1, 2),
             "b2": sympy.Rational(1, 2)}
    for component in avf:
        equations = [sympy.sympify(e, locals={k: sympy.Symbol(k) for k in [*point, "c1__", "c2__"]})
                     for e in component["equations"]]
        nodes = {n for e in equations for n in map(str, e.free_symbols)} - set(point)
        assert nodes == {"c1__", "c2__"}
        at = {sympy.Symbol(k): v for k, v in point.items()}
        # the nodes are the row sums, n1 and n2 in some order
        if any(sympy.simplify(e.subs({**at, sympy.Symbol("c1__"): n1, sympy.Symbol("c2__"): n2})) != 0
               for e in equations):
            continue
        break
    else:
        raise AssertionError("AVF over Gauss-2 is on no AVF component")


def test_the_printed_basis_is_reduced(capsys):
    """Reduced: monic in its order and each element reduced by the others — so sympy's
    reduced basis of the printed elements (in the variables left after elimination, the
    degree reverse lexicographic part) is those elements themselves."""
    import sympy

    doc = json.loads(run_cli(capsys, "solve", str(FAMILIES / "theorem1-s2-m3.toml"), "--route", "plain",
                             "--format", "json").out)
    rest = [v for v in doc["parameters"] if v not in doc["eliminated"]]
    symbols = sympy.symbols(rest)
    part = [sympy.sympify(g) for g in doc["groebner"]
            if not {str(s) for s in sympy.sympify(g).free_symbols} & set(doc["eliminated"])]
    ours = {sympy.expand(p) for p in part}
    theirs = {sympy.expand(p) for p in sympy.groebner(part, *symbols, order="grevlex").exprs}
    assert part and ours == theirs


@pytest.mark.parametrize("route", ["plain", "structured"])
def test_no_solution_is_the_unit_ideal_on_either_route(capsys, route):
    # 1 = 2 holds nowhere: the reduced basis of the unit ideal is [1], whatever was eliminated
    doc = json.loads(run_cli(capsys, "solve", str(FAMILIES / "theorem1-s2-m3.toml"), "--route", route,
                             "--where", "1=2", "--format", "json").out)
    assert doc["dimension"] == -1 and doc["groebner"] == ["1"]


def test_no_solution_after_elimination_is_the_unit_ideal(capsys, tmp_path):
    """A = [[p, 0], [q, p]], b = (1/2, 1/2).  By hand: Σ b_i c_i = 1/2 is 2p + q = 1, linear,
    eliminated first; classical order 3 then needs p − p² = 1/6, p = 1/2 ± √3/6 (the
    2-stage SDIRK of order 3).  Neither preserves energy to order 4 for every Hamiltonian
    (checked below by the exact verify, another engine), so there is no solution, and the
    basis is the unit ideal's alone."""
    path = tmp_path / "u.toml"
    path.write_text('[parameters]\np = "free"\nq = "free"\n[tableau]\nA = [["p","0"],["q","p"]]\n'
                    'b = ["1/2","1/2"]\n', encoding="utf-8")
    doc = json.loads(run_cli(capsys, "solve", str(path), "-m", "none", "-N", "4", "--classical-order", "3",
                             "--format", "json").out)
    assert doc["dimension"] == -1 and doc["groebner"] == ["1"]
    for sign in "+-":
        p = f"1/2 {sign} sqrt(3)/6"
        sdirk = rkcheck.loads(f'[tableau]\nA = [["{p}", "0"], ["1 - 2*({p})", "{p}"]]\nb = ["1/2", "1/2"]\n',
                              name="sdirk3.toml")
        res = rkcheck.verify(sdirk, degree=None, order=4)
        assert res.classical_order == 3 and res.failures
