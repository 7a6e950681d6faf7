"""JSON reports written as they are made: a large one is never held whole as text."""

from __future__ import annotations

import json
from collections import Counter

from support.counts import conditions_with
from support.limits import run_limited


def test_a_json_listing_is_written_as_it_is_made():
    # order 16: 18 MB of JSON; joined whole into one string (and encoded) on top of the
    # listing, the report ran out of memory under 300 MB after the listing was built
    run = run_limited(["-m", "rkcheck", "conditions", "--order", "16", "--format", "json"], memory_mb=300,
                      cpu_seconds=120)
    assert run.code == 0, (run.code, run.err[-300:])
    doc = json.loads(run.out)
    assert Counter(c["vertices"] for c in doc["conditions"]) == {n: conditions_with(n) for n in range(3, 18)}
