"""Reading files with a size limit: a tableau file, standard input or a pyproject.toml
can be a device (/dev/zero) or a pipe that never ends, whose size cannot be asked first."""

from __future__ import annotations

from rkcheck.errors import OptionError, UserError
from rkcheck.io.printable import printable

#: The size limit of one tableau file (and of standard input, and of pyproject.toml);
#: RKCHECK_MAX_FILE_BYTES changes it.  Shipped tableaux are under 10 kB.
MAX_FILE_BYTES = 16 * 1024 * 1024


def max_file_bytes() -> int:
    """The size limit of one tableau file or of standard input: MAX_FILE_BYTES, or the
    environment's RKCHECK_MAX_FILE_BYTES (a positive integer number of bytes)."""
    import os

    value = os.environ.get("RKCHECK_MAX_FILE_BYTES", "").strip().replace("_", "")
    if not value:
        return MAX_FILE_BYTES
    if not value.isdigit() or int(value) < 1:
        raise OptionError(f"RKCHECK_MAX_FILE_BYTES: expected a positive number of bytes, got {printable(value)!r}")
    return int(value)


def bounded_read(stream, limit: int, source: str) -> bytes:
    """At most ``limit`` bytes of a binary stream, or a UserError naming the limit (a
    device such as /dev/zero, or a pipe, has no size to ask for beforehand)."""
    data = stream.read(limit + 1)
    if len(data) > limit:
        raise UserError(f"file too large: more than {limit:,} bytes (the limit MAX_FILE_BYTES; set "
                        "RKCHECK_MAX_FILE_BYTES to change it)", source=source)
    return data
