"""The public API: same verdicts and JSON as the CLI, what array values mean, option
errors as RkcheckError, free trees and single conditions against the brute-force
reference (tests/support/reference.py, networkx + Fractions)."""

from __future__ import annotations

import inspect
import json
import random
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from support import reference as ref
from support.clirun import run_cli
from support.paths import TABLEAUX

import rkcheck
from rkcheck import errors


def without_timings(doc: dict) -> dict:
    doc = dict(doc)
    doc.pop("timings")
    return doc


# ------------------------------------------------------------------ same as the CLI


@pytest.mark.parametrize("rel, args", [
    ("collocation/implicit-midpoint.toml", []),  # the API agrees with the CLI: no failure
    ("avf/avf-gauss-2.toml", []),
    ("explicit/rk4.toml", ["--degree", "3", "--order", "6"]),
    ("counterexamples/kernel-zeta-third-beta-0.1.toml", ["--order", "5"]),
])
def test_to_json_is_the_cli_json(capsys, rel, args):
    path = str(TABLEAUX / rel)
    run = run_cli(capsys, "verify", path, "--format", "json", *args)
    kwargs = {}
    for flag, value in zip(args[::2], args[1::2]):
        kwargs[flag.lstrip("-")] = value if flag == "--degree" else int(value)
    result = rkcheck.verify(path, **kwargs)
    assert without_timings(json.loads(result.to_json())) == without_timings(json.loads(run.out))
    assert result.ok == (run.code == 0)


def test_the_file_check_table_is_used_like_the_cli():
    # implicit-midpoint.toml has [check] and claims: the API must judge it as verify does
    tab = rkcheck.load(TABLEAUX / "collocation" / "implicit-midpoint.toml")
    result = rkcheck.verify(tab)
    assert result.options.degree == tab.info.check.get("degree", None)
    assert result.ok and result.claims and all(c.met for c in result.claims)


def test_result_surface_by_hand_for_explicit_midpoint():
    # explicit midpoint: b = (0, 1), c = (0, 1/2).  Star [τ²] ~ Σ b c² = 1/4 ≠ 1/3 (definitions §3):
    # the 4-vertex star R = a([τ²])... fails, the 3-vertex path holds (Σ b c = 1/2): energy order 2
    result = rkcheck.verify(rkcheck.from_arrays([[0, 0], ["1/2", 0]], [0, 1]), order=4)
    assert result.verdict == "fails" and result.energy_order == 2 and result.classical_order == 2
    assert result.quadrature_order == 2
    first = result.failures[0]
    assert first.vertices == 4 and first.state == "fails" and isinstance(first.residual, Fraction)
    assert first.enclosure == (first.residual, 0, True)  # (mid, radius, exact)
    # every condition with 4 vertices, by the reference
    for cond in ref.energy_conditions(4):
        r = ref.energy_residual(cond, [[0, 0], [Fraction(1, 2), 0]], [0, 1])
        mine = [c for c in result.conditions if c.level_sequence == cond["id"]][0]
        assert abs(mine.residual) == abs(r)  # sign depends on the designated rooting
    assert len(result.conditions) == sum(1 for _ in result.conditions) == 1 + 1 + 3
    assert result.avf is None and result.certificate is None


def test_avf_and_certificate_with_a_degree():
    result = rkcheck.verify("@avf-gauss-2", degree=4, order=6)
    assert result.avf is not None and result.avf.equals_avf
    assert result.certificate is not None and result.certificate.certified
    assert result.energy_order_label == "all" and result.energy_order_all


# ------------------------------------------------------------------ from_arrays


def test_values_of_every_kind_are_exact():
    tab = rkcheck.from_arrays(
        [[Fraction(1, 4), "1/4 - sqrt(3)/6"], [sp.Rational(1, 4) + sp.sqrt(3) / 6, np.int64(0) + Fraction(1, 4)]],
        np.array([0.5, 0.5]), [Decimal("0.5") - Decimal("0.5") + sp.Rational(1, 2) - sp.sqrt(3) / 6, "1/2 + sqrt(3)/6"],
    )
    assert tab.A[0][0].exact == Fraction(1, 4) and tab.b[0].exact == Fraction(1, 2)
    assert tab.uses_sqrt and not tab.info.warnings  # 0.5 is exactly a double: nothing to warn about
    want = rkcheck.load(TABLEAUX / "collocation" / "gauss-2.toml")
    bits = 200
    for mine, theirs in zip([e for r in tab.A for e in r], [e for r in want.A for e in r]):
        a, b = mine.enclosure(bits, "auto"), theirs.enclosure(bits, "auto")
        assert abs(a.mid - b.mid) <= a.rad + b.rad


def test_floats_exact_opts_in_to_the_exact_binary_value():
    with pytest.warns(rkcheck.RkcheckWarning, match="exact binary value"):
        tab = rkcheck.from_arrays([[0.1]], [1.0], floats="exact")
    assert tab.A[0][0].exact == Fraction(3602879701896397, 2**55) == Fraction(0.1)
    assert tab.b[0].exact == 1
    assert len(tab.info.warnings) == 1 and "A[1][1]" in tab.info.warnings[0]


def test_a_float_is_by_default_the_decimal_it_prints_as():
    with pytest.warns(rkcheck.RkcheckWarning, match="A\\[1\\]\\[1\\]"):
        tab = rkcheck.from_arrays([[0.1]], [1.0])
    assert tab.A[0][0].exact == Fraction(1, 10) and not tab.A[0][0].is_rounded  # "0.1": < 6 digits, exact
    x = 0.21132486540518713
    with pytest.warns(rkcheck.RkcheckWarning):
        tab = rkcheck.from_arrays([[x]], [1])
    assert tab.A[0][0].text == repr(x) and tab.A[0][0].is_rounded
    assert issubclass(rkcheck.RkcheckWarning, UserWarning)


def test_floats_whose_readings_agree_do_not_warn():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tab = rkcheck.from_arrays(np.array([[0.5, 0.0], [0.25, 0.75]]), np.array([0.5, 0.5]))
    assert tab.A[1][0].exact == Fraction(1, 4) and not tab.info.warnings


def test_the_warning_points_at_the_callers_line():
    with pytest.warns(rkcheck.RkcheckWarning) as record:
        line = inspect.currentframe().f_lineno + 1
        rkcheck.from_arrays([[1 / 3]], [1])
    assert record[0].filename == __file__ and record[0].lineno == line


RK4_FLOATS = ([[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 1.0, 0]], [1 / 6, 1 / 3, 1 / 3, 1 / 6])


def test_rk4_floats_read_alike_by_the_api_and_the_cli(tmp_path, capsys):
    # RK4 has classical order 4 (Kutta 1901); in doubles its weights are the shortest
    # reprs 0.16666666666666666, 0.3333333333333333, whose rounding intervals contain 1/6
    # and 1/3, so order 4 is reached to digits and nothing is exact (not even Σb = 1)
    from support.clirun import run_cli

    A, b = RK4_FLOATS
    assert Fraction(1, 6) != Fraction(1 / 6)  # the binary value is not 1/6: "exact" would fail
    path = tmp_path / "rk4.json"
    path.write_text(json.dumps({"A": A, "b": b}))
    cli = json.loads(run_cli(capsys, "verify", str(path), "--order", "5", "--format", "json").out)
    with pytest.warns(rkcheck.RkcheckWarning):
        api = rkcheck.verify(rkcheck.from_arrays(np.array(A), np.array(b)), order=5).to_dict()
    assert api["summary"] == cli["summary"] and api["conditions"] == cli["conditions"]
    s = api["summary"]
    assert (s["classical_order"], s["classical_order_to_digits"]) == (0, 4)
    assert s["verdict"] == "fails" and s["first_failure"]["order"] == 5  # RK4's energy order is 4
    with pytest.warns(rkcheck.RkcheckWarning):
        exact = rkcheck.verify(rkcheck.from_arrays(np.array(A), np.array(b), floats="exact"), order=5)
    assert exact.classical.to_digits == 0  # Σb = 1 fails by the binary rounding of 1/6 and 1/3


def test_numpy_gauss_avf_binary_fails_tiny_and_trusted_digits_hold_to_digits():
    # AVF over 2-point Gauss: A = c bᵀ, c = 1/2 ∓ √3/6, b = 1/2 (definitions §4), in floats
    c = np.array([0.5 - np.sqrt(3) / 6, 0.5 + np.sqrt(3) / 6])
    b = np.array([0.5, 0.5])
    A = np.outer(c, b)
    with pytest.warns(rkcheck.RkcheckWarning):
        exact = rkcheck.verify(rkcheck.from_arrays(A, b, floats="exact"), degree=3, order=5)
    assert exact.verdict == "fails"
    assert all(abs(f.enclosure[0]) < Fraction(1, 10**15) for f in exact.failures)  # only the rounding
    # the digits one trusts, as strings: rounded decimals (definitions §5), judged over their intervals
    trusted = rkcheck.from_arrays([[f"{x:.15g}" for x in row] for row in A], [f"{x:.15g}" for x in b])
    result = rkcheck.verify(trusted, degree=3, order=5)
    assert result.verdict == "holds_to_digits" and not result.failures
    assert 12 <= min(c.digits for c in result.conditions) <= 16
    # shortest: the repr digits, the same tableau as a file with those strings would be
    with pytest.warns(rkcheck.RkcheckWarning):
        shortest = rkcheck.from_arrays(A, b)  # the default
    as_file = rkcheck.loads("[tableau]\nA = " + json.dumps([[repr(float(x)) for x in r] for r in A])
                            + "\nb = " + json.dumps([repr(float(x)) for x in b]) + "\n")
    mine = rkcheck.verify(shortest, degree=3, order=5).to_dict()
    theirs = rkcheck.verify(as_file, degree=3, order=5).to_dict()
    assert mine["summary"] == theirs["summary"] and mine["conditions"] == theirs["conditions"]


@pytest.mark.parametrize("A, b, place", [
    ([[0, 0], [1]], [1, 0], "A[2]"),
    ([[0, 0], [1, "x("]], [1, 0], "A[2][2]"),
    ([[True]], [1], "A[1][1]"),
    ([[float("nan")]], [1], "A[1][1]"),
    ([[0]], [1, 2], "b"),
    ([[sp.Symbol("x")]], [1], "A[1][1]"),
    ([[object()]], [1], "A[1][1]"),
    ([], [], "A"),
    (5, [1], "A"),
])
def test_bad_arrays_are_tableau_errors_with_a_place(A, b, place):
    with pytest.raises(rkcheck.TableauError) as err:
        rkcheck.from_arrays(A, b)
    assert err.value.place is not None and err.value.place.startswith(place)
    assert isinstance(err.value, rkcheck.RkcheckError) and "\n" not in str(err.value)


# ------------------------------------------------------------------ options


def test_degree_none_spellings_are_the_same_run():
    tab = rkcheck.load("@heun")
    for spelling in (None, "none", "all"):
        assert rkcheck.verify(tab, degree=spelling, order=4).options.degree is None
    assert rkcheck.verify(tab, degree="3", order=4).options.degree == 3


@pytest.mark.parametrize("kwargs, place", [
    ({"degree": "x"}, "degree"), ({"degree": 0}, "degree"), ({"order": 0}, "order"), ({"order": 99}, "order"),
    ({"dps": 5}, "dps"), ({"decimals": "fuzzy"}, "decimals"), ({"fail_on": "x"}, "fail_on"),
    ({"arithmetic": "x"}, "arithmetic"), ({"max_conditions": 0}, "max_conditions"),
])
def test_bad_options_are_option_errors(kwargs, place):
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.verify("@heun", **kwargs)
    assert err.value.place == place and isinstance(err.value, rkcheck.UserError)


def test_error_hierarchy():
    assert rkcheck.UserError is errors.UserError is rkcheck.InputError
    for cls in (rkcheck.TableauError, rkcheck.OptionError, rkcheck.UnknownMethodError, rkcheck.ResourceError):
        assert issubclass(cls, rkcheck.UserError) and issubclass(cls, rkcheck.RkcheckError)
    from rkcheck.dynamics.integrator import NewtonError
    from rkcheck.energy.budget import ResourceError

    assert ResourceError is rkcheck.ResourceError and issubclass(NewtonError, rkcheck.RkcheckError)
    located = rkcheck.TableauError("bad", "A[1][1]").located(source="f.toml")
    assert type(located) is rkcheck.TableauError and str(located) == "f.toml: A[1][1]: bad"


def test_resource_guard_applies():
    with pytest.raises(rkcheck.RkcheckError):
        rkcheck.verify("@heun", order=12, max_conditions=10)


# ------------------------------------------------------------------ trees


def test_free_tree_counts_from_the_definitions():
    # definitions §3: 1, 1, 3, 4, 11, 19, 47, 97, 235, 531 for n = 3..12 (A000055 − A000081(n/2))
    assert [len(rkcheck.free_trees(n)) for n in range(3, 13)] == [1, 1, 3, 4, 11, 19, 47, 97, 235, 531]
    assert rkcheck.free_trees(1) == [] == rkcheck.free_trees(2)


@pytest.mark.parametrize("n", range(3, 10))
@pytest.mark.parametrize("m", [None, 2, 3, 4])
def test_free_trees_are_the_reference_conditions(n, m):
    mine = rkcheck.free_trees(n, max_degree=m)
    want = ref.energy_conditions(n, max_degree=m)
    assert [t.level_sequence for t in mine] == sorted(d["id"] for d in want)
    assert [t.max_degree for t in mine] == [d["max_degree"] for d in sorted(want, key=lambda d: d["id"])]
    assert all(t.rootings == len(d["terms"]) for t, d in zip(mine, sorted(want, key=lambda d: d["id"])))
    assert all(t.vertices == n and t.order == n - 1 and t.id == ",".join(map(str, t.level_sequence)) for t in mine)


def test_energy_condition_matches_the_reference_residual():
    rng = random.Random(13)
    for _ in range(5):
        s = rng.randint(1, 3)
        A = [[Fraction(rng.randint(-5, 5), rng.randint(1, 6)) for _ in range(s)] for _ in range(s)]
        b = [Fraction(rng.randint(-5, 5), rng.randint(1, 6)) for _ in range(s)]
        tab = rkcheck.from_arrays(A, b)
        for n in (3, 5, 6):
            for cond in ref.energy_conditions(n):
                # give a non-canonical rooting: a leaf-rooted level sequence
                mine = rkcheck.energy_condition(cond["terms"][-1][0], tab)
                assert mine.level_sequence == cond["id"]
                assert mine.residual == ref.energy_residual(cond, A, b)
                assert mine.state == ("holds" if mine.residual == 0 else "fails")
                assert sorted(t.level_sequence for t in mine.terms) == sorted(u for u, *_ in cond["terms"])


def test_energy_condition_inputs_and_superfluous():
    a = rkcheck.energy_condition("1,2,3,2")  # the path with 4 vertices: u∘u, superfluous
    assert a.superfluous and not a.is_condition and a.id is None
    tree = rkcheck.free_trees(5)[0]
    for given in (tree, tree.id, list(tree.level_sequence)):
        assert rkcheck.energy_condition(given).level_sequence == tree.level_sequence
    cond = rkcheck.verify("@heun", order=4).conditions[0]
    assert rkcheck.energy_condition(cond, "@heun").residual == cond.residual
    with pytest.raises(rkcheck.OptionError):
        rkcheck.energy_condition("1,3")


# ------------------------------------------------------------------ the surface


def test_every_public_name_is_documented():
    for name in rkcheck.__all__:
        obj = getattr(rkcheck, name)
        if name == "__version__":
            continue
        assert inspect.getdoc(obj), f"rkcheck.{name} has no docstring"


def test_dir_and_unknown_attribute():
    assert set(rkcheck.__all__) <= set(dir(rkcheck))
    with pytest.raises(AttributeError):
        rkcheck.nope  # noqa: B018


def test_library_lists_shipped_and_classics():
    names = rkcheck.library()
    assert "collocation/gauss-3" in names and "sdirk2" in names and names == sorted(names)


def test_write_and_loads_round_trip():
    tab = rkcheck.load("@ralston")
    back = rkcheck.loads(rkcheck.write(tab, "json"), format="json")
    assert [[e.exact for e in r] for r in back.A] == [[0, 0], [Fraction(2, 3), 0]]


def test_import_rkcheck_is_light():
    import subprocess
    import sys

    code = "import sys, rkcheck; print(any(m.startswith('numpy') for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


def test_the_documented_settings_path_works_after_a_bare_import():
    # the docs' spelling after a bare import: rkcheck.api is the subpackage (not a public
    # name looked up in itself), and its submodules are its attributes
    import subprocess
    import sys

    code = ("import rkcheck; f = rkcheck.api.settings.use_listing_cache; "
            "print(f.__module__, rkcheck.api.batch.__name__, rkcheck.api.verify is rkcheck.verify)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["rkcheck.api.settings", "rkcheck.api.batch", "True"]
    with pytest.raises(AttributeError, match="no attribute 'settingz'"):
        rkcheck.api.settingz


@pytest.mark.parametrize("value", [-1, 0, 1001, 10**6, True, 3.5, "x", None])
def test_max_stages_is_refused_alike_by_every_constructor(tmp_path, value):
    # the 1–1000 range holds whatever the source: a file, a text, arrays, a study
    f = tmp_path / "m.toml"
    f.write_text('[tableau]\nA = [["1/2"]]\nb = ["1"]\n')
    messages = set()
    for make in (lambda: rkcheck.load(f, max_stages=value), lambda: rkcheck.loads(f.read_text(), max_stages=value),
                 lambda: rkcheck.from_arrays([["1/2"]], ["1"], max_stages=value),
                 lambda: rkcheck.work_precision([f], "harmonic", T="1", steps=[4], max_stages=value)):
        with pytest.raises(rkcheck.RkcheckError) as err:
            make()
        messages.add(str(err.value))
    assert len(messages) == 1 and messages.pop().startswith("max_stages: expected an integer from 1 to 1000, got ")


def test_tableau_from_arrays_is_the_same_constructor():
    a = rkcheck.Tableau.from_arrays([[0, 0], [0.5, 0]], ["0", 1], name="m")
    b = rkcheck.from_arrays([[0, 0], [0.5, 0]], ["0", 1], name="m")
    assert [[e.exact for e in r] for r in a.A] == [[e.exact for e in r] for r in b.A] == [[0, 0], [Fraction(1, 2), 0]]
    assert a.name == b.name == "m"


@pytest.mark.parametrize("require", ["any", "proof", "digits:40"])
def test_require_gate_same_as_the_cli(capsys, tmp_path, require):
    # AVF over 2-point Gauss in 16-digit decimals: every condition holds only to digits
    c = ["0.2113248654051871", "0.7886751345948129"]
    doc = {"A": [[f"{ci}*0.5", f"{ci}*0.5"] for ci in c], "b": ["0.5", "0.5"]}
    f = tmp_path / "avf16.json"
    f.write_text(json.dumps(doc))
    run = run_cli(capsys, "verify", str(f), "--degree", "3", "--order", "5", "--require", require, "--format", "json")
    result = rkcheck.verify(str(f), degree=3, order=5, require=require)
    assert result.options.require == require
    assert result.ok == (run.code == 0)
    assert without_timings(result.to_dict()) == without_timings(json.loads(run.out))
    if require == "any":
        assert result.ok and result.verdict == "holds_to_digits"


def test_bad_require_is_an_option_error():
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.verify("@heun", require="maybe")
    assert err.value.place == "require"


def test_values_out_of_reach_are_tableau_errors_naming_the_entry():
    # an integer past the entry length limit (str() alone would refuse it past 4 300
    # digits), and sympy numbers that are not algebraic: TableauError at their place
    with pytest.raises(rkcheck.TableauError, match=r"A\[1\]\[1\]: entry too long"):
        rkcheck.from_arrays([[10**100_000]], [1])
    for x in (sp.pi, sp.E, sp.oo, sp.zoo, sp.nan, sp.sqrt(2) * sp.pi):
        with pytest.raises(rkcheck.TableauError, match=r"A\[1\]\[2\]: .* is not an algebraic number"):
            rkcheck.from_arrays([[0, x], [0, 0]], [1, 0])
    # below the limit, a long integer is the exact value it is
    assert rkcheck.from_arrays([[10**5000]], [1]).A[0][0].exact == 10**5000


@pytest.mark.parametrize("require", ["proof", "digits:60"])
def test_an_exact_certificate_is_a_proof_whatever_evaluated_the_conditions(require):
    # Gauss-3 (exact, in Q(√15)) with its conditions forced into balls: they hold only to
    # digits, but its line-integral certificate for degree ≤ 2 is exact algebra on the
    # tableau, which proves every one of them (definitions §5)
    gauss3 = rkcheck.load(TABLEAUX / "collocation" / "gauss-3.toml")
    unclaimed = gauss3.replace(info=gauss3.info.replace(claims=()))
    result = rkcheck.verify(unclaimed, degree=2, order=8, arithmetic="ball", require=require)
    assert result.verdict == "holds_to_digits" and result.energy_order_all
    assert result.ok and result.to_dict()["summary"]["proven"] is True
    # it proves nothing of the file's claims on other properties: its energy order 6 for
    # degree 3, checked here in balls, is met only to digits
    claimed = rkcheck.verify(gauss3, degree=2, order=8, arithmetic="ball", require=require)
    assert not claimed.ok and "energy_order = 6" in claimed.to_dict()["summary"]["require"]["reason"]
    # without the certificate (degree 4: none holds), the same conditions are no proof
    result = rkcheck.verify(TABLEAUX / "collocation" / "gauss-3.toml", degree=4, order=6, arithmetic="ball",
                            require=require, fail_on="conditions")
    assert not result.energy_order_all and result.verdict == "holds_to_digits"
    assert not result.ok and result.to_dict()["summary"]["proven"] is False


def test_numbers_past_pythons_digit_limit_are_an_rkcheck_error_naming_it():
    # residuals of 1/(10^500 + 1) at order 12 have thousands of digits: past Python's
    # int_max_str_digits (4 300 unless raised) the document is refused with a one-line
    # RkcheckError, not a ValueError; raised, it is written in full
    import sys

    result = rkcheck.verify(rkcheck.from_arrays([["1/(10^500+1)"]], [1]), order=12)
    limit = sys.get_int_max_str_digits()
    try:
        sys.set_int_max_str_digits(4300)
        with pytest.raises(rkcheck.RkcheckError, match="more than 4,300 digits"):
            result.to_dict()
        sys.set_int_max_str_digits(0)
        doc = result.to_dict()
    finally:
        sys.set_int_max_str_digits(limit)
    assert doc["summary"]["conditions_failed"] > 0


def test_a_weight_sum_past_pythons_digit_limit_is_said_by_its_leading_digits():
    # Σb = 111…1 (5 000 ones) has more digits than Python writes under its default limit:
    # the check still runs, and its warning gives the 20 leading digits of 10^4999·(10/9)
    import sys

    before = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(4300)
    try:
        result = rkcheck.verify(rkcheck.from_arrays([["1/2"]], ["1" * 5000]), order=2)
    finally:
        sys.set_int_max_str_digits(before)
    assert result.failed
    assert any(w.startswith("Σb = ≈1.1111111111111111111e4999 ≠ 1") for w in result.warnings)


def test_a_condition_shows_itself_whatever_its_digits():
    # echoed in a REPL, a condition whose residual has more digits than Python writes
    # shows the rest of itself; a small one shows its residual (RK4's [τ⁵]: −1/2880)
    import sys

    assert "residual=Fraction(-1, 2880)" in repr(rkcheck.verify("@rk4", order=5).first_failure)
    before = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(4300)
    try:
        first = rkcheck.verify(rkcheck.from_arrays([["1" * 5000]], [1]), order=3).first_failure
        shown = repr(first)
    finally:
        sys.set_int_max_str_digits(before)
    assert shown.startswith("Condition(tree=FreeTree(level_sequence=(1, 2, 2)") and "verdict=Verdict(state='fails'" in shown
    assert "residual=<Fraction with more digits than sys.get_int_max_str_digits()>" in shown


def test_a_property_text_past_pythons_digit_limit_reads_as_a_decimal(tmp_path):
    """M₁₁ = b(1 − b) − … for a = 1/2 + 10⁻⁵⁰⁰⁰: an exact rational whose integers have more
    than Python's 4 300 digits (a library leaves that limit as it is); the check still
    runs and says the symplectic defect as a decimal, and only writing every exact number
    as text is refused, as a UserError."""
    import sys

    f = tmp_path / "huge.toml"
    f.write_text('[tableau]\nA = [["1/2 + 1/1' + "0" * 5000 + '"]]\nb = ["1"]\n')
    before = sys.get_int_max_str_digits()  # the CLI run in this process may have raised it
    sys.set_int_max_str_digits(4300)
    try:
        result = rkcheck.verify(f, order=3)
        assert result.properties.symplectic.verdict.state == "fails"
        assert "≈" in result.properties.symplectic.reason
        with pytest.raises(rkcheck.UserError, match="4,300 digits"):
            result.to_json()
    finally:
        sys.set_int_max_str_digits(before)


@pytest.mark.parametrize("build", [
    lambda name: rkcheck.Tableau.from_arrays([[0.5]], [1], name=name),
    lambda name: rkcheck.Tableau.from_arrays([[0.5]], [1]).replace(name=name),
    lambda name: rkcheck.ContinuousMethod.from_kernel("tau", name=name),
])
def test_a_name_that_is_not_a_string_is_refused_naming_the_argument(build):
    with pytest.raises(rkcheck.TableauError) as err:
        build(5)
    assert err.value.place == "name" and "expected a string, got int" in str(err.value)
