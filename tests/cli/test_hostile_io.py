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
from support.paths import REPO

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
    for bad in ("lots", "²"):  # '²' is a digit to str.isdigit, not to int()
        code, _, err = run("verify", str(path), env={"RKCHECK_MAX_FILE_BYTES": bad})
        assert code == 2 and err.count("\n") == 1 and "RKCHECK_MAX_FILE_BYTES: expected a positive" in err, err
    # a limit beyond what one read can ask for (Py_ssize_t) is no limit, for files and stdin
    for source, stdin in ((str(path), None), ("-", ONE_STAGE.encode())):
        code, out, err = run("verify", source, "--order", "2", stdin=stdin, env={"RKCHECK_MAX_FILE_BYTES": "9" * 30})
        assert code == 0 and "1 stage" in out, err


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


NAMES = {b"bad\xff.toml": "bad\\xff.toml", b"esc\x1b[2J.toml": "esc\\x1b[2J.toml", b"nl\nx.toml": "nl\\nx.toml"}


@pytest.mark.parametrize("fmt", ["json", "junit", "github", "csv", "text"])
def test_file_names_that_are_not_text_are_shown_escaped_in_every_format(tmp_path, fmt):
    claim = ONE_STAGE + "[expect]\nclassical_order = 3\n"  # broken: every row is a failure with its path
    for raw in NAMES:
        (tmp_path / os.fsdecode(raw)).write_text(claim, encoding="utf-8")
    proc = subprocess.run([sys.executable, "-m", "rkcheck", "scan", ".", "--order", "2", "--jobs", "1", "--format",
                           fmt], capture_output=True, timeout=60, cwd=tmp_path, env=dict(os.environ, NO_COLOR="1"))
    assert proc.returncode == 1, proc.stderr
    out = proc.stdout.decode("utf-8")  # valid UTF-8: no raw byte of a name
    assert not any(ch in out for ch in "\x1b\xff") and "\udcff" not in out
    for shown in NAMES.values():
        assert (json.dumps(shown)[1:-1] if fmt == "json" else shown) in out, (shown, out)
    if fmt == "junit":
        import xml.etree.ElementTree as ET

        names = {case.get("name") for case in ET.fromstring(out).iter("testcase")}
        assert names == {os.path.join(".", n) for n in NAMES.values()} or names == set(NAMES.values())


def test_a_file_name_with_an_escape_is_shown_escaped_by_verify(tmp_path):
    path = tmp_path / "esc\x1b[2J.toml"
    path.write_text(ONE_STAGE, encoding="utf-8")
    code, out, err = run("verify", str(path), "--order", "2")
    assert code == 0 and "\x1b" not in out and "esc\\x1b[2J.toml" in out, out


@pytest.mark.parametrize("command", [["show", "--format", "json"], ["bench", "--order", "2", "--format", "json"],
                                     ["perturb", "--order", "2", "--direction", "random", "--format", "json"]])
def test_json_documents_name_a_file_that_is_not_utf8_escaped(tmp_path, command):
    (tmp_path / os.fsdecode(b"bad\xff.toml")).write_text(ONE_STAGE, encoding="utf-8")
    proc = subprocess.run([sys.executable, "-m", "rkcheck", command[0], os.fsdecode(b"bad\xff.toml"), *command[1:]],
                          capture_output=True, timeout=120, cwd=tmp_path, env=dict(os.environ, NO_COLOR="1"))
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout.decode("utf-8"))["file"] == "bad\\xff.toml"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")
def test_a_named_pipe_is_read_once_and_never_waited_on_for_ever(tmp_path, capsys, monkeypatch):
    import threading
    import time

    from support.clirun import run_cli

    from rkcheck.io import bounded

    monkeypatch.setattr(bounded, "FIFO_WAIT_SECONDS", 0.3)
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    # nobody writes: refused after FIFO_WAIT_SECONDS, one line, exit 2 (it waited for ever)
    start = time.monotonic()
    r = run_cli(capsys, "verify", str(fifo))
    assert r.code == 2 and "FIFO_WAIT_SECONDS" in r.err and r.err.count("\n") == 1, r.err
    assert time.monotonic() - start < 5
    # a writer that comes later, as bash's <(…) does: the tableau is read once, and
    # checked (the family test read it first and left the check an empty pipe)
    writer = threading.Thread(target=lambda: (time.sleep(0.1), fifo.write_text(ONE_STAGE, encoding="utf-8")))
    writer.start()
    r = run_cli(capsys, "verify", str(fifo), "--order", "2")
    writer.join()
    assert r.code == 0 and "1 stage" in r.out, r.err


@pytest.mark.parametrize("args, code", [(["conditions", "--order", "14"], 0),  # 13 100 lines, exit 0
                                        (["verify", "{euler}", "--degree", "none", "--order", "12", "--all"], 1)])
def test_a_reader_that_leaves_early_keeps_the_verdicts_exit_code(tmp_path, args, code):
    # `rkcheck … | head -1` with more output than a pipe holds: the broken pipe is not an
    # error of the command (click made it exit 1 whatever the verdict); no traceback either
    euler = tmp_path / "euler.toml"  # no claims: the conditions decide, and 1 301 fail
    euler.write_text('[tableau]\nA = [["0"]]\nb = ["1"]\n', encoding="utf-8")
    argv = [a.format(euler=euler) for a in args]
    proc = subprocess.Popen([sys.executable, "-m", "rkcheck", *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.readline()
    proc.stdout.close()  # the reader goes; what rkcheck still writes meets a broken pipe
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == code and "Traceback" not in err and "Error" not in err, err


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")
def test_a_named_pipe_in_a_scanned_folder_is_one_error_row(tmp_path, capsys, monkeypatch):
    from support.clirun import run_cli

    from rkcheck.io import bounded

    monkeypatch.setattr(bounded, "FIFO_WAIT_SECONDS", 0.2)
    (tmp_path / "good.toml").write_text(ONE_STAGE, encoding="utf-8")
    os.mkfifo(tmp_path / "pipe.toml")  # it was left out without a row
    r = run_cli(capsys, "scan", str(tmp_path), "--order", "2", "--jobs", "1", "--format", "json")
    files = {os.path.basename(f["file"]): f for f in json.loads(r.out)["files"]}
    assert files["good.toml"]["status"] == "ok" and files["pipe.toml"]["status"] == "error", r.out
    assert "FIFO_WAIT_SECONDS" in files["pipe.toml"]["error"]


@pytest.mark.parametrize("args", [["new", "gauss", "-s", "2"], ["catalog", "tableaux/avf"],
                                  ["conditions", "-N", "4", "--emit", "python"]])
def test_a_report_that_cannot_be_written_names_the_users_path(tmp_path, args):
    # written through a temporary file beside the target: the error is about the path the
    # user gave, never that temporary file's name
    target = tmp_path / "missing" / "out.txt"
    code, _, err = run(*args, "-o", str(target), cwd=str(REPO))
    assert code == 2 and err.count("\n") == 1, err
    assert str(target) in err and ".rkcheck-" not in err and "cannot write" in err


@pytest.mark.parametrize("args", [["new", "gauss", "-s", "2"], ["conditions", "-N", "3", "--emit", "python"]])
def test_an_empty_output_name_is_refused_not_read_as_stdout(args):
    code, out, err = run(*args, "-o", "", cwd=str(REPO))
    assert code == 2 and out == "" and "--output: expected a file name" in err and err.count("\n") == 1, err
