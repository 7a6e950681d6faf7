"""Writers: TOML/JSON round trips are exact for every shipped tableau; the Python code
runs and gives the same numbers (sympy, independently of rkcheck's grammar); LaTeX and
Julia are compared with arrays written by hand."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from support.clirun import run_cli
from support.heavy import heavy
from support.numbers import exact_under
from support.paths import TABLEAUX, tableau_files

from rkcheck.io.formats import to_json, to_julia, to_latex, to_python, to_toml, write
from rkcheck.io.loader import load, loads
from rkcheck.numbers.expressions import to_text

# the tableaux (not the families or continuous-stage kernels), without [family] generators
FILES = sorted(Path(f) for f in tableau_files() if f.endswith(".toml") and "[family]" not in Path(f).read_text())


def texts(tab):
    return ([[e.text for e in row] for row in tab.A], [e.text for e in tab.b],
            None if tab.c is None else [e.text for e in tab.c],
            {k: to_text(v) for k, v in tab.info.constants.definitions.items()}, tab.info.expect, tab.info.check,
            tab.name)


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_toml_and_json_round_trips_are_exact(path):
    tab = load(str(path))
    for text, name in ((to_toml(tab), "x.toml"), (to_json(tab), "x.json")):
        back = loads(text, name)
        assert texts(back) == texts(tab)
        assert [[e.exact for e in r] for r in back.A] == [[e.exact for e in r] for r in tab.A]


def test_a_written_file_checks_what_the_original_does():
    # [check] degree = 4 kept: without it the written file would be checked for every degree
    # (three degree-5 conditions fail) while the original holds to digits
    import rkcheck

    path = TABLEAUX / "avf" / "avf-gauss-2-decimal16.toml"
    original = rkcheck.verify(path, order=6)
    written = rkcheck.verify(loads(to_toml(load(str(path))), "x.toml"), order=6)
    assert written.to_dict()["summary"] == original.to_dict()["summary"]
    assert original.options.degree == 4


def sympy_value(text, constants):
    loc: dict = {}
    for k, v in constants.items():  # a constant may use the ones before it
        loc[k] = sp.sympify(v.replace("^", "**"), locals=dict(loc))
    return sp.sympify(text.replace("^", "**"), locals=loc)


@pytest.mark.parametrize("path", [p for p in FILES if "decimal" not in p.stem and "hbvm" not in str(p)][:40],
                         ids=lambda p: p.stem)
def test_python_code_runs_and_gives_the_entries(path):
    tab = load(str(path))
    if any("root(" in e.text for e in tab.entries()):
        pytest.skip("root() has no code form")
    namespace: dict = {}
    exec(to_python(tab), namespace)  # our own output, not file content
    consts = {k: to_text(v) for k, v in tab.info.constants.definitions.items()}
    # resolve constants that use other constants, in sympy
    for row, code_row in zip(tab.A, namespace["A"]):
        for e, v in zip(row, code_row):
            want = sympy_value(e.text, {k: consts[k] for k in consts})
            assert sp.simplify(sp.sympify(v) - want) == 0, (e.text, v)


def test_python_code_rk4_is_fractions():
    ns: dict = {}
    exec(to_python(load("@rk4")), ns)
    assert ns["b"] == [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)]
    assert ns["c"] == [0, Fraction(1, 2), Fraction(1, 2), 1] and all(isinstance(x, Fraction) for x in ns["c"])


def test_latex_butcher_array_by_hand():
    tab = loads('[tableau]\nA = [[0, 0], ["2/3", 0]]\nb = ["1/4", "3/4"]\n', "ralston.toml")
    assert to_latex(tab).splitlines()[2:8] == [
        r"\begin{array}{c|cc}",
        r"  0 & 0 & 0 \\",
        r"  \frac{2}{3} & \frac{2}{3} & 0 \\",
        r"  \hline",
        r"   & \frac{1}{4} & \frac{3}{4}",
        r"\end{array}",
    ]


def test_latex_inlines_constants_and_writes_roots():
    tab = load(str(TABLEAUX / "collocation" / "gauss-2.toml"))
    text = to_latex(tab)
    assert r"\frac{1}{4} - \frac{\sqrt{3}}{6}" in text and "r3" not in text


def test_latex_products_by_hand():
    # LaTeX has no * for a product: a number beside a root or a name, \cdot otherwise
    tab = loads('[tableau]\nA = [["7*sqrt(6)/360", "2*x"], ["x*y", "(1/2)*(1/3)"]]\nb = ["1/2", "1/2"]\n'
                '[constants]\nx = "sqrt(2)"\ny = "sqrt(5)"\n', "p.toml")
    text = to_latex(tab)
    assert r"\frac{7\sqrt{6}}{360}" in text and r"2 \sqrt{2}" not in text and r"2\sqrt{2}" in text
    assr = r"\sqrt{2} \cdot \sqrt{5}"
    assert assr in text and "*" not in text, text


@pytest.mark.parametrize("path", tableau_files())
def test_latex_of_every_shipped_tableau_has_no_asterisk(path):
    assert "*" not in write(load(path), "latex")


def test_julia_by_hand():
    tab = loads('[tableau]\nA = [[0, 0], ["2/3", 0]]\nb = ["1/4", "3/4"]\n', "ralston.toml")
    lines = to_julia(tab).splitlines()
    assert lines[1:] == ["A = [big(0) big(0);", "     big(2)//3 big(0)]", "b = [big(1)//4, big(3)//4]",
                         "c = [big(0), big(2)//3]"]


def test_unknown_format_is_a_user_error():
    from rkcheck.errors import UserError

    with pytest.raises(UserError):
        write(load("@rk4"), "fortran")


@pytest.mark.parametrize("fmt", ["toml", "tableau-json", "latex", "julia", "python"])
def test_cli_show_formats(capsys, fmt):
    run = run_cli(capsys, "show", "@heun", "--format", fmt)
    assert run.code == 0 and run.err == ""
    if fmt in ("toml", "tableau-json"):
        back = loads(run.out, "x." + ("toml" if fmt == "toml" else "json"))
        assert [[e.exact for e in r] for r in back.A] == [[0, 0], [1, 0]]


@pytest.mark.parametrize("fmt", ["latex", "julia", "python"])
def test_code_writers_take_family_tableaux(capsys, fmt):
    """A family's coefficients are computed (no expression): the code writers wrote
    ``e.node`` and crashed.  A rational family is written exactly; one known only
    numerically is a user error, as for to_nodepy."""
    from rkcheck.methods.families import family_tableau, parse_spec

    lobatto = family_tableau(parse_spec({"name": "lobatto-iiia", "s": 3}))
    assert lobatto.is_rational
    text = write(lobatto, fmt)
    if fmt == "python":
        ns: dict = {}
        exec(text, ns)  # our own output
        assert ns["A"][1] == [Fraction(5, 24), Fraction(1, 3), Fraction(-1, 24)]
    else:
        assert ("5}{24}" if fmt == "latex" else "big(5)//24") in text
    # HBVM(6, 3)'s Gauss-6 nodes are written as root(p, k) constants, which the code
    # formats cannot express: a one-line user error, never an internal one
    run = run_cli(capsys, "show", str(TABLEAUX / "hbvm" / "hbvm-6-3.toml"), "--format", fmt)
    assert "internal error" not in run.err
    if run.code != 0:
        assert run.code == 2 and "root(…) has no exact form" in run.err


@pytest.mark.parametrize("params", [pytest.param({"name": "gauss", "s": 3}, id="gauss-3"),
                                    pytest.param({"name": "hbvm", "k": 6, "s": 3}, id="hbvm-6-3", marks=heavy),
                                    pytest.param({"name": "gauss", "s": 9}, id="gauss-9")])
@pytest.mark.parametrize("fmt", ["toml", "json"])
def test_family_tableaux_write_files_that_read_back(params, fmt):
    # show --format toml|json of a [family] wrote the "≈0.0203…" display texts, which
    # verify then refused.  Now: closed forms (or 60-digit decimals beyond 8 nodes), read
    # back and compared with the family's own coefficients, computed by a different route
    # (Lagrange integration in certified balls)
    from rkcheck.methods.families import family_tableau, parse_spec

    fam = family_tableau(parse_spec(params))
    back = loads(write(fam, fmt), f"written.{fmt}")
    assert "≈" not in write(fam, fmt)
    want_A, want_b = fam.enclosures(200, "auto")
    got_A, got_b = back.enclosures(200, "auto")
    for w, g in zip([x for row in want_A for x in row] + list(want_b), [x for row in got_A for x in row] + list(got_b)):
        assert abs(w.mid - g.mid) < Fraction(1, 10**55), (w, g)
    # Gauss-3 is exact in Q(√15), HBVM(6, 3) in the field of degree 48 of its root(p, k)
    # nodes; Gauss-9's 60-digit decimals are a box
    assert exact_under(back, "auto") == (params != {"name": "gauss", "s": 9})


def test_cli_new_classic_round_trip(capsys):
    run = run_cli(capsys, "new", "rk4")
    assert run.code == 0
    tab = loads(run.out, "rk4.toml")
    assert [[e.exact for e in r] for r in tab.A] == [[0, 0, 0, 0], [Fraction(1, 2), 0, 0, 0],
                                                      [0, Fraction(1, 2), 0, 0], [0, 0, 1, 0]]
    assert tab.info.expect["classical_order"] == 4


@pytest.mark.parametrize("fmt, decimals", [("python", True), ("julia", True), ("python", False)])
def test_code_of_decimals_says_they_are_at_face_value(fmt, decimals):
    name = "avf-gauss-2-decimal16.toml" if decimals else "avf-gauss-2.toml"
    first = write(load(str(TABLEAUX / "avf" / name)), fmt).splitlines()[0]
    assert ("decimals at face value" in first) == decimals, first


def test_a_check_table_without_a_degree_bound_is_written_and_read_back():
    # [check] degree = "none" is read as None, which TOML cannot write: it is "none" again
    tab = loads('[tableau]\nA = [["1/2"]]\nb = ["1"]\n[check]\ndegree = "none"\norder = 5\n', "t.toml")
    for text, name in ((to_toml(tab), "x.toml"), (to_json(tab), "x.json")):
        assert loads(text, name).info.check == tab.info.check


def test_latex_never_writes_a_number_beside_a_fraction():
    # 3\\frac{1}{3} reads as the mixed number 3⅓ (a decimal keeps the entry as written)
    tab = loads('[constants]\nk = "1/3"\n[tableau]\nA = [["0.5 + 3*k", "0"], ["0", "0"]]\nb = ["1", "0"]\n', "m.toml")
    text = to_latex(tab)
    assert r"3 \cdot \frac{1}{3}" in text and r"3\frac" not in text


def test_python_writes_roots_of_polynomials_exactly_and_julia_names_the_entry(tmp_path, capsys):
    # HBVM(6, 2): its nodes are root(p, k) of the degree-6 shifted Legendre polynomial;
    # numpy's Gauss–Legendre rule gives the same nodes and weights independently
    sympy = pytest.importorskip("sympy")
    np = pytest.importorskip("numpy")
    path = tmp_path / "h.toml"
    run_cli(capsys, "new", "hbvm", "-k", "6", "-s", "2", "-o", str(path))
    code = run_cli(capsys, "show", str(path), "--format", "python").out
    assert "sympy.CRootOf(" in code
    space: dict = {}
    exec(code, space)  # the code rkcheck wrote, not file content: it is what a user runs
    x, w = np.polynomial.legendre.leggauss(6)
    assert np.allclose([float(sympy.N(v, 30)) for v in space["c"]], (x + 1) / 2, atol=1e-14)
    assert np.allclose([float(sympy.N(v, 30)) for v in space["b"]], w / 2, atol=1e-14)
    julia = run_cli(capsys, "show", str(path), "--format", "julia")
    assert julia.code == 2 and f"{path}: A[1][1]: root(…) has no exact form in this output format" in julia.err
