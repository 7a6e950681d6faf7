"""One number format for counts in text output: plain below 10,000, comma groups of three
from there; JSON keeps plain integers."""

from __future__ import annotations

import json
import re

import pytest
from support.clirun import run_cli
from support.counts import conditions_with

from rkcheck.numbers.formatting import count_text


@pytest.mark.parametrize("n", [0, 7, 999, 1000, 9999, 10_000, 80_936, 522_472, 3_489_323, 10**12, -12_345])
def test_count_text_groups_from_ten_thousand(n):
    text = count_text(n)
    assert int(text.replace(",", "")) == n
    if abs(n) < 10_000:
        assert text == str(n)
    else:
        groups = text.lstrip("-").split(",")
        assert len(groups[0]) in (1, 2, 3) and all(len(g) == 3 for g in groups[1:])


def test_conditions_count_prints_every_count_in_one_format(capsys):
    r = run_cli(capsys, "conditions", "--order", "18", "--count")
    total = re.search(r": ([\d,]+)$", r.out.splitlines()[0]).group(1)
    rows = [line.split() for line in r.out.splitlines() if re.match(r"\s+\d+\s+\d+\s+[\d,]+$", line)]
    counts = {int(order): cell for order, _, cell in rows}
    assert {k: int(v.replace(",", "")) for k, v in counts.items()} == {k: conditions_with(k + 1) for k in range(2, 19)}
    assert int(total.replace(",", "")) == sum(conditions_with(n) for n in range(3, 20))
    for cell in [total, *counts.values()]:
        assert cell == count_text(int(cell.replace(",", "")))  # 1301 plain, 19,205 grouped
    doc = json.loads(run_cli(capsys, "conditions", "--order", "18", "--count", "--format", "json").out)
    assert doc["total"] == sum(conditions_with(n) for n in range(3, 20))  # JSON: a plain integer


def test_limit_messages_use_the_same_format(capsys):
    r = run_cli(capsys, "verify", "@rk4", "--order", "16", "--max-conditions", "1000")
    total = sum(conditions_with(n) for n in range(3, 18))
    assert r.code == 2 and f"has {count_text(total)} conditions, above --max-conditions 1000" in r.err
