"""rkcheck scan on a Dask cluster: the same rows, order, progress and error rows as a
local scan; a worker lost mid-scan has its files checked by the others; Ctrl-C cancels
the cluster's jobs; no Dask or no scheduler is one line and exit 2.

The reference for every cluster result is the same scan run in this process
(``jobs=1``), which shares no code with the cluster path beyond checking one file.
"""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from support.clirun import run_cli
from support.guards import hang_guard

import rkcheck
from rkcheck.batch.executors import SCHEDULER_ENV, SCHEDULER_TIMEOUT_ENV, resolve_scheduler

DENSE = ('[tableau]\nA = [["1/7", "-2/9", "3/11", "1/13"], ["2/5", "1/8", "-1/6", "3/10"],'
         ' ["-1/12", "5/9", "1/4", "2/15"], ["3/8", "1/3", "-2/7", "1/5"]]\nb = ["1/5", "3/10", "1/4", "1/4"]\n')
MIDPOINT = '[tableau]\nA = [["1/2"]]\nb = [1]\n[expect]\nquadrature_order = 2\n'
RK4_WRONG = ('[tableau]\nA = [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]]\n'
             'b = ["1/6", "1/3", "1/3", "1/6"]\n[expect]\nclassical_order = 5\n')


def mixed_folder(tmp_path: Path) -> Path:
    folder = tmp_path / "mixed"
    (folder / "sub").mkdir(parents=True)
    files = {"a.toml": MIDPOINT, "b-wrong.toml": RK4_WRONG, "c-broken.toml": '[tableau]\nA = [["1/4", "1/4 - )"]]\n',
             "d-other.toml": '[project]\nname = "x"\n', "sub/e.toml": DENSE, "f.toml": DENSE}
    for name, text in files.items():
        (folder / name).write_text(text, encoding="utf-8")
    return folder


def dense_folder(tmp_path: Path, n: int) -> Path:
    folder = tmp_path / "dense"
    folder.mkdir()
    for i in range(n):
        (folder / f"t{i:02d}.toml").write_text(DENSE, encoding="utf-8")
    return folder


def comparable(result) -> list[tuple]:
    """A scan's rows without their times: path, status, error, verdict and energy order."""
    return [(r.path, r.status, r.error, None if r.verification is None else
             (str(r.verification.verdict), r.verification.energy_order)) for r in result.rows]


def closed_port() -> str:
    with socket.socket() as s:  # bound and closed: nothing listens there
        s.bind(("127.0.0.1", 0))
        return f"tcp://127.0.0.1:{s.getsockname()[1]}"


# ------------------------------------------------------------- without a cluster


def test_the_scheduler_comes_from_the_option_then_the_environment_then_the_project(monkeypatch):
    monkeypatch.delenv(SCHEDULER_ENV, raising=False)
    assert resolve_scheduler(None, None) is None
    assert resolve_scheduler(None, "tcp://c:1") == "tcp://c:1"
    monkeypatch.setenv(SCHEDULER_ENV, "tcp://e:1")
    assert resolve_scheduler(None, "tcp://c:1") == "tcp://e:1"
    assert resolve_scheduler("tcp://o:1", "tcp://c:1") == "tcp://o:1"
    assert resolve_scheduler("local", "tcp://c:1") is None  # the option forces local processes
    monkeypatch.setenv(SCHEDULER_ENV, "  ")  # empty: not set
    assert resolve_scheduler(None, None) is None
    assert resolve_scheduler(None, "local") is None


def test_without_dask_a_scheduler_is_one_line_naming_the_extra(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed -> ImportError
    folder = mixed_folder(tmp_path)
    r = run_cli(capsys, "scan", str(folder), "--scheduler", "tcp://127.0.0.1:8786")
    assert r.code == 2 and r.out == ""
    assert r.err == "rkcheck: error: scheduler: --scheduler needs Dask: pip install 'rkcheck[cluster]'\n"
    with pytest.raises(rkcheck.RkcheckError, match=r"rkcheck\[cluster\]"):
        rkcheck.scan([folder], scheduler="tcp://127.0.0.1:8786")


def test_a_local_scan_needs_no_dask(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)
    monkeypatch.delenv(SCHEDULER_ENV, raising=False)
    r = run_cli(capsys, "scan", str(mixed_folder(tmp_path)), "--order", "4", "--jobs", "1", "--format", "json")
    assert r.code == 1 and "scheduler" not in json.loads(r.out)["options"]


# ------------------------------------------------------------- with Dask


def test_an_unreachable_scheduler_is_one_line_within_the_connect_limit(tmp_path, capsys, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setenv(SCHEDULER_TIMEOUT_ENV, "1")
    folder = mixed_folder(tmp_path)
    address = closed_port()
    for how in ("option", "environment", "project"):
        args = ["scan", str(folder)]
        monkeypatch.delenv(SCHEDULER_ENV, raising=False)
        if how == "option":
            args += ["--scheduler", address]
        elif how == "environment":
            monkeypatch.setenv(SCHEDULER_ENV, address)
        else:
            (tmp_path / "pyproject.toml").write_text(f'[tool.rkcheck]\nscheduler = "{address}"\n', encoding="utf-8")
            monkeypatch.chdir(tmp_path)
        with hang_guard(30):
            r = run_cli(capsys, *args)
        assert r.code == 2 and r.out == "", how
        assert r.err.count("\n") == 1 and r.err.startswith("rkcheck: error: scheduler: cannot reach the Dask "
                                                           f"scheduler at {address} within 1 s"), (how, r.err)
        assert "SCHEDULER_CONNECT_TIMEOUT" in r.err
    r = run_cli(capsys, "scan", str(folder), "--scheduler", "nonsense")
    assert r.code == 2 and r.err.startswith("rkcheck: error: scheduler: not a scheduler address")
    for value in ("soon", "0", "3601"):  # the range the message states is the one held
        monkeypatch.setenv(SCHEDULER_TIMEOUT_ENV, value)
        r = run_cli(capsys, "scan", str(folder), "--scheduler", address)
        assert r.code == 2 and r.err.startswith(f"rkcheck: error: {SCHEDULER_TIMEOUT_ENV}: expected a number of "
                                                f"seconds above 0 and at most 3600, got '{value}'")


@pytest.fixture(scope="module")
def thread_cluster():
    """One worker thread in this process: quick to start, and it sees the test's patches."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        yield cluster


def test_a_cluster_scan_gives_the_rows_progress_and_exit_of_a_local_scan(tmp_path, thread_cluster, monkeypatch):
    monkeypatch.delenv(SCHEDULER_ENV, raising=False)
    folder = mixed_folder(tmp_path)
    local = rkcheck.scan([folder], order=8, jobs=1)
    steps: list[tuple[int, int]] = []
    rows: list[str] = []
    remote = rkcheck.scan([folder], order=8, scheduler=thread_cluster.scheduler_address,
                          progress=lambda done, total: steps.append((done, total)),
                          on_file=lambda row, done, total: rows.append(row.path))
    assert comparable(remote) == comparable(local)
    assert [r.status for r in remote.rows] == ["ok", "failed", "error", "skipped", "ok", "ok"]
    assert remote.failed and local.failed and not remote.interrupted
    assert steps == [(k, 6) for k in range(7)]  # one bar: files, 0 to 6
    assert sorted(rows) == sorted(r.path for r in local.rows)
    assert remote.options["scheduler"] == thread_cluster.scheduler_address
    assert json.loads(remote.report("json"))["files"][2]["error"] == local.rows[2].error


def test_a_check_that_crashes_on_the_cluster_is_one_row(tmp_path, thread_cluster, monkeypatch):
    import rkcheck.energy.claims

    real = rkcheck.energy.claims.judge_tableau

    def buggy(tab, *args, **kwargs):
        if tab.info.source.endswith("t01.toml"):
            raise RuntimeError("simulated bug")
        return real(tab, *args, **kwargs)

    monkeypatch.setattr(rkcheck.energy.claims, "judge_tableau", buggy)  # the worker thread shares it
    result = rkcheck.scan([dense_folder(tmp_path, 3)], order=4, scheduler=thread_cluster.scheduler_address)
    assert [r.status for r in result.rows] == ["ok", "error", "ok"]
    assert "internal error: RuntimeError: simulated bug" in result.rows[1].error


def scan_killing_a_worker(cluster, client, folder: Path):
    """Scan ``folder`` on ``cluster``, killing (SIGKILL) a worker that holds jobs as
    soon as the first file has finished; the result and the keys the dead worker held."""
    killed: dict[str, object] = {}

    def kill_a_busy_worker(row, done, total):
        if killed:
            return
        busy = {w: keys for w, keys in client.processing().items() if keys}
        if busy:
            worker, keys = next(iter(busy.items()))
            pid = client.run(os.getpid, workers=[worker])[worker]
            killed["keys"] = keys
            os.kill(pid, signal.SIGKILL)

    with hang_guard(240):
        result = rkcheck.scan([folder], order=10, scheduler=cluster.scheduler_address, on_file=kill_a_busy_worker)
    assert killed, "no worker was busy"
    return result, killed["keys"]


@pytest.mark.parametrize("allowed_failures, files", [(3, 16), (0, 16), (0, 48)],
                         ids=["resubmitted", "given up", "chunk retried file by file"])
def test_a_worker_killed_mid_scan_has_its_files_checked_by_the_others(tmp_path, monkeypatch, allowed_failures, files):
    # Dask gives the tasks of a dead worker to the others; a task that was on more than
    # allowed-failures dead workers is given up: a one-file task is then an error row,
    # a task of several files (48 files on 2 workers: 3 a task) is tried file by file
    distributed = pytest.importorskip("distributed")
    import dask

    from rkcheck.batch.dask_executor import chunk_size

    assert chunk_size(files, 2) == (1 if files == 16 else 3)
    monkeypatch.delenv(SCHEDULER_ENV, raising=False)
    folder = dense_folder(tmp_path, files)
    local = rkcheck.scan([folder], order=10, jobs=1)
    with dask.config.set({"distributed.scheduler.allowed-failures": allowed_failures}), \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster, set_as_default=False) as client:
        remote, held = scan_killing_a_worker(cluster, client, folder)
    if allowed_failures or files > 16:
        assert comparable(remote) == comparable(local)  # every file, the killed worker's ones too
        return
    lost = [r for r in remote.rows if r.status == "error"]
    # the jobs the dead worker held (not exactly `held`: it may take one more between the
    # look and the kill), and only they, are error rows
    assert lost and held
    assert all("the Dask workers running it died each time it was tried" in r.error for r in lost)
    kept = [row for row in comparable(remote) if row[1] != "error"]
    assert kept == [row for row in comparable(local) if row[0] not in {r.path for r in lost}]
    assert len(remote.rows) == files and remote.failed


def test_ctrl_c_cancels_the_clusters_jobs_and_reports_what_finished(tmp_path):
    distributed = pytest.importorskip("distributed")
    folder = dense_folder(tmp_path, 30)
    out = tmp_path / "report.json"
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster, set_as_default=False) as client:
        proc = subprocess.Popen([sys.executable, "-m", "rkcheck", "scan", str(folder), "--order", "13", "--format", "json",
                                 "-o", str(out), "--verbose", "--scheduler", cluster.scheduler_address],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                env=dict(os.environ, NO_COLOR="1"))
        with hang_guard(120):
            while True:
                line = proc.stderr.readline()
                assert line, "the scan ended before any file finished"
                if line.startswith("rkcheck: [1/"):
                    break
            proc.send_signal(signal.SIGINT)
            _, stderr = proc.communicate()
            assert proc.returncode == 130, stderr
            assert "Traceback" not in stderr
            assert all(line.startswith("rkcheck: ") for line in stderr.splitlines()), stderr  # no Dask log lines
            while any(key.startswith("rkcheck-") for keys in client.processing().values() for key in keys):
                time.sleep(0.1)  # cancelled: the worker is left with nothing of ours
    doc = json.loads(out.read_text())
    assert doc["interrupted"] is True and 0 < len(doc["files"]) < 30
    assert all(f["status"] == "ok" for f in doc["files"])
    files = [f["file"] for f in doc["files"]]
    assert files == sorted(files)


def test_a_bad_scheduler_in_the_project_is_one_line_naming_the_key(tmp_path, capsys, monkeypatch):
    monkeypatch.delenv(SCHEDULER_ENV, raising=False)
    folder = mixed_folder(tmp_path)
    (tmp_path / "pyproject.toml").write_text("[tool.rkcheck]\nscheduler = 8786\n", encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    r = run_cli(capsys, "scan", str(folder))
    assert r.code == 2
    assert r.err == (f"rkcheck: error: {tmp_path / 'pyproject.toml'}: tool.rkcheck.scheduler: expected a scheduler "
                     "address such as 'tcp://host:8786', got 8786\n")


def test_a_scheduler_without_workers_is_one_line(tmp_path, capsys, monkeypatch):
    distributed = pytest.importorskip("distributed")
    monkeypatch.setenv(SCHEDULER_TIMEOUT_ENV, "1")
    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster, hang_guard(60):
        r = run_cli(capsys, "scan", str(mixed_folder(tmp_path)), "--scheduler", cluster.scheduler_address)
    assert r.code == 2 and r.out == ""
    assert r.err == (f"rkcheck: error: scheduler: the Dask scheduler at {cluster.scheduler_address} has no worker "
                     "(waited 1 s, the limit SCHEDULER_CONNECT_TIMEOUT)\n")


def test_scheduler_local_overrides_the_environment(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # and needs no Dask
    monkeypatch.setenv(SCHEDULER_ENV, closed_port())
    folder = mixed_folder(tmp_path)
    r = run_cli(capsys, "scan", str(folder), "--order", "4", "--jobs", "1", "--format", "json", "--scheduler", "local")
    doc = json.loads(r.out)
    assert r.code == 1 and "scheduler" not in doc["options"] and len(doc["files"]) == 6
    assert run_cli(capsys, "scan", str(folder), "--order", "4").code == 2  # without it, the environment's scheduler
