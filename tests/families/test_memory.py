"""Families within the memory available: a computation on the conditions' polynomials
that outgrows it stops with one line (FLINT, out of memory, would abort the process with
no message of ours), and a kernel family's surrogate takes no more than its factors."""

from __future__ import annotations

import json

import pytest
from support.limits import run_limited

import rkcheck
from rkcheck.errors import ResourceError
from rkcheck.numbers import room
from rkcheck.numbers.room import RoomWatch, room_read_by
from rkcheck.reports.families import polynomial_text

MB = 10**6  # as the messages count


def _free_tableau(tmp_path, s=4):
    """A tableau of ``s`` stages whose every entry is its own parameter."""
    A = [[f"a{i}{j}" for j in range(1, s + 1)] for i in range(1, s + 1)]
    b = [f"b{i}" for i in range(1, s + 1)]
    f = tmp_path / "free.toml"
    f.write_text("[parameters]\n" + "".join(f'{n} = "free"\n' for n in sum(A, []) + b)
                 + f"[tableau]\nA = {json.dumps(A)}\nb = {json.dumps(b)}\n")
    return f


def test_a_family_that_outgrows_the_memory_is_refused_in_one_line(tmp_path):
    # every entry of a 4-stage tableau free (20 parameters): its energy conditions to
    # order 8 take about 850 MB; under 500 MB FLINT aborted the process (exit -6)
    run = run_limited(["-m", "rkcheck", "verify", str(_free_tableau(tmp_path)), "--order", "8", "--degree", "none"],
                      memory_mb=500, cpu_seconds=120)
    assert run.code == 2, (run.code, run.out[-300:], run.err[-300:])
    assert run.err.count("\n") == 1 and "need more memory than is available" in run.err and "MIN_ROOM" in run.err
    assert "FLINT" not in run.out + run.err


def test_a_kernel_familys_surrogate_is_read_through_its_factors_within_the_memory(tmp_path):
    # a 241-node surrogate (τ-degree 30, trees of 9 vertices): its n² entries, rationals
    # of hundreds of digits, took 340 MB formed and written out, and under 300 MB FLINT
    # aborted; read through A = V C Wᵀ the check fits, and its first orders' conditions
    # are those of the same family checked to order 5 in this process
    f = tmp_path / "k.toml"
    f.write_text('[parameters]\nk = "free"\n[continuous]\nA = "tau + k*tau^30*(sigma - 1/2)"\nb = "1"\n')
    run = run_limited(["-m", "rkcheck", "verify", str(f), "--order", "8", "--format", "json"],
                      memory_mb=300, cpu_seconds=120)
    assert run.code == 0, (run.code, run.out[-300:], run.err[-300:])
    doc = json.loads(run.out)
    assert doc["family"]["surrogate"]["nodes"] == 241
    low = rkcheck.family_conditions(f, order=5, degree=None)
    limited = {c["id"]: c["polynomial"] for c in doc["conditions"] if c["kind"] == "energy" and c["order"] <= 5}
    assert limited == {c.id: str(c.polynomial) for c in low.energy}
    assert any(p != "0" for p in limited.values())


def test_a_kernel_family_over_a_number_field_is_read_through_its_factors_too(tmp_path):
    # with √3 among its constants the surrogate's 241² entries were formed one by one in
    # Q(√3) before any condition (GMP aborted under 300 MB; later, refused there); its
    # factors over Q(√3) fit, and it ends with the same verdict line as without a limit
    f = tmp_path / "k.toml"
    f.write_text('[parameters]\nk = "free"\n[constants]\nr = "sqrt(3)"\n'
                 '[continuous]\nA = "tau + k*r*tau^30*(sigma - 1/2)"\nb = "1"\n')
    run = run_limited(["-m", "rkcheck", "verify", str(f), "--order", "8", "--degree", "none", "--format", "json"],
                      memory_mb=300, cpu_seconds=120)
    assert run.code == 0, (run.code, run.out[-300:], run.err[-300:])
    doc = json.loads(run.out)
    assert doc["family"]["surrogate"]["nodes"] == 241 and doc["family"]["field"] == "sqrt(3)"
    low = rkcheck.family_conditions(f, order=5, degree=None)
    limited = {c["id"]: c["polynomial"] for c in doc["conditions"] if c["kind"] == "energy" and c["order"] <= 5}
    assert limited == {c.id: polynomial_text(c.polynomial, low.family.ring.field) for c in low.energy}


class _Memory:
    """A reader of the memory left that replays ``values`` (MB)."""

    def __init__(self, *values):
        self.values = [v * MB for v in values]

    def __call__(self):
        return self.values.pop(0)


@pytest.fixture
def every_step_read(monkeypatch):
    monkeypatch.setattr(room, "READ_INTERVAL", 0.0)


def test_a_step_starts_while_the_memory_left_holds_the_margin(every_step_read):
    # MIN_ROOM 48 MB, STEP_MARGIN 3: steps that took 10 MB each leave room to 48 MB;
    # one that took 30 MB asks for 90 MB before the next
    with room_read_by(_Memory(500, 490, 480, 450, 95, 89)):
        watch = RoomWatch("the polynomials", "do less")
        for _ in range(4):
            watch.step()
        assert watch.largest == 30 * MB
        with pytest.raises(ResourceError, match="95 MB left"):  # 450 → 95: the next may take 3 × 355 MB
            watch.step()


def test_the_floor_and_the_margin_refuse_in_one_line(every_step_read):
    with room_read_by(_Memory(47)), pytest.raises(ResourceError) as err:
        RoomWatch("the polynomials", "do less").step()
    assert str(err.value).startswith("the polynomials need more memory than is available: 47 MB left")
    assert str(err.value).endswith("(MIN_ROOM, STEP_MARGIN); do less")
    with room_read_by(_Memory(300, 290, 200)):
        watch = RoomWatch("the polynomials", "do less")
        watch.step(), watch.step()  # 10 MB taken: the floor holds
        with pytest.raises(ResourceError, match="200 MB left, less than the 270 MB"):  # 90 MB taken, three times
            watch.step()


def test_nothing_is_watched_without_a_reader_or_a_reading(every_step_read):
    RoomWatch("the polynomials", "do less").step()
    with room_read_by(lambda: None):
        watch = RoomWatch("the polynomials", "do less")
        watch.step(), watch.step()
        assert watch.left is None
