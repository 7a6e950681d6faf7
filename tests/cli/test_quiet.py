"""``-q`` prints problems only: broken claims, the failing conditions that decide the
verdict, the files that fail or cannot be read; then the verdict line."""

from __future__ import annotations

from fractions import Fraction

from support import reference as ref
from support.clirun import run_cli
from support.paths import TABLEAUX

RK4_A = [[0, 0, 0, 0], [Fraction(1, 2), 0, 0, 0], [0, Fraction(1, 2), 0, 0], [0, 0, 1, 0]]
RK4_B = [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)]
CLAIM_KINDS = ("energy_order", "classical_order", "quadrature_order", "symplectic", "symmetric", "stability_defect")


def rk4_with_claims(tmp_path, classical: int):
    text = (TABLEAUX / "explicit" / "rk4.toml").read_text(encoding="utf-8")
    head, _, _ = text.partition("[expect]")
    path = tmp_path / "rk4.toml"
    path.write_text(head + f"[expect]\nclassical_order = {classical}\nquadrature_order = 4\nsymplectic = false\n",
                    encoding="utf-8")
    return path


def test_quiet_verify_prints_the_broken_claims_only(capsys, tmp_path):
    # RK4's classical order is 4 (brute force below): a claim of 5 is the one broken claim
    assert ref.classical_order(RK4_A, RK4_B, 6) == 4
    r = run_cli(capsys, "verify", "-q", str(rk4_with_claims(tmp_path, 5)))
    assert r.code == 1
    rows = [line.split()[0] for line in r.out.splitlines() if line.split() and line.split()[0] in CLAIM_KINDS]
    assert rows == ["classical_order"]
    assert "Failing conditions" not in r.out  # judged by its claims: failing conditions are no problem
    assert r.out.rstrip().splitlines()[-1].startswith("CLAIMS BROKEN: 1 of 3")


def test_quiet_verify_of_a_file_whose_claims_hold_is_its_verdict_line(capsys, tmp_path):
    r = run_cli(capsys, "verify", "-q", str(rk4_with_claims(tmp_path, 4)))
    assert r.code == 0
    assert r.out.strip().splitlines() == [r.out.strip()] and r.out.startswith("OK: all 3 claims met")


def test_quiet_verify_judged_by_conditions_lists_the_failing_ones(capsys):
    # no claims: the failing conditions decide the verdict; they are those the brute-force
    # reference finds nonzero (RK4 to order 5 = trees with 6 vertices)
    r = run_cli(capsys, "verify", "-q", "@rk4", "--order", "5", "--fail-on", "auto", "--degree", "none")
    ids = {",".join(map(str, c["id"])) for c in ref.energy_conditions(6) if ref.energy_residual(c, RK4_A, RK4_B) != 0}
    listed = {line.split()[0] for line in r.out.splitlines() if line.strip().startswith("1,")}
    # @rk4 has claims: they decide under auto, so nothing is listed; --fail-on conditions lists them
    assert r.code == 0 and listed == set()
    r = run_cli(capsys, "verify", "-q", "@rk4", "--order", "5", "--fail-on", "conditions", "--degree", "none")
    listed = {line.split()[0] for line in r.out.splitlines() if line.strip().startswith("1,")}
    assert r.code == 1 and listed == ids
    assert "Claims" not in r.out  # the claims hold: not a problem


def test_quiet_scan_prints_the_problem_rows_only(capsys, tmp_path):
    good = rk4_with_claims(tmp_path, 4).rename(tmp_path / "good.toml")
    rk4_with_claims(tmp_path, 5).rename(tmp_path / "wrong.toml")
    (tmp_path / "bad.toml").write_text("[tableau]\nA = [[\"1/\"]]\nb = [1]\n", encoding="utf-8")
    r = run_cli(capsys, "scan", "-q", str(tmp_path), "--jobs", "1")
    assert r.code == 1
    assert "wrong.toml" in r.out and "bad.toml" in r.out and "good.toml" not in r.out
    assert r.out.rstrip().splitlines()[-1].startswith("3 files: 1 ok, 1 failed, 1 error")
    good_only = run_cli(capsys, "scan", "-q", str(good), "--jobs", "1")
    assert good_only.code == 0 and good_only.out.strip().splitlines() == [good_only.out.strip()]
