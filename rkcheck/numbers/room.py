"""Stopping a computation on exact polynomials before it runs out of memory.

The polynomials of a family's conditions grow in ways no estimate made beforehand
follows (their coefficients, rationals of hundreds of digits, take more than their terms
do), and FLINT, asked for memory the machine no longer has, aborts the process with a
line on standard output and no way to catch it.  So a long computation looks at the
memory left between its steps, and stops with a :class:`~rkcheck.errors.ResourceError`
while there is still room to say so: when what is left falls below what the largest step
so far took, several times over (:data:`STEP_MARGIN`), or below :data:`MIN_ROOM`.

How the memory left is read is the caller's business (this is the core: no I/O):
:func:`room_read_by` installs a reader for the computations run inside it; without one
nothing is watched.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Callable, Iterable, Iterator, TypeVar

from rkcheck.errors import ResourceError
from rkcheck.numbers.formatting import human_bytes

#: a step of a watched computation is not started with less than this left
MIN_ROOM = 48 * 2**20
#: ... or with less than this many times what the largest step so far took: the next may
#: be larger (the first steps of an order, a product whose result is not kept yet)
STEP_MARGIN = 3
#: the memory left is read at most this often (seconds; reading it costs about 0.2 ms)
READ_INTERVAL = 0.02

T = TypeVar("T")

_reader: ContextVar[Callable[[], int | None] | None] = ContextVar("rkcheck_room_reader", default=None)


@contextmanager
def room_read_by(read: Callable[[], int | None] | None) -> Iterator[None]:
    """Within the block, watched computations call ``read()`` for the bytes this process
    can still use (None: unknown, not watched)."""
    token = _reader.set(read)
    try:
        yield
    finally:
        _reader.reset(token)


class RoomWatch:
    """The memory left, read between the steps of one computation (``what``: how its
    refusal begins, ``remedy``: what it tells the user to try)."""

    def __init__(self, what: str, remedy: str):
        self.what, self.remedy = what, remedy
        self.read = _reader.get()
        self.left: int | None = None  # the memory left at the last reading
        self.largest = 0  # the most taken between two readings
        self.read_at = -READ_INTERVAL

    def step(self) -> None:
        """Refuse (:class:`ResourceError`) to go on when the memory left would not hold
        another step like the largest so far."""
        if self.read is None:
            return
        now = time.monotonic()
        if now - self.read_at < READ_INTERVAL:
            return
        self.read_at = now
        left = self.read()
        if left is None:
            return
        if self.left is not None:
            self.largest = max(self.largest, self.left - left)
        self.left = left
        need = max(MIN_ROOM, STEP_MARGIN * self.largest)
        if left < need:
            raise ResourceError(f"{self.what} need more memory than is available: {human_bytes(left)} left, less "
                                f"than the {human_bytes(need)} kept for their next step (MIN_ROOM, STEP_MARGIN); "
                                f"{self.remedy}")


def each_watched(items: Iterable[T], what: str, remedy: str) -> Iterator[T]:
    """``items``, the memory left read before each (a loop forming large values one by
    one: :meth:`RoomWatch.step`)."""
    room = RoomWatch(what, remedy)
    for item in items:
        room.step()
        yield item
