"""Text from a tableau file (its name, an error) is literal text in the catalogue: no
emphasis, link, HTML or extra table cell can come from a file."""

from __future__ import annotations

import markdown
import pytest
from support.clirun import run_cli

NAME = "*bold* _it_ [link](http://example.com) <b>html</b> | cell ~~gone~~ &amp; `code`"


@pytest.mark.parametrize("stem", ["plain", "a`b|c"])
def test_a_name_with_markup_stays_text_in_the_catalogue(tmp_path, capsys, stem):
    path = tmp_path / f"{stem}.toml"
    path.write_text(f'[method]\nname = "{NAME}"\n[tableau]\nA = [["1/2"]]\nb = ["1"]\n', encoding="utf-8")
    out = tmp_path / "cat.md"
    r = run_cli(capsys, "catalog", str(path), "-o", str(out))
    assert r.code == 0, r.err
    text = out.read_text(encoding="utf-8")
    row = next(line for line in text.splitlines() if NAME[:3].replace("*", "\\*") in line)
    html = markdown.markdown(text, extensions=["tables"])
    for tag in ("<em>", "<strong>", "<a ", "<b>", "<del>", "<s>"):
        assert tag not in html, tag
    # the row keeps as many cells as the header: the name's "|" is escaped
    header = next(line for line in text.splitlines() if line.startswith("| file |"))
    assert row.replace("\\|", "").count("|") == header.count("|")
    assert "&lt;b&gt;html&lt;/b&gt;" in html and "&amp;amp;" in html
