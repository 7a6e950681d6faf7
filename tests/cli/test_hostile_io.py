"""Hostile sources and targets: devices, endless pipes, /dev/stdout.  Reads are bounded by
a named limit (MAX_FILE_BYTES, RKCHECK_MAX_FILE_BYTES); each case is run as a real
process, with a timeout as the guard against a hang."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from support.clirun import run_subprocess

ONE_STAGE = '[tableau]\nA = [["1/2"]]\nb = ["1"]\n'


def run(*args: str, stdin: bytes | None = None, env: dict[str, str] | None = None, cwd: str | None = None):
    proc = subprocess.run([sys.executable, "-m", "rkcheck", *args], input=stdin, capture_output=True, timeout=60,
                          env=dict(os.environ, NO_COLOR="1", **(env or {})), cwd=cwd)
    return proc.returncode, proc.stdout.decode("utf-8", "replace"), proc.stderr.decode("utf-8", "replace")


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_a_device_is_refused_not_read():
    code, _, err = run("verify", "/dev/zero")
    assert code == 2 and err == "rkcheck: error: /dev/zero: is a device, not a tableau file\n", err


def test_standard_input_is_read_up_to_the_limit():
    # 17 MiB of zeros on stdin: more than the default MAX_FILE_BYTES of 16 MiB
    code, _, err = run("verify", "-", stdin=bytes(17 * 2**20))
    assert code == 2 and "-: file too large: more than 16,777,216 bytes" in err and "MAX_FILE_BYTES" in err, err
    assert len(err.splitlines()) == 1


def test_the_limit_is_settable_and_holds_for_files_and_stdin(tmp_path, monkeypatch):
    path = tmp_path / "t.toml"
    path.write_text(ONE_STAGE, encoding="utf-8")
    size = len(ONE_STAGE.encode())
    monkeypatch.chdir(tmp_path)  # no pyproject.toml above: the limit holds for it too
    code, _, err = run("verify", str(path), "--order", "2", env={"RKCHECK_MAX_FILE_BYTES": str(size - 1)})
    assert code == 2 and f"({size} bytes; the limit MAX_FILE_BYTES is {size - 1}" in err, err
    code, _, err = run("verify", "-", stdin=ONE_STAGE.encode(), env={"RKCHECK_MAX_FILE_BYTES": str(size - 1)})
    assert code == 2 and f"more than {size - 1} bytes" in err, err
    code, out, err = run("verify", "-", "--order", "2", stdin=ONE_STAGE.encode(),
                         env={"RKCHECK_MAX_FILE_BYTES": str(size)})
    assert code == 0 and "1 stage" in out, err  # the implicit midpoint rule: order 2 holds
    code, _, err = run("verify", str(path), env={"RKCHECK_MAX_FILE_BYTES": "lots"})
    assert code == 2 and err.startswith("rkcheck: error: RKCHECK_MAX_FILE_BYTES: expected a positive"), err


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_a_link_to_a_device_in_a_scanned_folder_is_one_error_row(tmp_path):
    (tmp_path / "good.toml").write_text(ONE_STAGE, encoding="utf-8")
    os.symlink("/dev/zero", tmp_path / "zero.toml")
    code, out, err = run("scan", str(tmp_path), "--order", "2", "--jobs", "1", "--format", "json")
    assert code == 1, err
    files = {os.path.basename(f["file"]): f for f in json.loads(out)["files"]}
    assert files["good.toml"]["status"] == "ok"
    assert files["zero.toml"]["status"] == "error" and "is a device" in files["zero.toml"]["error"]


@pytest.mark.parametrize("command", [["scan", "@gauss-2", "--order", "3", "--format", "json"],
                                     ["conditions", "-N", "3", "--emit", "python"]])
def test_output_to_dev_stdout_on_a_pipe(command):
    # stdout is a pipe here: /dev/stdout resolves to no file name, yet opens fine
    r = run_subprocess(*command, "-o", "/dev/stdout")
    assert r.code == 0, r.err
    if command[0] == "scan":
        assert json.loads(r.out)["totals"]["files"] == 1
    else:
        compile(r.out, "conditions.py", "exec")
