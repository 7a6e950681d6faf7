"""A member of a family at exact real values of its parameters (``Family.at``): the
algebraic solutions ``solve`` finds, or texts written as entries are, give the method
itself, checked exactly."""

from __future__ import annotations

import json
from fractions import Fraction

import mpmath
import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

import rkcheck
from rkcheck.errors import UserError

THEOREM_S3 = TABLEAUX / "families" / "theorem1-s3-m6.toml"


@pytest.fixture(autouse=True)
def _precision():
    """60 digits for mpmath here, the global precision as it was afterwards."""
    with mpmath.workdps(60):
        yield


def _value(entry, digits=40):
    """An entry's value to ``digits`` digits, from its certified enclosure."""
    box = entry.enclosure(4 * digits)
    assert box.hi - box.lo < Fraction(1, 10**digits)
    return mpmath.mpf(box.lo.numerator) / box.lo.denominator


def test_solves_solutions_are_the_avf_methods_over_gauss_3_and_check_as_such():
    # Theorem 1 (s = 3, m = 6): exactly AVF over 3-point Gauss, the outer nodes either
    # way round: a_ij = c_i b_j with c = 1/2 ∓ √15/10, 1/2, 1/2 ± √15/10 and b = (5, 8, 5)/18
    res = rkcheck.solve(THEOREM_S3, degree=6, order=7)
    fam = rkcheck.load_family(THEOREM_S3)
    b = [mpmath.mpf(5) / 18, mpmath.mpf(8) / 18, mpmath.mpf(5) / 18]
    r = mpmath.sqrt(15) / 10
    orders = set()
    for solution in res.solutions:
        member = fam.at(solution.values)
        first = _value(member.A[0][0]) / b[0]  # the first node: 1/2 - √15/10 or 1/2 + √15/10
        sign = 1 if first > mpmath.mpf(1) / 2 else -1
        c = [mpmath.mpf(1) / 2 + sign * r, mpmath.mpf(1) / 2, mpmath.mpf(1) / 2 - sign * r]
        for i in range(3):
            for j in range(3):
                assert abs(_value(member.A[i][j]) - c[i] * b[j]) < mpmath.mpf(10) ** -35
        report = rkcheck.verify(member, degree=6, order=7)
        assert {cond.verdict.state for cond in report.conditions} == {"holds"}  # exact, not to digits
        orders.add(sign)
    assert orders == {1, -1}


def test_a_cubic_solution_is_the_real_root_it_names_and_a_complex_one_is_refused(tmp_path):
    path = tmp_path / "x.toml"
    path.write_text('[parameters]\nx = "free"\n[tableau]\nA = [["x"]]\nb = ["1"]\n', encoding="utf-8")
    res = rkcheck.solve(path, degree=2, order=1, where=["x^3 - x - 1"])
    fam = rkcheck.load_family(path)
    real = [s for s in res.solutions if s.real]
    assert len(res.solutions) == 3 and len(real) == 1
    plastic = mpmath.findroot(lambda x: x**3 - x - 1, 1.3)  # the plastic number, the one real root
    assert abs(_value(fam.at(real[0].values).A[0][0]) - plastic) < mpmath.mpf(10) ** -35
    complex_one = next(s for s in res.solutions if not s.real)
    with pytest.raises(UserError, match=r"^x: .* is not a real number: a method's entries are real$"):
        fam.at(complex_one.values)


def test_a_cubic_root_among_several_real_ones_is_numbered_as_the_grammar_numbers_them(tmp_path):
    # y³ − 3y + 1 has three real roots, 2 cos(2π/9 · (1, 2, 4)) up to order: each solution
    # must give back its own root, not another of the three
    path = tmp_path / "y.toml"
    path.write_text('[parameters]\ny = "free"\n[tableau]\nA = [["y"]]\nb = ["1"]\n', encoding="utf-8")
    res = rkcheck.solve(path, degree=2, order=1, where=["y^3 - 3*y + 1"])
    fam = rkcheck.load_family(path)
    want = sorted(2 * mpmath.cos(2 * mpmath.pi * k / 9) for k in (2, 4, 8))
    got = sorted(_value(fam.at(s.values).A[0][0]) for s in res.solutions)
    assert len(got) == 3 and all(abs(g - w) < mpmath.mpf(10) ** -35 for g, w in zip(got, want))
    for s in res.solutions:  # each to the value solve printed
        assert abs(_value(fam.at(s.values).A[0][0]) - s.values["y"].approx.real) < 1e-9


def test_a_value_written_as_an_entry_is_taken_exactly(tmp_path):
    path = tmp_path / "c.toml"
    path.write_text('[parameters]\nc = "free"\n[tableau]\nA = [["c/2", "0"], ["c", "c/2"]]\nb = ["1/2", "1/2"]\n',
                    encoding="utf-8")
    fam = rkcheck.load_family(path)
    member = fam.at({"c": "1/2 - sqrt(3)/6"})
    assert abs(_value(member.A[1][0]) - (mpmath.mpf(1) / 2 - mpmath.sqrt(3) / 6)) < mpmath.mpf(10) ** -35
    # a rational as Python writes it stays that rational, not a rounded decimal's interval
    assert fam.at({"c": "0.3333333"}).A[1][0].exact == Fraction(3333333, 10**7)


@pytest.mark.parametrize("value, message", [
    ("sqrt(-3)", "c: square root of a negative number"),
    ("k + 1", "c: unknown name 'k' at column 1: a parameter's value is a number"),
    ("sqrt(2", "c: "),
    ("1/0", "c: division by zero"),
    (None, "c: expected a number (an int, a Fraction, a text such as '1/2 - sqrt(3)/6', or a value from solve), "
           "got NoneType"),
])
def test_a_value_that_is_not_an_exact_real_number_is_refused_at_its_parameter(tmp_path, value, message):
    path = tmp_path / "c.toml"
    path.write_text('[parameters]\nc = "free"\n[tableau]\nA = [["c"]]\nb = ["1"]\n', encoding="utf-8")
    with pytest.raises(UserError) as err:
        rkcheck.load_family(path).at({"c": value})
    assert str(err.value).startswith(message), str(err.value)


def _gauss_family(tmp_path):
    # Gauss-2's A with weights moved by k: Gauss-2, symplectic, at k = √3/6 = r/6
    path = tmp_path / "g.toml"
    path.write_text('[parameters]\nk = "free"\n[constants]\nr = "sqrt(3)"\n'
                    '[tableau]\nA = [["1/4", "1/4 - r/6"], ["1/4 + r/6", "1/4"]]\n'
                    'b = ["1/2 + k - r/6", "1/2 - k + r/6"]\n', encoding="utf-8")
    return path


def test_an_extra_equation_may_name_a_constant_with_a_root(tmp_path):
    # --where "6*k = r" with r = √3: the family's own constant, a number of its field
    # (it was refused: "cannot read this part of the entry as a polynomial")
    path = _gauss_family(tmp_path)
    res = rkcheck.solve(path, degree=2, order=4, where=["6*k = r"])
    assert [s.values["k"].text for s in res.solutions] == ["1/6*sqrt(3)"]
    member = rkcheck.load_family(path).at(res.solutions[0].values)
    gauss = rkcheck.load("@gauss-2")
    for i in range(2):
        for j in range(2):
            assert abs(_value(member.A[i][j]) - _value(gauss.A[i][j])) < mpmath.mpf(10) ** -35


def test_an_extra_equation_outside_the_entries_field_is_refused_in_one_line(tmp_path):
    with pytest.raises(UserError) as err:
        rkcheck.solve(_gauss_family(tmp_path), degree=2, order=4, where=["k = sqrt(2)"])
    # with the equation √2 satisfies over Q (by hand: x² − 2), which any field can hold
    assert str(err.value).endswith("sqrt(2) is not a number of the entries' field, Q(sqrt(3)); write the "
                                   "polynomial equation it is a root of instead: x^2 - 2 = 0 for x = sqrt(2)"), \
        str(err.value)
    with pytest.raises(UserError) as err:
        rkcheck.solve(_gauss_family(tmp_path), degree=2, order=4, where=["k = 1 + root(x^3 - 2, 1)/3"])
    # x = 1 + ∛2/3: (3(x − 1))³ = 2, 27x³ − 81x² + 81x − 29 = 0
    assert str(err.value).endswith("27*x^3 - 81*x^2 + 81*x - 29 = 0 for x = 1 + root(x^3 - 2, 1)/3"), str(err.value)


def _gauss_with_free_nodes(tmp_path):
    """Gauss-2 with its off-diagonal entries moved by k, and Gauss-2's file's [check] and
    [expect] (published: classical order 4, symplectic, symmetric, degree-4 energy to
    order 4): Gauss-2 at k = √3/6."""
    shipped = (TABLEAUX / "collocation" / "gauss-2.toml").read_text(encoding="utf-8")
    check = shipped[shipped.index("[check]"):]
    path = tmp_path / "gauss-k.toml"
    path.write_text('[parameters]\nk = "free"\n[tableau]\nA = [["1/4", "1/4 - k"], ["1/4 + k", "1/4"]]\n'
                    f'b = ["1/2", "1/2"]\n{check}', encoding="utf-8")
    return path


def test_verify_at_checks_the_member_with_the_files_claims(tmp_path, capsys):
    path = _gauss_with_free_nodes(tmp_path)
    member = run_cli(capsys, "verify", str(path), "--at", "k = sqrt(3)/6", "--format", "json")
    shipped = run_cli(capsys, "verify", str(TABLEAUX / "collocation" / "gauss-2.toml"), "--format", "json")
    assert member.code == shipped.code == 0, member.err
    got, want = json.loads(member.out), json.loads(shipped.out)
    assert [(c["id"], c["state"], c["residual_exact"]) for c in got["conditions"]] == \
        [(c["id"], c["state"], c["residual_exact"]) for c in want["conditions"]]
    assert len(got["claims"]) == len(want["claims"]) == 8 and all(c["met"] for c in got["claims"])
    assert not any("not judged" in w for w in got["warnings"])
    # at k = 1/4 the nodes are 1/4 and 3/4: b·c² = 5/16 ≠ 1/3, classical order 2, the claim of 4 broken
    other = run_cli(capsys, "verify", str(path), "--at", "k=1/4", "--format", "json")
    assert other.code == 1
    broken = {c["claim"] for c in json.loads(other.out)["claims"] if not c["met"]}
    assert "classical_order" in broken


@pytest.mark.parametrize("args, message", [
    (["--at", "k=sqrt(-3)"], "--at k: square root of a negative number"),
    (["--at", "k"], "--at: expected NAME=VALUE, got 'k'"),
    (["--at", "k=1", "--at", "k=2"], "--at: k is given twice"),
    (["--at", "z=1"], "--at: no value for the parameter k"),
    (["--at", "k=1", "--at", "z=1"], "--at: 'z' is not a parameter (the parameters are k)"),
])
def test_verify_at_refuses_a_bad_value_in_one_line(tmp_path, capsys, args, message):
    run = run_cli(capsys, "verify", str(_gauss_with_free_nodes(tmp_path)), *args)
    assert run.code == 2 and run.err.count("\n") == 1 and message in run.err, run.err


def test_show_at_writes_the_member_as_a_file_that_reads_back_as_gauss_2(tmp_path, capsys):
    run = run_cli(capsys, "show", str(_gauss_with_free_nodes(tmp_path)), "--at", "k=sqrt(3)/6", "--format", "toml")
    assert run.code == 0
    written = tmp_path / "member.toml"
    written.write_text(run.out, encoding="utf-8")
    member, gauss = rkcheck.load(written), rkcheck.load("@gauss-2")
    assert all(abs(_value(member.A[i][j]) - _value(gauss.A[i][j])) < mpmath.mpf(10) ** -35
               for i in range(2) for j in range(2))
    assert len(member.info.claims) == len(gauss.info.claims)


def test_at_on_a_file_of_one_method_is_refused(capsys):
    run = run_cli(capsys, "verify", str(TABLEAUX / "collocation" / "gauss-2.toml"), "--at", "k=1")
    assert run.code == 2 and "has no free [parameters]: it is one method already" in run.err


def test_two_roots_closer_than_a_first_enclosure_are_told_apart(tmp_path):
    # x⁴ = 2(10¹⁰x − 1)²: two real roots near 10⁻¹⁰, about 3·10⁻³⁰ apart; each solution
    # was named (and built by at()) as the same root
    path = tmp_path / "x.toml"
    path.write_text('[parameters]\nx = "free"\n[tableau]\nA = [["x"]]\nb = ["1"]\n', encoding="utf-8")
    res = rkcheck.solve(path, degree=2, order=1, where=["x^4 - 2*(10^10*x - 1)^2"])
    assert len({s.values["x"].text for s in res.solutions}) == 4
    mpmath.mp.dps = 80  # within the fixture's workdps: restored after the test
    want = sorted(mpmath.polyroots([1, 0, -2 * 10**20, 4 * 10**10, -2], maxsteps=200, extraprec=400))
    fam = rkcheck.load_family(path)
    got = sorted(_value(fam.at(s.values).A[0][0], digits=60) for s in res.solutions)
    assert all(abs(g - w) < mpmath.mpf(10) ** -45 for g, w in zip(got, want))
    assert got[2] - got[1] > mpmath.mpf(10) ** -31


def test_an_extra_equations_number_written_with_another_generator_of_the_field_is_in_it(tmp_path):
    # built again with the entries' parts, root(x^2 - 12, 2) gives Q(√3) with another
    # generator (√12): the same field, and the same solution as with r = √3 itself
    path = _gauss_family(tmp_path)
    same = rkcheck.solve(path, degree=2, order=4, where=["12*k = root(x^2 - 12, 2)"])
    assert [s.values["k"].text for s in same.solutions] == ["1/6*sqrt(3)"]


@pytest.mark.parametrize("constant, r, where, k", [
    ("sqrt(3) + sqrt(5)", lambda: mpmath.sqrt(3) + mpmath.sqrt(5), "k = sqrt(8 + 2*sqrt(15))",
     lambda: mpmath.sqrt(3) + mpmath.sqrt(5)),
    ("sqrt(3) + sqrt(5)", lambda: mpmath.sqrt(3) + mpmath.sqrt(5), "k = sqrt(15)", lambda: mpmath.sqrt(15)),
    ("root(x^3 - 2, 1)", lambda: mpmath.cbrt(2), "k = root(x^3 - 4, 1)", lambda: mpmath.cbrt(4)),  # r², a root of its own
])
def test_a_number_of_the_field_with_another_generator_is_carried_into_the_entries(tmp_path, constant, r, where, k):
    # the entries' field Q(√3 + √5) (degree 4) or Q(∛2); the equation's number built
    # again has another generator: it was refused as "not a number of the entries' field"
    path = tmp_path / "r.toml"
    path.write_text(f'[parameters]\nk = "free"\n[constants]\nr = "{constant}"\n[tableau]\nA = [["k*r"]]\nb = ["1"]\n',
                    encoding="utf-8")
    res = rkcheck.solve(path, degree=2, order=1, where=[where])
    assert len(res.solutions) == 1
    member = rkcheck.load_family(path).at(res.solutions[0].values)
    assert abs(_value(member.A[0][0]) - k() * r()) < mpmath.mpf(10) ** -35



def test_numbers_of_numpy_decimal_and_sympy_are_taken_exactly(tmp_path):
    # as family_from_arrays takes them: numpy's integers and floats, Decimals, sympy
    from decimal import Decimal

    import numpy as np
    import sympy

    path = tmp_path / "c.toml"
    path.write_text('[parameters]\nc = "free"\n[tableau]\nA = [["c"]]\nb = ["1"]\n', encoding="utf-8")
    fam = rkcheck.load_family(path)
    assert fam.at({"c": np.int64(3)}).A[0][0].exact == 3
    assert fam.at({"c": np.float32(0.1)}).A[0][0].exact == Fraction(13421773, 2**27)  # float32's 0.1, exactly
    assert fam.at({"c": Decimal("0.1")}).A[0][0].exact == Fraction(1, 10)
    assert fam.at({"c": sympy.Rational(1, 3)}).A[0][0].exact == Fraction(1, 3)
    entry = fam.at({"c": sympy.sqrt(3) / 6 + sympy.Rational(1, 2)}).A[0][0]
    assert abs(_value(entry) - (mpmath.sqrt(3) / 6 + mpmath.mpf(1) / 2)) < mpmath.mpf(10) ** -35
    with pytest.raises(UserError, match="got bool"):
        fam.at({"c": np.bool_(True)})


def test_a_member_has_the_files_warnings_not_the_familys(tmp_path):
    # "z appears in no entry: every value of it gives the same method" is about the
    # family; the member at z = 3 is one method (the note was carried over to it)
    path = tmp_path / "unused.toml"
    path.write_text('[parameters]\nk = "free"\nz = "free"\n[tableau]\nA = [["1/4", "1/4 - k"], ["1/4 + k", "1/4"]]\n'
                    'b = ["1/2", "1/2"]\n[expect]\nsymplectic = true\n', encoding="utf-8")
    fam = rkcheck.load_family(path)
    assert any("z appears in no entry" in w for w in fam.warnings)
    assert any("claims are not judged" in w for w in fam.warnings)
    member = fam.at({"k": Fraction(1, 6), "z": 3})
    assert member.info.warnings == () and len(member.info.claims) == 1
    assert rkcheck.verify(member, order=3).claims[0].met  # b_i a_ij + b_j a_ji = b_i b_j for every k
