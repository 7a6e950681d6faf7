"""JSON reports written as they are made: a large one is never held whole as text."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from collections import Counter

import pytest
from support.counts import conditions_with
from support.limits import run_limited
from support.paths import TABLEAUX


def test_a_json_listing_is_written_as_it_is_made():
    # order 16: 18 MB of JSON; joined whole into one string (and encoded) on top of the
    # listing, the report ran out of memory under 300 MB after the listing was built
    run = run_limited(["-m", "rkcheck", "conditions", "--order", "16", "--format", "json"], memory_mb=300,
                      cpu_seconds=120)
    assert run.code == 0, (run.code, run.err[-300:])
    doc = json.loads(run.out)
    assert Counter(c["vertices"] for c in doc["conditions"]) == {n: conditions_with(n) for n in range(3, 18)}


def _free_family(folder):
    """A 3-stage tableau whose every entry is its own parameter: 12.7 MB of conditions
    as polynomials at order 8."""
    A = [[f"a{i}{j}" for j in range(1, 4)] for i in range(1, 4)]
    b = [f"b{i}" for i in range(1, 4)]
    path = folder / "free.toml"
    path.write_text("[parameters]\n" + "".join(f'{n} = "free"\n' for n in sum(A, []) + b)
                    + f"[tableau]\nA = {json.dumps(A)}\nb = {json.dumps(b)}\n", encoding="utf-8")
    return path


def _interrupted_while_listing(args, rows):
    """``rkcheck ARGS``'s JSON, read until its list ``rows`` begins; then a SIGINT, while
    the writer (its reader stopped, the pipe full) is writing the list.  Returns the
    document, checked to close (``<rows>_complete`` false) with exit 130, the interrupt's
    line and no traceback."""
    proc = subprocess.Popen([sys.executable, "-m", "rkcheck", *args, "--format", "json"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=dict(os.environ, NO_COLOR="1"))
    head = []
    while not head or not head[-1].startswith(f'  "{rows}": ['):
        head.append(proc.stdout.readline())
        assert head[-1], f"the document ended before its {rows}"
    proc.send_signal(signal.SIGINT)
    rest = proc.stdout.read()
    err = proc.stderr.read()
    proc.wait(timeout=120)
    doc = json.loads("".join(head) + rest)
    assert proc.returncode == 130 and "interrupted while writing" in err and "Traceback" not in err
    assert doc[f"{rows}_complete"] is False
    return doc


@pytest.mark.parametrize("family", [False, True], ids=["trees", "family"])
def test_a_ctrl_c_while_the_conditions_are_written_closes_the_document(tmp_path, family):
    # as verify's report: the rows end, the document closes with conditions_complete
    # false, exit 130 (the document was cut off mid-row)
    args = ["conditions", str(_free_family(tmp_path)), "--order", "8"] if family else ["conditions", "--order", "15"]
    doc = _interrupted_while_listing(args, "conditions")
    written, vertices = len(doc["conditions"]), 9 if family else 16
    assert 0 < written < sum(conditions_with(n) for n in range(3, vertices + 1))


def test_a_ctrl_c_while_a_sweeps_points_are_written_closes_the_document():
    # 10 000 points (1 MB): the reader stops at the list, so the writer blocks on the
    # full pipe and the signal arrives while the points are written
    family = TABLEAUX / "families" / "sweep-s2-lobatto.toml"
    doc = _interrupted_while_listing(["sweep", str(family), "--grid", "beta=-1:1:100", "--grid", "gamma=0:1:100",
                                      "--order", "3"], "points")
    assert 0 < len(doc["points"]) < 100 * 100
    # the points written are the grid's first, in its order
    assert [p["values"] for p in doc["points"][:2]] == [{"beta": "-1", "gamma": "0"}, {"beta": "-1", "gamma": "1/99"}]
