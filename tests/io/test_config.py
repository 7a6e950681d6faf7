"""[tool.rkcheck] in pyproject.toml: validated like every other source."""

from __future__ import annotations

import pytest
from support.clirun import run_cli

MIDPOINT = '[tableau]\nA = [["1/2"]]\nb = [1]\n'


@pytest.mark.parametrize(
    "pyproject, message",
    [
        ('tool = "x"\n', "tool: [tool] must be a table"),
        ("tool = 1\n", "tool: [tool] must be a table"),
        ("[tool]\nrkcheck = 1\n", "[tool.rkcheck] must be a table"),
        ("[tool.rkcheck]\njobs = 2000\n", "tool.rkcheck.jobs: expected an integer from 1 to 256, got 2000"),
        ("[tool.rkcheck]\norder = 99\n", "tool.rkcheck.order: expected an integer from 1 to 30, got 99"),
        ("[tool.rkcheck]\ndps = 1\n", "tool.rkcheck.dps: expected an integer from 10 to 5000, got 1"),
        ("[tool.rkcheck]\nformt = 'json'\n", "tool.rkcheck.formt: unknown key (did you mean 'format'?)"),
        ("[tool.rkcheck]\nx = 1\nx = 2\n", "cannot read [tool.rkcheck]"),
        ("[tool.rkcheck]\npaths = ['.', '']\n",
         "tool.rkcheck.paths: an empty path: give a file or folder (. for the project's folder)"),
        (b"[tool]\nname = '\xff'\n", "cannot read [tool.rkcheck]"),
    ],
)
def test_bad_project_configuration_is_one_line_exit_2(tmp_path, capsys, monkeypatch, pyproject, message):
    project = tmp_path / "pyproject.toml"
    if isinstance(pyproject, bytes):
        project.write_bytes(pyproject)
    else:
        project.write_text(pyproject, encoding="utf-8")
    (tmp_path / "t.toml").write_text(MIDPOINT, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    for command in (["verify", "t.toml"], ["scan", "t.toml", "--jobs", "1"]):
        r = run_cli(capsys, *command)
        assert r.code == 2, (command, r.err)
        assert r.err.count("\n") == 1 and "Traceback" not in r.err
        assert r.err.startswith(f"rkcheck: error: {project}: {message}"), r.err


def test_configured_paths_are_named_as_on_the_command_line(tmp_path, capsys, monkeypatch):
    """[tool.rkcheck] paths = ["tabs"]: a scan from the project's folder names its files
    tabs/a.toml, as `rkcheck scan tabs` does (not by where the project was checked out);
    from a folder outside them, by their absolute path."""
    import json

    (tmp_path / "tabs").mkdir()
    (tmp_path / "tabs" / "a.toml").write_text('[tableau]\nA = [["1/2"]]\nb = ["1"]\n', encoding="utf-8")
    (tmp_path / "pyproject.toml").write_text('[tool.rkcheck]\npaths = ["tabs"]\n', encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    configured = json.loads(run_cli(capsys, "scan", "--format", "json", "-N", "3").out)
    given = json.loads(run_cli(capsys, "scan", "tabs", "--format", "json", "-N", "3").out)
    assert [f["file"] for f in configured["files"]] == [f["file"] for f in given["files"]] == ["tabs/a.toml"]
    (tmp_path / "sub").mkdir()
    monkeypatch.chdir(tmp_path / "sub")
    outside = json.loads(run_cli(capsys, "scan", "--format", "json", "-N", "3").out)
    assert [f["file"] for f in outside["files"]] == [str(tmp_path / "tabs" / "a.toml")]
