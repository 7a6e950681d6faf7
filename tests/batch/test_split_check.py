"""One exact check split into passes over other processes (``verify --jobs``/``--scheduler``):
every residual is still the reference's, whichever process computed its pass."""

from __future__ import annotations

import os
from fractions import Fraction
from pathlib import Path

import pytest
from support import reference as ref
from support.clirun import run_cli

import rkcheck
import rkcheck.batch.passes as passes
import rkcheck.evaluation.modular as modular
from rkcheck.errors import OptionError
from rkcheck.evaluation.scaled import ScaledTableau

A = [[Fraction(1, 7), Fraction(-2, 9), Fraction(3, 11)], [Fraction(2, 5), Fraction(1, 8), Fraction(-1, 6)],
     [Fraction(-1, 12), Fraction(5, 9), Fraction(1, 4)]]
B = [Fraction(1, 5), Fraction(3, 10), Fraction(1, 2)]
ORDER = 6


def tableau_file(tmp_path: Path) -> Path:
    rows = ", ".join("[" + ", ".join(f'"{x}"' for x in row) + "]" for row in A)
    path = tmp_path / "dense.toml"
    path.write_text(f'[tableau]\nA = [{rows}]\nb = [{", ".join(chr(34) + str(x) + chr(34) for x in B)}]\n',
                    encoding="utf-8")
    return path


@pytest.fixture
def one_channel_per_pass(monkeypatch):
    """A small check has all its channels in one pass; one per pass makes several.  And
    every pass goes over the listing: screened, the primes after the first would be
    evaluated here for the few conditions zero at it (rkcheck.evaluation.modular)."""
    monkeypatch.setattr(ScaledTableau, "channels_per_pass", lambda self, listing, top: 1)
    monkeypatch.setattr(modular, "_screened", lambda *args: False)


@pytest.fixture
def pass_log(tmp_path, monkeypatch):
    """Where each pass ran: one line per pass, the process id and thread name."""
    import threading

    log = tmp_path / "passes.log"
    real = passes._channel_pass

    def logged(item):
        with open(log, "a", encoding="utf-8") as f:
            f.write(f"{os.getpid()} {threading.current_thread().name}\n")
        return real(item)

    monkeypatch.setattr(passes, "_channel_pass", logged)
    return log


def assert_reference_residuals(result) -> None:
    """Every condition's exact residual is the reference's (up to the designated sign)."""
    for n in range(3, ORDER + 2):
        for cond in ref.energy_conditions(n):
            mine = [c for c in result.conditions if c.level_sequence == cond["id"]][0]
            assert abs(mine.residual) == abs(ref.energy_residual(cond, A, B))
    assert len(result.conditions) == sum(len(ref.energy_conditions(n)) for n in range(3, ORDER + 2))


def test_passes_on_local_processes_give_the_reference_residuals(tmp_path, one_channel_per_pass, pass_log):
    result = rkcheck.verify(tableau_file(tmp_path), order=ORDER, degree=None, jobs=2)
    assert_reference_residuals(result)
    ran = pass_log.read_text(encoding="utf-8").split("\n")[:-1]
    assert len(ran) >= 2 and all(int(line.split()[0]) != os.getpid() for line in ran)


def test_passes_on_a_cluster_give_the_reference_residuals(tmp_path, one_channel_per_pass, pass_log):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        result = rkcheck.verify(tableau_file(tmp_path), order=ORDER, degree=None, scheduler=cluster.scheduler_address)
    assert_reference_residuals(result)
    ran = pass_log.read_text(encoding="utf-8").split("\n")[:-1]
    assert len(ran) >= 2 and all("MainThread" not in line for line in ran)  # the cluster's worker thread


class _LosingExecutor:
    """Loses the first job (as a cluster that gave up on it), runs the others here."""

    def map_unordered(self, fn, items, failed):
        for i, item in enumerate(items):
            yield i, failed(item, "lost") if i == 0 else fn(item)


def test_a_lost_pass_is_computed_here(tmp_path, one_channel_per_pass):
    from rkcheck.evaluation.passes import passes_run_by

    with passes_run_by(passes.executor_passes(_LosingExecutor(), cache=False)):
        result = rkcheck.verify(tableau_file(tmp_path), order=ORDER, degree=None)
    assert_reference_residuals(result)


def test_bad_split_options_are_one_line(tmp_path, capsys):
    with pytest.raises(OptionError, match="jobs"):
        rkcheck.verify(tableau_file(tmp_path), order=4, jobs=0)
    with pytest.raises(OptionError, match="scheduler"):
        rkcheck.verify(tableau_file(tmp_path), order=4, scheduler=8786)  # type: ignore[arg-type]
    r = run_cli(capsys, "verify", str(tableau_file(tmp_path)), "--order", "4", "--jobs", "0")
    assert r.code == 2 and "--jobs" in r.err


def test_an_unreachable_scheduler_is_one_line_about_the_option(tmp_path, capsys, monkeypatch):
    """Not the file's fault: the line names the scheduler, not the file."""
    import socket

    pytest.importorskip("distributed")
    from rkcheck.batch.executors import SCHEDULER_TIMEOUT_ENV

    with socket.socket() as s:  # bound and closed: nothing listens there
        s.bind(("127.0.0.1", 0))
        address = f"tcp://127.0.0.1:{s.getsockname()[1]}"
    monkeypatch.setenv(SCHEDULER_TIMEOUT_ENV, "1")
    r = run_cli(capsys, "verify", str(tableau_file(tmp_path)), "--order", "4", "--scheduler", address)
    assert r.code == 2 and r.err.startswith(f"rkcheck: error: scheduler: cannot reach the Dask scheduler at {address}")
    assert len(r.err.strip().splitlines()) == 1
