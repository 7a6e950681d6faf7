"""What this machine offers a check: the memory available to this process.

The smallest of the kernel's ``MemAvailable`` (``/proc/meminfo``), the room left under
a cgroup memory limit (v2 ``memory.max`` − ``memory.current``, or v1
``memory.limit_in_bytes`` − ``memory.usage_in_bytes``) — a container's limit is what
the kernel enforces, whatever the host has free — and the room left under this
process's own address-space limit (``ulimit -v``, ``prlimit --as``: ``RLIMIT_AS`` less
the ``VmSize`` already mapped).  None when nothing can be read (then no memory-based
refusal is made).
"""

from __future__ import annotations

from pathlib import Path


def _read_int(path: str) -> int | None:
    try:
        text = Path(path).read_text().strip()
    except OSError:
        return None
    if not text or text == "max":
        return None
    try:
        return int(text.split()[0])
    except ValueError:
        return None


def _meminfo_available() -> int | None:
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


def _cgroup_room() -> int | None:
    limit, used = _read_int("/sys/fs/cgroup/memory.max"), _read_int("/sys/fs/cgroup/memory.current")
    if limit is None:
        limit, used = (_read_int("/sys/fs/cgroup/memory/memory.limit_in_bytes"),
                       _read_int("/sys/fs/cgroup/memory/memory.usage_in_bytes"))
        if limit is not None and limit >= 1 << 60:  # v1 writes "no limit" as a huge number
            limit = None
    if limit is None:
        return None
    return max(0, limit - (used or 0))


def _address_space_room() -> int | None:
    try:
        import resource
    except ImportError:  # Windows
        return None
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY:
        return None
    mapped = None
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmSize:"):
                mapped = int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return max(0, soft - (mapped or 0))


def available_memory() -> int | None:
    """Bytes this process can still use, or None when unknown."""
    values = [v for v in (_meminfo_available(), _cgroup_room(), _address_space_room()) if v is not None]
    return min(values) if values else None
