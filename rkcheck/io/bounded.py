"""Reading files with a size limit: a tableau file, standard input or a pyproject.toml
can be a device (/dev/zero) or a pipe that never ends, whose size cannot be asked first."""

from __future__ import annotations

from rkcheck.errors import OptionError, UserError
from rkcheck.io.printable import printable

#: The size limit of one tableau file (and of standard input, and of pyproject.toml);
#: RKCHECK_MAX_FILE_BYTES changes it.  Shipped tableaux are under 10 kB.
MAX_FILE_BYTES = 16 * 1024 * 1024

#: bytes asked for by one read of :func:`bounded_read`
_READ_PART = 1 << 20

#: how long a named pipe (a FIFO, or bash's ``<(…)``) may stay without a writer or data
#: before it is refused: opening one that no process writes to would wait for ever
FIFO_WAIT_SECONDS = 10


def max_file_bytes() -> int:
    """The size limit of one tableau file or of standard input: MAX_FILE_BYTES, or the
    environment's RKCHECK_MAX_FILE_BYTES (a positive integer number of bytes)."""
    import os

    value = os.environ.get("RKCHECK_MAX_FILE_BYTES", "").strip().replace("_", "")
    if not value:
        return MAX_FILE_BYTES
    if not (value.isascii() and value.isdigit()) or int(value) < 1:
        raise OptionError(f"RKCHECK_MAX_FILE_BYTES: expected a positive number of bytes, got {printable(value)!r}")
    return int(value)


def bounded_read(stream, limit: int, source: str) -> bytes:
    """At most ``limit`` bytes of a binary stream, or a UserError naming the limit (a
    device such as /dev/zero, or a pipe, has no size to ask for beforehand)."""
    # in parts: a read asks for its whole size up front, which a large limit cannot
    parts, size = [], 0
    while size <= limit:
        part = stream.read(min(_READ_PART, limit + 1 - size))
        if not part:
            break
        parts.append(part)
        size += len(part)
    data = b"".join(parts)
    if len(data) > limit:
        raise UserError(f"file too large: more than {limit:,} bytes (the limit MAX_FILE_BYTES; set "
                        "RKCHECK_MAX_FILE_BYTES to change it)", source=source)
    return data


def read_fifo(path: str, limit: int) -> bytes:
    """The bytes of a named pipe, up to ``limit``: opened without waiting for a writer,
    then refused (a UserError naming :data:`FIFO_WAIT_SECONDS`) when nothing arrives in
    that time; once a writer has written, read to its end like a file."""
    import os
    import select

    if not hasattr(select, "poll"):  # no poll (Windows has no FIFOs either): a plain read
        with open(path, "rb") as fh:
            return bounded_read(fh, limit, path)
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        waiting = select.poll()
        waiting.register(fd, select.POLLIN)
        if not waiting.poll(FIFO_WAIT_SECONDS * 1000):
            raise UserError(f"a named pipe that nothing was written to within {FIFO_WAIT_SECONDS} s "
                            "(FIFO_WAIT_SECONDS)", source=path)
        os.set_blocking(fd, True)
        fh = os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
    with fh:
        return bounded_read(fh, limit, path)
