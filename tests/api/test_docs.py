"""docs/api.md never goes stale: every ``>>>`` example on the page is run (doctest), in
order, in one namespace, from a directory outside the clone."""

from __future__ import annotations

import doctest
import os

import pytest
from support.paths import REPO

PAGE = REPO / "docs" / "api.md"


@pytest.mark.parametrize("page, minimum", [(PAGE, 30), (REPO / "README.md", 5)], ids=["api.md", "README.md"])
def test_api_page_examples_run(tmp_path, page, minimum):
    # a code fence ends an example's expected output, as a blank line does
    text = "\n".join("" if line.startswith("```") else line for line in page.read_text(encoding="utf-8").splitlines())
    test = doctest.DocTestParser().get_doctest(text, {}, page.name, str(page), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    here = os.getcwd()
    os.chdir(tmp_path)  # @name must not depend on the working directory
    try:
        runner.run(test)
    finally:
        os.chdir(here)
    results = runner.summarize(verbose=False)
    assert results.attempted >= minimum
    assert results.failed == 0


def test_the_page_has_no_untested_python_blocks():
    text = PAGE.read_text(encoding="utf-8")
    assert "```python" not in text, "use ```pycon blocks with >>> so that the test runs them"
