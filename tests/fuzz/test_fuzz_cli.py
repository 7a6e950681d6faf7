"""Fuzzing the front door: random entries, whole files (bytes, text, TOML and
JSON documents) and option sets never give a traceback, an internal error or an exit code
other than 0, 1 or 2; stderr is at most 3 lines.  The costliest option sets the fuzz can
draw run in a child process under 500 MB and 5 CPU seconds (the kernel enforces both), so
validated options never start a check that does not fit.

Bounded for CI (a few seconds per test); ``RKCHECK_FUZZ_EXAMPLES=2000`` runs longer.
Runs go through the CLI in-process (``main()``), so an escaping exception is an exit 3.
"""

from __future__ import annotations

import json
import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from support.clirun import run_cli
from support.limits import run_limited

EXAMPLES = int(os.environ.get("RKCHECK_FUZZ_EXAMPLES", "40"))
FUZZ = settings(max_examples=EXAMPLES, deadline=None, derandomize=not os.environ.get("RKCHECK_FUZZ_EXAMPLES"),
                suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
CPU_SECONDS_PER_RUN = 5
MEMORY_MB_PER_RUN = 500

# pieces of the entry grammar, and the characters around it that users (and attackers) type
TOKENS = ["1", "2", "0", "1/3", "0.5", "1.2345678", "1e-3", "1e400", "9" * 50, "+", "-", "*", "/", "^", "**",
          "(", ")", "sqrt(", "root(", "x", ",", " ", "r", "c0", "\u2212", "\u00d7", "\u00b7", "\u03c0", "\u00b2",
          "\u0661", "\x00", "\x1b", "\ud800", "\n", ".", "e", "2^1000", "10^999", "nan", "inf"]
entries = st.lists(st.sampled_from(TOKENS), min_size=0, max_size=25).map("".join) | st.text(max_size=40)


def check_run(r) -> None:
    assert r.code in (0, 1, 2), (r.code, r.err)
    assert "Traceback" not in r.err and "internal error" not in r.err, r.err
    assert len(r.err.splitlines()) <= 3, r.err


@FUZZ
@given(a=entries, b=entries, constant=entries)
def test_random_entries(tmp_path_factory, capsys, a, b, constant):
    doc = {"constants": {"c0": constant}, "tableau": {"A": [[a, "0"], ["1/2", "1/2"]], "b": [b, "1/2"]}}
    path = tmp_path_factory.mktemp("e") / "t.json"
    try:
        text = json.dumps(doc)
    except UnicodeEncodeError:  # pragma: no cover - json escapes surrogates, never raises
        return
    path.write_text(text, encoding="utf-8")
    check_run(run_cli(capsys, "verify", str(path), "--order", "3"))


@FUZZ
@given(data=st.binary(max_size=300))
def test_random_bytes(tmp_path_factory, capsys, data):
    folder = tmp_path_factory.mktemp("b")
    for name in ("t.toml", "t.json"):
        (folder / name).write_bytes(data)
        check_run(run_cli(capsys, "verify", str(folder / name), "--order", "3"))


scalars = st.one_of(st.integers(min_value=-10**30, max_value=10**30), st.booleans(), st.text(max_size=12),
                    st.sampled_from(["1/2", "0", "1", "sqrt(2)", "none", "all", "exact", "rounded"]),
                    st.floats(allow_nan=False, allow_infinity=False))
values = st.recursive(scalars, lambda children: st.lists(children, max_size=4)
                      | st.dictionaries(st.sampled_from(["A", "b", "c", "x", "name", "order", "value"]), children,
                                        max_size=3), max_leaves=12)
TABLES = ["method", "constants", "tableau", "check", "expect", "family", "other"]
KEYS = {"method": ["name", "description", "references"], "constants": ["r3", "q", "x"],
        "tableau": ["A", "b", "c"], "check": ["degree", "order", "dps", "decimals", "ordr"],
        "expect": ["energy_order", "avf", "classical_order", "quadrature_order", "other"],
        "family": ["name", "s", "k", "rule", "zeta", "beta"], "other": ["x"]}


@st.composite
def documents(draw):
    doc = {}
    for table in draw(st.lists(st.sampled_from(TABLES), max_size=4, unique=True)):
        doc[table] = {key: draw(values) for key in draw(st.lists(st.sampled_from(KEYS[table]), max_size=3, unique=True))}
    if draw(st.booleans()):  # often a nearly valid tableau, so that the deeper layers are reached
        s = draw(st.integers(min_value=1, max_value=3))
        cell = st.sampled_from(["0", "1/2", "1/3", "sqrt(3)/6", "0.2113248654", "1e-3", "-1"]) | values
        doc["tableau"] = {"A": [[draw(cell) for _ in range(s)] for _ in range(s)], "b": [draw(cell) for _ in range(s)]}
    return doc


def toml_text(doc) -> str | None:
    """A small TOML writer for the generated documents (None when TOML cannot say it)."""
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (int, float)):
            return repr(v)
        if isinstance(v, str):
            return json.dumps(v)  # a JSON string is a TOML basic string
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return "{" + ", ".join(f"{k} = {value(x)}" for k, x in v.items()) + "}"

    lines = []
    for table, body in doc.items():
        lines.append(f"[{table}]")
        lines.extend(f"{k} = {value(v)}" for k, v in body.items())
    return "\n".join(lines) + "\n"


@FUZZ
@given(doc=documents(), as_toml=st.booleans())
def test_random_documents(tmp_path_factory, capsys, doc, as_toml):
    folder = tmp_path_factory.mktemp("d")
    if as_toml:
        path = folder / "t.toml"
        path.write_text(toml_text(doc), encoding="utf-8", errors="surrogateescape")
    else:
        path = folder / "t.json"
        path.write_text(json.dumps(doc), encoding="utf-8")
    check_run(run_cli(capsys, "verify", str(path), "--order", "3"))
    check_run(run_cli(capsys, "show", str(path)))


OPTIONS = st.lists(st.tuples(
    st.sampled_from(["--order", "--dps", "--degree", "--decimals", "--max-stages", "--arithmetic", "--format",
                     "--max-conditions", "--jobs", "--fail-on", "-N", "-m"]),
    st.sampled_from(["0", "1", "3", "-1", "31", "10", "5000", "5001", "none", "x", "", "1e9", "exact", "ball",
                     "json", "99999999999999999999"])), max_size=4)


@FUZZ
@given(options=OPTIONS, command=st.sampled_from(["verify", "show", "scan", "conditions"]))
def test_random_option_sets(tmp_path_factory, capsys, options, command):
    folder = tmp_path_factory.mktemp("o")
    path = folder / "t.toml"
    path.write_text('[tableau]\nA = [["1/2"]]\nb = [1]\n', encoding="utf-8")
    args = [command] + ([] if command == "conditions" else [str(path)])
    for flag, value in options:
        args += [flag, value]
    if command == "scan":
        args += ["--jobs", "1"]
    # keep each run small: options that pass validation must still finish in seconds
    if not any(flag in ("--order", "-N") for flag, _ in options):
        args += ["--order", "4"]
    check_run(run_cli(capsys, *args))


# the costliest option sets the alphabet above can draw (order 10: "31" is out of range;
# 5 000 digits in balls; no bound on the conditions), one per command, and an order
# beyond the range with the condition bound lifted
COSTLIEST = [
    ["verify", "--order", "10", "--arithmetic", "ball", "--dps", "5000", "--max-conditions", "99999999999999999999"],
    ["scan", "--order", "10", "--arithmetic", "ball", "--dps", "5000", "--jobs", "1"],
    ["show", "--format", "json"],
    ["conditions", "-N", "10", "-m", "none", "--format", "json"],
    ["verify", "--order", "31", "--max-conditions", "99999999999999999999"],
]


@pytest.mark.parametrize("args", COSTLIEST, ids=[" ".join(a[:3]) for a in COSTLIEST])
def test_costliest_option_sets_run_within_500_mb_and_5_cpu_seconds(tmp_path, args):
    path = tmp_path / "t.toml"
    path.write_text('[tableau]\nA = [["1/2"]]\nb = [1]\n', encoding="utf-8")
    argv = args[:1] + ([] if args[0] == "conditions" else [str(path)]) + args[1:]
    run = run_limited(["-m", "rkcheck", *argv], memory_mb=MEMORY_MB_PER_RUN, cpu_seconds=CPU_SECONDS_PER_RUN)
    assert not run.killed, f"over {CPU_SECONDS_PER_RUN} CPU seconds: {run.code}"
    check_run(run)
    assert "out of memory" not in run.err, run.err
    assert args[2] != "31" or (run.code == 2 and "31" in run.err), run.err
