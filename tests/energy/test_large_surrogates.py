"""Checks of tableaux of hundreds of stages (a kernel's surrogate) within their memory:
the surrogate is weighed before it is built, and its channels run in passes whose
images of the tableau fit a bound — however narrow the passes, the residues are those
of one wide pass, here checked against the independent reference (exact rationals,
tree by tree)."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest
from support import reference as ref
from support.heavy import heavy
from support.limits import run_limited
from support.paths import TABLEAUX

import rkcheck
import rkcheck.evaluation.scaled as scaled
import rkcheck.properties.orders as orders


def _tableau(stages: int, digits: int, seed: int) -> tuple[list[list[Fraction]], list[Fraction]]:
    """A dense rational tableau whose entries have about ``digits`` digits: many channels."""
    rng = random.Random(seed)

    def entry() -> Fraction:
        return Fraction(rng.randint(-10**digits, 10**digits), rng.randint(1, 10**digits))

    A = [[entry() for _ in range(stages)] for _ in range(stages)]
    b = [entry() for _ in range(stages - 1)]
    return A, b + [1 - sum(b)]  # consistent: classical order at least 1


def _high_degree(folder):
    """``A = τ⁴⁹σ``, ``B = 1``: surrogates of hundreds of nodes with entries of a thousand
    digits."""
    path = folder / "high-degree.toml"
    path.write_text('[continuous]\nA = "tau^49*sigma"\nb = "1"\n', encoding="utf-8")
    return path


def _refusal(argv: list[str], memory_mb: int, cpu_seconds: int) -> str:
    """``rkcheck ARGV`` under the limits: exit 2 with one line on stderr, that line."""
    run = run_limited(["-m", "rkcheck", *argv], memory_mb=memory_mb, cpu_seconds=cpu_seconds)
    assert run.code == 2, run.err
    [line] = run.err.strip().splitlines()
    return line


@pytest.fixture
def one_channel_per_pass(monkeypatch):
    """Every pass, screen and classical-order group as narrow as it can be."""
    for module in (scaled, orders):
        monkeypatch.setattr(module, "channels_per_image_pass", lambda stages: 1)


@pytest.mark.parametrize("seed", [1, 2])
def test_narrow_passes_give_the_reference_residuals_and_classical_order(one_channel_per_pass, seed):
    A, b = _tableau(4, 30, seed)
    tab = rkcheck.from_arrays([[str(x) for x in row] for row in A], [str(x) for x in b])
    result = rkcheck.verify(tab, order=5, degree=None)
    assert len(result.values.scaled.primes_for(result.values.scaled.decision_bits(6, 6))) > 4  # several passes
    assert {c.level_sequence: c.residual for c in result.conditions} == {
        cond["id"]: ref.energy_residual(cond, A, b) for n in range(3, 7) for cond in ref.energy_conditions(n)}
    assert result.classical_order == ref.classical_order(A, b, 5)


def test_narrow_passes_keep_a_kernels_verdicts(one_channel_per_pass):
    # Hairer's energy-preserving collocation with s = 2 (tableaux/continuous/epcm-2.toml):
    # classical order 2s = 4, and every energy condition holds (it preserves energy)
    result = rkcheck.verify("tableaux/continuous/epcm-2.toml", order=6, degree=None)
    assert result.classical_order == 4
    assert result.all_hold


@heavy
def test_a_kernel_check_the_estimate_lets_through_fits_the_memory_it_was_given(tmp_path):
    # τ⁴⁹σ to order 7: a surrogate of 295 stages whose entries need 533 channels.  With
    # all their images in one pass the check took 1.4 GB where it estimated 0.93 GB, so
    # under an address space of 1.3 GB it was let through and ran out of memory
    path = _high_degree(tmp_path)
    run = run_limited(["-m", "rkcheck", "verify", str(path), "--order", "7", "--no-cache", "-q"],
                      memory_mb=1300, cpu_seconds=120)
    assert run.code == 1, run.err  # a verdict (some condition fails), not "out of memory" (exit 2)
    conditions = sum(ref.count_nonsuperfluous(n) for n in range(3, 9))  # free trees of order <= 7
    assert f"of {conditions} conditions" in run.out.strip().splitlines()[-1], run.out


def test_a_surrogate_the_memory_cannot_hold_is_refused_before_it_is_built(tmp_path):
    # τ⁴⁹σ to order 8: 344 nodes, entries of some 1 500 characters (118 680 of them).
    # Built before the budget was consulted, under 600 MB the surrogate alone ran the
    # process out of memory: GMP, failing to allocate, aborted it (SIGABRT, no message)
    path = _high_degree(tmp_path)
    line = _refusal(["verify", str(path), "--order", "8", "--no-cache"], memory_mb=600, cpu_seconds=60)
    assert line.startswith("rkcheck: error: order 8 needs about ") and " MB is available" in line, line


def test_a_decimal_kernels_box_is_weighed_with_its_entries(tmp_path):
    # a kernel of degree 40 in 6-digit decimals at order 3: 121 nodes, 14 762 entries of
    # about 1 100 characters, each enclosed, centred and differentiated in the decimals
    # (81 s and 578 MB measured); estimated at 195 MB, it started under 400 MB and ran
    # out of memory after 80 s: now refused before the surrogate is built
    path = tmp_path / "decimal-40.toml"
    path.write_text('[continuous]\nA = "tau + 0.250000*tau^40*sigma^40 - 0.333333*tau^39*sigma^2"\n'
                    'b = "1 + 0.142857*sigma^40 - 0.142857*sigma^39"\n', encoding="utf-8")
    line = _refusal(["verify", str(path), "--order", "3", "--no-cache"], memory_mb=400, cpu_seconds=20)
    assert line.startswith("rkcheck: error: order 3 needs about ") and " MB is available" in line, line


def test_explain_weighs_the_surrogate_before_it_builds_it(tmp_path):
    # the same surrogate for one tree of 8 vertices: GMP aborted explain under 500 MB
    path = _high_degree(tmp_path)
    line = _refusal(["explain", "1,2,3,3,2,2,2,2", "--tableau", str(path)], memory_mb=500, cpu_seconds=60)
    assert line.startswith(f"rkcheck: error: {path}: the surrogate exact for trees of 8 vertices (344 nodes) needs "
                           "about "), line
    assert line.endswith("explain a tree of fewer vertices"), line


def test_a_catalogue_weighs_each_file_against_the_memory_available(tmp_path):
    # the same surrogate in a catalogue: its row says why it was refused (with the
    # catalogue's own options), the other files are catalogued; it ran out of memory
    # instead (or GMP aborted the whole catalogue)
    _high_degree(tmp_path)
    (tmp_path / "rk4.toml").write_text((TABLEAUX / "explicit" / "rk4.toml").read_text(encoding="utf-8"), encoding="utf-8")
    run = run_limited(["-m", "rkcheck", "catalog", str(tmp_path), "--order", "8"], memory_mb=600, cpu_seconds=120)
    assert run.code == 1, run.err
    rows: dict[str, str] = {}
    for line in run.out.splitlines():  # the first table's rows (the constants' table follows)
        if line.startswith("| `"):
            rows.setdefault(line.split("|")[1].strip(), line)
    assert "error: " in rows["`high-degree.toml`"] and "order 8 needs about " in rows["`high-degree.toml`"]
    assert rows["`high-degree.toml`"].count("lower --order or --degrees") == 1 and "--max-conditions" not in run.out
    assert "error" not in rows["`rk4.toml`"] and "| 4 |" in rows["`rk4.toml`"]  # RK4: 4 stages, classical order 4
