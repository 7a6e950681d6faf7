"""Methods of equal energy order compared by the energy error constant: scan --sort energy,
the scan CSV/JSON keys, and the catalogue's columns and ranking.

Expected values: C² = Σ R² over the first failing conditions, by the brute-force reference
(tests/support/reference.py) on the rational shipped tableaux; symplecticity and symmetry
from Hairer–Lubich–Wanner (Gauss: both; Lobatto IIIA: symmetric only; explicit: neither)."""

from __future__ import annotations

import csv
import io
import json
from fractions import Fraction as F

from support import reference as ref
from support.clirun import run_cli
from support.paths import TABLEAUX

from rkcheck.batch.catalog import catalog_row
from rkcheck.io.loader import load
from rkcheck.reports.markdown import catalog_markdown

ORDER3 = ["explicit/ralston.toml", "explicit/ssprk3.toml", "collocation/radau-iia-2.toml", "collocation/radau-ia-2.toml"]


def reference_constant_squared(path: str, degree):
    tab = load(str(TABLEAUX / path))
    A, b = tab.exact_A(), tab.exact_b()
    for n in range(3, 9):
        residuals = [ref.energy_residual(c, A, b) for c in ref.energy_conditions(n, degree)]
        if any(residuals):
            return n - 2, sum(r * r for r in residuals)
    return None


def test_scan_sorts_equal_energy_orders_by_the_constant(capsys):
    paths = [str(TABLEAUX / p) for p in ORDER3 + ["explicit/rk4.toml", "explicit/heun.toml"]]
    r = run_cli(capsys, "scan", *paths, "--degree", "4", "--sort", "energy", "--format", "json", "--jobs", "1")
    files = json.loads(r.out)["files"]
    got = [f["file"].split("tableaux/")[1] for f in files]
    expected = sorted(
        (p for p in ORDER3 + ["explicit/rk4.toml", "explicit/heun.toml"]),
        key=lambda p: (-reference_constant_squared(p, 4)[0], reference_constant_squared(p, 4)[1]),
    )
    assert got == expected
    for f in files:
        p = f["file"].split("tableaux/")[1]
        ec = f["result"]["summary"]["error_constant"]
        assert F(ec["squared"]) == reference_constant_squared(p, 4)[1]


def test_scan_csv_has_the_new_columns(capsys):
    r = run_cli(capsys, "scan", str(TABLEAUX / "collocation" / "lobatto-iiia-3.toml"), "--format", "csv", "--jobs", "1")
    (row,) = list(csv.DictReader(io.StringIO(r.out)))
    assert (row["symplectic"], row["symmetric"]) == ("fails", "holds")
    assert row["error_constant"] == ""  # its [check] degree is 2, proven for every order: no constant
    r = run_cli(capsys, "scan", str(TABLEAUX / "collocation" / "lobatto-iiia-3.toml"), "--degree", "4",
                "--format", "csv", "--jobs", "1")
    (row,) = list(csv.DictReader(io.StringIO(r.out)))
    exact = reference_constant_squared("collocation/lobatto-iiia-3.toml", 4)[1]
    assert abs(F(row["error_constant"]) ** 2 / exact - 1) < F(1, 10**10)  # 12 significant digits
    # the text report has a C column
    out = run_cli(capsys, "scan", str(TABLEAUX / "explicit" / "rk4.toml"), "--jobs", "1", "--sort", "energy").out
    header = next(line for line in out.splitlines() if "energy" in line)
    assert header.split()[:7] == ["file", "method", "s", "m", "classical", "energy", "C"]
    assert "0.015 " in out  # RK4, all H: C = 0.01514 (compact form)


def test_catalog_columns_and_ranking():
    paths = ["collocation/gauss-2.toml", "collocation/lobatto-iiia-3.toml", "explicit/rk4.toml"] + ORDER3
    rows = []
    for p in paths:
        row = catalog_row(str(TABLEAUX / p), [4], 8)
        row.path = p
        rows.append(row)
    cells = {r.path: (r.symplectic, r.symmetric) for r in rows}
    assert cells["collocation/gauss-2.toml"][0] in ("yes", "yes†") and cells["collocation/gauss-2.toml"][1] in ("yes", "yes†")
    assert cells["collocation/lobatto-iiia-3.toml"] == ("no", "yes")
    assert cells["explicit/rk4.toml"] == ("no", "no")
    text = catalog_markdown(rows, ["m=4"], 8, "test")
    line = next(x for x in text.splitlines() if x.startswith("- m=4, energy order 3:"))
    ranked = [part.split("`")[1] for part in line.split(":", 1)[1].split(" < ")]
    assert ranked == sorted(ORDER3, key=lambda p: reference_constant_squared(p, 4)[1])


def test_a_long_path_folds_and_the_verdict_columns_keep_their_width(capsys, tmp_path):
    # found by a new user: in a clone under a long folder, the one-file scan's absolute
    # path squeezed every column to "ener…"; the path must fold instead
    deep = tmp_path / ("a" * 60) / ("b" * 60)
    deep.mkdir(parents=True)
    (deep / "rk4.toml").write_text((TABLEAUX / "explicit" / "rk4.toml").read_text(encoding="utf-8"), encoding="utf-8")
    out = run_cli(capsys, "scan", str(deep / "rk4.toml"), "--jobs", "1", "--sort", "energy").out
    header = next(line for line in out.splitlines() if "energy" in line)
    assert header.split()[:7] == ["file", "method", "s", "m", "classical", "energy", "C"]
    assert "0.015 " in out  # RK4's C in full, not "0.0…"
    assert "rk4.toml" in out and "…" not in header
