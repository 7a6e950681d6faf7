"""Hostile and unusual entries: every one is either a correct value or one
UserError line naming the column, in bounded time; nothing recurses with the input length."""

from __future__ import annotations

from fractions import Fraction

import pytest
from support.clirun import run_subprocess
from support.guards import cpu_guard

from rkcheck.errors import UserError
from rkcheck.numbers import expressions as xp
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Constants, Entry


def exact(text: str, **consts: str) -> Fraction | None:
    c = Constants({k: ex.parse(v) for k, v in consts.items()})
    return Entry.parse(text, c).exact


@pytest.mark.parametrize(
    "text, value",
    [
        ("2\u22121", Fraction(1)),  # U+2212 MINUS SIGN, as papers print it
        ("\u22121/4", Fraction(-1, 4)),  # ... also unary
        ("2\u00d73", Fraction(6)),  # U+00D7 MULTIPLICATION SIGN
        ("2\u00b73", Fraction(6)),  # U+00B7 MIDDLE DOT
        ("1/2 \u2212 1/3\u00b73", Fraction(-1, 2)),  # same precedence as - and *
        ("2^\u22121", Fraction(1, 2)),
    ],
)
def test_typographic_operators_mean_their_ascii_twins(text, value):
    assert exact(text) == value


@pytest.mark.parametrize(
    "text, shown, column",
    [
        ("\u03c0", "'\u03c0' (U+03C0)", 1),  # Greek pi
        ("2\u00b2", "'\u00b2' (U+00B2)", 2),  # superscript two (isdigit() is True for it)
        ("\u00e9", "'\u00e9' (U+00E9)", 1),
        ("\u0661", "'\u0661' (U+0661)", 1),  # Arabic-Indic one: int() would accept it
        ("1\u00a0+ 1", "'\\xa0' (U+00A0)", 2),  # no-break space
        ("1\u2009+1", "'\\u2009' (U+2009)", 2),  # thin space
        ("1\x1b[2J", "'\\x1b'", 2),  # an escape sequence stays escaped
        ("1\x0b+1", "'\\x0b'", 2),  # vertical tab: only space, tab and line breaks separate
        ("1+\ud800", "'\\ud800' (U+D800)", 3),  # lone surrogate (JSON can carry one)
        ("2\u2013 1", "'\u2013' (U+2013)", 2),  # en dash is not a minus
        ("2\u22c53", "'\u22c5' (U+22C5)", 2),  # dot operator: only the three listed are read
    ],
)
def test_other_characters_are_refused_by_name_and_column(text, shown, column):
    with pytest.raises(UserError) as err:
        Entry.parse(text)
    message = str(err.value)
    assert message == f"unexpected character {shown} at column {column}"
    assert message.isprintable()


def test_literals_past_pythons_4300_digit_limit_keep_every_digit():
    # repunits by the geometric series: 77…7 (n digits) = 7 (10^n - 1) / 9
    assert exact("7" * 9000) == 7 * (10**9000 - 1) // 9
    assert exact("0." + "3" * 6000) == Fraction(3 * (10**6000 - 1) // 9, 10**6000)


@pytest.mark.parametrize("n", [3000, 9000])
def test_flat_sums_and_products_need_no_recursion(n):
    with cpu_guard(20):
        assert exact("+".join(["1"] * n)) == n
        assert exact("-".join(["1"] * n)) == 2 - n
        assert exact("*".join(["h"] * (n // 3)), h="1/2") == Fraction(1, 2 ** (n // 3))
        node = ex.parse("/".join(["2"] * (n // 3)))
        assert xp.evaluate_exact(node, {}) == Fraction(2, 2 ** (n // 3 - 1))
        k = n // 4
        iv = xp.enclose(ex.parse("+".join(["sqrt(2)"] * k)), 80, "exact", {})
        assert 0 < iv.lo and iv.lo**2 <= 2 * k * k <= iv.hi**2  # contains k·sqrt(2)
        assert iv.hi - iv.lo < Fraction(k, 2**70)
        text = "+".join(["1"] * n)
        assert xp.to_text(ex.parse(text)) == " + ".join(["1"] * n)


def test_to_text_keeps_the_meaning_of_nested_forms():
    # the rendering is re-parsed and compared by value (an independent route)
    for text in ["-(1-2)^3", "2^-1", "(2^3)^2", "2^3^2", "1-(2-3)", "1/(2/3)", "-(-2)", "(-2)^2",
                 "sqrt(2)*(1+sqrt(3))", "root(x^2-2, 2)/3"]:
        a, b = ex.parse(text), ex.parse(xp.to_text(ex.parse(text)))
        assert xp.enclose(a, 64, "exact", {}) == xp.enclose(b, 64, "exact", {}), text


def test_a_chain_of_3000_constants_needs_no_recursion():
    defs = {"c0": "1"} | {f"c{i}": f"c{i - 1} + 1" for i in range(1, 3000)}
    with cpu_guard(20):
        assert exact("c2999", **defs) == 3000


def test_constant_cycles_name_each_constant_once():
    with pytest.raises(UserError) as err:
        Constants({"a": ex.parse("b"), "b": ex.parse("c"), "c": ex.parse("a")})
    assert str(err.value) == "constants.a: constants refer to each other in a cycle: a -> b -> c -> a"


def test_squaring_chains_of_constants_hit_the_size_budget():
    # c0 = 2^1000 (1 001 bits); c_{i+1} = c_i^2 doubles the size: c8 would be 256 001 bits,
    # above MAX_BITS = 200 000; every step alone is allowed, the chain is not
    defs = {"c0": "2^1000"} | {f"c{i}": f"c{i - 1}*c{i - 1}" for i in range(1, 31)}
    with cpu_guard(10):
        with pytest.raises(UserError) as err:
            Constants({k: ex.parse(v) for k, v in defs.items()}).exact_values()
    assert str(err.value).startswith("constants.c8: value at column 3 is too large")


def test_products_of_allowed_powers_hit_the_size_budget():
    # each 2^1000 is allowed, 250 of them (250 001 bits) are not
    text = "*".join(["2^1000"] * 250)
    with cpu_guard(10):
        with pytest.raises(UserError, match="too large"):
            Entry.parse(text)
        with pytest.raises(UserError, match="too large"):
            xp.enclose(ex.parse(text), 64, "exact", {})
    assert exact("*".join(["2^1000"] * 100)) == 2**100_000  # below the budget: exact


def test_overflowing_interval_messages_do_not_crash():
    # sqrt of an interval straddling 0 whose end points overflow a float
    with pytest.raises(UserError, match="cannot be shown to be >= 0"):
        Entry.parse("sqrt(1.000000e400 - 1.000000e400)").enclosure(64, "rounded")


@pytest.mark.parametrize("decimals", ["auto", "rounded", "float64"])
def test_a_rounded_decimal_inside_a_roots_polynomial_is_refused_naming_the_entry(tmp_path, decimals):
    # root(p, k) reads its polynomial's numbers exactly: 1.000000 (7 digits, ± 5e−7) there
    # would be taken at face value, and a verdict could claim what the box does not allow
    # (here the box holds 1.0000003, where p = x² − 3 and the tableau is Gauss-2 exactly)
    path = tmp_path / "root.toml"
    path.write_text('[constants]\nr = "root(x^2 - 3 - (1.000000 - 10000003/10000000)*x, 2)"\n[tableau]\n'
                    'A = [["1/4", "1/4 - r/6"], ["1/4 + r/6", "1/4"]]\nb = ["1/2", "1/2"]\n')
    run = run_subprocess("verify", str(path), "--order", "3", "--decimals", decimals)
    assert run.code == 2 and "Traceback" not in run.err
    assert f"{path}: A[1][2]: root(p, k)" in run.err and "1.000000" in run.err
    assert run_subprocess("verify", str(path), "--order", "3", "--decimals", "exact").code in (0, 1)
