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


def test_what_the_child_prints_goes_to_standard_error(capfd):
    # a C library's last words (FLINT's "Unable to allocate memory" as it aborts) are
    # written to file descriptor 1: never into the parent's report on standard output
    with pytest.raises(MemoryError):
        call_within(30, lambda: (os.write(1, b"last words\n"), os._exit(134)))  # as abort() ends, without a core file
    out, err = capfd.readouterr()
    assert "last words" not in out and "last words" in err


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


def _fields(entries, constants=None):
    """``field_of`` in this process and in a child, with the calls to the child counted."""
    from rkcheck.numbers import field_builder
    from rkcheck.numbers import grammar as ex

    nodes = [ex.parse(e) for e in entries]
    defs = {k: ex.parse(v) for k, v in (constants or {}).items()}
    forks = []
    original = field_builder.call_within

    def counted(*args):
        forks.append(args)
        return original(*args)

    field_builder.call_within = counted
    try:
        found = field_builder.field_of(nodes, defs)
    finally:
        field_builder.call_within = original
    alone = field_builder._field_of(nodes, defs, field_builder.MAX_FIELD_DEGREE)  # the child's work, here
    assert found.field.degree == alone.field.degree
    assert [v.enclosure(100) for v in found.values] == [v.enclosure(100) for v in alone.values]
    return len(forks)


def test_small_square_roots_need_no_child():
    """A few square roots of small rationals are built here (the same field and values
    as the child's); nested roots, ``root(p, k)``, large radicands and many roots keep
    their time limit in a child."""
    assert _fields(["sqrt(3)/6", "1/2 + sqrt(3)", "sqrt(12)"]) == 0
    assert _fields(["sqrt(a) + sqrt(5)"], {"a": "2/3"}) == 0
    assert _fields(["sqrt(2) + sqrt(3) + sqrt(5) + sqrt(7)"]) == 1
    assert _fields(["sqrt(sqrt(2))"]) == 1
    assert _fields(["sqrt(a)"], {"a": "sqrt(2)"}) == 1
    assert _fields(["sqrt(3 + 2^70)"]) == 1
    assert _fields(["root(x^3 - 2, 1)"]) == 1
