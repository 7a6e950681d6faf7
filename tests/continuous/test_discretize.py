"""Discretisation of continuous-stage methods: HBVM(k, 2) is the s = 2 energy-preserving
collocation kernel on k Gauss nodes (Brugnano–Iavernaro–Trigiante 2010, Hairer 2010),
compared with the shipped tableaux exactly; the degree it keeps against verify."""

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import rkcheck
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.expressions import substituted
from rkcheck.numbers.field_builder import field_of

ROOT = Path(__file__).resolve().parents[2]
EPCM2 = ROOT / "tableaux" / "continuous" / "epcm-2.toml"


def _renamed(node, names, prefix):
    return substituted(node, {n: ex.Name(prefix + n, 1) for n in names})


def assert_same_tableau(mine, theirs):
    """Every entry of A and b equal exactly: the differences (each file's constants kept
    apart by a prefix) are zero in the number field of them all."""
    defs = {}
    for prefix, tab in (("m_", mine), ("t_", theirs)):
        names = list(tab.info.constants.definitions)
        defs |= {prefix + k: _renamed(v, names, prefix) for k, v in tab.info.constants.definitions.items()}
    pairs = [(x, y) for rm, rt in zip(mine.A, theirs.A) for x, y in zip(rm, rt)] + list(zip(mine.b, theirs.b))
    assert mine.stages == theirs.stages and len(pairs) == mine.stages * (mine.stages + 1)
    m_names, t_names = list(mine.info.constants.definitions), list(theirs.info.constants.definitions)
    diffs = [ex.Binary("-", _renamed(x.node, m_names, "m_"), _renamed(y.node, t_names, "t_"), 1) for x, y in pairs]
    found = field_of(diffs, defs)
    assert all(v == 0 or (hasattr(v, "coeffs") and not any(v.coeffs)) for v in found.values)


@pytest.mark.parametrize("k", [3, 4])
def test_gauss_k_discretisation_is_hbvm_k_2(k):
    text, note = rkcheck.discretize(str(EPCM2), f"gauss-{k}")
    mine = rkcheck.loads(text)
    theirs = rkcheck.load(f"@hbvm-{k}-2")
    assert_same_tableau(mine, theirs)
    assert f"degree ≤ {k}" in note  # 2k/s with s = 2 (the shipped HBVM(k, 2) claims the same)


def test_a_different_tableau_is_told_apart():
    mine = rkcheck.loads(rkcheck.discretize(str(EPCM2), "gauss-3")[0])
    other = rkcheck.load("@hbvm-3-2")
    bent = other.replace(b=(other.b[1], other.b[0], other.b[2]))
    with pytest.raises(AssertionError):
        assert_same_tableau(mine, bent)


def test_kept_degree_against_verify():
    """Gauss-3 on the s = 2 kernel: ⌊6/2⌋ = 3.  Degree 3: every condition holds; degree 4:
    one fails (the quadrature error of the line integral)."""
    text, _ = rkcheck.discretize(str(EPCM2), "gauss-3")
    tab = rkcheck.loads(text)
    assert tomllib.loads(text)["check"]["degree"] == 3
    assert rkcheck.verify(tab, degree=3, order=8).all_hold
    assert not rkcheck.verify(tab, degree=4, order=8).all_hold


def test_rules_and_cli(tmp_path):
    avf = ROOT / "tableaux" / "continuous" / "avf.toml"
    # AVF on Lobatto-3 is the shipped avf-lobatto-3 tableau (rational)
    tab = rkcheck.loads(rkcheck.discretize(str(avf), "lobatto-3")[0])
    shipped = rkcheck.load("@avf-lobatto-3")
    assert [[e.exact for e in r] for r in tab.A] == [[e.exact for e in r] for r in shipped.A]
    assert [e.exact for e in tab.b] == [e.exact for e in shipped.b]
    # a rule from a file: the b and c of Gauss-2 collocation
    rule_file = ROOT / "tableaux" / "collocation" / "gauss-2.toml"
    t2 = rkcheck.loads(rkcheck.discretize(str(EPCM2), str(rule_file))[0])
    assert_same_tableau(t2, rkcheck.load("@gauss-2"))  # HBVM(s, s) is Gauss collocation
    nc = rkcheck.loads(rkcheck.discretize(str(avf), "newton-cotes-3")[0])
    assert [e.exact for e in nc.b] == [e.exact for e in rkcheck.load("@avf-lobatto-3").b]  # Simpson
    out = subprocess.run([sys.executable, "-m", "rkcheck", "discretize", str(EPCM2), "--rule", "gauss-9x"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    out = subprocess.run([sys.executable, "-m", "rkcheck", "discretize", str(rule_file), "--rule", "gauss-2"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and "continuous" in out.stderr


def test_no_degree_without_the_certificate():
    m = rkcheck.ContinuousMethod.from_kernel("2*tau*sigma")
    text, note = rkcheck.discretize(m, "gauss-2")
    assert "no degree is guaranteed" in note
    doc = tomllib.loads(text)
    assert "check" not in doc and "expect" not in doc
    # the tableau is a_ij = b_j·2c_i c_j, b_i: with Gauss-2 nodes c = 1/2 ∓ √3/6, b = 1/2
    tab = rkcheck.loads(text)
    c1 = 0.5 - 3 ** 0.5 / 6
    assert abs(float(tab.A[0][0].enclosure(64).mid) - 0.5 * 2 * c1 * c1) < 1e-15


@pytest.mark.parametrize("rule", ["radau-i-1", "radau-ii-1"])
def test_no_degree_below_the_kernels_degree(rule):
    """A rule of quadrature order q = 1 on the s = 2 kernel (degree p = 2 in τ): ⌊q/p⌋ = 0
    guarantees nothing, so no [check] degree or claim is written, and the file it writes
    is one rkcheck reads (it refused `degree = 0`)."""
    text, note = rkcheck.discretize(str(EPCM2), rule)
    assert "⌊q/p⌋ = 0" in note and "no degree with an energy condition is guaranteed" in note
    doc = tomllib.loads(text)
    assert "check" not in doc and "expect" not in doc
    assert rkcheck.verify(rkcheck.loads(text), order=4).per_order  # loads and checks


def test_no_claim_for_linear_hamiltonians_only():
    """EPCM(3) has τ-degree p = 3; Radau IIA with 3 nodes has quadrature order q = 5, so
    ⌊q/p⌋ = 1: degree 1 has no energy condition (every method preserves a linear H), and a
    claim about it would be empty — none is written."""
    text, note = rkcheck.discretize(str(ROOT / "tableaux" / "continuous" / "epcm-3.toml"), "radau-ii-3")
    assert "⌊q/p⌋ = 1" in note
    doc = tomllib.loads(text)
    assert "check" not in doc and "expect" not in doc


def test_newton_cotes_takes_both_ends():
    from fractions import Fraction

    avf = ROOT / "tableaux" / "continuous" / "avf.toml"
    # two equispaced nodes with both ends: the trapezoidal rule, b = (1/2, 1/2), c = (0, 1)
    trap = rkcheck.loads(rkcheck.discretize(str(avf), "newton-cotes-2")[0])
    assert [e.exact for e in trap.b] == [Fraction(1, 2)] * 2
    assert [sum(e.exact for e in row) for row in trap.A] == [0, 1]
    # one node cannot be both ends
    with pytest.raises(rkcheck.RkcheckError, match="newton-cotes needs at least 2 nodes"):
        rkcheck.discretize(str(avf), "newton-cotes-1")


@pytest.mark.parametrize("A, c, q", [
    # Gauss-2's A with c = (0, 1): the tableau is built on the nodes 0 and 1 with b = ½, ½
    # — the trapezoidal rule, q = 2 (not Gauss-2's 4, which A·1 would give)
    ('[["1/4", "1/4 - sqrt(3)/6"], ["1/4 + sqrt(3)/6", "1/4"]]', '["0", "1"]', 2),
    # A = 0 with Gauss-2's nodes: q = 4 (not the 1 that A·1 = 0 would give)
    ('[["0", "0"], ["0", "0"]]', '["1/2 - sqrt(3)/6", "1/2 + sqrt(3)/6"]', 4),
])
def test_a_rule_from_a_file_is_its_b_and_c_even_where_c_is_not_the_row_sums(tmp_path, A, c, q):
    sp = pytest.importorskip("sympy")
    rule = tmp_path / "rule.toml"
    rule.write_text(f'[tableau]\nA = {A}\nb = ["1/2", "1/2"]\nc = {c}\n', encoding="utf-8")
    nodes = [sp.sympify(x) for x in tomllib.loads(rule.read_text())["tableau"]["c"]]
    exact = [k for k in range(1, 6) if sp.simplify(sum(sp.Rational(1, 2) * x ** (k - 1) for x in nodes)
                                                    - sp.Rational(1, k)) == 0]
    assert q == len(exact) == exact[-1]  # the rule's quadrature order, by sympy
    avf = ROOT / "tableaux" / "continuous" / "avf.toml"
    text, note = rkcheck.discretize(str(avf), str(rule))
    assert f"quadrature order q = {q}" in note and tomllib.loads(text)["check"]["degree"] == q
    tab = rkcheck.loads(text)
    assert rkcheck.verify(tab, degree=q, order=6).all_hold  # the claim the file writes holds
    assert not rkcheck.verify(tab, degree=q + 1, order=6).all_hold


def test_a_kernel_of_rounded_decimals_is_written_at_face_value_and_says_so(tmp_path):
    # κ = 2.99999999 stands for an interval (9 digits, definitions §5); the written tableau
    # is exact — its entries at κ's face value — and the note says so
    kernel = tmp_path / "k.toml"
    kernel.write_text('[continuous]\nA = "tau + 2.99999999*(tau^2 - tau)*(2*sigma - 1)"\n', encoding="utf-8")
    text, note = rkcheck.discretize(str(kernel), "gauss-3")
    assert "taken at face value" in note and "9 significant digits" in note
    written = rkcheck.loads(text)
    assert not written.is_box("auto")
    exact = tmp_path / "e.toml"
    exact.write_text('[continuous]\nA = "tau + 3*(tau^2 - tau)*(2*sigma - 1)"\n', encoding="utf-8")
    assert "face value" not in rkcheck.discretize(str(exact), "gauss-3")[1]


@pytest.mark.parametrize("rule", ["gauss-12", "radau-ii-15", "lobatto-20"])
def test_a_rule_of_many_irrational_nodes_is_written_in_decimals_read_back(rule):
    """Past 8 irrational nodes the exact entries (Lagrange integrals of root(p, k) nodes)
    run to megabytes, past what a file may hold: each entry is written as a 60-digit
    decimal, within half a unit of its last digit of b_j A(c_i, c_j) on the rule's nodes
    and weights computed here by mpmath at 100 digits, and the file reads back."""
    mpmath = pytest.importorskip("mpmath")
    text, note = rkcheck.discretize(str(EPCM2), rule)
    assert "60-digit decimals" in note and len(text) < 100_000
    tab = rkcheck.loads(text)
    name, k = rule.rsplit("-", 1)
    k = int(k)
    with mpmath.workdps(100):
        if name == "gauss":
            x = [(r + 1) / 2 for r in mpmath.polyroots(mpmath.taylor(lambda t: mpmath.legendre(k, t), 0, k)[::-1],
                                                        maxsteps=400, extraprec=400)]
        elif name == "radau-ii":  # zeros of P_k − P_{k−1} on [−1, 1], 1 among them
            x = [(r + 1) / 2 for r in mpmath.polyroots(mpmath.taylor(
                lambda t: mpmath.legendre(k, t) - mpmath.legendre(k - 1, t), 0, k)[::-1], maxsteps=400, extraprec=400)]
        else:  # both ends and the zeros of P'_{k−1}
            inner = mpmath.polyroots(mpmath.taylor(lambda t: mpmath.diff(lambda u: mpmath.legendre(k - 1, u), t),
                                                   0, k - 2)[::-1], maxsteps=400, extraprec=400)
            x = [mpmath.mpf(0)] + [(r + 1) / 2 for r in inner] + [mpmath.mpf(1)]
        x = sorted(mpmath.re(v) for v in x)
        # weights: ∫₀¹ of each Lagrange basis polynomial, from the moments
        V = mpmath.matrix([[xi**p for xi in x] for p in range(k)])
        w = mpmath.lu_solve(V, mpmath.matrix([mpmath.mpf(1) / (p + 1) for p in range(k)]))

        def A(t, s):
            return t + 3 * (t**2 - t) * (2 * s - 1)

        for i in range(k):
            assert _within_last_digit(tab.b[i].text, w[i])
            for j in range(k):
                assert _within_last_digit(tab.A[i][j].text, w[j] * A(x[i], x[j])), (i, j)
    assert rkcheck.verify(tab, degree=4, order=6).ok


def _within_last_digit(text: str, value) -> bool:
    from decimal import Decimal, localcontext

    with localcontext() as ctx:
        ctx.prec = 200
        d = Decimal(text)
        if d == 0:  # an exact zero (a row at c = 0 of a kernel with A(0, σ) = 0)
            return abs(Decimal(str(value))) < Decimal("1e-90")
        assert len(d.as_tuple().digits) == 60
        half = Decimal(1).scaleb(d.adjusted() - 59) / 2
        return abs(d - Decimal(str(value))) <= half
