"""The shipped library: every file meets its claims; family and explicit forms agree;
HBVM identities; `rkcheck new | rkcheck verify -` round-trips."""

from __future__ import annotations

import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest
from support import reference as ref
from support.heavy import heavy, shipped_params
from support.numbers import exact_under
from support.paths import TABLEAUX, tableau_files

from rkcheck.energy.check import CheckOptions, CheckRunner, check
from rkcheck.energy.claims import check_claims
from rkcheck.io.loader import load
from rkcheck.methods.families import FamilySpec, family_tableau

FILES = tableau_files()


def test_the_library_has_at_least_40_documented_files_in_every_kind():
    assert len(FILES) >= 40
    kinds = {Path(f).relative_to(TABLEAUX).parts[0] for f in FILES}
    assert kinds >= {"avf", "collocation", "hbvm", "explicit", "pseudo-energy-preserving", "counterexamples"}
    for f in FILES:
        tab = load(f)
        assert tab.name and tab.info.description and tab.info.references, f
        assert tab.info.claims, f"{f} has no [expect] claims"


@pytest.mark.parametrize("path", shipped_params(FILES))
def test_every_shipped_tableau_meets_its_claims(path):
    tab = load(path)
    runner = CheckRunner()
    results = check_claims(tab, tab.info.claims, CheckOptions(order=8), runner)
    broken = [(r.claim.place, r.claimed, r.found, r.note) for r in results if not r.met]
    assert broken == []


# The "done when": every shipped tableau with square roots or roots of a named
# polynomial (directly or as a [family]) is decided exactly, so its claims are met by
# proof, not to digits; only decimal tableaux are numerical.
ALGEBRAIC = [f for f in FILES if not load(f).is_rational and not load(f).is_box("auto")]


def test_the_library_has_algebraic_tableaux():
    assert len(ALGEBRAIC) >= 10


# HBVM(6, 2) stays in the default run: the one exact check there in the largest field shipped
@pytest.mark.parametrize("path", shipped_params(ALGEBRAIC, lambda p: p.endswith("hbvm-6-3.toml")))
def test_every_shipped_algebraic_tableau_is_checked_exactly(path):
    # HBVM(6, σ) included: the six Gauss-6 nodes generate the splitting field of P6, of
    # degree |Gal| = 48 (tests/numbers/test_algebraic.py), the largest field shipped
    tab = load(path)
    assert exact_under(tab, "auto"), getattr(tab, "exact_reason", None)
    res = check(tab, CheckOptions(order=8))
    assert res.backend == "exact"
    assert {r.verdict.state for r in res.conditions} <= {"holds", "fails"}
    assert res.quadrature.verdict.state == "holds" and res.quadrature.verdict.digits is None


# ------------------------------------------------- claims by a second route


def _reference_energy_order(A, b, degree, max_vertices):
    """First failing vertex count − 2 by the slow reference (Fractions), capped."""
    for n in range(3, max_vertices + 1):
        for cond in ref.energy_conditions(n, degree):
            if ref.energy_residual(cond, A, b) != 0:
                return n - 2
    return None  # every condition up to max_vertices holds


RATIONAL = [f for f in FILES if load(f).is_rational and exact_under(load(f), "rounded") and load(f).info.family is None]


@pytest.mark.parametrize("path", RATIONAL, ids=[str(Path(f).relative_to(TABLEAUX)) for f in RATIONAL])
def test_rational_claims_agree_with_the_reference_implementation(path):
    tab = load(path)
    A, b = tab.exact_A(), tab.exact_b()
    max_vertices = 7
    for claim in tab.info.claims:
        if claim.kind == "energy_order":
            found = _reference_energy_order(A, b, claim.degree, max_vertices)
            if claim.value == "all":
                assert found is None
            elif claim.value <= max_vertices - 2:
                assert found == claim.value, claim
            else:
                assert found is None  # the claimed first failure lies beyond 7 vertices
        elif claim.kind == "classical_order":
            assert ref.classical_order(A, b, claim.value + 1) == claim.value
        elif claim.kind == "quadrature_order":
            c = [sum(row, Fraction(0)) for row in A]
            ok = [sum(bi * ci ** (k - 1) for bi, ci in zip(b, c)) == Fraction(1, k) for k in range(1, 2 * len(b) + 1)]
            assert (ok + [False]).index(False) == claim.value


# ------------------------------------------------- family form vs explicit form


def _states(tab, degree, order=8):
    res = check(tab, CheckOptions(degree=degree, order=order))
    # certified_all: a certificate, exact or (for the 60-digit decimals) to digits
    return {r.id: r.verdict.holds for r in res.conditions}, res.certified_all


@heavy
@pytest.mark.parametrize("degree", [6, 7])
def test_hbvm_6_2_family_and_60_digit_forms_give_the_same_verdicts(degree):
    family = load(str(TABLEAUX / "hbvm" / "hbvm-6-2.toml"))
    explicit = load(str(TABLEAUX / "hbvm" / "hbvm-6-2-decimal60.toml"))
    assert family.info.family is not None and explicit.info.family is None
    assert _states(family, degree) == _states(explicit, degree)


def test_gauss_3_exact_expressions_and_family_give_the_same_verdicts():
    exact_file = load(str(TABLEAUX / "collocation" / "gauss-3.toml"))
    assert exact_file.uses_sqrt and exact_file.info.family is None
    family = family_tableau(FamilySpec("gauss", 3))
    for degree in (2, 3, 4):
        assert _states(exact_file, degree) == _states(family, degree)


# ------------------------------------------------------------ HBVM identities


@pytest.mark.parametrize("s", [1, 2, 3, 4])
def test_hbvm_s_s_is_gauss_collocation(s):
    # A = I_s P_sᵀ Ω with k = s is the collocation matrix (Brugnano et al.): compare the
    # certified enclosures entry by entry (they must overlap and be tiny)
    bits = 200
    hb, _ = family_tableau(FamilySpec("hbvm", s, k=s)).enclosures(bits, "exact")
    ga, _ = family_tableau(FamilySpec("gauss", s)).enclosures(bits, "exact")
    for row_h, row_g in zip(hb, ga):
        for x, y in zip(row_h, row_g):
            assert x.lo <= y.hi and y.lo <= x.hi
            assert x.hi - x.lo < Fraction(1, 2**150)


@pytest.mark.parametrize("k", [1, 2, 3, 4])
def test_hbvm_k_1_is_avf(k):
    res = check(family_tableau(FamilySpec("hbvm", 1, k=k)), CheckOptions(degree=2 * k, order=6))
    assert res.avf.equals_avf and res.certificate.sigma == 1


FIRST_FAILURE = {
    # (k, s): first failing condition for degree ⌊2k/s⌋ + 1, at order 2k + 1 (energy
    # order 2k: the k-point Gauss quadrature error of the line integral). Found with
    # `rkcheck verify --fail-fast`; each is a "spider" whose centre has degree m + 1.
    (2, 1): "1,2,2,2,2,2",
    (3, 2): "1,2,3,2,3,2,3,2",
    (4, 3): "1,2,3,3,2,3,3,2,3,3",
    (6, 2): "1,2,3,2,3,2,3,2,3,2,3,2,3,2",
}


@pytest.mark.parametrize("k, s", [pytest.param(k, s, id=f"hbvm-{k}-{s}", marks=[heavy] if k == 6 else [])
                                  for k, s in FIRST_FAILURE])
@pytest.mark.parametrize("arithmetic", ["exact", "ball"])
def test_hbvm_holds_to_2k_over_s_and_fails_beyond(k, s, arithmetic):
    # every HBVM(k, s) here is exact in the field of its Gauss nodes (degree 48 for k = 6);
    # the same verdicts in 50-digit balls
    tab = family_tableau(FamilySpec("hbvm", s, k=k))
    m = (2 * k) // s
    res = check(tab, CheckOptions(degree=m, order=8, arithmetic=arithmetic))
    assert res.backend == arithmetic
    assert res.failures == [] and res.certificate.certified
    res = check(tab, CheckOptions(degree=m + 1, order=2 * k + 1, fail_fast=True, arithmetic=arithmetic))
    assert res.energy_order_to_digits == 2 * k
    # balls prove no hold: the energy order they prove is the vacuous 1
    assert res.energy_order == (2 * k if arithmetic == "exact" else 1)
    assert res.first_failure.id == FIRST_FAILURE[(k, s)]


# ------------------------------------------------------------------ new | verify -


def test_new_pipes_into_verify_from_stdin():
    new = subprocess.run([sys.executable, "-m", "rkcheck", "new", "gauss", "-s", "3"],
                         capture_output=True, text=True, check=True)
    # exact entries in Q(√15), as published (Hairer–Wanner II, Table 7.4)
    assert '["5/36", "2/9 - sqrt(15)/15", "5/36 - sqrt(15)/30"]' in new.stdout
    assert 'c = ["1/2 - sqrt(15)/10", "1/2", "1/2 + sqrt(15)/10"]' in new.stdout
    ver = subprocess.run([sys.executable, "-m", "rkcheck", "verify", "-", "--degree", "2", "--format", "json"],
                         input=new.stdout, capture_output=True, text=True)
    assert ver.returncode == 0, ver.stderr
    assert '"energy_order_all": true' in ver.stdout


@pytest.mark.parametrize("args", [pytest.param(["hbvm", "-k", "6", "-s", "2"], marks=heavy),
                                  ["hbvm", "-k", "4", "-s", "2"], ["radau-iia", "-s", "3", "--digits", "30"],
                                  ["kernel", "--zeta", "1/3", "--beta", "1/10"], ["avf", "-s", "2", "--rule", "radau-ii"]],
                         ids=["hbvm-6-2", "hbvm-4-2", "radau-iia-3", "kernel", "avf-radau-ii-2"])
def test_new_files_reproduce_the_family_verdicts(tmp_path, args):
    out = tmp_path / "new.toml"
    subprocess.run([sys.executable, "-m", "rkcheck", "new", *args, "-o", str(out)], check=True)
    written = load(str(out))
    from rkcheck.methods.families import parse_spec

    table = {"name": args[0]}
    it = iter(args[1:])
    for flag in it:
        value = next(it)
        key = {"-k": "k", "-s": "s", "--zeta": "zeta", "--beta": "beta", "--rule": "rule"}.get(flag)
        if key:
            table[key] = int(value) if key in ("k", "s") else value
    family = family_tableau(parse_spec(table))
    for degree in (3, 4):
        assert _states(written, degree, order=6) == _states(family, degree, order=6)


def test_new_exact_uses_root_forms_when_square_roots_do_not_suffice(tmp_path):
    # Radau IIA 4: after removing the node 1 an irreducible cubic remains; its zeros are
    # written root(P, k) and the tableau is checked exactly in their field
    out = tmp_path / "radau4.toml"
    r = subprocess.run([sys.executable, "-m", "rkcheck", "new", "radau-iia", "-s", "4", "--exact", "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    assert "root(" in text and "sqrt" not in text
    tab = load(str(out))
    values = tab.exact_values()
    assert values is not None and values.field.degree in (3, 6)
    # Radau IIA s = 4 has quadrature order 2s − 1 = 7 (published): Σ b c^(k−1) = 1/k
    # exactly for k ≤ 7 and not for k = 8
    b, c = values.b, values.c
    for k in range(1, 9):
        residual = sum((bi * ci ** (k - 1) for bi, ci in zip(b, c)), Fraction(0)) - Fraction(1, k)
        assert residual.is_zero() == (k <= 7), k


@heavy
def test_catalog_matches_the_committed_readme():
    # tableaux/README.md is generated, not edited: regenerate and compare
    r = subprocess.run([sys.executable, "-m", "rkcheck", "catalog", "tableaux/", "-o", "-"],
                       capture_output=True, text=True, cwd=TABLEAUX.parent)
    committed = (TABLEAUX / "README.md").read_text(encoding="utf-8")
    generated = r.stdout
    strip = lambda t: [line for line in t.splitlines() if not line.startswith("Generated by")]  # noqa: E731
    assert strip(generated) == strip(committed)
