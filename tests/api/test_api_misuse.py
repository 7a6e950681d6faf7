"""What a library caller can get wrong ends in an RkcheckError subclass with the CLI's
one-line message, never in another exception."""

from __future__ import annotations

import re
from fractions import Fraction

import pytest
from support.paths import TABLEAUX

import rkcheck


def test_scan_of_one_folder_given_as_a_string_scans_that_folder():
    folder = TABLEAUX / "explicit"
    one = rkcheck.scan(str(folder), order=2, jobs=1)
    listed = rkcheck.scan([str(folder)], order=2, jobs=1)
    assert [r.path for r in one.rows] == [r.path for r in listed.rows]
    assert len(one.rows) == len(list(folder.glob("*.toml")))


def test_scan_of_something_that_is_no_path_is_an_rkcheck_error():
    with pytest.raises(rkcheck.RkcheckError, match="expected a path or a list of paths"):
        rkcheck.scan([42])


def _own_rounding_interval(np, x):
    """The reals that round to x in its own precision: halfway to each neighbour (past
    the largest float, the spacing below mirrored)."""
    def exact(y):
        return Fraction(*y.item().as_integer_ratio()) if y.dtype.itemsize > 8 else Fraction(float(y))

    value = exact(x)
    lo, hi = (np.nextafter(x, np.asarray(d, dtype=x.dtype)) for d in (-np.inf, np.inf))
    lo = exact(lo) if np.isfinite(lo) else 2 * value - exact(hi)
    hi = exact(hi) if np.isfinite(hi) else 2 * value - lo
    return (lo + value) / 2, (value + hi) / 2


def _covers(np, entry, x):
    lo, hi = entry.node.interval("auto")
    r_lo, r_hi = _own_rounding_interval(np, x)
    return lo <= r_lo and r_hi <= hi


def test_a_numpy_longdouble_entry_is_read_like_a_float():
    import warnings

    import numpy as np

    x = np.longdouble(1) / 3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the API warns when it reads floats
        tab = rkcheck.from_arrays([[x]], [np.longdouble(1)])
        binary = rkcheck.from_arrays([[x]], [np.longdouble(1)], floats="exact")
    num, den = x.as_integer_ratio()
    # by default a decimal covering every real that rounds to it in its own precision
    # (1/3 among them); floats="exact": its binary value
    assert _covers(np, tab.A[0][0], x) and tab.b[0].exact == 1
    lo, hi = tab.A[0][0].node.interval("auto")
    assert lo < Fraction(1, 3) < hi and lo < Fraction(num, den) < hi
    assert binary.A[0][0].exact == Fraction(num, den)


@pytest.mark.parametrize("value", ["inf", "nan"])
def test_a_non_finite_longdouble_is_an_rkcheck_error_naming_the_entry(value):
    import numpy as np

    with pytest.raises(rkcheck.RkcheckError) as err:
        rkcheck.from_arrays([[np.longdouble(value)]], [1])
    assert str(err.value) == f"A[1][1]: {value} is not a finite number"


@pytest.mark.parametrize("call, message", [
    (lambda: rkcheck.load(123), "source: expected a path (str or os.PathLike) or '@name', got int"),
    (lambda: rkcheck.load(None), "source: expected a path (str or os.PathLike) or '@name', got NoneType"),
    (lambda: rkcheck.loads(b"\xff"), "<string>: not UTF-8 text (byte 0)"),
    (lambda: rkcheck.loads(42), "<string>: expected the text of a tableau file (str), got int"),
    (lambda: rkcheck.write(5, "toml"), "expected a Tableau (rkcheck.load, rkcheck.from_arrays), got int"),
])
def test_wrong_types_are_rkcheck_errors(call, message):
    with pytest.raises(rkcheck.RkcheckError) as err:
        call()
    assert str(err.value) == message


def test_loads_takes_the_bytes_of_a_file():
    tab = rkcheck.loads('[tableau]\nA = [["1/2"]]\nb = [1]\n'.encode())
    assert str(tab.A[0][0].exact) == "1/2"


SWEEP = TABLEAUX / "families" / "sweep-s2-lobatto.toml"
THEOREM = TABLEAUX / "families" / "theorem1-s2-m3.toml"


def _kernel_family():
    return rkcheck.load_family(TABLEAUX / "families" / "seed-kernel-zeta-0.toml")


@pytest.mark.parametrize("call, message", [
    (lambda: rkcheck.load_family(5), "path: expected a path (str or os.PathLike) or '@name', got int"),
    (lambda: rkcheck.load_family(None), "path: expected a path (str or os.PathLike) or '@name', got NoneType"),
    (lambda: rkcheck.solve(THEOREM, degree=3, order=4, where=[5]),
     "where: expected texts, but the list holds a value of type int"),
    (lambda: rkcheck.solve(THEOREM, degree=3, order=4, where=7), "where: expected a text or a list of texts, got int"),
    (lambda: rkcheck.solve(THEOREM, degree=3, order=4, max_seconds=0.5),
     "max_seconds: expected a number of seconds from 1 to 86,400, got 0.5"),
    (lambda: rkcheck.sweep(SWEEP, None), "grids: expected a text or a list of texts, got NoneType"),
    (lambda: rkcheck.sweep(SWEEP, [1]), "grids: expected texts, but the list holds a value of type int"),
    (lambda: _kernel_family().at(None), "values: expected a mapping of the parameters to their values, got NoneType"),
    (lambda: _kernel_family().at({"beta": 10**100_000}), "beta: value is too large (332,193 bits; the limit MAX_BITS is 200,000 bits)"),
    (lambda: _kernel_family().covering("5"), "vertices: expected a positive number of vertices, got '5'"),
    (lambda: _kernel_family().covering(0), "vertices: expected a positive number of vertices, got 0"),
])
def test_wrong_family_arguments_are_rkcheck_errors(call, message):
    with pytest.raises(rkcheck.RkcheckError) as err:
        call()
    assert str(err.value) == message


def test_family_arguments_a_library_may_well_pass(tmp_path):
    # where=None (no extra equation), a float time limit, and a value beyond str()'s
    # 4 300 digits (x = 10^5000 + 1/3: exact, taken whole)
    free = rkcheck.solve(THEOREM, degree=3, order=4)
    again = rkcheck.solve(THEOREM, degree=3, order=4, where=None, max_seconds=30.5)
    assert (again.dimension, again.groebner) == (free.dimension, free.groebner)
    path = tmp_path / "x.toml"
    path.write_text('[parameters]\nx = "free"\n[tableau]\nA = [["2*x"]]\nb = ["1"]\n', encoding="utf-8")
    x = 10**5000 + Fraction(1, 3)
    assert rkcheck.load_family(path).at({"x": x}).A[0][0].exact == 2 * x


def test_a_kernel_matrix_of_floats_reads_them_as_their_decimals():
    from rkcheck.methods.continuous import ContinuousMethod

    # M = [[1]] is AVF (A = τ, B = 1); 1.0 is that number, a decimal kept as written (the
    # decimals rule reads it exactly: two significant digits), so every condition holds
    assert ContinuousMethod.from_matrix([[1]]).A == "tau"
    floats = ContinuousMethod.from_matrix([[1.0]])
    assert floats.A == "1.0*tau"
    report = rkcheck.verify(floats, order=5)
    assert report.all_hold and all(c.state == "holds" for c in report.conditions)
    with pytest.raises(rkcheck.RkcheckError, match=r"M\[1\]\[1\]: nan is not a finite number"):
        ContinuousMethod.from_matrix([[float("nan")]])


@pytest.mark.parametrize("call", [
    lambda: rkcheck.simulate("@euler", None),
    lambda: rkcheck.simulate("@euler", 5),
    lambda: rkcheck.empirical_energy_order("@euler", None),
    lambda: rkcheck.work_precision(["@euler"], None),
])
def test_a_problem_that_is_neither_a_name_nor_a_hamiltonian_is_an_rkcheck_error(call):
    with pytest.raises(rkcheck.RkcheckError, match="^problem: expected a problem's name"):
        call()


@pytest.mark.parametrize("steps", [[10**12], "20,99999999999999999999"])
def test_workprec_step_counts_are_bounded_as_simulates(steps):
    # each count is a run of that many steps: simulate's bound holds for every count
    from rkcheck.options import STEPS_RANGE

    with pytest.raises(rkcheck.RkcheckError, match=f"from 1 to {STEPS_RANGE[1]:,}"):
        rkcheck.work_precision(["@rk4"], "harmonic", T="1", steps=steps)


def test_perturb_takes_one_eps_and_refuses_what_is_not_eps():
    from fractions import Fraction

    assert [r.eps for r in rkcheck.perturb("@avf-gauss-2", "kernel", degree=3, order=4, eps=0.001).rows] == [
        Fraction(1, 1000)]  # a float as its shortest decimal
    assert [r.eps for r in rkcheck.perturb("@avf-gauss-2", "kernel", degree=3, order=4, eps=Fraction(1, 3)).rows] == [
        Fraction(1, 3)]
    for bad in (None, True, b"1e-3"):
        with pytest.raises(rkcheck.RkcheckError, match="^eps: expected ε values"):
            rkcheck.perturb("@avf-gauss-2", "kernel", degree=3, order=4, eps=bad)


@pytest.mark.parametrize("call, place", [
    (lambda: rkcheck.kernel(4, 2, rule=None), "rule"),
    (lambda: rkcheck.perturb("@rk4", None), "direction"),
    (lambda: rkcheck.write(rkcheck.load("@rk4"), []), "format"),
    (lambda: rkcheck.work_precision(None, "harmonic"), "tableaux"),
    (lambda: rkcheck.is_family_file(None), "path"),
    (lambda: rkcheck.family_from_arrays([["p"]], ["1"], ["p"], constants=5), "constants"),
    (lambda: rkcheck.family_from_arrays([["p"]], ["1"], ["p", "p"]), "parameters"),
    (lambda: rkcheck.scan(["@rk4"], exclude=5), "exclude"),
    (lambda: rkcheck.scan([""]), "paths"),
    (lambda: rkcheck.load(""), "path"),
    (lambda: rkcheck.scan(["@rk4"], order=2, jobs=1).report("xml"), "format"),
])
def test_an_argument_of_the_wrong_kind_is_a_one_line_error_naming_it(call, place):
    with pytest.raises(rkcheck.RkcheckError) as err:
        call()
    assert err.value.place == place and "\n" not in str(err.value)


def test_free_trees_past_the_memory_is_refused_before_it_is_listed():
    from rkcheck.api.trees import free_trees

    with pytest.raises(rkcheck.RkcheckError, match="available"):
        free_trees(27)  # order 26: hundreds of GB of rooted trees


def test_one_exclude_pattern_as_a_string_is_one_pattern(tmp_path):
    (tmp_path / "sub").mkdir()
    for name in ("a.toml", "sub/b.toml"):
        (tmp_path / name).write_text((TABLEAUX / "explicit" / "rk4.toml").read_text(), encoding="utf-8")
    result = rkcheck.scan([str(tmp_path)], exclude="sub/*", order=2, jobs=1)
    assert [r.path for r in result.rows] == [str(tmp_path / "a.toml")]


def test_float32_arrays_are_read_as_decimals_covering_their_own_rounding():
    import warnings

    import numpy as np

    A = np.array([[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 1, 0]], dtype=np.float32)
    b = np.array([1 / 6, 1 / 3, 1 / 3, 1 / 6], dtype=np.float32)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tab = rkcheck.from_arrays(A, b)
        result = rkcheck.verify(tab, order=5)
    assert all(_covers(np, e, x) for e, x in zip(tab.b, b))
    # RK4 to float32's digits: consistent, classical order 4 to digits (the doubles
    # the float32 values widen to sum to 1.0000000298…: not consistent)
    assert result.classical.to_digits == 4 and not any("inconsistent" in w for w in result.warnings)


@pytest.mark.parametrize("dtype", ["float32", "longdouble"])
def test_avf_over_radau_in_narrow_floats_holds_to_digits_not_fails(dtype):
    # AVF over Radau I-2 (A = c bᵀ, c = (1/3, 1), b = (3/4, 1/4)): with a12 = 1/12 + e its
    # conditions for cubic H are −3e/4, −e(3e+2)/8, 3e(9e+2)/32, 9e²/8 (sympy), zero at
    # e = 0; 1/12 rounds to the float entry, so no condition may fail
    import warnings

    import numpy as np

    c, w = np.array([1, 3], dtype=dtype) / 3, np.array([3, 1], dtype=dtype) / 4
    A = np.outer(c, w)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tab = rkcheck.from_arrays(A, w)
        result = rkcheck.verify(tab, degree=3, order=4)
    assert all(_covers(np, e, x) for row, xs in zip(tab.A, A) for e, x in zip(row, xs))
    assert result.verdict == "holds_to_digits" and not result.failures


def test_a_float16_is_taken_at_its_binary_value_with_a_warning_saying_so():
    # 3.3 digits: no decimal of six digits or more covers its rounding interval
    import numpy as np

    with pytest.warns(rkcheck.RkcheckWarning, match="exact binary value"):
        tab = rkcheck.from_arrays(np.array([[1 / 12]], dtype=np.float16), np.array([1], dtype=np.float16))
    assert tab.A[0][0].exact == Fraction(float(np.float16(1 / 12)))


@pytest.mark.parametrize("A, b, place", [
    (lambda np: np.zeros((2, 2, 2)), lambda np: [1, 1], "A[1][1]"),
    (lambda np: np.zeros((1, 1, 1)), lambda np: [1], "A[1][1]"),
    (lambda np: [[0]], lambda np: np.zeros((1, 1)), "b[1]"),
])
def test_arrays_with_an_axis_too_many_are_refused_naming_the_entry(A, b, place):
    # a 2×2×2 A has a 2-vector where a number belongs; (1, 1, 1) one of size 1, which
    # numpy's item() would have read as that number
    np = pytest.importorskip("numpy")
    with pytest.raises(rkcheck.TableauError, match=rf"^{re.escape(place)}: expected a number, got an array"):
        rkcheck.from_arrays(A(np), b(np))


@pytest.mark.parametrize("call, place", [
    (lambda: rkcheck.scan(["@rk4"], order=4, progress=5), "progress"),
    (lambda: rkcheck.scan(["@rk4"], order=4, on_file="x"), "on_file"),
    (lambda: rkcheck.scan(["@rk4"], order=4, allow_empty="x"), "allow_empty"),
    (lambda: rkcheck.scan(["@rk4"], order=4, project="yes"), "project"),
    (lambda: rkcheck.scan(["@rk4"], order=4, json_in_workers=1), "json_in_workers"),
    (lambda: rkcheck.verify("@rk4", order=4, project="x"), "project"),
    (lambda: rkcheck.verify("@rk4", order=4, fail_fast="no"), "fail_fast"),
    (lambda: rkcheck.loads('[tableau]\nA = [["1/2"]]\nb = [1]\n', name=5), "name"),
])
def test_a_flag_or_callback_of_the_wrong_type_is_an_option_error_naming_it(call, place):
    # 'no' and 'x' are true in Python: taken as flags they would turn an option on
    with pytest.raises(rkcheck.OptionError) as err:
        call()
    assert err.value.place == place and "\n" not in str(err.value)


def test_a_text_is_held_to_the_limit_of_a_file(monkeypatch):
    from rkcheck.io.bounded import MAX_FILE_BYTES

    with pytest.raises(rkcheck.RkcheckError, match="text too large .* the limit MAX_FILE_BYTES"):
        rkcheck.loads(" " * (MAX_FILE_BYTES + 1))
    monkeypatch.setenv("RKCHECK_MAX_FILE_BYTES", "100")
    with pytest.raises(rkcheck.RkcheckError, match="text too large"):
        rkcheck.loads("[tableau]\nA = [[\"1/2\"]]\nb = [1]\n" + "#" * 100)


def test_the_largest_narrow_floats_are_read_covering_their_rounding():
    # past the largest float32 the next one is inf: the rounding interval's upper half
    # mirrors the lower one, as IEEE rounding to nearest has it
    import warnings

    import numpy as np

    top = np.finfo(np.float32).max
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tab = rkcheck.from_arrays([[top, np.float32(3e38)], [-top, np.float16(65504)]], [1, 0])
    assert _covers(np, tab.A[0][0], top) and _covers(np, tab.A[0][1], np.float32(3e38))
    assert tab.A[1][0].text == "-" + tab.A[0][0].text and tab.A[1][1].exact == 65504


def test_each_way_floats_were_read_has_its_own_true_warning():
    import numpy as np

    def said(A, b, **kwargs):
        with pytest.warns(rkcheck.RkcheckWarning) as record:
            rkcheck.from_arrays(A, b, **kwargs)
        return [str(w.message) for w in record]

    mixed = said([[np.float16(1 / 3), np.float32(1 / 3)], [np.float32(1 / 7), np.longdouble(1) / 7]], [1, 0])
    assert len(mixed) == 2
    assert mixed[0].startswith("3 float entries (first A[1][2] = 0.333333) were read as a decimal")
    assert mixed[1].startswith("1 float entries (first A[1][1]) were taken at their exact binary value: they have "
                               "fewer digits")
    # a double's short decimal is that decimal, not its binary value
    assert said([[0.1]], [1])[0].startswith("1 float entries (first A[1][1] = 0.1) were read as a decimal")
    # floats='exact' says so for every precision, and an exactly representable float32
    # still stands for an interval, which is said
    assert said([[np.float32(1 / 12)]], [1], floats="exact")[0].startswith(
        "1 float entries (first A[1][1]) were taken at their exact binary value, which is not the decimal")
    assert said([[np.float32(0.5)]], [1])[0].startswith("1 float entries (first A[1][1] = 0.5000000) were read")


@pytest.mark.parametrize("call, place", [
    (lambda: rkcheck.conditions(6, count="no"), "count"),
    (lambda: rkcheck.new_toml("gauss", stages=2, exact="no"), "exact"),
    (lambda: rkcheck.conditions(6, announce=3), "announce"),
    (lambda: rkcheck.catalog(degrees=b"3"), "degrees"),
    (lambda: rkcheck.catalog(degrees=3.0), "degrees"),
    (lambda: rkcheck.catalog(progress=3), "progress"),
    (lambda: rkcheck.api.settings.use_listing_cache("x"), "enabled"),
    (lambda: rkcheck.api.settings.use_listing_cache(True, 3), "directory"),
])
def test_flags_callbacks_and_lists_are_checked_not_read_as_truthy(call, place):
    """'no' is a true string, b"3" iterates as 51, 3 is not a function: each refused,
    naming the argument, where it was read as something else or failed deep inside."""
    with pytest.raises(rkcheck.OptionError) as err:
        call()
    assert err.value.place == place


def test_a_masked_array_is_refused_and_a_sympy_vector_is_a_vector():
    np = pytest.importorskip("numpy")
    sympy = pytest.importorskip("sympy")
    with pytest.raises(rkcheck.TableauError, match="masked"):
        rkcheck.from_arrays(np.ma.masked_array([[0, 0], [0.5, 0]], mask=[[0, 0], [1, 0]]), [0, 1])
    half = sympy.Rational(1, 2)
    lists = rkcheck.from_arrays([[0, 0], ["1/2", 0]], [0, 1], c=[0, "1/2"])
    for b, c in ((sympy.Matrix([0, 1]), sympy.Matrix([0, half])), (sympy.Matrix([[0, 1]]), sympy.Matrix([[0, half]]))):
        assert rkcheck.from_arrays(sympy.Matrix([[0, 0], [half, 0]]), b, c=c) == lists


def test_results_of_one_check_compare_equal_across_runs_and_pickling():
    """Two checks of Gauss-2 (entries in Q(√3)) build the field twice: their conditions,
    and a kernel basis and its pickled copy, compare equal instead of raising."""
    import pickle

    a, b = (rkcheck.verify("@gauss-2", order=5) for _ in range(2))
    assert list(a.conditions) == list(b.conditions) and a.first_failure == b.first_failure
    k = rkcheck.kernel(4, 2)
    assert k == rkcheck.kernel(4, 2) and pickle.loads(pickle.dumps(k)) == k


def test_a_rational_residual_of_an_algebraic_tableau_is_that_rational_exactly():
    """Gauss-2's first failing condition, [[τ]²τ], has the rational residual 1/288 (its
    entries are in Q(√3)): verify gives the Fraction with an exact enclosure, as
    energy_condition does."""
    first = rkcheck.verify("@gauss-2", order=5).first_failure
    other = rkcheck.energy_condition(first.id, "@gauss-2")
    assert first.residual == other.residual == Fraction(1, 288) and isinstance(first.residual, Fraction)
    assert first.enclosure.exact and first.enclosure == other.enclosure


def test_a_rational_argument_past_pythons_digit_limit_is_an_rkcheck_error():
    import sys

    limit = sys.get_int_max_str_digits()
    try:
        sys.set_int_max_str_digits(4300)
        for call in (lambda: rkcheck.new("kernel", zeta=Fraction(1, 10**5000)),
                     lambda: rkcheck.perturb("@avf-gauss-2", direction="random", eps=[Fraction(1, 10**5000)],
                                             degree=3, order=4)):
            with pytest.raises(rkcheck.RkcheckError, match="more than 4,300 digits"):
                call()
    finally:
        sys.set_int_max_str_digits(limit)


@pytest.mark.parametrize("call, place, error", [
    (lambda: rkcheck.load_family(TABLEAUX / "families" / "design-s2-m3.toml", max_stages=None), "max_stages",
     rkcheck.OptionError),
    (lambda: rkcheck.load_family(TABLEAUX / "families" / "design-s2-m3.toml", max_stages=True), "max_stages",
     rkcheck.OptionError),
    (lambda: rkcheck.family_from_arrays(A=3, b=[1], parameters=["p"]), "A", rkcheck.RkcheckError),
    (lambda: rkcheck.family_from_arrays(A=[["p"]], b=[1], parameters=["p"], name=object()), "name",
     rkcheck.RkcheckError),
    (lambda: rkcheck.ContinuousMethod.from_kernel("2*tau*sigma", constants=3), "constants", rkcheck.TableauError),
    (lambda: rkcheck.verify(True), "tableau", rkcheck.TableauError),
    (lambda: rkcheck.catalog([TABLEAUX / "explicit" / "euler.toml"], order=2).to_markdown(""), "command",
     rkcheck.OptionError),
])
def test_family_kernel_and_catalogue_arguments_are_refused_naming_them(call, place, error):
    with pytest.raises(error) as err:
        call()
    assert err.value.place == place


def test_an_errors_text_is_one_printable_line_as_the_cli_prints_it():
    with pytest.raises(rkcheck.RkcheckError) as err:
        rkcheck.load("x\ny\x1b[2J.toml")
    assert str(err.value) == "x\\ny\\x1b[2J.toml: no such file"


def test_long_rationals_pass_through_every_constructor_and_repr():
    """A rational of 5 000 digits (past Python's 4 300-digit text limit) is written at any
    length by from_matrix, from_kernel's constants and family_from_arrays, and the reprs
    of a tableau and a sweep that hold one do not raise."""
    import sys

    tiny = Fraction(1, 10**5000)
    limit = sys.get_int_max_str_digits()
    try:
        sys.set_int_max_str_digits(4300)
        m = rkcheck.ContinuousMethod.from_matrix([[tiny]])
        assert m.kernel.A_poly != 0
        k = rkcheck.ContinuousMethod.from_kernel("tau + k*tau*(sigma - 1/2)", constants={"k": tiny})
        assert "k" in k.info.constants.definitions
        assert repr(rkcheck.from_arrays([[tiny]], [1])).startswith("Tableau(")
        fam = rkcheck.family_from_arrays([["q"]], [1 - tiny], ["q"])
        assert fam.stages == 1
        sweep = rkcheck.sweep(TABLEAUX / "families" / "seed-kernel-zeta-0.toml",
                              grids=["beta=0:" + "1" * 5000 + ":2"], order=3)
        assert "(2)" in repr(sweep)
    finally:
        sys.set_int_max_str_digits(limit)


def test_a_kernel_matrix_takes_what_from_arrays_takes_and_refuses_masked_cells():
    np = pytest.importorskip("numpy")
    sympy = pytest.importorskip("sympy")
    from_texts = rkcheck.ContinuousMethod.from_matrix([["1", "1/2"], ["1/2", "1"]])
    from_sympy = rkcheck.ContinuousMethod.from_matrix(sympy.Matrix([[1, sympy.Rational(1, 2)],
                                                                    [sympy.Rational(1, 2), 1]]))
    assert (from_sympy.A, from_sympy.b) == (from_texts.A, from_texts.b)
    with pytest.raises(rkcheck.TableauError, match="masked"):
        rkcheck.ContinuousMethod.from_matrix(np.ma.masked_array([[1.0, 2.0]], mask=[[0, 1]]))
    q = sympy.Symbol("q")
    fam = rkcheck.family_from_arrays([["q", 0], [0, "q"]], sympy.Matrix([q, 1 - q]), ["q"])
    assert fam.stages == 2
