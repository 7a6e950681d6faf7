"""Reports name things as they are: a cube root is not a square root, a merged pair of
stages whose weights cancel is not a pair of dead stages, and the one-vertex condition
reads ``Σ b_i = 1``."""

from __future__ import annotations

import json

import pytest
from support.clirun import run_cli


def _write(tmp_path, name, doc):
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return str(path)


@pytest.mark.parametrize("entry, kind", [("root(x^3-2, 1)/4", "algebraic (roots)"),
                                         ("sqrt(2)/4", "algebraic (square roots)")])
def test_the_number_kind_names_the_roots(tmp_path, capsys, entry, kind):
    # 2^(1/3) is the real root of x³ − 2: a cube root, in a field of degree 3 (by hand)
    path = _write(tmp_path, "r.json", {"A": [[entry]], "b": ["1"]})
    out = run_cli(capsys, "verify", path, "--order", "2").out
    assert out.splitlines()[1].endswith(kind)
    doc = json.loads(run_cli(capsys, "verify", path, "--order", "2", "--format", "json").out)
    assert doc["tableau"]["numbers"] == kind


# Stages 2 and 3 have the same row, so they merge into one stage of weight 1/2 − 1/2 = 0
# that no stage uses (column sums of A over {2, 3} are 0): it is dropped.  Neither stage
# is dead by itself (b_2, b_3 ≠ 0).  Stage 4 is dead (b_4 = 0, unused).
CANCELLING = {"A": [["1/2", "0", "0", "0"], ["1/3", "0", "0", "0"], ["1/3", "0", "0", "0"], ["1/5", "0", "0", "0"]],
              "b": ["1", "1/2", "-1/2", "0"]}


def test_a_merged_cancelling_pair_is_not_called_dead(tmp_path, capsys):
    path = _write(tmp_path, "cancel.json", CANCELLING)
    out = run_cli(capsys, "verify", path, "--degree", "2", "--order", "2").out
    text = " ".join(out.split())  # the terminal wraps long rows
    line = text[text.index("reduced from"):].split(")")[0]
    assert "reduced from 4 to 1 stage (" in line + ")"
    assert "merged stages 2+3 into one with weight 0 that nothing uses, then dropped it" in line
    assert "dropped dead stage 4" in line and "dead stages 2" not in line and "dead stage 2" not in line
    red = json.loads(run_cli(capsys, "verify", path, "--degree", "2", "--order", "2",
                             "--format", "json").out)["summary"]["reduction"]
    assert red["dropped"] == [2, 3, 4] and red["cancelled"] == [[2, 3]] and red["classes"] == [[1]]


def test_an_inconsistent_method_fails_sum_b_equals_one(tmp_path, capsys):
    # b = (0.49, 0.5): Σb = 0.99 ≠ 1, so order 1 fails: a(τ) = Σ b_i, γ(τ) = 1
    path = _write(tmp_path, "s99.json", {"A": [["0", "0"], ["1", "0"]], "b": ["0.49", "0.5"]})
    out = run_cli(capsys, "verify", path, "--order", "2").out
    assert "classical order   0  (Σ b_i = 1 fails)" in out and "a(τ)" not in out
    doc = json.loads(run_cli(capsys, "verify", path, "--order", "2", "--format", "json").out)
    assert doc["summary"]["classical_first_failure"] == "Σ b_i = 1"


def test_one_effective_stage_is_singular(tmp_path, capsys):
    # two equal rows merge into the implicit midpoint rule: 1 stage, below Theorem 1's
    # s_min = 2 for degree 3
    path = _write(tmp_path, "mid2.json", {"A": [["1/2", "0"], ["0", "1/2"]], "b": ["1/2", "1/2"]})
    text = " ".join(run_cli(capsys, "verify", path, "--degree", "3", "--order", "3").out.split())
    assert "reduced from 2 to 1 stage (merged stages 1+2)" in text
    assert "this method has 1 effective stage, so it cannot" in text
