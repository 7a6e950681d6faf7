"""call_within: a computation in a forked child, killed at its time limit."""

import os
import time

import pytest

from rkcheck.errors import UserError
from rkcheck.numbers import deadline
from rkcheck.numbers.deadline import Overrun, call_within

pytestmark = pytest.mark.skipif(not deadline.FORK, reason="no fork: computations run in-process")


def _slow(seconds):
    time.sleep(seconds)
    return "finished"


def _fails():
    raise UserError("cannot parse 'sqrt(3'", place="A[2][3]", source="t.toml")


def test_the_result_comes_back_from_the_child():
    big = list(range(200_000))  # more than a pipe's buffer: read while the child writes
    pid, value = call_within(30, lambda: (os.getpid(), big))
    assert pid != os.getpid() and value == big


def test_an_exception_comes_back_as_it_was():
    with pytest.raises(UserError) as info:
        call_within(30, _fails)
    assert str(info.value) == "t.toml: A[2][3]: cannot parse 'sqrt(3'"


def test_the_child_is_stopped_at_the_limit():
    # without the limit the call would return "finished" after a minute
    with pytest.raises(Overrun):
        call_within(0.3, _slow, 60)


def _deep(n):
    return _deep(n + 1)


def _fails_after_a_recursion():
    try:
        _deep(0)
    except RecursionError:
        raise UserError("nested too deeply") from None


def test_an_exception_comes_back_without_its_chain():
    # distributed installs tblib's pickling of tracebacks and chained exceptions: the
    # thousand frames of the RecursionError behind the error must not travel (pickling
    # them overflowed the stack, and the error came back as a RuntimeError)
    pickling_support = pytest.importorskip("tblib.pickling_support")
    pickling_support.install()
    with pytest.raises(UserError, match="nested too deeply"):
        call_within(30, _fails_after_a_recursion)
