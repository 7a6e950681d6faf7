"""Continuous-stage methods through verify, the API and the CLI: the quoted cases of
definitions §6, a brute-force route (a k-point Gauss discretisation at high precision,
k large enough for every integral the conditions need) and the one-line errors."""

import json
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import mpmath
import pytest

import rkcheck
from rkcheck.errors import RkcheckError
from rkcheck.methods.continuous import ContinuousMethod
from support.paths import continuous_files

ROOT = Path(__file__).resolve().parents[2]
S2 = "tau + 3*(tau^2 - tau)*(2*sigma - 1)"
S3 = S2 + " + 5*(2*tau^3 - 3*tau^2 + tau)*(6*sigma^2 - 6*sigma + 1)"
MB4 = [["-6/5", "72/5", "-36", "24"], ["72/5", "-144/5", "-48", "72"],
       ["-36", "-48", "720", "-720"], ["24", "72", "-720", "720"]]


def run(*args, stdin=None):
    return subprocess.run([sys.executable, "-m", "rkcheck", *args], capture_output=True, text=True, input=stdin,
                          cwd=ROOT)


def test_avf_kernel_and_matrix():
    for method in (ContinuousMethod.from_kernel("tau"), ContinuousMethod.from_matrix([["1"]])):
        res = rkcheck.verify(method, degree=None, order=6)
        assert res.verdict == "holds" and res.energy_order_all
        assert res.avf.equals_avf
        assert res.classical_order == 2


def test_collocation_orders():
    res = rkcheck.verify(ContinuousMethod.from_kernel(S2), degree=None, order=8)
    assert res.verdict == "holds" and res.energy_order_all and not res.avf.equals_avf
    assert res.classical_order == 4  # Hairer 2010: order 2s
    res3 = rkcheck.verify(ContinuousMethod.from_kernel(S3), degree=None, order=7)
    assert res3.classical_order == 6


P3 = "20*sigma^3 - 30*sigma^2 + 12*sigma - 1"  # the shifted Legendre polynomial of degree 3


def test_a_kernel_avf_for_its_degree_has_the_avf_certificate():
    """A = τ·B(σ), B = 1 + P₃: the stages are y₀ + τ(y₁ − y₀), and ∫B τ^k = 1/(k+1) for
    k ≤ 2 (P₃ is orthogonal to every quadratic), so for a cubic H the update integrates
    the quadratic f(y₀ + τΔ) exactly: AVF for degree 3, a proof of every order.  For
    degree 4 ∫P₃ τ³ = 1/140 ≠ 0: not AVF, no certificate (by hand)."""
    method = ContinuousMethod.from_kernel(f"tau*(1 + {P3})", f"1 + {P3}")
    res = rkcheck.verify(method, degree=3, order=6)
    assert res.energy_order_all and res.certificate.kind == "avf" and res.verdict == "holds"
    res4 = rkcheck.verify(method, degree=4, order=6)
    assert not res4.energy_order_all and not res4.certificate.certified


def test_two_tau_sigma_first_failure_by_hand():
    """A = 2τσ, B = 1.  The condition [[τ]²] (5 vertices) is, from its rootings,
    R = (∫BC)²/2 − ∫∫B A C · ∫B + ∫∫∫ B A A C with C(τ) = τ:
    1/8 − 1/3 + 2/9 = 1/72 (∫2τσ·σ = 1/3; ∫A(σ,ρ)ρ dρ = 2σ/3, ∫A(τ,σ)2σ/3 dσ = 4τ/9, ∫4τ/9 = 2/9)."""
    res = rkcheck.verify(ContinuousMethod.from_kernel("2*tau*sigma"), degree=None, order=5)
    first = res.first_failure
    assert len(first.tree.level_sequence) == 5 and first.tree.level_sequence == (1, 2, 3, 2, 3)
    assert abs(first.residual) == Fraction(1, 72)
    assert not res.energy_order_all and res.certificate is not None and not res.certificate.certified


def test_miyatake_butcher_4x4_preserves_energy():
    res = rkcheck.verify(ContinuousMethod.from_matrix(MB4), degree=None, order=7)
    assert res.verdict == "holds" and len(res.failures) == 0 and res.energy_order_all


def gauss_tableau(A_text, b_text, k, dps=60):
    """a_ij = b_j A(c_i, c_j), b_i = b_i B(c_i) on the k-point Gauss rule, as 60-digit decimals."""
    import sympy

    with mpmath.workdps(dps + 10):  # not the global precision: other tests read mpmath's default
        x, w = mpmath.mp.gauss_quadrature(k, "legendre") if hasattr(mpmath.mp, "gauss_quadrature") else _gauss(k)
        c = [(xi + 1) / 2 for xi in x]
        bw = [wi / 2 for wi in w]
        t, s = sympy.symbols("tau sigma")
        A = sympy.lambdify((t, s), sympy.sympify(A_text.replace("^", "**")), "mpmath")
        B = sympy.lambdify((t,), sympy.sympify(b_text.replace("^", "**")), "mpmath")
        text = lambda v: mpmath.nstr(mpmath.mpf(v), dps, strip_zeros=False)  # noqa: E731
        return rkcheck.from_arrays([[text(bw[j] * A(c[i], c[j])) for j in range(k)] for i in range(k)],
                                   [text(bw[i] * B(c[i])) for i in range(k)])


def _gauss(k):
    """Gauss–Legendre nodes and weights on [−1, 1] by mpmath's polynomial roots."""
    P = lambda z: mpmath.legendre(k, z)  # noqa: E731
    x = [mpmath.findroot(P, mpmath.cos(mpmath.pi * (i + 0.75) / (k + 0.5))) for i in range(k)]
    w = [2 / ((1 - xi ** 2) * mpmath.diff(P, xi) ** 2) for xi in x]
    return x, w


@pytest.mark.parametrize("A_text,b_text", [("2*tau*sigma", "1"), ("tau - tau^2*sigma + 2*tau*sigma^2/3", "3/2 - tau")])
def test_every_condition_against_gauss_brute_force(A_text, b_text):
    order = 5  # 6 vertices: integrands of degree ≤ 1 + 5·2 = 11 < 2k with k = 8
    exact = rkcheck.verify(ContinuousMethod.from_kernel(A_text, b_text), degree=None, order=order)
    brute = rkcheck.verify(gauss_tableau(A_text, b_text, 8), degree=None, order=order, decimals="exact",
                           arithmetic="ball", dps=50)
    pairs = list(zip(exact.conditions, brute.conditions))
    assert len(pairs) == len(exact.conditions) == len(brute.conditions) > 0
    for e, g in pairs:
        assert e.id == g.id
        assert abs(Fraction(e.residual) - Fraction(g.enclosure.mid)) < Fraction(1, 10**40), e.id


def test_certificate_never_meets_a_failure_in_the_library():
    files = continuous_files()
    assert len(files) >= 8 and any("counterexamples" in f for f in files)
    for path in files:
        res = rkcheck.verify(str(path), degree=None, order=6)
        if res.certificate is not None and res.certificate.certified:
            assert len(res.failures) == 0, path
        assert res.ok, path  # every [expect] claim of a shipped method is met


def test_api_load_and_json():
    method = rkcheck.load(str(ROOT / "tableaux" / "continuous" / "epcm-2.toml"))
    assert isinstance(method, rkcheck.ContinuousMethod)
    doc = json.loads(rkcheck.verify(method, order=4).to_json())
    assert doc["tableau"]["structure"] == "continuous"
    assert doc["tableau"]["kernel"]["degree_tau"] == 2 and doc["tableau"]["kernel"]["degree_sigma"] == 1
    assert doc["summary"]["certificate"]["kind"] == "continuous_kernel"
    assert doc["summary"]["energy_order_all"] is True


def test_symmetry_and_symplecticity_of_kernels():
    # Gauss-like kernel of the 1-stage midpoint in continuous form: A = 1/2, B = 1 is
    # symmetric and symplectic (B(τ)A(τ,σ)+B(σ)A(σ,τ) = 1 = B(τ)B(σ))
    res = rkcheck.verify(ContinuousMethod.from_kernel("1/2"), degree=None, order=3)
    assert res.properties.symmetric.holds and res.properties.symplectic.holds
    res = rkcheck.verify(ContinuousMethod.from_kernel("2*tau*sigma"), degree=None, order=3)
    assert not res.properties.symmetric.holds


@pytest.mark.parametrize("table,message", [
    ('A = "tau"\nM = [["1"]]', "either A (and b) or M"),
    ('A = "sqrt(tau)"', "continuous.A"),
    ('A = "1/tau"', "continuous.A"),
    ('A = "tau*x"', "unknown name 'x'"),
    ('M = [["1", "2"], ["3"]]', "M[2]"),
    ('A = "tau^(1/2)"', "continuous.A"),
])
def test_bad_kernels_are_one_line_errors(tmp_path, table, message):
    f = tmp_path / "k.toml"
    f.write_text(f"[continuous]\n{table}\n")
    out = run("verify", str(f))
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1 and message in out.stderr and str(f) in out.stderr
    with pytest.raises(RkcheckError):
        rkcheck.load(str(f))


def test_greek_aliases_and_decimals():
    greek = ContinuousMethod.from_kernel("τ + 3*(τ^2 - τ)*(2*σ - 1)")
    assert rkcheck.verify(greek, order=4).classical_order == 4
    # a decimal at face value is exact; it is the same kernel as 1/2
    assert rkcheck.verify(ContinuousMethod.from_kernel("0.5"), order=3, decimals="exact").properties.symplectic.holds


def test_cli_verify_scan_show(tmp_path):
    f = tmp_path / "k.toml"
    f.write_text('[continuous]\nA = "2*tau*sigma"\n')
    out = run("verify", str(f), "--order", "4", "--format", "json")
    assert out.returncode == 1
    doc = json.loads(out.stdout)
    assert doc["summary"]["first_failure"]["id"] == "1,2,3,2,3"
    out = run("scan", str(ROOT / "tableaux" / "continuous"), str(f), "--order", "4", "--format", "json")
    files = json.loads(out.stdout)["files"]
    assert len(files) == 8 and all(x["status"] == "ok" for x in files)  # no claims in k.toml: not judged
    mine = next(x for x in files if x["file"] == str(f))
    assert mine["result"]["summary"]["first_failure"]["id"] == "1,2,3,2,3"
    assert mine["result"]["tableau"]["structure"] == "continuous"
    out = run("show", str(f))
    assert out.returncode == 0 and "certificate  no" in out.stdout
    out = run("--no-color", "verify", str(f), "--require", "proof", "--order", "3")
    assert out.returncode == 0


@pytest.mark.parametrize("args", [["simulate", "{f}", "--problem", "harmonic"], ["bench", "{f}"],
                                  ["perturb", "{f}", "--direction", "random"], ["kernel", "-m", "3", "--tableau", "{f}"],
                                  ["conditions", "{f}", "--order", "3"]])
def test_commands_that_need_stages_refuse_a_kernel_in_one_line(args):
    f = str(ROOT / "tableaux" / "continuous" / "avf.toml")
    out = run(*[a.format(f=f) for a in args])
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and "continuous-stage method" in out.stderr
    assert out.stderr.startswith(f"rkcheck: error: {f}")


def test_api_functions_that_need_stages_refuse_a_kernel():
    for call in (rkcheck.bench, rkcheck.write):
        with pytest.raises(rkcheck.TableauError, match="continuous-stage method"):
            call(ContinuousMethod.from_kernel("tau"))


def test_rounded_decimals_make_a_box_judged_to_digits():
    """0.50000000000000000000 (20 digits) stands for [0.5 − 5e−21, 0.5 + 5e−21]: written
    twice, two numbers x, y, and A = (x + y)τ.  ∂τA = x + y is symmetric for every x, y
    and A(0, σ) = 0, but A(1, σ) − B = x + y − 1 ranges over [−1e−20, 1e−20]: the
    certificate holds to 20 digits, never as a proof; at face value (decimals exact) it is
    AVF exactly."""
    m = ContinuousMethod.from_kernel("0.50000000000000000000*tau + 0.50000000000000000000*tau")
    res = rkcheck.verify(m, order=4)
    assert not res.energy_order_all and res.energy_order_all_digits == 20
    assert res.avf.verdict.state == "holds_to_digits"
    exact = rkcheck.verify(m, order=4, decimals="exact")
    assert exact.energy_order_all and exact.avf.verdict.state == "holds"
    # a box every kernel of which lacks the certificate: fails, certainly
    bent = ContinuousMethod.from_kernel("2.0000000000000000000*tau*sigma")
    assert rkcheck.verify(bent, order=4).certificate.verdict.state == "fails"


def test_a_decimal_kernel_is_judged_alike_at_every_order():
    """A = (0.500000 + τ² − σ²)·2σ, B = 2σ: its literal stands for 1/2 ± 5·10⁻⁷.  A
    residual of the kernel at face value (``decimals="exact"``, an exact surrogate on
    equispaced nodes) that is nonzero by far more than that moves it fails over the whole
    box at every order checked, and a zero one holds to the digits the literal allows —
    however many nodes the surrogate of the order needs (the equispaced rule's weights
    would widen every enclosure by Σ|w_i|, 175 at 19 nodes, at every level of a tree)."""
    m = ContinuousMethod.from_kernel("(0.500000 + tau^2 - sigma^2)*2*sigma", "2*sigma")
    exact = {c.id: Fraction(c.residual) for c in rkcheck.verify(m, order=6, decimals="exact").conditions}
    for order in (6, 10):
        res = rkcheck.verify(m, order=order)
        for c in res.conditions:
            if c.id not in exact:
                continue
            if abs(exact[c.id]) > Fraction(1, 10**4):
                assert c.state == "fails", (order, c.id)
            elif exact[c.id] == 0:
                assert c.state == "holds_to_digits" and c.digits >= 5, (order, c.id)


def test_a_symmetric_decimal_matrix_holds_to_its_digits_at_every_order(tmp_path):
    """M = [[4, m], [m, 12]] with m = −6.00000 ± 5·10⁻⁶ is symmetric for every m, so
    every energy condition vanishes on the whole box (definitions §6): each holds to the
    same digits at order 10 as at order 5."""
    path = tmp_path / "m.toml"
    path.write_text('[constants]\nm = "-6.00000"\n[continuous]\nM = [["4", "m"], ["m", "12"]]\n', encoding="utf-8")
    low, high = (rkcheck.verify(path, degree=4, order=n) for n in (5, 10))
    assert high.ok and high.min_digits >= low.min_digits - 1 >= 4


def test_algebraic_kernel_is_exact_in_its_field():
    """A = τ + √2(τ² − τ)(2σ − 1): ∂τA = 1 + √2(2τ − 1)(2σ − 1) is symmetric, so the
    certificate holds, and exactly (in Q(√2)); C(τ) = τ, so a([τ]) = 1/2 but
    a([[τ]]) = ∫∫A σ = 1/6 + √2·∫(τ²−τ)dτ·∫(2σ−1)σ dσ = 1/6 − √2/36 ≠ 1/6: order 2."""
    m = ContinuousMethod.from_kernel("tau + r*(tau^2 - tau)*(2*sigma - 1)", constants={"r": "sqrt(2)"})
    res = rkcheck.verify(m, order=5)
    assert res.backend == "exact" and res.verdict == "holds" and res.energy_order_all
    assert res.classical_order == 2 and res.classical.first_failure is not None


def test_json_file_with_greek_letters(tmp_path):
    f = tmp_path / "k.json"
    f.write_text('{"method": {"name": "AVF"}, "continuous": {"A": "τ", "b": "1"}}', encoding="utf-8")
    res = rkcheck.verify(str(f), order=4)
    assert res.avf.equals_avf and res.energy_order_all and res.tableau.name == "AVF"


def test_non_symmetric_miyatake_butcher_matrix_has_no_certificate_and_fails():
    """M = [[1, 2], [0, −4]]: ∂τA = 1 + 2σ − 4τσ is not symmetric (M₁₂ ≠ M₂₁); B = A(1, σ)
    = 1. C(τ) = ∫A dσ = 2τ − τ², so a([τ]) = ∫C = 2/3 ≠ 1/2: the 3-vertex condition
    a([τ]) − a(τ)²/2 (by its two rootings) is ±1/6."""
    res = rkcheck.verify(ContinuousMethod.from_matrix([["1", "2"], ["0", "-4"]]), order=4)
    assert not res.certificate.certified and "not symmetric" in res.certificate.reason
    assert res.first_failure.id == "1,2,2" and abs(res.first_failure.residual) == Fraction(1, 6)


def test_a_decimal_kernel_is_shown_and_verified_over_its_box(tmp_path):
    # "1.000000" (7 digits) stands for [0.9999995, 1.0000005]: the kernel certificate and
    # AVF hold to 6 digits over that box, never exactly; show must say what verify says
    f = tmp_path / "k.toml"
    f.write_text('[continuous]\nA = "1.000000*tau"\n', encoding="utf-8")
    out = run("show", str(f))
    assert out.returncode == 0, out.stderr
    assert "decimal (a box of kernels)" in out.stdout
    assert "certificate  yes, to 6 digits" in out.stdout and "AVF          yes, to 6 digits" in out.stdout
    doc = json.loads(run("show", str(f), "--format", "json").stdout)
    assert doc["certificate"]["state"] == "holds_to_digits" and doc["certificate"]["digits"] == 6
    assert doc["avf"]["state"] == "holds_to_digits"
    exact = json.loads(run("show", str(f), "--format", "json", "--decimals", "exact").stdout)
    assert exact["certificate"]["state"] == "holds" and exact["tableau"]["numbers"] == "rational"
    out = run("--no-color", "verify", str(f))
    last = out.stdout.strip().splitlines()[-1]
    assert out.returncode == 0 and "not a proof" in out.stdout and "None" not in out.stdout
    assert "for every Hamiltonian" in out.stdout.replace("\n", " "), last


@pytest.mark.parametrize("M, message", [
    ([["4", "-6"], ["-6"]], "M[2]: row has 1 entries, expected 2"),
    ([[]], "M[1]: expected a non-empty row"),
    ("1", "continuous.M: expected a non-empty list of rows"),
    ([["1", "2"]] * 41, "41 rows exceed the limit MAX_KERNEL_MATRIX = 40"),
    ([["1"] * 41] * 2, "M[1]: 41 columns exceed the limit MAX_KERNEL_MATRIX = 40"),
    ([["1", True]], "M[1][2]: expected a number (int, Fraction, float) or a string, got bool"),
])
def test_a_matrix_from_python_is_checked_as_a_file_s(M, message, tmp_path):
    # the API and a file's [continuous] M go through the same checks, with the same words
    with pytest.raises(RkcheckError) as err:
        ContinuousMethod.from_matrix(M)
    assert message in str(err.value)
    f = tmp_path / "m.json"
    f.write_text(json.dumps({"continuous": {"M": M}}), encoding="utf-8")
    out = run("verify", str(f))
    assert out.returncode == 2 and message in out.stderr and out.stderr.count("\n") == 1, out.stderr


def test_the_largest_matrix_allowed_is_read(tmp_path):
    # 40 × 40, the limit MAX_KERNEL_MATRIX: its kernel's text (1 600 terms) is longer than
    # one entry may be, and was refused as "M: entry too long" though no entry of M is
    M = [[str((i + j) % 3 + 1) for j in range(40)] for i in range(40)]
    method = ContinuousMethod.from_matrix(M)
    # A = Σ M_ij τ^i/i σ^(j−1): degree 40 in τ, 39 in σ; B(σ) = A(1, σ): degree 39
    assert (method.kernel.deg_tau, method.kernel.deg_sigma, method.kernel.deg_b) == (40, 39, 39)
    # with decimals M is written term by term (each literal kept), a text every entry of
    # the surrogate would copy: refused in one line naming that limit, not an entry of M
    f = tmp_path / "m.json"
    f.write_text(json.dumps({"continuous": {"M": [[x + ".000001" for x in row] for row in M]}}), encoding="utf-8")
    out = run("verify", str(f))
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert "M: with decimals, M is written term by term" in out.stderr and "MAX_ENTRY_LENGTH" in out.stderr


@pytest.mark.parametrize("M, constants", [
    ('[["4", "-6.000000"], ["-6.000000", "12"]]', ""),
    ('[["4", "-k"], ["-6", "12"]]', '[constants]\nk = "6.000000"\n'),
])
def test_a_matrix_decimal_follows_the_decimals_rule_as_in_the_kernel(tmp_path, M, constants):
    # the same kernel written through A and b, whose decimals are read as rounded to their
    # last digit (definitions §5): the matrix's decimals are read the same way, never exact
    written = tmp_path / "written.toml"
    # A = Σ M_ij τ^i/i σ^(j−1), B(σ) = A(1, σ)
    written.write_text('[continuous]\nA = "4*tau - 6.000000*tau*sigma - 6.000000/2*tau^2 + 6*tau^2*sigma"\n'
                       'b = "4 - 6.000000*tau - 6.000000/2 + 6*tau"\n', encoding="utf-8")
    matrix = tmp_path / "matrix.toml"
    matrix.write_text(f"{constants}[continuous]\nM = {M}\n", encoding="utf-8")
    exact = tmp_path / "exact.toml"
    exact.write_text('[continuous]\nM = [["4", "-6"], ["-6", "12"]]\n', encoding="utf-8")

    def states(path, *options):
        r = run("verify", str(path), "-N", "4", "-m", "none", "--format", "json", *options)
        doc = json.loads(r.stdout)
        return [(c["id"], c["state"]) for c in doc["conditions"]], doc["summary"]["energy_order"]

    reference = states(written)
    assert {s for _, s in reference[0]} == {"holds_to_digits"}, reference  # a box, not a proof
    assert states(matrix) == reference
    assert states(matrix, "--decimals", "exact") == states(exact)
    assert {s for _, s in states(exact)[0]} == {"holds"}


@pytest.mark.parametrize("written, column", [("σ*σ*σ + 1/0", 10), ("τ + σ*)", 7), ("tau + sigma*)", 13)])
def test_an_error_column_counts_the_kernel_as_written(tmp_path, written, column):
    # τ and σ are one character each where the user wrote them (counted by hand above: the
    # '/' of 1/0 and the stray ')'), whatever the parser reads them as
    path = tmp_path / "k.toml"
    path.write_text(f'[continuous]\nA = "{written}"\n', encoding="utf-8")
    with pytest.raises(rkcheck.TableauError, match=rf"continuous\.A: .* at column {column}$"):
        rkcheck.load(str(path))
    with pytest.raises(rkcheck.TableauError, match=rf"at column {column}$"):
        ContinuousMethod.from_kernel(written)


def test_over_a_box_the_series_search_claims_no_agreement():
    """A = τ + (1.00000 − 1)·10⁹τ²(2σ − 1), B = 1: at face value AVF, which is not
    symplectic (u = τ, v = [τ]: a([[τ]]) + a([τ, τ]) − a(τ)a([τ]) = 1/4 + 1/3 − 1/2 = 1/12,
    with AVF's a([t₁…t_q]) = Π a(t_i)/(q + 1)); over the box the extra term reaches
    ±5000τ²(2σ − 1), so the balls of the series search contain 0 for every pair: not
    refuted — and not shown to agree."""
    m = ContinuousMethod.from_kernel("tau + (1.00000 - 1)*1e9*tau^2*(2*sigma-1)")
    res = rkcheck.verify(m, degree=1, order=4)
    symplectic = res.properties.symplectic
    assert symplectic.verdict.state == "undecided"
    assert "over the box of its decimals" in symplectic.reason and "for every pair" not in symplectic.reason
    exact = rkcheck.verify(m, degree=1, order=4, decimals="exact").properties.symplectic
    assert exact.verdict.state == "fails"  # at face value the B-series refutes it


def test_from_kernel_takes_numbers_as_a_file_does():
    # b = 1 written as a number is AVF's B, exactly; what is neither text nor an exact
    # number is a TableauError naming the argument
    assert rkcheck.verify(ContinuousMethod.from_kernel("tau", b=1), order=3).energy_order_all
    assert rkcheck.verify(ContinuousMethod.from_kernel("tau", b=Fraction(1)), order=3).energy_order_all
    # B = 1 + 10⁻⁵⁰⁰⁰, past the digits Python writes: read and reported, not refused
    near = rkcheck.verify(ContinuousMethod.from_kernel("tau", b=Fraction(10**5000 + 1, 10**5000)), order=2)
    assert near.avf.verdict.state == "fails" and "(≈ 1 against 1)" in near.avf.reason
    for bad in (0.5, True, None, ["1"]):
        with pytest.raises(rkcheck.TableauError, match=r"^b: expected an expression in tau and sigma"):
            ContinuousMethod.from_kernel("tau", b=bad)
