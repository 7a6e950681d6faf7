"""Bad input to the family commands: each a one-line error naming the place, exit 2, no
partial output."""

from __future__ import annotations

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

from rkcheck.numbers.parametric import MAX_PARAMETERS

FAMILIES = TABLEAUX / "families"


def _one_line(r, *words):
    assert r.code == 2 and r.err.count("\n") == 1 and not r.out, (r.code, r.out, r.err)
    for w in words:
        assert w in r.err, r.err


def test_too_many_parameters(capsys, tmp_path):
    n = MAX_PARAMETERS + 1
    names = [f"p{k}" for k in range(n)]
    path = tmp_path / "many.toml"
    entries = ", ".join(f'"{x}"' for x in names[:1])
    path.write_text("[parameters]\n" + "\n".join(f'{x} = "free"' for x in names)
                    + f"\n[tableau]\nA = [[{entries}]]\nb = [\"1\"]\n", encoding="utf-8")
    _one_line(run_cli(capsys, "solve", str(path), "--degree", "2", "--order", "2"), "MAX_PARAMETERS", str(n))


@pytest.mark.parametrize(("equation", "words"), [
    ("a11 = delta", ["unknown name 'delta'", "--where"]),
    ("sqrt(a11) = 1", ["a parameter under sqrt", "--where"]),
    ("2^a11 = 1", ["a parameter in an exponent", "--where"]),
    ("a11 = (1", ["cannot read the equation", "--where"]),
    # the option's own numbers: the error names --where, not the family file
    ("a11 = 1/0", ["cannot read the equation 'a11 = 1/0': division by zero", "--where"]),
    ("a11 = 2^100000", ["exponent 100000", "--where"]),
])
def test_bad_where_equations(capsys, equation, words):
    r = run_cli(capsys, "solve", str(FAMILIES / "theorem1-s2-m3.toml"), "--degree", "3", "--order", "6",
                "--where", equation)
    _one_line(r, *words)
    assert "theorem1-s2-m3.toml" not in r.err


def test_a_kernel_from_python_names_the_entry_it_cannot_read():
    import rkcheck

    for A, b, place in (("tau", "1/0", "continuous.b"), ("tau/0", "1", "continuous.A")):
        with pytest.raises(rkcheck.RkcheckError, match=f"^{place}: division by zero"):
            rkcheck.ContinuousMethod.from_kernel(A, b=b).kernel


def test_parameter_under_root_in_a_constant(capsys, tmp_path):
    path = tmp_path / "c.toml"
    path.write_text('[parameters]\nbeta = "free"\n[constants]\nk = "root(x^2 - beta, 2)"\n'
                    '[tableau]\nA = [["k"]]\nb = ["1"]\n', encoding="utf-8")
    _one_line(run_cli(capsys, "verify", str(path)), "constants.k")


def test_time_limit_prints_nothing_partial(capsys):
    r = run_cli(capsys, "solve", str(FAMILIES / "theorem1-s3-m5.toml"), "--degree", "5", "--order", "6",
                "--where", "b1 + b2 + b3 = 1", "--max-seconds", "1", "--format", "json")
    _one_line(r, "time limit")


def test_unknown_route_and_structured_on_a_family_it_does_not_fit(capsys):
    r = run_cli(capsys, "solve", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--degree", "3", "--order", "6",
                "--route", "structured")
    _one_line(r, "--route: the structured route needs A free")  # the option as typed, not the API's "route"


def test_emit_with_a_family_needs_a_family_language(capsys):
    r = run_cli(capsys, "conditions", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--order", "4", "--emit", "matlab")
    _one_line(r, "python, sympy, julia, latex")


@pytest.mark.parametrize("name, lang", [("lambda", "python"), ("Fraction", "python"), ("sympy", "sympy"),
                                        ("end", "julia"), ("theta", "python")])
def test_emit_refuses_a_parameter_the_code_could_not_name(capsys, tmp_path, name, lang):
    f = tmp_path / "f.toml"
    f.write_text(f'[parameters]\n{name} = "free"\n[tableau]\nA = [["{name}"]]\nb = ["1"]\n')
    r = run_cli(capsys, "conditions", str(f), "--order", "3", "--emit", lang)
    _one_line(r, "--emit", repr(name), f"{lang} code")


@pytest.mark.parametrize("entry, message", [("k + 3^100000000", "out of range (|n| <= 1000)"),
                                            ("k + (sqrt(2) + 1)^100000000", "out of range (|n| <= 1000)"),
                                            ("k + (3^999)^999", "too large")])
def test_a_familys_numbers_keep_the_entries_limits(capsys, tmp_path, entry, message):
    """The entry grammar's limits on powers hold in a family's parameter-free parts too:
    3^100000000 was computed (a hang) where a tableau's entry is refused at once."""
    f = tmp_path / "f.toml"
    f.write_text(f'[parameters]\nk = "free"\n[tableau]\nA = [["{entry}"]]\nb = ["1"]\n')
    r = run_cli(capsys, "verify", str(f), "--order", "2")
    _one_line(r, "A[1][1]", message)


def _family(tmp_path, entry: str, names: list[str], kernel: bool = False):
    path = tmp_path / "grow.toml"
    body = f'[continuous]\nA = "{entry}"\n' if kernel else f'[tableau]\nA = [["{entry}"]]\nb = ["1"]\n'
    path.write_text("[parameters]\n" + "".join(f'{x} = "free"\n' for x in names) + body, encoding="utf-8")
    return path


@pytest.mark.parametrize(("entry", "kernel", "words"), [
    # (p0 + … + p9)^64 has C(73, 9) ≈ 10^11 terms
    ("(" + "+".join(f"p{k}" for k in range(10)) + ")^64", False, ["A[1][1]", "MAX_ENTRY_TERMS", "column 32"]),
    ("tau*(" + "+".join(f"p{k}" for k in range(10)) + "+sigma)^64", True, ["continuous.A", "MAX_ENTRY_TERMS"]),
    # 4 097 terms to the 64th: 64 products of up to 4 097 × 258 049 terms
    ("(((p0+1)^64)^64)^64", False, ["A[1][1]", "MAX_PRODUCT_WORK", "× 4,097 terms"]),
])
def test_an_entry_that_expands_past_the_limits(capsys, tmp_path, entry, kernel, words):
    path = _family(tmp_path, entry, [f"p{k}" for k in range(10)] if "p9" in entry else ["p0"], kernel)
    _one_line(run_cli(capsys, "verify", str(path), "--order", "2", "--degree", "2"), str(path), *words)


def test_conditions_that_outgrow_the_limits_are_refused(capsys, tmp_path, monkeypatch):
    from rkcheck.evaluation import polynomial

    # a 2-stage tableau with every entry free: its conditions' terms, counted by hand
    # from the reference's polynomials, stay small at order 3 and grow past a small limit
    path = tmp_path / "free2.toml"
    names = ["a11", "a12", "a21", "a22", "b1", "b2"]
    path.write_text("[parameters]\n" + "".join(f'{x} = "free"\n' for x in names)
                    + '[tableau]\nA = [["a11", "a12"], ["a21", "a22"]]\nb = ["b1", "b2"]\n', encoding="utf-8")
    whole = run_cli(capsys, "verify", str(path), "--order", "3", "--degree", "none", "--format", "json")
    monkeypatch.setattr(polynomial, "MAX_FAMILY_TERMS", 400)
    assert run_cli(capsys, "verify", str(path), "--order", "3", "--degree", "none", "--format", "json").out == whole.out
    _one_line(run_cli(capsys, "verify", str(path), "--order", "6", "--degree", "none"), str(path), "MAX_FAMILY_TERMS",
              "400")
    monkeypatch.setattr(polynomial, "MAX_PRODUCT_WORK", 50)
    _one_line(run_cli(capsys, "verify", str(path), "--order", "6", "--degree", "none"), str(path), "MAX_PRODUCT_WORK")


def test_claims_in_a_family_are_not_judged_and_it_says_so(capsys, tmp_path):
    import json

    path = tmp_path / "fexp.toml"
    path.write_text('[parameters]\nx = "free"\n[tableau]\nA = [["x"]]\nb = ["1"]\n'
                    '[expect]\nenergy_order = {degree = 3, value = "all"}\nsymplectic = true\n', encoding="utf-8")
    text = run_cli(capsys, "verify", str(path), "--order", "4", "--degree", "3")
    assert text.code == 0 and "claims are not judged for a family" in text.err + text.out
    doc = json.loads(run_cli(capsys, "verify", str(path), "--order", "4", "--degree", "3", "--format", "json").out)
    assert any("claims are not judged for a family" in w for w in doc["warnings"])
    # a family without claims has no such warning
    path.write_text('[parameters]\nx = "free"\n[tableau]\nA = [["x"]]\nb = ["1"]\n', encoding="utf-8")
    doc = json.loads(run_cli(capsys, "verify", str(path), "--order", "4", "--degree", "3", "--format", "json").out)
    assert not any("claims" in w for w in doc["warnings"])


def test_an_order_out_of_range_names_where_it_was_given(capsys, tmp_path):
    path = tmp_path / "ford.toml"
    path.write_text('[parameters]\nx = "free"\n[tableau]\nA = [["x"]]\nb = ["1"]\n[check]\norder = 20\n',
                    encoding="utf-8")
    for command in (["verify", str(path)], ["sweep", str(path), "--grid", "x=0:1:3"]):
        _one_line(run_cli(capsys, *command), f"{path}: check.order: expected an integer from 1 to 12, got 20")
    _one_line(run_cli(capsys, "verify", str(FAMILIES / "seed-kernel-zeta-0.toml"), "--order", "13"),
              "--order: expected an integer from 1 to 12, got 13")


def test_check_options_that_do_not_apply_to_a_family_are_named_not_dropped(capsys):
    import json

    path = str(FAMILIES / "seed-kernel-zeta-0.toml")
    doc = json.loads(run_cli(capsys, "verify", path, "--decimals", "rounded", "--dps", "80", "--format", "json").out)
    assert any(w.startswith("--dps, --decimals do not apply to a family") for w in doc["warnings"]), doc["warnings"]
    plain = json.loads(run_cli(capsys, "verify", path, "--format", "json").out)
    assert not any("do not apply" in w for w in plain["warnings"])
    assert doc["conditions"] == plain["conditions"]  # the conditions themselves are the same
    # a family of kernels too: its surrogate is built again for the order, and the note
    # was lost with the family it widened
    kernel = str(FAMILIES / "continuous-collocation-kappa.toml")
    doc = json.loads(run_cli(capsys, "verify", kernel, "--order", "3", "--dps", "80", "--format", "json").out)
    assert any(w.startswith("--dps does not apply to a family") for w in doc["warnings"]), doc["warnings"]


def test_conditions_of_a_family_say_output_goes_with_emit(capsys):
    # -o without --emit was refused by a message listing --output among the options allowed
    run = run_cli(capsys, "conditions", str(TABLEAUX / "families" / "seed-kernel-zeta-0.toml"), "--order", "3",
                  "--format", "json", "-o", "out.json")
    assert run.code == 2 and run.err.rstrip().endswith("(--output goes with --emit)"), run.err
