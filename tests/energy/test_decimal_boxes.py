"""Decimal tableaux as one box of inputs (definitions §5.2), the three decimals modes and
the proof gate (§5.3), against values derived independently:

* the residuals on the box come from the brute-force reference (``reference``: exact
  Fractions, SPEC §3), evaluated at the box's corners, centre and random points;
* the 1-stage case ``A = [[1/2]]``: by hand, ``R([τ²]) = (Σb)²/2 − bᵀc = b(b − 1)/2`` (for
  one stage c = 1/2, so ``bᵀc = b/2``);
* RK4's classical order 4 (Kutta 1901) and energy order 4 for general H (its conditions
  at five vertices fail: Hairer–Lubich–Wanner, and the engine's exact check);
* the binary64 rounding interval from Python's own ``math.nextafter``.
"""

from __future__ import annotations

import itertools
import json
import math
import random
import sys
from decimal import Decimal
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from support import reference as ref
from support.clirun import run_cli, run_subprocess

import rkcheck
from rkcheck.energy.check import check
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.doubles import double_interval
from rkcheck.numbers.grammar import parse
from rkcheck.options import CheckOptions
from rkcheck.verdicts import FAILS, HOLDS_TO_DIGITS


def _write(tmp_path, name: str, doc: dict) -> str:
    p = tmp_path / name
    p.write_text(json.dumps(doc))
    return str(p)


def _json(run) -> dict:
    assert run.code in (0, 1), run.err
    return json.loads(run.out)


# ------------------------------------------------------------------ literal intervals


@pytest.mark.parametrize("x", [1 / 6, 1 / 3, 0.1, 2.0**-30, 1e300, 1.0, 3.0])
def test_double_interval_is_the_set_of_reals_rounding_to_the_double(x):
    lo, hi = double_interval(Fraction(repr(x)))
    below, above = Fraction(math.nextafter(x, -math.inf)), Fraction(math.nextafter(x, math.inf))
    assert lo == (Fraction(x) + below) / 2 and hi == (Fraction(x) + above) / 2
    # just inside rounds to x, just outside does not (ties aside, float() rounds correctly)
    eps = (hi - lo) / 10**6
    assert float(lo + eps) == x and float(hi - eps) == x
    assert float(lo - eps) != x and float(hi + eps) != x


def test_auto_covers_the_double_only_for_shortest_reprs():
    sixth = parse("0.16666666666666666")  # repr(1/6)
    lo, hi = sixth.interval("auto")
    assert lo <= Fraction(1, 6) <= hi  # the double's interval contains 1/6
    lo_r, hi_r = sixth.interval("rounded")
    assert hi_r < Fraction(1, 6)  # 1/6 − 0.16666666666666666 = 6.7e-18 > half a unit, 5e-18
    longer = parse("0.166666666666666666666")  # not a double's shortest repr: half-unit only
    assert longer.interval("auto") == longer.interval("rounded")
    assert parse("0.5").interval("auto") is None and parse("0.5").interval("float64") is not None
    assert parse("0.0").interval("float64") is None  # zero keeps the structure exact


@pytest.mark.parametrize("x", [2.0**49, 2.0**49 + 1, 1e15, 9007199254740993.0, 123456.0])
def test_auto_covers_a_whole_double_written_with_its_point_zero(x):
    # repr(2.0**49) = '562949953421312.0' is a double's shortest repr as written: auto
    # covers the reals that round to it, whose half-ulp (1/16) is wider than the literal's
    # half unit (1/20), as float64 does
    literal = parse(repr(x))
    (lo, hi), (d_lo, d_hi) = literal.interval("auto"), literal.interval("float64")
    assert repr(x).endswith(".0") and lo <= d_lo and d_hi <= hi


def test_a_whole_double_and_its_true_value_are_one_verdict(capsys, tmp_path):
    # a21 = 2^49 + 0.06 rounds to the double 2^49, written as Python writes it; b makes
    # [τ²]'s residual vanish at the true a21: so it holds to digits, not fails
    path = tmp_path / "big.toml"
    path.write_text('[tableau]\nA = [["0", "0"], ["562949953421312.0", "0"]]\n'
                    'b = ["1 - 1/(2*(562949953421312 + 3/50))", "1/(2*(562949953421312 + 3/50))"]\n')
    assert float(Fraction(2**49) + Fraction(3, 50)) == 2.0**49
    doc = _json(run_cli(capsys, "verify", str(path), "--degree", "2", "--order", "2", "--format", "json"))
    assert [c["state"] for c in doc["conditions"]] == ["holds_to_digits"]


@pytest.mark.parametrize("text", ["1e-400", "2e-324", "2.4703282292062327e-324"])
def test_float64_reads_a_decimal_below_the_subnormals_as_zeros_interval(text):
    # IEEE 754 round to nearest, ties to even: every real in (0, 2^-1075] rounds to +0, so
    # the double such a literal reads as is zero and it stands for [0, 2^-1075]
    lo, hi = parse(text).interval("float64")
    half = Fraction(1, 2**1075)
    assert (lo, hi) == (0, half) and lo <= parse(text).value <= hi
    assert float(half) == 0.0 and float(half + Fraction(1, 10**400)) == 5e-324


def test_float64_refuses_a_decimal_no_double_stands_for(tmp_path):
    # the doubles end where rounding reaches infinity, at 2^1024 − 2^970 (IEEE 754)
    limit = 2**1024 - 2**970
    with pytest.raises(OverflowError):
        float(Fraction(limit))
    top = parse(repr(sys.float_info.max))  # the largest double: reals up to the limit round to it
    assert top.interval("float64")[1] == limit and parse(str(limit - 1) + ".0").interval("float64") == top.interval("float64")
    path = _write(tmp_path, "big.json", {"tableau": {"A": [["0", "0"], ["2/3", "0"]], "b": ["1/4", "3/4 + 0*1e400"]}})
    run = run_subprocess("verify", path, "--decimals", "float64")
    assert run.code == 2 and "b[2]: 1e400 is beyond the range of binary64 doubles" in run.err
    assert _json(run_subprocess("verify", path, "--format", "json"))["summary"]["verdict"] == "fails"


def test_float64_judges_an_entry_below_the_subnormals_over_its_interval(tmp_path):
    # a21 = sqrt(1e-400) reads as sqrt([0, 2^-1075]) ∋ 0: R([[τ]²]) = b2·a21²/… and
    # R([[τ²]τ]) vanish at a21 = 0 (explicit, by hand), so on that box they cannot fail,
    # while read exactly (a21 = 1e-200) they do
    path = _write(tmp_path, "tiny.json", {"tableau": {"A": [["0", "0"], ["sqrt(1e-400)", "0"]], "b": ["1/2", "1/2"]}})
    rows = {d: {c["id"]: c["state"] for c in _json(run_subprocess(
        "verify", path, "--order", "4", "--decimals", d, "--format", "json"))["conditions"]} for d in ("float64", "exact")}
    assert rows["exact"]["1,2,3,2,3"] == rows["exact"]["1,2,3,3,2"] == FAILS
    assert rows["float64"]["1,2,3,2,3"] == rows["float64"]["1,2,3,3,2"] == HOLDS_TO_DIGITS


@pytest.mark.parametrize("text, digits", [("0.500000000000000000000000000000", 30), ("0.5000000000000000", 16),
                                          ("0.16666666666666666000", 20), ("1.000000", 7)])
def test_auto_judges_the_binary64_reading_from_the_text(text, digits):
    # by hand: a literal with D significant digits whose last digit sits at 10^e stands
    # for ± 5·10^(e−1); these are not what repr() prints for their double (0.5, 1/6, 1.0
    # print as '0.5', '0.16666666666666666', '1.0'), so the double's ±2^-54-wide interval
    # must not be added, whatever the value
    lit = parse(text)
    assert lit.digits == digits
    exponent = -(len(text.split(".")[1]))
    half = Fraction(5, 10) * Fraction(10) ** exponent
    assert lit.interval("auto") == (lit.value - half, lit.value + half)
    assert lit.interval("auto") == lit.interval("rounded")


def test_thirty_digit_half_holds_to_thirty_digits_not_to_sixteen(tmp_path):
    # one stage, a = 0.5 (30 digits written), b = 1: R([τ²]) = 1/2 − a (by hand), so on the
    # box |R| ≤ 5·10⁻³¹ (30 digits); read as the double 0.5 it would be 2⁻⁵⁴ ≈ 5.6·10⁻¹⁷
    path = _write(tmp_path, "half30.json", {"tableau": {"A": [["0.500000000000000000000000000000"]], "b": ["1"]}})
    doc = _json(run_subprocess("verify", path, "--degree", "2", "--order", "2", "--format", "json"))
    row = next(c for c in doc["conditions"] if c["id"] == "1,2,2")
    assert row["state"] == "holds_to_digits" and row["digits"] >= 30
    assert Fraction(row["radius"]) <= Fraction(5, 10**31) * 2


# ------------------------------------------------------------------ the cases


def test_b_close_to_one_fails_on_the_whole_box(tmp_path):
    path = _write(tmp_path, "b.json", {"tableau": {"A": [["1/2"]], "b": ["0.9999999999"]}})
    # by hand: R = b(b − 1)/2 on b ∈ [0.99999999985, 0.99999999995]: both ends negative
    h = Fraction(1, 2 * 10**10)
    for b in (Fraction("0.9999999999") - h, Fraction("0.9999999999") + h):
        assert b * (b - 1) / 2 < 0
    doc = _json(run_subprocess("verify", path, "--degree", "2", "--order", "4", "--format", "json"))
    assert doc["summary"]["verdict"] == "fails"
    assert doc["summary"]["inconsistent"] is True
    assert doc["summary"]["first_failure"]["id"] == "1,2,2"
    row = next(c for c in doc["conditions"] if c["id"] == "1,2,2")
    assert row["state"] == "fails"


def test_rk4_from_json_dumps_keeps_order_four(tmp_path):
    A = [[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 1.0, 0]]
    b = [1 / 6, 1 / 3, 1 / 3, 1 / 6]
    path = tmp_path / "rk4.json"
    path.write_text(json.dumps({"tableau": {"A": A, "b": b}}))  # 0.16666666666666666, ...
    doc = _json(run_subprocess("verify", str(path), "--order", "5", "--format", "json"))
    s = doc["summary"]
    # order 4 is reached to digits only: the orders count proven holds (definitions §5),
    # and a(τ) = Σb = 1 already holds only to digits for these doubles' rounding intervals
    assert (s["classical_order"], s["classical_order_to_digits"]) == (0, 4)
    assert (s["energy_order"], s["energy_order_to_digits"]) == (1, 4)
    assert 14 <= s["classical_order_digits"] <= 17 and 14 <= s["energy_order_digits"] <= 17
    held = [c for c in doc["conditions"] if c["order"] <= 4]
    assert held and all(c["state"] == "holds to digits" or c["digits"] for c in held)
    assert 14 <= s["per_order"][0]["min_digits"] <= 17
    rounded = _json(run_subprocess("verify", str(path), "--order", "5", "--decimals", "rounded", "--format", "json"))
    assert rounded["summary"]["classical_order_to_digits"] == 3  # half a unit of the 17th digit excludes 1/6


def test_six_digit_gauss2_is_not_called_a_certificate(tmp_path):
    r3 = 3**0.5 / 6
    A = [[f"{0.25:.6f}", f"{0.25 - r3:.6g}"], [f"{0.25 + r3:.6g}", f"{0.25:.6f}"]]
    path = _write(tmp_path, "g2.json", {"tableau": {"A": A, "b": ["0.500000", "0.500000"]}})
    run = run_subprocess("verify", path, "--degree", "2", "--order", "6")
    assert run.code == 0
    last = run.out.strip().splitlines()
    text = " ".join(last[-3:])
    assert "OK to" in text and "not a proof" in text and "certificate" not in text
    gate = run_subprocess("verify", path, "--degree", "2", "--order", "6", "--require", "proof")
    assert gate.code == 1 and "--require proof" in gate.out
    assert run_subprocess("verify", path, "--degree", "2", "--order", "6", "--require", "digits:3").code == 0
    assert run_subprocess("verify", path, "--degree", "2", "--order", "6", "--require", "digits:30").code == 1


def test_require_proof_passes_exact_tableaux(tmp_path):
    path = _write(tmp_path, "mid.json", {"tableau": {"A": [["1/2"]], "b": ["1"]}})
    run = run_subprocess("verify", path, "--degree", "2", "--order", "6", "--require", "proof")
    assert run.code == 0


@pytest.mark.parametrize("bad", ["maybe", "digits:", "digits:0", "digits:x", "proof:3"])
def test_require_rejects_bad_values_in_one_line(tmp_path, bad):
    path = _write(tmp_path, "mid.json", {"tableau": {"A": [["1/2"]], "b": ["1"]}})
    run = run_subprocess("verify", path, "--require", bad)
    assert run.code == 2 and len(run.err.strip().splitlines()) == 1 and "Traceback" not in run.err


# ------------------------------------------------------------------ box soundness


def _reference_conditions(max_vertices: int, degree: int):
    out = []
    for n in range(3, max_vertices + 1):
        for cond in ref.energy_conditions(n, degree):
            keys = {ref.canonicalize(u) for u, *_ in cond["terms"]}
            out.append((keys, cond))
    return out


REFERENCE = _reference_conditions(5, 3)


def _decimal(x: Fraction, digits: int) -> str:
    if x == 0:
        return "0"
    e = math.floor(math.log10(abs(float(x))))
    q = round(x * Fraction(10) ** (digits - 1 - e))
    return format(Decimal(q).scaleb(e - digits + 1), "f")  # exactly `digits` significant digits


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10**9), digits=st.integers(6, 9))
def test_box_verdicts_hold_at_every_point_of_the_box(seed, digits):
    rng = random.Random(seed)
    # near a consistent method, so that conditions are small and the box matters
    b0 = Fraction(rng.randint(1, 11), 12)
    b = [b0, 1 - b0]
    if seed % 2:  # AVF over a 2-point rule (A = c bᵀ): its low conditions vanish exactly
        c = [Fraction(rng.randint(-12, 12), rng.randint(1, 12)) for _ in range(2)]
        A = [[ci * bj for bj in b] for ci in c]
    else:
        A = [[Fraction(rng.randint(-12, 12), rng.randint(1, 12)) for _ in range(2)] for _ in range(2)]
    texts_A = [[_decimal(x, digits) for x in row] for row in A]
    texts_b = [_decimal(x, digits) for x in b]
    tab = Tableau.from_values(texts_A, texts_b)
    if not tab.is_box("auto"):
        return
    res = check(tab, CheckOptions(degree=3, order=4))
    centre_A = [[Fraction(t) for t in row] for row in texts_A]
    centre_b = [Fraction(t) for t in texts_b]
    boxes = [(e.enclosure(200, "auto").lo, e.enclosure(200, "auto").hi) for row in tab.A for e in row]
    boxes += [(e.enclosure(200, "auto").lo, e.enclosure(200, "auto").hi) for e in tab.b]
    points = [list(corner) for corner in itertools.product(*boxes)]
    points.append([x for row in centre_A for x in row] + centre_b)
    for _ in range(4):
        points.append([lo + (hi - lo) * Fraction(rng.randint(0, 1000), 1000) for lo, hi in boxes])
    states = set()
    for r in res.conditions:
        states.add(r.verdict.state)
        key = ref.canonicalize(r.level_sequence)
        cond = next(c for keys, c in REFERENCE if key in keys)
        values = []
        for p in points:
            Ap = [p[0:2], p[2:4]]
            values.append(ref.energy_residual(cond, Ap, p[4:6]))
        if r.verdict.state == FAILS:
            assert all(v > 0 for v in values) or all(v < 0 for v in values), r.id
        elif r.verdict.state == HOLDS_TO_DIGITS:
            assert all(abs(v) <= Fraction(1, 10**r.verdict.digits) for v in values), r.id


def _decimal_tableau(A, b, digits: int) -> str:
    """A TOML tableau of exact entries written as ``digits``-digit decimals (rounded)."""
    def text(x: Fraction) -> str:
        if x == 0:
            return "0"
        e = math.floor(math.log10(abs(x)))
        q = round(x * Fraction(10) ** (digits - 1 - e))
        return f"{q}e{e - digits + 1}"
    rows = ", ".join("[" + ", ".join(f'"{text(x)}"' for x in row) + "]" for row in A)
    return f"[tableau]\nA = [{rows}]\nb = [{', '.join(chr(34) + text(x) + chr(34) for x in b)}]\n"


def _half_unit(x: Fraction, digits: int) -> Fraction:
    """Half a unit of the last of ``digits`` significant digits of the decimal x: the
    radius of its box (a corner of the box, not beyond it)."""
    if x == 0:
        return Fraction(0)
    e = math.floor(math.log10(abs(x)))
    if Fraction(10) ** e > abs(x):  # log10 rounded up across a power of ten
        e -= 1
    return Fraction(1, 2) * Fraction(10) ** (e - digits + 1)


@pytest.mark.parametrize("digits", [400, 600])
def test_decimals_of_hundreds_of_digits_are_judged_to_their_own_digits(tmp_path, digits):
    # a box whose radii lie below float64's range: its verdicts reach the input's own
    # digits (past float64's 2^−1074, about 323 digits), and each stays sound — every
    # residual at the box's centre and at random corners, exactly, within 10^−D
    # AVF over the Radau IIA rule (1/3, 1; 3/4, 1/4): its conditions hold for cubic H and
    # some fail beyond; 1/12 has no finite decimal, so the box is not a point
    rng = random.Random(digits)
    A = [[Fraction(1, 4), Fraction(1, 12)], [Fraction(3, 4), Fraction(1, 4)]]
    b = [Fraction(3, 4), Fraction(1, 4)]
    path = tmp_path / "t.toml"
    path.write_text(_decimal_tableau(A, b, digits), encoding="utf-8")
    # 400 digits at the default --dps: the balls then work past the input's own digits,
    # as the box's centre would (at 50 digits they certified about 64)
    dps = ["--dps", str(digits + 400)] if digits == 600 else []
    out = run_subprocess("verify", str(path), "-m", "none", "-N", "4", *dps, "--format", "json")
    doc = json.loads(out.out)
    from rkcheck.io.loader import load

    tab = load(str(path))
    held = 0
    conds = {c["id"]: c for c in doc["conditions"]}
    for n in range(3, 6):
        for cond in ref.energy_conditions(n):
            key = ",".join(map(str, cond["id"]))
            got = conds[key]
            centre = [[e.exact for e in row] for row in tab.A], [e.exact for e in tab.b]
            points = [centre] + [
                ([[x + rng.choice((-1, 1)) * _half_unit(x, digits) for x in row] for row in centre[0]],
                 [x + rng.choice((-1, 1)) * _half_unit(x, digits) for x in centre[1]]) for _ in range(3)]
            values = [ref.energy_residual(cond, *p) for p in points]
            if got["state"] == "fails":
                assert all(v != 0 and (v > 0) == (values[0] > 0) for v in values)
            else:
                assert got["state"] == "holds_to_digits" and got["digits"] > digits - 10, got
                assert all(abs(v) <= Fraction(10) ** -got["digits"] for v in values)
                held += 1
    assert held >= 2


# ------------------------------------------------------------------ a double's interval


def _double_box(text: str) -> tuple[Fraction, Fraction]:
    """The reals that round to the double nearest ``text``, from Python's own float:
    half an ulp on each side (away from a power of two)."""
    d = float(text)
    half = Fraction(math.ulp(d)) / 2
    return Fraction(d) - half, Fraction(d) + half


def _residuals_at(cond, A_of, b_of, points):
    return [ref.energy_residual(cond, A_of(x), b_of(x)) for x in points]


@pytest.mark.parametrize("mode", ["float64", "auto"])
def test_a_condition_nonzero_on_a_doubles_whole_interval_fails(mode):
    """a₂₁ = c = x·r with r = 10¹⁷/(10¹⁷ − 7), x = 0.6666666666666667, b = (1 − 1/(2c), 1/(2c)):
    the [τ³] residual is a multiple of Σbc² − 1/3 = c/2 − 1/3, linear in x, and vanishes
    only where c = 2/3, at x = 0.66666666666666662…, outside the
    double's rounding interval of the literal (and, in auto, outside its half unit too):
    it has one sign on the whole box — evaluated here by the reference at both ends of the
    box, which Python's float gives — and fails, however wide the box is about the face
    value.  About the face value, the box the literal's half-ulp interval makes reaches
    past that zero: the centre is the middle of the interval, not the decimal."""
    r = Fraction(10**17, 10**17 - 7)
    text = "0.6666666666666667"
    lo, hi = _double_box(text)
    if mode == "auto":
        half = Fraction(1, 2 * 10**16)
        lo, hi = min(lo, Fraction(text) - half), max(hi, Fraction(text) + half)
    cond = next(c for keys, c in REFERENCE if ref.canonicalize((1, 2, 2, 2)) in keys)
    ends = _residuals_at(cond, lambda x: [[0, 0], [x * r, 0]], lambda x: [1 - 1 / (2 * x * r), 1 / (2 * x * r)],
                         [lo, hi, (lo + hi) / 2])
    assert all(v < 0 for v in ends) or all(v > 0 for v in ends)  # linear in x: one sign between the ends
    tab = rkcheck.loads(f'[constants]\nx = "{text}"\nr = "{r.numerator}/{r.denominator}"\n'
                        '[tableau]\nA = [["0", "0"], ["x*r", "0"]]\nb = ["1 - 1/(2*x*r)", "1/(2*x*r)"]\n')
    res = check(tab, CheckOptions(degree=3, order=3, decimals=mode))
    (cond_result,) = [c for c in res.conditions if ref.canonicalize(c.level_sequence) == ref.canonicalize((1, 2, 2, 2))]
    assert cond_result.verdict.state == FAILS


def test_a_double_at_a_power_of_two_is_centred_on_its_interval():
    """In float64 the literal 1.0 stands for the reals that round to the double 1: the
    spacing is 2⁻⁵³ below 1 and 2⁻⁵² above, so [1 − 2⁻⁵⁴, 1 + 2⁻⁵³], whose middle is
    1 + 2⁻⁵⁵ — the centre a box is judged about, not the face value 1."""
    node = parse("1.0")
    assert node.centre("float64") == 1 + Fraction(1, 2**55)
    assert node.centre("exact") == node.centre("rounded") == 1


def test_a_certificate_of_every_order_does_not_prove_a_claim_on_another_property(tmp_path):
    """A = [[1/2]], b = [1.000000] (b ∈ [1 − 5·10⁻⁷, 1 + 5·10⁻⁷]): every method preserves
    linear energies, so degree 1 has a certificate of every order; the claim classical
    order 2 rests on Σb = 1 and Σbc = 1/2, which hold only to 6 digits over the box:
    met, but no proof, and not to 7 digits."""
    path = tmp_path / "mid.toml"
    path.write_text('[tableau]\nA = [["1/2"]]\nb = ["1.000000"]\n[expect]\nclassical_order = 2\n', encoding="utf-8")
    base = ("verify", str(path), "--degree", "1")
    assert run_subprocess(*base, "--require", "proof").code == 1
    assert run_subprocess(*base, "--require", "digits:7").code == 1
    assert run_subprocess(*base, "--require", "digits:6").code == 0
