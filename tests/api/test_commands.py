"""One public function per command: each is checked against values derived by
hand or by the brute-force reference (tests/support/reference.py), never against output
copied from rkcheck; where the CLI prints JSON, the API's result must agree with it; bad
options raise OptionError with the CLI's one-line message."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import pytest
from support import reference as ref
from support.clirun import run_cli

import rkcheck

MIDPOINT_TOML = '[method]\nname = "explicit midpoint"\n[tableau]\nA = [[0, 0], ["1/2", 0]]\nb = [0, 1]\n'
SQRT3 = math.sqrt(3)


def cli_message(capsys, *args: str) -> str:
    """The one line ``rkcheck ARGS`` prints for a user error (exit 2), without the prefix."""
    run = run_cli(capsys, *args)
    assert run.code == 2 and run.err.startswith("rkcheck: error: ") and run.err.count("\n") == 1, run.err
    return run.err[len("rkcheck: error: "):-1]


def value(entry, bits: int = 80) -> float:
    iv = entry.enclosure(bits)
    return float((iv.lo + iv.hi) / 2)


# ------------------------------------------------------------------ new


def test_new_rk4_is_kuttas_tableau():
    tab = rkcheck.new("rk4")
    h = Fraction(1, 2)
    assert [[e.exact for e in row] for row in tab.A] == [[0, 0, 0, 0], [h, 0, 0, 0], [0, h, 0, 0], [0, 0, 1, 0]]
    assert [e.exact for e in tab.b] == [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)]
    assert tab.info.claims  # the classical order 4 etc. of the literature, judged by verify
    assert rkcheck.verify(tab, order=4).ok


def test_new_families_by_hand():
    # AVF over 2-point Radau II: c = (1/3, 1), b = (3/4, 1/4), A = c bᵀ (definitions §4)
    avf = rkcheck.new("avf", stages=2, rule="radau-ii")
    assert [[e.exact for e in row] for row in avf.A] == [[Fraction(1, 4), Fraction(1, 12)],
                                                          [Fraction(3, 4), Fraction(1, 4)]]
    # Gauss, 2 stages: A = [[1/4, 1/4 − √3/6], [1/4 + √3/6, 1/4]], b = (1/2, 1/2)
    gauss = rkcheck.new("gauss", stages=2, name="mine")
    want = [[0.25, 0.25 - SQRT3 / 6], [0.25 + SQRT3 / 6, 0.25]]
    for row, wrow in zip(gauss.A, want):
        for e, w in zip(row, wrow):
            assert abs(value(e) - w) < 1e-15
    assert gauss.name == "mine"
    result = rkcheck.verify(gauss, order=4)  # Gauss with s stages has order 2s, quadrature order 2s
    assert result.classical_order == 4 and result.quadrature_order == 4


def test_new_toml_reads_back_as_the_same_method():
    rk4 = rkcheck.loads(rkcheck.new_toml("rk4", name="K"))
    assert rk4.name == "K" and [e.exact for e in rk4.b] == [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)]
    text = rkcheck.new_toml("gauss", stages=2)
    assert "sqrt(3)" in text and "Written by `rkcheck new gauss -s 2`" in text
    back = rkcheck.loads(text)
    assert abs(value(back.A[0][1]) - (0.25 - SQRT3 / 6)) < 1e-15 and abs(value(back.A[1][0]) - (0.25 + SQRT3 / 6)) < 1e-15
    decimals = rkcheck.loads(rkcheck.new_toml("gauss", stages=2, digits=20))
    assert decimals.A[0][1].text.startswith("-0.038675134594812882") and decimals.A[0][1].rounded_digits == 20


@pytest.mark.parametrize("method, stages", [("gauss", 2), ("rk4", None)])
def test_new_toml_writes_any_name_as_a_valid_toml_string(method, stages):
    # a newline, a tab, DEL, a quote and a backslash: TOML wants all but the tab escaped
    # (the standard library's parser is the independent judge)
    import tomllib

    name = 'a\nb\tc\x7fd"e\\f'
    text = rkcheck.new_toml(method, stages=stages, name=name)
    assert tomllib.loads(text)["method"]["name"] == name
    assert rkcheck.loads(text).name.startswith("a")  # reads back (names are shown printable)


def test_new_toml_is_what_the_cli_writes(capsys):
    for args, kwargs in ((["rk4"], {}), (["avf", "-s", "2", "--rule", "radau-ii"], {"stages": 2, "rule": "radau-ii"}),
                         (["kernel", "--zeta", "1/3", "--beta", "1e-12"], {"zeta": "1/3", "beta": "1e-12"})):
        run = run_cli(capsys, "new", *args)
        assert run.code == 0 and run.out == rkcheck.new_toml(args[0], **kwargs)


@pytest.mark.parametrize("cli, call", [
    (["new", "gauss"], lambda: rkcheck.new("gauss")),
    (["new", "hbvm", "-s", "2"], lambda: rkcheck.new_toml("hbvm", stages=2)),
    (["new", "gauss", "-s", "2", "--exact", "--digits", "3"], lambda: rkcheck.new_toml("gauss", stages=2, exact=True, digits=3)),
    (["new", "avf", "-s", "2", "--rule", "simpson"], lambda: rkcheck.new("avf", stages=2, rule="simpson")),
])
def test_new_refuses_with_the_cli_message(capsys, cli, call):
    with pytest.raises(rkcheck.OptionError) as err:
        call()
    assert str(err.value) == cli_message(capsys, *cli)


def test_new_bad_names_and_sizes_are_option_errors():
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.new("rk5")
    assert err.value.place == "method"
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.new("gauss", stages=21)
    assert err.value.place == "stages"
    with pytest.raises(rkcheck.OptionError):
        rkcheck.new_toml("gauss", stages=2, digits=0)


# ------------------------------------------------------------------ scan


def test_scan_gives_an_ok_row_an_error_row_and_never_raises(tmp_path):
    (tmp_path / "good.toml").write_text(MIDPOINT_TOML)
    bad = tmp_path / "bad.toml"
    bad.write_text('[tableau]\nA = [["1/2", "x"]]\nb = [1]\n')
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n')
    with pytest.raises(rkcheck.RkcheckError) as load_err:  # the file's own one-line message
        rkcheck.load(bad)
    rows_seen = []
    result = rkcheck.scan([tmp_path], jobs=1, on_file=lambda row, done, total: rows_seen.append((row.path, done, total)))
    by_name = {r.path.rsplit("/", 1)[-1]: r for r in result.rows}
    assert {n: r.status for n, r in by_name.items()} == {"bad.toml": "error", "good.toml": "ok",
                                                         "pyproject.toml": "skipped"}
    assert by_name["bad.toml"].error == str(load_err.value) and by_name["bad.toml"].verification is None
    good = by_name["good.toml"].verification
    # explicit midpoint: Σ b c = 1/2 (3 vertices holds), Σ b c² = 1/4 ≠ 1/3 (the star fails): energy order 2
    assert good is not None and good.energy_order == 2
    assert result.failed and not result.interrupted  # an error row fails the scan
    assert [d for _, d, _ in rows_seen] == [1, 2, 3] and {t for _, _, t in rows_seen} == {3}


def test_scan_agrees_with_the_cli_json(tmp_path, capsys):
    (tmp_path / "good.toml").write_text(MIDPOINT_TOML)
    (tmp_path / "bad.json").write_text("{")
    run = run_cli(capsys, "scan", str(tmp_path), "--format", "json", "--jobs", "1", "--order", "4")
    result = rkcheck.scan([str(tmp_path)], order=4, jobs=1)
    doc = json.loads(run.out)
    mine = json.loads(result.report("json"))
    assert run.code == 1 and result.failed
    assert [(f["file"], f["status"], f["error"]) for f in doc["files"]] == [
        (r.path, r.status, r.error) for r in result.rows]
    assert [f["status"] for f in mine["files"]] == [f["status"] for f in doc["files"]]
    assert mine["options"] == doc["options"]


def test_scan_refusals_are_rkcheck_errors(tmp_path, capsys):
    with pytest.raises(rkcheck.UserError) as err:  # no paths and no [tool.rkcheck] paths
        rkcheck.scan([])
    assert "give PATH" in str(err.value)
    with pytest.raises(rkcheck.UserError) as err:
        rkcheck.scan([tmp_path / "nope"])
    assert str(err.value) == cli_message(capsys, "scan", str(tmp_path / "nope"))
    for kwargs, place in (({"fail_on": "sometimes"}, "fail_on"), ({"jobs": 0}, "jobs"), ({"sort": "size"}, "sort"),
                          ({"order": 0}, "order")):
        with pytest.raises(rkcheck.OptionError) as err:
            rkcheck.scan([tmp_path], **kwargs)
        assert err.value.place == place


# ------------------------------------------------------------------ catalog


def test_catalog_orders_by_hand(tmp_path):
    (tmp_path / "mid.toml").write_text(MIDPOINT_TOML)
    (tmp_path / "README.md").write_text("not a tableau")
    cat = rkcheck.catalog([tmp_path], degrees=[2, None], order=6)
    assert cat.labels == ["m=2", "all H"] and len(cat.rows) == 1
    row = cat.rows[0]
    # classical order 2; quadrature: Σb = 1, Σbc = 1/2, Σbc² = 1/4 ≠ 1/3 → 2; quadratic H:
    # R(z) = 1 + z + z²/2, R(z)R(−z) = 1 + z⁴/4 → energy order 3; all H: the star fails → 2
    assert (row.path, row.classical, row.quadrature) == ("mid.toml", "2", "2")
    assert row.energy == {"m=2": "3", "all H": "2"}
    page = cat.to_markdown("rkcheck catalog x")
    assert "`rkcheck catalog x`" in page and "| `mid.toml` |" in page
    assert cat.families == [] and "## Families" not in page
    assert "ranked by C" not in page  # one method: no two share an energy order
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.catalog([tmp_path], degrees=["x"])
    assert err.value.place == "degrees"


def test_catalog_names_the_families_it_leaves_out(tmp_path):
    # a family (free [parameters]) is no one method: no row, but named, not silently dropped
    (tmp_path / "mid.toml").write_text(MIDPOINT_TOML)
    (tmp_path / "fam.toml").write_text('[parameters]\np = "free"\n[tableau]\nA = [["p"]]\nb = ["1"]\n')
    cat = rkcheck.catalog([tmp_path], degrees=[2], order=4)
    assert [r.path for r in cat.rows] == ["mid.toml"] and cat.families == ["fam.toml"]
    page = cat.to_markdown()
    assert "## Families" in page and "- `fam.toml`" in page


# ------------------------------------------------------------------ kernel


def test_kernel_gauss_rank_and_kernel_direction():
    # seed: Gauss and m = 2s gives rank s² − 1 with kernel (1 − c)bᵀ; here s = 2, c = 1/2 ∓ √3/6,
    # so the second row of the basis matrix is (1 − c₂)/(1 − c₁) = 2 − √3 times the first
    k = rkcheck.kernel(4, 2)
    assert (k.s, k.rank, k.dimension, k.exact) == (2, 3, 1, True)
    (N,) = k.basis
    first = [x.enclosure(80) for x in N[0]]
    second = [x.enclosure(80) for x in N[1]]
    for a, b in zip(first, second):
        assert abs(float(b.mid / a.mid) - (2 - SQRT3)) < 1e-15


def test_kernel_zero_row_sum_direction_is_the_seeds_N():
    # m = 2s − 1 = 3 at 2-point Radau II (ζ = 1): rank s² − 3 = 1, and ker M ∩ {N·1 = 0} is
    # spanned by the seed's N = ((ζ−1)1 − 2ζc) bᵀ(I − 2C), c = (1/3, 1), b = (3/4, 1/4)
    k = rkcheck.kernel(3, 2, rule="radau-ii")
    assert (k.rank, k.dimension, len(k.zero_row_sum)) == (1, 3, 1)
    zeta, c, b = 1, [Fraction(1, 3), Fraction(1)], [Fraction(3, 4), Fraction(1, 4)]
    seed = [[((zeta - 1) - 2 * zeta * c[i]) * b[j] * (1 - 2 * c[j]) for j in range(2)] for i in range(2)]
    (N,) = k.zero_row_sum
    ratio = N[0][0] / seed[0][0]
    assert all(N[i][j] == ratio * seed[i][j] for i in range(2) for j in range(2))
    # ζ = −1 (Radau I), s = 3, m = 5: rank s² − s − 1 = 5
    assert rkcheck.kernel(5, 3, rule="radau-i").rank == 5


def test_kernel_matches_the_cli_and_refuses_like_it(capsys):
    run = run_cli(capsys, "kernel", "-m", "3", "--tableau", "@avf-radau-ii-2")
    k = rkcheck.kernel(3, tableau="@avf-radau-ii-2")
    assert f"rank M = {k.rank}   dim ker M = {k.dimension}" in run.out
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.kernel(4)
    assert str(err.value) == cli_message(capsys, "kernel", "-m", "4")
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.kernel(2, 2)
    assert err.value.place == "degree"


# ------------------------------------------------------------------ perturb


def test_perturb_slopes_and_the_cli_json(capsys):
    # seed §2.3–2.4: along the kernel direction every linear condition holds and the others
    # fail quadratically (slope 2); a generic direction fails linearly (slope 1)
    args = dict(degree=3, order=5, eps="1e-1..1e-6")
    along = rkcheck.perturb("@avf-gauss-2", "kernel", **args)
    assert along.slope is not None and abs(along.slope - 2) < 0.05
    generic = rkcheck.perturb("@avf-gauss-2", "random", **args)
    assert generic.slope is not None and abs(generic.slope - 1) < 0.05
    run = run_cli(capsys, "perturb", "@avf-gauss-2", "--direction", "kernel", "--degree", "3", "--order", "5",
                  "--eps", "1e-1..1e-6", "--format", "json")
    doc = json.loads(run.out)
    assert doc["slope"] == along.slope and doc["direction"] == along.direction
    assert [(Fraction(r["eps"]), r["first_failing_order"], r["failing"], r["detected"]) for r in doc["rows"]] == [
        (r.eps, r.first_failing_order, r.failing, r.detected) for r in along.rows]
    assert [r.eps for r in along.rows] == [Fraction(1, 10 ** k) for k in range(1, 7)]


@pytest.mark.parametrize("cli, kwargs", [
    (["--direction", "kernel", "--degree", "3", "--eps", "2"], dict(direction="kernel", degree=3, eps="2")),
    (["--direction", "kernel", "--degree", "3", "--eps", "x"], dict(direction="kernel", degree=3, eps="x")),
    (["--direction", "kernel", "--order", "4"], dict(direction="kernel", order=4)),
    (["--direction", "sideways", "--degree", "3"], dict(direction="sideways", degree=3)),
    (["--direction", "random", "--dps", "3"], dict(direction="random", dps="3")),
])
def test_perturb_refuses_with_the_cli_message(capsys, cli, kwargs):
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.perturb("@avf-gauss-2", **kwargs)
    assert str(err.value) == cli_message(capsys, "perturb", "@avf-gauss-2", *cli)


def test_perturb_takes_a_list_of_eps():
    res = rkcheck.perturb("@avf-gauss-2", "entry:1,2", order=3, eps=[Fraction(1, 100), "1e-4"], dps=[15])
    assert [r.eps for r in res.rows] == [Fraction(1, 100), Fraction(1, 10000)]


# ------------------------------------------------------------------ bench


def test_bench_backends_agree_with_the_reference():
    # Heun: c = (0, 1), b = (1/2, 1/2); its failing conditions up to order 4 by brute force
    A, b = [[0, 0], [1, 0]], [Fraction(1, 2), Fraction(1, 2)]
    conds = [c for n in range(3, 6) for c in ref.energy_conditions(n)]
    failing = sum(1 for c in conds if ref.energy_residual(c, A, b) != 0)
    res = rkcheck.bench("@heun", order=4, dps=[15, 30], repeat=1)
    assert [r.backend for r in res.rows] == ["float64", "dps:15", "dps:30", "exact"]
    assert all(r.conditions == len(conds) == 5 and r.failures == failing and r.agrees for r in res.rows)
    assert res.degree is None and res.order == 4 and res.tables_seconds >= 0
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.bench("@heun", order=4, repeat=0)
    assert err.value.place == "repeat"


# ------------------------------------------------------------------ simulate, workprec


def test_hamiltonians_and_their_degrees(capsys):
    assert [rkcheck.hamiltonian(p).degree for p in ("harmonic", "henon-heiles", "quartic", "fpu")] == [2, 3, 4, 4]
    ham = rkcheck.hamiltonian("random:degree=5,dim=1,seed=3")
    assert ham.degree == 5 and ham.dim == 2
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.hamiltonian("pendulum")
    assert str(err.value) == cli_message(capsys, "simulate", "@rk4", "--problem", "pendulum")


def test_simulate_energy_by_hand():
    # explicit Euler on H = (q² + p²)/2 multiplies H by 1 + h² each step: from (1, 0),
    # |ΔH| after n steps is ((1 + h²)^n − 1)/2; implicit midpoint keeps quadratic H exactly
    euler = rkcheck.simulate("@euler", "harmonic", h="1/10", steps=100)
    assert euler.h == Fraction(1, 10) and euler.times[-1] == pytest.approx(10)
    assert euler.max_energy_error == pytest.approx((1.01 ** 100 - 1) / 2, rel=1e-12)
    midpoint = rkcheck.simulate("@implicit-midpoint", rkcheck.hamiltonian("harmonic"), h=Fraction(1, 10), steps=100)
    assert midpoint.max_energy_error < 1e-14


def test_simulate_refuses_with_the_cli_message(capsys):
    with pytest.raises(rkcheck.RkcheckError) as err:
        rkcheck.simulate("@rk4", "harmonic", h="0")
    assert str(err.value) == cli_message(capsys, "simulate", "@rk4", "--problem", "harmonic", "--h", "0")
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.simulate("@rk4", "harmonic", steps=0)
    assert err.value.place == "steps"


def test_empirical_energy_order_of_rk4_on_quadratic_h():
    # RK4: R(z)R(−z) = 1 + z⁶/72 + …, so ΔH = O(h⁶) for quadratic H: energy order 5
    fit = rkcheck.empirical_energy_order("@rk4", "harmonic", points=2)
    assert fit.empirical_order is not None and round(fit.empirical_order) == 5
    assert fit.agree and fit.algebraic_order == "5" and not fit.at_solver_precision


def test_work_precision_error_falls_like_h_to_the_order(capsys):
    wp = rkcheck.work_precision(["@rk4"], "harmonic", T=1, steps=[10, 20])
    assert [(r.steps, r.h) for r in wp.rows] == [(10, Fraction(1, 10)), (20, Fraction(1, 20))]
    assert 12 < wp.rows[0].error / wp.rows[1].error < 20  # order 4: halving h divides the error by about 16
    assert wp.T == 1 and "6-stage Gauss" in wp.reference
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.work_precision(["@rk4"], "harmonic", steps="10,x")
    assert str(err.value) == cli_message(capsys, "workprec", "@rk4", "--problem", "harmonic", "--steps", "10,x")


# ------------------------------------------------------------------ conditions, explain


def test_conditions_counts_from_the_definitions_and_the_reference():
    # definitions §3: 1, 1, 3, 4, 11, 19, 47, 97, 235 conditions with 3 … 11 vertices
    listed = rkcheck.conditions(10)
    assert listed.counts == dict(zip(range(2, 11), [1, 1, 3, 4, 11, 19, 47, 97, 235]))
    assert listed.total == 418 and rkcheck.conditions(10, count=True).counts == listed.counts
    bounded = rkcheck.conditions(6, 3)
    want = sorted((tuple(c["id"]) for n in range(3, 8) for c in ref.energy_conditions(n, max_degree=3)),
                  key=lambda s: (len(s), s))
    assert [t.level_sequence for t in bounded.free_trees] == want
    # the three 5-vertex trees by hand: star, path (centre rooting), and the chair's larger centre
    assert [t.id for t in rkcheck.conditions(4).free_trees if t.vertices == 5] == ["1,2,2,2,2", "1,2,3,2,3", "1,2,3,3,2"]
    assert rkcheck.conditions(30, count=True).free_trees == []


def test_conditions_agree_with_the_cli_json_and_refuse_like_it(capsys):
    run = run_cli(capsys, "conditions", "--order", "6", "--degree", "3", "--format", "json")
    doc = json.loads(run.out)
    listed = rkcheck.conditions(6, degree=3)
    assert {c["order"]: c["conditions"] for c in doc["counts"]} == listed.counts
    assert [c["id"] for c in doc["conditions"]] == [t.id for t in listed.free_trees]
    with pytest.raises(rkcheck.RkcheckError) as err:
        rkcheck.conditions(8, max_conditions=5)
    assert str(err.value) == cli_message(capsys, "conditions", "--order", "8", "--max-conditions", "5")
    for kwargs, place in (({"order": 0}, "order"), ({"order": 4, "degree": "x"}, "degree")):
        with pytest.raises(rkcheck.OptionError) as err:
            rkcheck.conditions(**kwargs)
        assert err.value.place == place


def test_energy_condition_loads_a_named_tableau_and_keeps_the_report_input():
    # the 4-vertex star: R = (Σb)³/σ([τ³]) − Σ b c²/σ([[τ²]]) = 1/6 − Σ b c²/2;
    # RK4: Σ b c² = 1/3 → 0; Heun: Σ b c² = 1/2 → −1/12 (up to the rooting's sign)
    assert rkcheck.energy_condition("1,2,2,2", "@rk4").residual == 0
    heun = rkcheck.energy_condition((1, 2, 2, 2), "@heun")
    assert abs(heun.residual) == Fraction(1, 12) and heun.state == "fails"
    assert heun.tableau is not None and heun.tableau.name.startswith("Heun")
    with pytest.raises(rkcheck.RkcheckError):
        rkcheck.energy_condition("1,2,2,2", "@rk4", max_stages=2)
    with pytest.raises(rkcheck.OptionError) as err:
        rkcheck.energy_condition("1,2,2,2", "@rk4", dps=3)
    assert err.value.place == "dps"


def test_show_warnings_through_the_api():
    from rkcheck.api.tableaux import tableau_warnings

    tab = rkcheck.from_arrays([["1/2"]], ["1/2"], ["1/3"])  # Σb = 1/2, c ≠ A·1 = 1/2
    said = tableau_warnings(tab)
    assert any("c differs from the row sums" in w for w in said) and any("Σb" in w for w in said)
