"""Every shell transcript in the docs is the real output of its commands.

A transcript is a fenced block whose first line starts with ``$ ``: each ``$ `` line is a
command, run with bash from the repository root (``rkcheck`` is this interpreter's
console script), and the lines up to the next ``$ `` line are what it prints, stdout and
stderr together.  A line ``...`` in the expected output stands for any number of lines.
Timings are the only thing that may differ (see ``normalise``): a changed report makes
the page fail here instead of going stale.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest
from support.paths import REPO

PAGES = sorted((REPO / "docs").rglob("*.md")) + [REPO / "README.md"]
FENCE = re.compile(r"^(\s*)```")
#: table columns whose cells are wall times (by their header)
TIMING_HEADERS = {"time", "time s", "conditions/s"}
#: JSON keys whose number values are wall times
TIMING_KEYS = {"trees", "evaluation", "orders_and_avf", "total", "time", "seconds"}


@dataclass(frozen=True)
class Command:
    line: str
    expected: tuple[str, ...]


@dataclass(frozen=True)
class Transcript:
    page: Path
    lineno: int
    commands: tuple[Command, ...]

    @property
    def name(self) -> str:
        return f"{self.page.relative_to(REPO)}:{self.lineno}"


def fenced_blocks(text: str):
    """(line number of the opening fence, the lines inside) for every fenced block."""
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if FENCE.match(lines[i]):
            start, body = i, []
            i += 1
            while i < len(lines) and not FENCE.match(lines[i]):
                body.append(lines[i])
                i += 1
            yield start + 1, body
        i += 1


def transcripts(page: Path) -> list[Transcript]:
    found = []
    for lineno, body in fenced_blocks(page.read_text(encoding="utf-8")):
        if not body or not body[0].startswith("$ "):
            continue
        commands: list[Command] = []
        for line in body:
            if line.startswith("$ "):
                commands.append(Command(line[2:], ()))
            else:
                last = commands[-1]
                commands[-1] = Command(last.line, last.expected + (line,))
        found.append(Transcript(page, lineno, tuple(commands)))
    return found


ALL = [t for page in PAGES for t in transcripts(page)]


def _cells(line: str) -> list[str]:
    # rich pads every cell by one space on each side, so columns are 2+ spaces apart
    return re.split(r" {2,}", line.strip())


def normalise(lines: list[str]) -> list[str]:
    """Timings replaced by ``<t>``, runs of spaces by two (a wider timing column shifts
    the others), table rules by one ``─``, the version by ``<version>``, the memory
    this machine has free by ``<mem>``; trailing blank lines dropped."""
    out: list[str] = []
    timing_from_end: list[int] = []
    for i, raw in enumerate(lines):
        line = raw.rstrip()
        if line and set(line.strip()) == {"─"}:
            header = _cells(lines[i - 1]) if i else []
            timing_from_end = [k - len(header) for k, h in enumerate(header) if h in TIMING_HEADERS]
            out.append("─")
            continue
        if not line.strip():
            timing_from_end = []
        elif timing_from_end:
            cells = _cells(line)
            for k in timing_from_end:
                if len(cells) >= -k:
                    cells[k] = "<t>"
            line = "  ".join(cells)
        line = re.sub(r"\b\d+(?:\.\d+)? s\b", "<t> s", line)
        line = re.sub(r'^(\s*"(?:%s)": )[0-9.e-]+' % "|".join(TIMING_KEYS), r"\1<t>", line)
        line = re.sub(r"\d+(?:\.\d+)? GB is available", "<mem> GB is available", line)
        line = re.sub(r'(rkcheck"?:? "?)\d+\.\d+\.\d+', r"\1<version>", line)
        out.append(re.sub(r"(?<=\S) {2,}", "  ", line))
    while out and not out[-1]:  # a fence cannot end in blank lines; rich's reports do
        out.pop()
    return out


def matches(expected: list[str], actual: list[str]) -> bool:
    """Line-by-line equality, ``...`` matching any run of lines (backtracking)."""
    if not expected:
        return not actual
    if expected[0].strip() == "...":
        return any(matches(expected[1:], actual[k:]) for k in range(len(actual) + 1))
    return bool(actual) and actual[0] == expected[0] and matches(expected[1:], actual[1:])


def run(command: str) -> list[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("COLUMNS", "LINES", "FORCE_COLOR")}
    env["NO_COLOR"] = "1"
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    proc = subprocess.run(["bash", "-c", command], cwd=REPO, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, stdin=subprocess.DEVNULL, timeout=120)
    return proc.stdout.splitlines()


def test_the_docs_have_transcripts():
    assert len(ALL) >= 20
    assert {t.page.name for t in ALL} >= {"README.md", "verify.md", "scan.md"}


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_no_transcript_hides_from_the_test(page):
    # a block with a prompt anywhere but on its first line would not be found above
    for lineno, body in fenced_blocks(page.read_text(encoding="utf-8")):
        if any(line.startswith("$ ") for line in body):
            assert body[0].startswith("$ "), f"{page.name}:{lineno}: a transcript starts with its first command"


@pytest.mark.parametrize("transcript", ALL, ids=lambda t: t.name)
def test_transcript_is_the_real_output(transcript):
    for command in transcript.commands:
        assert re.match(r"(rkcheck|cat) ", command.line), f"{transcript.name}: only rkcheck and cat run here"
        actual = normalise(run(command.line))
        expected = normalise(list(command.expected))
        assert matches(expected, actual), (
            f"{transcript.name}: `$ {command.line}` printed\n" + "\n".join(actual))


@pytest.mark.parametrize("text, ok", [
    (["a", "...", "d"], True),
    (["a", "...", "x"], False),
    (["...", "c", "d"], True),
    (["a", "b"], False),
])
def test_ellipsis_matches_runs_of_lines(text, ok):
    # the matcher itself, on a fixed output: an ellipsis may swallow lines, not change them
    assert matches(text, ["a", "b", "c", "d"]) is ok


def test_normalise_keeps_everything_but_timings():
    table = ["", " file    time", " ──────────", " a.toml  0.10", " b.toml  12.5", "2 files; 0.4 s"]
    other = ["", " file    time", " ──────────", " a.toml  3.20", " b.toml  0.01", "2 files; 11 s"]
    assert normalise(table) == normalise(other)
    assert normalise([" a.toml  0.10 x"]) != normalise([" a.toml  0.11 x"])  # no header: not a timing
