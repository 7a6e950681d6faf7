"""What a library caller can get wrong ends in an RkcheckError subclass with the CLI's
one-line message, never in another exception."""

from __future__ import annotations

import pytest
from support.paths import TABLEAUX

import rkcheck


def test_scan_of_one_folder_given_as_a_string_scans_that_folder():
    folder = TABLEAUX / "explicit"
    one = rkcheck.scan(str(folder), order=2, jobs=1)
    listed = rkcheck.scan([str(folder)], order=2, jobs=1)
    assert [r.path for r in one.rows] == [r.path for r in listed.rows]
    assert len(one.rows) == len(list(folder.glob("*.toml")))


def test_scan_of_something_that_is_no_path_is_an_rkcheck_error():
    with pytest.raises(rkcheck.RkcheckError, match="expected a path or a list of paths"):
        rkcheck.scan([42])
