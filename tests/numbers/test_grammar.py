"""The entry grammar and the number model (SPEC §5), against values computed by hand."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest
from support.guards import cpu_guard

from rkcheck.errors import UserError
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Constants, Entry
from rkcheck.numbers.intervals import Interval


def exact(text: str, **consts: str) -> Fraction | None:
    c = Constants({k: ex.parse(v) for k, v in consts.items()})
    return Entry.parse(text, c).exact


@pytest.mark.parametrize(
    "text, value",
    [
        ("1/4", Fraction(1, 4)),
        ("-5/48", Fraction(-5, 48)),
        ("2^-1", Fraction(1, 2)),  # exponent binds the unary minus
        ("-2^2", Fraction(-4)),  # ... and ^ binds tighter than unary minus
        ("2**3**2", Fraction(512)),  # right associative: 2^(3^2)
        ("(1+2)*3 - 4/8", Fraction(17, 2)),
        ("1 - 2 - 3", Fraction(-4)),  # left associative
        ("12/4/3", Fraction(1)),
        ("1.5e-3", Fraction(3, 2000)),
        (".5", Fraction(1, 2)),
        ("5.", Fraction(5)),
        ("sqrt(9/4)", Fraction(3, 2)),  # roots of rational squares stay exact
        ("--3", Fraction(3)),
        ("+7", Fraction(7)),
    ],
)
def test_exact_values(text, value):
    assert exact(text) == value


def test_irrational_entries_have_no_exact_value_and_a_tight_enclosure():
    e = Entry.parse("1/2 - sqrt(3)/6")
    assert e.exact is None and e.uses_sqrt
    enc = e.enclosure(200)
    # (3 - sqrt 3)/6 by an independent route: integer square root at 400 bits
    r = math.isqrt(3 << 800)
    lo = (Fraction(3) - Fraction(r + 1, 1 << 400)) / 6
    hi = (Fraction(3) - Fraction(r, 1 << 400)) / 6
    assert enc.lo <= hi and enc.hi >= lo  # both contain the true value, so they overlap
    assert enc.hi - enc.lo < Fraction(1, 2**190)


def test_sqrt_enclosure_contains_the_root():
    for bits in (10, 64, 300):
        enc = Interval.point(Fraction(2)).sqrt(bits)
        assert enc.lo * enc.lo <= 2 <= enc.hi * enc.hi
        assert enc.hi - enc.lo <= Fraction(2, 1 << bits)


def test_constants_may_refer_to_each_other_in_any_order():
    assert exact("h + 1", h="r/2", r="3") == Fraction(5, 2)


def test_long_decimal_keeps_every_digit():
    digits = "0.21132486540518711774542560974902127217619912436493"
    e = Entry.parse(digits)
    assert e.exact == Fraction(21132486540518711774542560974902127217619912436493, 10**50)
    assert e.rounded_digits == 50
    # rounded reading: half a unit of the 50th decimal
    enc = e.enclosure(64, "rounded")
    assert enc.hi - enc.lo == Fraction(1, 10**50)
    assert e.enclosure(64, "exact").is_point


@pytest.mark.parametrize(
    "text, digits",
    [("0.5", None), ("0.25", None), ("0.12345", None), ("0.123456", 6), ("1.50e-3", None),
     ("2.000000", 7), ("0.0000", None), ("1234567", None)],
)
def test_which_decimals_are_rounded(text, digits):
    # definitions §5 with the decision in docs/decisions.md: decimals with >= 6 significant digits are
    # rounded; shorter ones and integers are exact.
    assert Entry.parse(text).rounded_digits == digits


@pytest.mark.parametrize(
    "text, message",
    [
        ("1/4 + )", "unexpected ')' at column 7"),
        ("sqrt(3", "unexpected end of expression at column 7"),
        ("1 2", "unexpected '2' at column 3"),
        ("", "empty expression"),
        ("1/0", "division by zero at column 2"),
        ("1/(2-2)", "division by zero at column 2"),
        ("sqrt(-2)", "square root of a negative number"),
        ("cos(1)", "unknown function 'cos' at column 1"),
        ("2^(1/2)", "exponent 1/2 at column 2 is not an integer"),
        ("1 $ 2", "unexpected character '$' at column 3"),
        ("r5 + 1", "unknown constant 'r5' at column 1"),
        ("sqrt", "sqrt needs parentheses"),
        ("1e99999", "out of range"),
    ],
)
def test_errors_name_the_column(text, message):
    with pytest.raises(UserError) as err:
        Entry.parse(text)
    assert message in str(err.value)


def test_constant_cycle_is_reported():
    with pytest.raises(UserError) as err:
        Constants({"a": ex.parse("b + 1"), "b": ex.parse("a")})
    assert "cycle" in str(err.value) and "constants." in str(err.value)


HOSTILE = {
    "dunder import": ("__import__('os')", "unexpected character"),
    "class attribute": ("().__class__", "unexpected character '.' at column 3"),
    "power tower": ("9**9**9**9", "out of range"),
    "10000-deep parentheses": ("(" * 10_000 + "1" + ")" * 10_000, "entry too long"),
    "150-deep parentheses": ("(" * 150 + "1" + ")" * 150, "parentheses nested deeper than 100 at column 101"),
    "10000 unary minus": ("-" * 10_000 + "1", "nested deeper than 100"),
    "5 MB entry": ("1" * 5_000_000, "entry too long"),
    "huge power": ("(10^1000)^1000", "too large"),
}


@pytest.mark.parametrize("text, message", list(HOSTILE.values()), ids=list(HOSTILE))
def test_hostile_strings_are_refused_quickly(text, message):
    with cpu_guard(10):
        with pytest.raises(UserError) as err:
            Entry.parse(text)
    assert message in str(err.value)
    assert len(str(err.value)) < 200  # one clean line


def test_no_eval_anywhere_in_the_package():
    # file content must never reach eval/exec: the package never calls them at all
    import ast
    import pathlib

    import rkcheck

    root = pathlib.Path(rkcheck.__file__).parent
    for path in root.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
                assert node.func.id not in ("eval", "exec", "compile", "__import__"), f"{node.func.id} in {path}"


def test_to_text_round_trips():
    for text in ["1/4 - r3/6", "-(1 + 2)^2", "2^-1", "sqrt(3)/6 - 1/2", "a - (b - c)", "a/(b*c)"]:
        node = ex.parse(text)
        again = ex.parse(xp.to_text(node))
        assert again == node or xp.to_text(again) == xp.to_text(node)


# ------------------------------------------------------------------ root(p, k)


def test_root_is_the_kth_real_root_certified():
    # Shifted Legendre P4 (Gauss-4 nodes): closed form 1/2 ± sqrt(3/7 ∓ 2/7·sqrt(6/5))/2
    p4 = "70*x^4 - 140*x^3 + 90*x^2 - 20*x + 1"
    closed = [
        "1/2 - sqrt(3/7 + 2/7*sqrt(6/5))/2", "1/2 - sqrt(3/7 - 2/7*sqrt(6/5))/2",
        "1/2 + sqrt(3/7 - 2/7*sqrt(6/5))/2", "1/2 + sqrt(3/7 + 2/7*sqrt(6/5))/2",
    ]
    for k, form in enumerate(closed, start=1):
        r = Entry.parse(f"root({p4}, {k})")
        assert r.exact is None and r.uses_sqrt
        a, b = r.enclosure(200), Entry.parse(form).enclosure(200)
        assert a.hi - a.lo < Fraction(1, 2**200)
        assert a.lo <= b.hi and b.lo <= a.hi  # the same number


def test_rational_roots_are_exact_and_x_is_bound_inside_root_only():
    assert Entry.parse("root(x^2 - 4, 2)").exact == 2
    assert Entry.parse("root((x - 1/3)*(x - 2)^2, 1)").exact == Fraction(1, 3)
    assert Entry.parse("root((x - 1/3)*(x - 2)^2, 2)").exact == 2  # double root counted once
    assert xp.to_text(ex.parse("root(x^2 - 2, 1)")) == "root(x^2 - 2, 1)"
    with pytest.raises(UserError, match="unknown constant 'x'"):
        Entry.parse("x + 1")


@pytest.mark.parametrize(
    "text, message",
    [
        ("root(x^2 + 1, 1)", "only 0 real roots"),
        ("root(x^2 - 2, 3)", "only 2 real roots"),
        ("root(y^2 - 2, 1)", "only the variable 'x'"),
        ("root(x^2 - 2)", "takes 2 arguments"),
        ("sqrt(2, 3)", "takes 1 argument"),
        ("root(x^2 - 2, 1/2)", "k must be a positive integer"),
        ("root(5, 1)", "degree >= 1"),
        ("root(x^-1, 1)", "negative power"),
        ("root(sqrt(x), 1)", "no function inside"),
    ],
)
def test_root_errors_name_the_problem(text, message):
    with pytest.raises(UserError, match=message):
        Entry.parse(text)
