"""rkcheck scan: rows, exit codes per --fail-on, jobs, formats, configuration, Ctrl-C."""

from __future__ import annotations

import csv
import io
import json
import os
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from support.clirun import run_cli
from support.paths import TABLEAUX

MIDPOINT_OK = """[method]
name = "midpoint, honest claims"
[tableau]
A = [["1/2"]]
b = [1]
[check]
degree = 2
[expect]
energy_order = {degree = 2, value = "all"}
quadrature_order = 2
"""
# RK4 claims classical order 5 (wrong: it is 4)
RK4_WRONG = """[method]
name = "RK4, wrong claim"
[tableau]
A = [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]]
b = ["1/6", "1/3", "1/3", "1/6"]

[expect]
classical_order = 5
"""
RK4_NO_CLAIMS = """{"method": {"name": "RK4 without claims"},
 "tableau": {"A": [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]],
             "b": ["1/6", "1/3", "1/3", "1/6"]}}
"""
BROKEN = '[tableau]\nA = [["1/4", "1/4 - )"], [0, 0]]\nb = [1, 0]\n'
NOT_TABLEAU = '[project]\nname = "something"\n'


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "sub").mkdir()
    files = {
        "a-good.toml": MIDPOINT_OK,
        "b-wrong-claim.toml": RK4_WRONG,
        "sub/c-no-claims.json": RK4_NO_CLAIMS,
        "d-broken.toml": BROKEN,
        "e-other.toml": NOT_TABLEAU,
        "notes.txt": "not scanned",
    }
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    return tmp_path


def scan_json(capsys, folder, *extra):
    r = run_cli(capsys, "scan", str(folder), "--format", "json", "--jobs", "1", *extra)
    return r, json.loads(r.out)


def test_rows_statuses_and_order(capsys, folder):
    r, doc = scan_json(capsys, folder)
    rows = [(Path(f["file"]).relative_to(folder).as_posix(), f["status"]) for f in doc["files"]]
    # deterministic sorted order; txt ignored; statuses under the default --fail-on claims
    assert rows == [
        ("a-good.toml", "ok"),
        ("b-wrong-claim.toml", "failed"),
        ("d-broken.toml", "error"),
        ("e-other.toml", "skipped"),
        ("sub/c-no-claims.json", "ok"),
    ]
    broken = doc["files"][2]
    assert broken["error"].endswith("A[1][2]: unexpected ')' at column 7") and broken["result"] is None
    wrong = doc["files"][1]["result"]
    assert wrong["claims"][0]["claimed"] == "5" and wrong["claims"][0]["found"] == "4"
    assert r.code == 1
    assert doc["totals"] == {"files": 5, "ok": 2, "failed": 1, "error": 1, "skipped": 1}


def test_exit_codes_follow_fail_on(capsys, folder):
    _, doc = scan_json(capsys, folder, "--fail-on", "conditions")
    status = {Path(f["file"]).name: f["status"] for f in doc["files"]}
    assert status["c-no-claims.json"] == "failed"  # RK4 fails higher energy conditions
    assert status["b-wrong-claim.toml"] == "failed" and status["a-good.toml"] == "ok"
    assert run_cli(capsys, "scan", str(folder), "--fail-on", "never", "--jobs", "1").code == 0
    ok_only = run_cli(capsys, "scan", str(folder), "--jobs", "1", "--exclude", "b-*", "--exclude", "d-*")
    assert ok_only.code == 0
    auto = run_cli(capsys, "scan", str(folder / "sub"), "--fail-on", "auto", "--jobs", "1")
    assert auto.code == 1  # no claims: judged by its conditions


def test_jobs_1_and_2_give_identical_results(capsys, folder):
    def strip_times(doc):
        for f in doc["files"]:
            f.pop("time")
            if f["result"]:
                f["result"].pop("timings")
        doc["options"].pop("jobs")
        return doc

    _, one = scan_json(capsys, folder)
    r2 = run_cli(capsys, "scan", str(folder), "--format", "json", "--jobs", "2")
    two = json.loads(r2.out)
    assert strip_times(one) == strip_times(two)


def test_workers_send_back_exact_algebraic_results(capsys, tmp_path):
    # results of tableaux checked in a number field (FLINT polynomials inside) cross the
    # process boundary: jobs 2 gives the rows and residuals that jobs 1 gives
    from support.paths import TABLEAUX

    folder = tmp_path / "alg"
    folder.mkdir()
    for rel in ("collocation/gauss-2.toml", "collocation/gauss-3.toml", "counterexamples/kernel-gauss-beta-0.1.toml"):
        (folder / Path(rel).name).write_text((TABLEAUX / rel).read_text(encoding="utf-8"), encoding="utf-8")
    docs = []
    for jobs in ("1", "2"):
        r = run_cli(capsys, "scan", str(folder), "--format", "json", "--jobs", jobs, "--degree", "4")
        doc = json.loads(r.out)
        assert [f["status"] for f in doc["files"]] == ["ok", "ok", "ok"], doc["files"]
        docs.append([(f["file"], f["result"]["summary"]["energy_order"],
                      [c.get("residual_exact") for c in f["result"]["conditions"]]) for f in doc["files"]])
    assert docs[0] == docs[1]


def test_names_of_the_shipped_library_scan_like_their_files(capsys):
    # @name works wherever a file does; same verdicts as the file itself
    from support.paths import TABLEAUX

    by_name = json.loads(run_cli(capsys, "scan", "@rk4", "@heun", "--format", "json", "--degree", "3").out)
    by_path = json.loads(run_cli(capsys, "scan", str(TABLEAUX / "explicit" / "rk4.toml"),
                                 str(TABLEAUX / "explicit" / "heun.toml"), "--format", "json", "--degree", "3").out)
    assert [f["file"] for f in by_name["files"]] == ["@rk4", "@heun"]
    assert [f["status"] for f in by_name["files"]] == ["ok", "ok"]
    summaries = [[f["result"]["summary"]["energy_order"] for f in d["files"]] for d in (by_name, by_path)]
    assert summaries[0] == summaries[1]
    r = run_cli(capsys, "scan", "@rk5")
    assert r.code == 2 and "@rk4" in r.err and len(r.err.strip().splitlines()) == 1


def test_junit_parses_with_the_right_counts(capsys, folder):
    r = run_cli(capsys, "scan", str(folder), "--format", "junit", "--jobs", "1")
    root = ET.fromstring(r.out)
    suite = root.find("testsuite")
    assert suite.get("tests") == "5" and suite.get("failures") == "1" and suite.get("errors") == "1"
    assert suite.get("skipped") == "1"
    cases = suite.findall("testcase")
    assert len(cases) == 5
    failure = next(c for c in cases if c.find("failure") is not None)
    assert "expect.classical_order: claimed 5, found 4" in failure.find("failure").get("message")
    assert next(c for c in cases if c.find("error") is not None).get("name").endswith("d-broken.toml")


def test_csv_round_trips(capsys, folder):
    r = run_cli(capsys, "scan", str(folder), "--format", "csv", "--jobs", "1")
    rows = list(csv.DictReader(io.StringIO(r.out)))
    assert [Path(row["file"]).name for row in rows] == [
        "a-good.toml", "b-wrong-claim.toml", "d-broken.toml", "e-other.toml", "c-no-claims.json"]
    rk4 = rows[1]
    assert rk4["classical_order"] == "4" and rk4["claims_ok"] == "false" and rk4["stages"] == "4"
    assert "claimed 5, found 4" in rk4["broken_claims"]
    # write it back with the csv module and read it again: identical
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=rows[0].keys(), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    assert list(csv.DictReader(io.StringIO(buf.getvalue()))) == rows


ANNOTATION = re.compile(r"^::(error|warning|notice) file=[^,:]+(,line=\d+)?,title=[^:]+::.+$")


def test_github_annotations_point_at_the_claim_line(capsys, folder):
    r = run_cli(capsys, "scan", str(folder), "--format", "github", "--jobs", "1")
    lines = r.out.strip().splitlines()
    assert lines and all(ANNOTATION.match(line) for line in lines), lines
    claim = next(line for line in lines if "classical_order" in line)
    expect_line = RK4_WRONG.splitlines().index("classical_order = 5") + 1
    assert f",line={expect_line}," in claim
    broken = next(line for line in lines if "d-broken.toml" in line)
    assert broken.startswith("::error")


def test_pyproject_configuration_and_flags_override(tmp_path, capsys, folder, monkeypatch):
    (folder / "pyproject.toml").write_text(
        '[tool.rkcheck]\npaths = ["."]\nexclude = ["d-*", "b-*"]\nformat = "json"\ndegree = 3\njobs = 1\n',
        encoding="utf-8")
    work = folder / "sub"
    monkeypatch.chdir(work)  # config is found by walking up
    r = run_cli(capsys, "scan")
    doc = json.loads(r.out)
    names = [Path(f["file"]).name for f in doc["files"]]
    assert "d-broken.toml" not in names and "b-wrong-claim.toml" not in names
    no_claims = next(f for f in doc["files"] if f["file"].endswith("c-no-claims.json"))
    assert no_claims["result"]["options"]["degree"] == 3  # from [tool.rkcheck]
    r = run_cli(capsys, "scan", "--degree", "4", "--format", "csv")
    assert "degree" in r.out.splitlines()[0] and ",4," in r.out  # flags override the config
    bad = folder / "pyproject.toml"
    bad.write_text('[tool.rkcheck]\ndegre = 3\n', encoding="utf-8")
    r = run_cli(capsys, "scan")
    assert r.code == 2 and "tool.rkcheck.degre: unknown key" in r.err


# Ctrl-C, SIGTERM and worker death: tests/batch/test_scan_signals.py


def test_a_scan_that_finds_nothing_is_an_error_unless_allowed(capsys, tmp_path, folder, monkeypatch):
    import rkcheck

    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "notes.txt").write_text("no tableau here", encoding="utf-8")
    refused = run_cli(capsys, "scan", str(empty))
    assert refused.code == 2 and refused.out == "" and len(refused.err.strip().splitlines()) == 1
    assert str(empty) in refused.err and "--allow-empty" in refused.err
    # a glob that leaves nothing: the same refusal, saying how many files it took away
    # (the fixture folder has 5 *.toml/*.json files)
    r = run_cli(capsys, "scan", str(folder), "--exclude", "*.toml", "--exclude", "*.json")
    assert r.code == 2 and "(5 excluded" in r.err
    allowed = run_cli(capsys, "scan", str(empty), "--allow-empty")
    assert allowed.code == 0 and "0 files" in allowed.out
    # the API: an RkcheckError with the CLI's message, or an empty result when allowed
    with pytest.raises(rkcheck.RkcheckError) as err:
        rkcheck.scan([empty])
    assert refused.err.strip() == f"rkcheck: error: {err.value}"
    assert rkcheck.scan([empty], allow_empty=True).rows == []
    # [tool.rkcheck] allow_empty, validated like every other key
    (empty / "pyproject.toml").write_text("[tool.rkcheck]\npaths = ['sub']\nallow_empty = true\n", encoding="utf-8")
    (empty / "sub").mkdir()
    monkeypatch.chdir(empty)
    assert run_cli(capsys, "scan").code == 0
    (empty / "pyproject.toml").write_text("[tool.rkcheck]\npaths = ['sub']\nallow_empty = 'yes'\n", encoding="utf-8")
    r = run_cli(capsys, "scan")
    assert r.code == 2 and "tool.rkcheck.allow_empty: expected true or false" in r.err


def test_a_gate_that_fails_a_file_is_its_annotation_and_junit_failure(capsys, tmp_path):
    # the 6-digit Gauss-2 tableau meets its claims only to its digits: no claim is broken,
    # no condition fails, and --require proof fails the file — which must still say why
    (tmp_path / "g.toml").write_text((TABLEAUX.parent / "docs" / "examples" / "g2six.toml").read_text(encoding="utf-8")
                                     + "\n[expect]\nsymplectic = true\n", encoding="utf-8")
    args = ("scan", str(tmp_path), "--degree", "4", "--order", "1", "--require", "proof", "--jobs", "1")
    r = run_cli(capsys, *args, "--format", "github")
    errors = [line for line in r.out.splitlines() if line.startswith("::error")]
    assert r.code == 1 and len(errors) == 1 and ANNOTATION.match(errors[0])
    assert "title=rkcheck%3A --require proof not met::--require proof: the claim symplectic = true" in errors[0]
    junit = ET.fromstring(run_cli(capsys, *args, "--format", "junit").out)
    (failure,) = junit.iter("failure")
    assert failure.get("message").startswith("--require proof: the claim symplectic = true holds only to")


@pytest.mark.parametrize("marker", [".git", "pyproject.toml"])
def test_github_annotations_name_files_from_the_repository_root(capsys, tmp_path, monkeypatch, marker):
    # a repository whose pyproject.toml sits in a subproject: GitHub wants paths from the
    # repository root (the .git folder), else from the pyproject.toml's folder
    repo = tmp_path / "repo"
    project = repo / "project"
    (project / "tabs" / "sub").mkdir(parents=True)
    if marker == ".git":
        (repo / ".git").mkdir()
    (project / "pyproject.toml").write_text('[tool.rkcheck]\npaths = ["tabs"]\nformat = "github"\njobs = 1\n',
                                            encoding="utf-8")
    (project / "tabs" / "sub" / "wrong.toml").write_text(RK4_WRONG, encoding="utf-8")
    (project / "tabs" / "broken.toml").write_text(BROKEN, encoding="utf-8")
    root = repo if marker == ".git" else project
    want = {name: (project / "tabs" / name).relative_to(root).as_posix() for name in ("sub/wrong.toml", "broken.toml")}
    for cwd in (project, project / "tabs" / "sub"):  # [tool.rkcheck] paths are absolute once read
        monkeypatch.chdir(cwd)
        lines = run_cli(capsys, "scan").out.strip().splitlines()
        files = [re.match(r"::error file=([^,]+),", line).group(1) for line in lines]
        assert files == [want["broken.toml"], want["sub/wrong.toml"]], lines
        # the error message names the file the same way
        assert lines[0].endswith(f"::{want['broken.toml']}: A[1][2]: unexpected ')' at column 7")
    monkeypatch.chdir(tmp_path)  # paths given on the command line, from outside the repository
    lines = run_cli(capsys, "scan", str(project / "tabs"), "--format", "github").out.strip().splitlines()
    assert [re.match(r"::error file=([^,]+),", line).group(1) for line in lines] == [
        want["broken.toml"], want["sub/wrong.toml"]]


def test_github_annotations_outside_a_repository_keep_the_path_given(capsys, tmp_path, monkeypatch):
    from rkcheck.reports.scan_ci import repository_root

    (tmp_path / "w.toml").write_text(RK4_WRONG, encoding="utf-8")
    if repository_root(str(tmp_path / "w.toml")) is not None:
        pytest.skip("the temporary folder lies inside a repository")
    monkeypatch.chdir(tmp_path)
    out = run_cli(capsys, "scan", "w.toml", "--format", "github").out
    assert out.startswith("::error file=w.toml,")


RK4_A = [["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]]
RK4_B = ["1/6", "1/3", "1/3", "1/6"]
# RK4 claims energy order 5 (it is 4) and classical order 5 (it is 4)
RK4_OVERCLAIMS = """[method]
name = "RK4, two wrong claims"
[tableau]
A = [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]]
b = ["1/6", "1/3", "1/3", "1/6"]
[expect]
energy_order = {degree = "none", value = 5}
classical_order = 5
"""
CONDITION_LINE = re.compile(r"condition ([\d,]+) \S+ \(order (\d+)\) fails: R = (\S+)$")


def _reference_failures(vertices):
    """(id, exact residual) of RK4's failing energy conditions with this many vertices,
    from the brute-force reference."""
    from fractions import Fraction

    from support import reference as ref

    A = [[Fraction(x) for x in row] for row in RK4_A]
    b = [Fraction(x) for x in RK4_B]
    out = {}
    for cond in ref.energy_conditions(vertices):
        r = ref.energy_residual(cond, A, b)
        if r != 0:
            out[",".join(map(str, cond["id"]))] = r
    return out


def _junit_failure(capsys, path, *extra):
    r = run_cli(capsys, "scan", str(path), "--format", "junit", "--jobs", "1", *extra)
    case = ET.fromstring(r.out).find("testsuite").find("testcase")
    return case.find("failure")


def test_junit_lists_what_the_broken_claims_cover_with_exact_residuals(capsys, tmp_path):
    from fractions import Fraction

    from support import reference as ref

    path = tmp_path / "rk4.toml"
    path.write_text(RK4_OVERCLAIMS, encoding="utf-8")
    failure = _junit_failure(capsys, path)  # checked to order 8: conditions fail at orders 5 to 8
    lines = failure.text.splitlines()
    energy = lines.index("claim expect.energy_order: claimed 5, found 4")
    classical = lines.index("claim expect.classical_order: claimed 5, found 4")
    listed = {}
    for line in lines[energy + 1:classical]:
        m = CONDITION_LINE.search(line)
        assert m, line
        assert m.group(2) == "5"  # what the claim "energy order 5" covers, nothing beyond
        listed[m.group(1)] = Fraction(m.group(3))  # an exact value, not a decimal ± 0
    assert listed == _reference_failures(6)  # order 5 = 6 vertices
    # the classical claim: the first failing condition a(t) = 1/γ(t), a tree with 5 vertices
    (evidence,) = lines[classical + 1:]
    assert evidence.startswith("  first failing classical condition: a(")
    A = [[Fraction(x) for x in row] for row in RK4_A]
    b = [Fraction(x) for x in RK4_B]
    failing_gammas = {ref.gamma(t) for t in ref.rooted_trees(5) if ref.elementary_weight(t, A, b) != Fraction(1, ref.gamma(t))}
    assert int(evidence.rsplit("= 1/", 1)[1]) in failing_gammas


def test_junit_judged_by_conditions_lists_them_exactly_or_as_balls(capsys, tmp_path):
    from fractions import Fraction

    path = tmp_path / "rk4.json"
    path.write_text(RK4_NO_CLAIMS, encoding="utf-8")
    failure = _junit_failure(capsys, path, "--order", "5", "--fail-on", "conditions")
    listed = {m.group(1): Fraction(m.group(3)) for m in map(CONDITION_LINE.search, failure.text.splitlines())}
    assert listed == _reference_failures(6)
    assert "±" not in failure.text and "±" not in failure.get("message")
    # certified balls: an inexact residual is a ball with a nonzero radius around the exact value
    balls = _junit_failure(capsys, path, "--order", "5", "--fail-on", "conditions", "--arithmetic", "ball", "--dps", "30")
    exact = _reference_failures(6)
    for line in balls.text.splitlines():
        m = re.search(r"condition ([\d,]+) .* fails: R = (\S+) ± (\S+)$", line)
        assert m, line
        mid, rad = Fraction(m.group(2)), Fraction(m.group(3))
        assert 0 < rad < Fraction(1, 10**25) and abs(mid - exact[m.group(1)]) <= rad


def test_the_short_form_is_scanned_like_verify_reads_it(capsys, tmp_path):
    # A and b at the top level (the documented short form): the implicit midpoint rule
    (tmp_path / "midpoint.json").write_text('{"A": [["1/2"]], "b": ["1"]}', encoding="utf-8")
    (tmp_path / "package.json").write_text('{"name": "x", "b": 1}', encoding="utf-8")
    _, doc = scan_json(capsys, tmp_path, "--degree", "3", "--order", "3")
    status = {Path(f["file"]).name: f["status"] for f in doc["files"]}
    assert status == {"midpoint.json": "ok", "package.json": "skipped"}
    row = next(f for f in doc["files"] if f["file"].endswith("midpoint.json"))
    verified = json.loads(run_cli(capsys, "verify", str(tmp_path / "midpoint.json"), "--degree", "3",
                                  "--order", "3", "--format", "json").out)
    # the midpoint rule: classical order 2 (one stage, c = 1/2 is the Gauss point)
    scanned, alone = row["result"]["summary"], verified["summary"]
    assert scanned["classical_order"] == alone["classical_order"] == 2
    # degree 3 needs the rule exact for cubics; the midpoint rule is not (Σ b c² = 1/4 ≠ 1/3),
    # and the bush [τ³] fails at order 3
    assert scanned["energy_order"] == alone["energy_order"] == 2


def test_results_encoded_by_the_workers_give_the_same_json_report(folder):
    """``json_in_workers``: each file's result is encoded where it was checked and the
    report splices the texts; from the same outcomes, the report built the plain way
    (every document encoded at once, in this process) is the same text, byte for byte —
    files of the shipped library with algebraic entries and long names included."""
    from support.paths import TABLEAUX

    import rkcheck
    from rkcheck.batch.scan import _Packed
    from rkcheck.reports.jsondoc import check_doc

    res = rkcheck.scan([folder, TABLEAUX / "collocation", TABLEAUX / "continuous"], order=6, jobs=2,
                       json_in_workers=True)
    spliced = res.report("json")
    # the report came from the documents alone: the results crossed from the workers
    # pickled and are still so; read, one is the check the worker encoded
    packed = [o for o in res.outcomes if isinstance(o.__dict__["_result"], _Packed)]
    assert packed and all(o.document is not None for o in packed)
    assert check_doc(packed[0].result) == json.loads(packed[0].document)
    checked = [o for o in res.outcomes if o.result is not None]
    assert len(checked) == len(packed)
    for o in res.outcomes:
        o.document = None
    assert spliced == res.report("json")
    assert json.loads(spliced)["totals"]["files"] == len(res.outcomes)


def test_a_worker_that_cannot_encode_leaves_the_result_to_the_report(folder):
    from rkcheck.batch.scan import scan_file

    def broken(result):
        raise ValueError("no")

    out = scan_file(str(folder / "a-good.toml"), {}, {}, "claims", document=broken)
    assert out.status == "ok" and out.result is not None and out.document is None


def test_a_text_report_reads_the_failing_conditions_of_the_full_document():
    """The text report builds each file's document with its failing conditions only: the
    full document's conditions, filtered to those that fail, in the same order."""
    from rkcheck import Tableau, verify
    from rkcheck.reports.jsondoc import check_doc

    rk4 = [["0", "0", "0", "0"], ["1/2", "0", "0", "0"], ["0", "1/2", "0", "0"], ["0", "0", "1", "0"]]
    res = verify(Tableau.from_values(rk4, ["1/6", "1/3", "1/3", "1/6"]), degree=3, order=7)
    full, failing = check_doc(res), check_doc(res, failing_only=True)
    assert [c for c in full["conditions"] if c["state"] == "fails"] == failing["conditions"]
    assert len(failing["conditions"]) < len(full["conditions"]) and failing["conditions"]
    assert {k: v for k, v in full.items() if k != "conditions"} == {k: v for k, v in failing.items()
                                                                    if k != "conditions"}


KAPPA = '''[parameters]
kappa = "free"

[continuous]
A = "tau + kappa*(tau^2 - tau)*(2*sigma - 1)"
'''


def test_a_kernel_family_is_validated_then_skipped(capsys, tmp_path):
    """A scan skips a family of kernels on the surrogate of its smallest trees, with the
    same validation: an unknown name is still an error row, as loading the whole family
    (``load_family``) says."""
    from rkcheck.api import load_family
    from rkcheck.errors import RkcheckError

    (tmp_path / "good.toml").write_text(KAPPA)
    bad = tmp_path / "bad.toml"
    bad.write_text(KAPPA.replace("kappa*", "zeta*"))
    rows = {Path(f["file"]).name: f for f in
            json.loads(run_cli(capsys, "scan", str(tmp_path), "--format", "json", "--jobs", "1").out)["files"]}
    assert rows["good.toml"]["status"] == "skipped"
    with pytest.raises(RkcheckError) as whole:
        load_family(str(bad))
    assert rows["bad.toml"]["status"] == "error" and "unknown name 'zeta'" in rows["bad.toml"]["error"]
    assert "unknown name 'zeta'" in str(whole.value)


def test_a_csv_file_named_on_the_command_line_is_read_as_verify_reads_it(capsys, tmp_path):
    # Heun's method as a Butcher table in CSV (docs/examples/heun.csv): its suffix says CSV
    path = Path(__file__).resolve().parents[2] / "docs" / "examples" / "heun.csv"
    _, doc = scan_json(capsys, path, "--degree", "3", "--order", "4")
    (row,) = doc["files"]
    assert row["status"] in ("ok", "failed"), row
    alone = json.loads(run_cli(capsys, "verify", str(path), "--degree", "3", "--order", "4", "--format", "json").out)
    # Heun: classical order 2 (by hand: Σb = 1, Σbc = 1/2, Σbc² = 1/2 ≠ 1/3)
    assert row["result"]["summary"]["classical_order"] == alone["summary"]["classical_order"] == 2
    assert row["result"]["summary"]["energy_order"] == alone["summary"]["energy_order"]


RK4_FILE = Path(__file__).resolve().parents[2] / "tableaux" / "explicit" / "rk4.toml"


def test_a_file_over_max_conditions_is_one_row_when_the_scan_gives_no_order(tmp_path, capsys):
    # RK4 at order 4 has 1 + 1 + 3 = 5 conditions (SPEC §3), at the default order 8 86
    (tmp_path / "a-default.toml").write_text(RK4_FILE.read_text(), encoding="utf-8")
    (tmp_path / "b-order4.toml").write_text(RK4_FILE.read_text().split("[expect]")[0] + "\n[check]\norder = 4\n",
                                            encoding="utf-8")
    r = run_cli(capsys, "scan", str(tmp_path), "--max-conditions", "10", "--jobs", "1", "--format", "json")
    doc = json.loads(r.out)
    assert r.code == 1 and [f["status"] for f in doc["files"]] == ["error", "ok"]
    assert "86 conditions, above --max-conditions 10" in doc["files"][0]["error"]
    # an order given to the scan is every file's: refused before any file
    r = run_cli(capsys, "scan", str(tmp_path), "--max-conditions", "10", "--order", "8", "--jobs", "1")
    assert r.code == 2 and r.err.startswith("rkcheck: error: order 8 has 86 conditions")


def test_a_text_scan_of_absolute_and_relative_paths_shows_each_as_given(tmp_path, capsys, monkeypatch):
    (tmp_path / "mine.toml").write_text(RK4_FILE.read_text(), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    r = run_cli(capsys, "scan", "@rk4", str(tmp_path / "mine.toml"), "--order", "2", "--jobs", "1")
    assert r.code == 0, r.err
    shown = "".join(r.out.split())  # a long path wraps in its cell
    assert "@rk4" in shown and "mine.toml" in shown and "2files:2ok" in shown


def test_exclude_matches_within_the_folder_scanned_and_links_to_folders_are_left_out(tmp_path, capsys):
    root = tmp_path / "tableaux"
    (root / "drafts").mkdir(parents=True)
    (root / "ok.toml").write_text(RK4_FILE.read_text(), encoding="utf-8")
    (root / "drafts" / "wip.toml").write_text("not toml [", encoding="utf-8")
    (root / "linked.toml").symlink_to(root / "drafts", target_is_directory=True)
    r = run_cli(capsys, "scan", str(root), "--exclude", "drafts/*", "--order", "2", "--jobs", "1", "--format", "json")
    assert r.code == 0, r.out
    assert [Path(f["file"]).name for f in json.loads(r.out)["files"]] == ["ok.toml"]


def test_an_empty_path_is_refused_not_read_as_the_current_folder(capsys):
    r = run_cli(capsys, "scan", "")
    assert r.code == 2 and "an empty path" in r.err
    r = run_cli(capsys, "verify", "")
    assert r.code == 2 and "an empty path" in r.err


@pytest.mark.parametrize("width", [80, 90, 140])
def test_the_file_column_stays_readable_on_a_narrow_terminal(width):
    from rich.console import Console

    import rkcheck
    from rkcheck.reports.scan import render_scan_text

    result = rkcheck.scan([str(RK4_FILE.parent)], order=2, jobs=1)
    console = Console(file=io.StringIO(), width=width, no_color=True)
    render_scan_text(result.outcomes, console, 0.0, False)
    text = console.file.getvalue()
    assert all(len(line) <= width for line in text.splitlines())
    for name in ("euler.toml", "rk4.toml", "heun.toml"):  # short names: each whole in its cell
        assert any(line.split()[:1] == [name] for line in text.splitlines()), (width, text)


def test_a_misspelt_table_is_an_error_and_a_scan_that_checks_nothing_does_not_pass(tmp_path, capsys):
    (tmp_path / "typo.toml").write_text('[tabelau]\nA = [[0]]\nb = [1]\n[expect]\nclassical_order = 5\n',
                                        encoding="utf-8")
    (tmp_path / "other.json").write_text('{"content": 1, "name": "x"}', encoding="utf-8")  # not ours: skipped
    (tmp_path / "empty.toml").write_text("", encoding="utf-8")
    r = run_cli(capsys, "scan", str(tmp_path), "--jobs", "1", "--format", "json")
    rows = {Path(f["file"]).name: f for f in json.loads(r.out)["files"]}
    assert r.code == 1 and rows["typo.toml"]["status"] == "error"
    assert "unknown table [tabelau] (did you mean [tableau]?)" in rows["typo.toml"]["error"]
    assert rows["other.json"]["status"] == "skipped"
    # an empty file is a tableau file left empty, in TOML as in JSON: an error, not passed over
    assert rows["empty.toml"]["status"] == "error" and rows["empty.toml"]["error"].endswith(
        "empty.toml: the file is empty; the smallest tableau file is [tableau] A = [[\"1/2\"]] b = [1]  (TOML), "
        "or {\"A\": [[\"1/2\"]], \"b\": [1]} (JSON)")
    (tmp_path / "empty.json").write_text("  \n", encoding="utf-8")
    doc = json.loads(run_cli(capsys, "scan", str(tmp_path), "--jobs", "1", "--format", "json").out)
    assert {Path(f["file"]).name: f["status"] for f in doc["files"]}["empty.json"] == "error"
    for name in ("typo.toml", "empty.toml", "empty.json"):
        (tmp_path / name).unlink()
    (tmp_path / "more.toml").write_text("[tool.other]\nx = 1\n", encoding="utf-8")
    r = run_cli(capsys, "scan", str(tmp_path), "--jobs", "1")
    assert r.code == 2 and "none of the 2 files found is a tableau" in r.err
    assert run_cli(capsys, "scan", str(tmp_path), "--jobs", "1", "--allow-empty").code == 0


def test_a_text_report_written_with_o_is_the_piped_one(tmp_path):
    # the same layout through -o as through `>`: no trailing spaces, the same width
    import re
    import subprocess
    import sys

    env = dict(os.environ, NO_COLOR="1")
    folder = str(TABLEAUX / "explicit")
    out = tmp_path / "r.txt"
    subprocess.run([sys.executable, "-m", "rkcheck", "scan", folder, "-j", "1", "-o", str(out)], env=env,
                   capture_output=True, text=True)
    piped = subprocess.run([sys.executable, "-m", "rkcheck", "scan", folder, "-j", "1"], env=env,
                           capture_output=True, text=True).stdout

    def timeless(text):
        return [re.sub(r"\d+\.\d+( s)?\b", "<t>", line) for line in text.splitlines()]

    written = out.read_text(encoding="utf-8")
    assert not any(line.endswith(" ") for line in written.splitlines())
    assert timeless(written) == timeless(piped)


def test_rkcheck_reports_are_no_tableaux(tmp_path, capsys):
    # a verify or show JSON report has [tableau] and [method] too: read back it is refused
    # with the way to write a tableau file, and in a scanned folder it is skipped
    folder = tmp_path / "methods"
    folder.mkdir()
    (folder / "rk4.toml").write_text((TABLEAUX / "explicit" / "rk4.toml").read_text(encoding="utf-8"), encoding="utf-8")
    for command in (["verify", "--order", "3"], ["show"]):
        report = folder / f"{command[0]}.json"
        report.write_text(run_cli(capsys, command[0], str(folder / "rk4.toml"), *command[1:], "--format", "json").out,
                          encoding="utf-8")
        refused = run_cli(capsys, "verify", str(report))
        assert refused.code == 2 and "this is a JSON report of rkcheck" in refused.err and "--format tableau-json" in refused.err
    family = TABLEAUX / "families" / "theorem1-s2-m3.toml"
    for name, command in (("family.json", ["verify", str(family)]), ("solve.json", ["solve", str(family)]),
                          ("scan.json", ["scan", str(folder / "rk4.toml"), "-j", "1"])):
        (folder / name).write_text(run_cli(capsys, *command, "--format", "json").out, encoding="utf-8")
        refused = run_cli(capsys, "verify", str(folder / name))
        assert refused.code == 2 and "this is a JSON report of rkcheck" in refused.err
    doc = json.loads(run_cli(capsys, "scan", str(folder), "-j", "1", "--format", "json").out)
    assert sorted((Path(f["file"]).name, f["status"]) for f in doc["files"]) == [
        ("family.json", "skipped"), ("rk4.toml", "ok"), ("scan.json", "skipped"), ("show.json", "skipped"),
        ("solve.json", "skipped"), ("verify.json", "skipped")]


def test_the_shared_listing_is_built_only_when_the_budget_allows_it(monkeypatch):
    # built in the parent before the workers fork: a listing past the memory available
    # is left to each file's own check (its row meets the limit), and one that runs out
    # of memory while built is given up, not the whole scan
    import rkcheck.trees.listing
    from rkcheck.batch.scan import warm_tables
    from rkcheck.energy.budget import Budget

    built = []
    monkeypatch.setattr(rkcheck.trees.listing, "condition_listing", lambda n, m: built.append((n, m)))
    warm_tables({"order": 18, "degree": None}, {}, Budget(available_bytes=50 * 2**20))
    assert built == []
    warm_tables({"order": 6, "degree": 2}, {}, Budget(available_bytes=50 * 2**30))
    assert built == [(6, 2)]

    def starved(n, m):
        raise MemoryError

    monkeypatch.setattr(rkcheck.trees.listing, "condition_listing", starved)
    warm_tables({"order": 6, "degree": 2}, {}, None)


def test_one_file_spelt_several_ways_is_checked_once(tmp_path, capsys, monkeypatch):
    # a.toml, ../p/a.toml, its absolute path, a link and a hard link to it, its folder: one row
    folder = tmp_path / "p"
    folder.mkdir()
    (folder / "a.toml").write_text('[tableau]\nA = [["1/2"]]\nb = [1]\n', encoding="utf-8")
    (tmp_path / "link.toml").symlink_to(folder / "a.toml")
    os.link(folder / "a.toml", tmp_path / "hard.toml")
    monkeypatch.chdir(folder)
    r = run_cli(capsys, "scan", "a.toml", "../p/a.toml", str(folder / "a.toml"), "../link.toml", "../hard.toml", ".",
                "--format", "json", "--order", "4", "--degree", "2")
    assert [f["file"] for f in json.loads(r.out)["files"]] == ["a.toml"]


def test_the_classical_column_reads_an_order_held_to_digits_as_verify_does(capsys, tmp_path):
    # the 6-digit Gauss-2 tableau: classical order 0 proven (nothing is exact), order 4 to
    # its digits, and a condition of order 5 fails (Gauss-2 has order 4: Hairer–Wanner)
    (tmp_path / "g.toml").write_text((TABLEAUX.parent / "docs" / "examples" / "g2six.toml").read_text(encoding="utf-8"),
                                     encoding="utf-8")
    doc = json.loads(run_cli(capsys, "verify", str(tmp_path / "g.toml"), "--format", "json").out)["summary"]
    want = f"{doc['classical_order']}; {doc['classical_order_to_digits']} to {doc['classical_order_digits']} digits"
    assert doc["classical_order_to_digits"] == 4 and doc["classical_first_failure"] is not None
    row = next(line for line in run_cli(capsys, "scan", str(tmp_path), "--jobs", "1").out.splitlines()
               if "Gauss–Legendre" in line)  # the method's name: a long path wraps
    assert want in row


def test_the_pre_commit_hook_passes_a_commit_of_files_it_does_not_check(tmp_path, capsys):
    """The hook runs on every staged *.toml/*.json: a commit of a pyproject.toml or of a
    family alone checks nothing and must pass, while a failing tableau still fails it."""
    root = Path(__file__).resolve().parents[2]
    entry = next(line.split(":", 1)[1].split() for line in (root / ".pre-commit-hooks.yaml").read_text().splitlines()
                 if line.strip().startswith("entry:"))
    assert entry[:2] == ["rkcheck", "scan"]
    (tmp_path / "pyproject.toml").write_text("[tool.x]\na = 1\n", encoding="utf-8")
    (tmp_path / "fam.toml").write_text('[parameters]\np = "free"\n[tableau]\nA = [["p"]]\nb = ["1"]\n', encoding="utf-8")
    for staged in ("pyproject.toml", "fam.toml"):
        assert run_cli(capsys, *entry[1:], str(tmp_path / staged)).code == 0, staged
    (tmp_path / "euler.toml").write_text('[tableau]\nA = [["0"]]\nb = ["1"]\n[expect]\nclassical_order = 2\n',
                                         encoding="utf-8")
    assert run_cli(capsys, *entry[1:], str(tmp_path / "euler.toml")).code == 1


def test_a_table_or_short_form_key_in_another_case_is_an_error_on_every_route(tmp_path, capsys):
    """[Parameters] and the short form's B are refused by verify; a scan, a catalogue and
    solve read the same document and refuse them alike, never passing over the file as
    no tableau, nor reading the family as having no parameters."""
    (tmp_path / "s1.toml").write_text('A = [["1/2"]]\nB = ["1"]\n', encoding="utf-8")
    (tmp_path / "f.toml").write_text('[tableau]\nA = [["p"]]\nb = ["1"]\n[Parameters]\np = "free"\n', encoding="utf-8")
    doc = json.loads(run_cli(capsys, "scan", str(tmp_path), "--format", "json", "--jobs", "1").out)
    errors = {Path(f["file"]).name: f["error"] for f in doc["files"]}
    assert [f["status"] for f in doc["files"]] == ["error", "error"]
    assert "write [parameters]" in errors["f.toml"] and "write b" in errors["s1.toml"]
    r = run_cli(capsys, "solve", str(tmp_path / "f.toml"), "-m", "2", "-N", "2")
    assert r.code == 2 and "Parameters: unknown table" in r.err
    r = run_cli(capsys, "catalog", str(tmp_path), "-N", "3")
    assert r.code == 1 and "write b" in r.out


@pytest.mark.parametrize("memory_mb", [120, 130, 140, 160])
def test_a_scan_short_of_memory_says_so_in_each_row_not_a_bug(memory_mb):
    # under a limit this low FLINT's shared library cannot be mapped when a worker first
    # imports it (an ImportError), or an allocation fails: the machine's memory, which the
    # rows called "internal error … a bug in rkcheck"
    from support.limits import run_limited

    run = run_limited(["-m", "rkcheck", "scan", str(TABLEAUX / "collocation"), "-j", "1", "--format", "json"],
                      memory_mb=memory_mb, cpu_seconds=120)
    assert "internal error" not in run.out + run.err and "Traceback" not in run.err, (run.out[-500:], run.err[-500:])
    if run.code in (0, 1):
        rows = json.loads(run.out)["files"]
        assert rows and all(r["status"] in ("ok", "failed") or r["error"] for r in rows)
