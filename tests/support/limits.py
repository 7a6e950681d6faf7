"""Run a Python program in a child process under hard resource limits.

A resource bound ("refused before any work", "finishes within 500 MB and 5 s") is
checked by letting the kernel enforce it on a child, not by measuring this process:
pytest's own peak memory and the wall clock depend on the other tests and on the load
of the machine, CPU seconds and a child's address space do not.  A child over its CPU
limit is killed by SIGXCPU (a negative return code); over its memory limit, an
allocation fails (``MemoryError``, which rkcheck reports as "out of memory").
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from dataclasses import dataclass

MB = 2**20

#: numerical libraries reserve address space per thread; one thread keeps the child's
#: footprint independent of the number of cores of the machine
ONE_THREAD = {name: "1" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}


@dataclass
class LimitedRun:
    code: int
    out: str
    err: str

    @property
    def killed(self) -> bool:
        """Ended by a signal (SIGXCPU: over the CPU limit)."""
        return self.code < 0


def run_limited(argv: list[str], *, memory_mb: int, cpu_seconds: int, stdin: str | None = None,
                cwd: str | None = None) -> LimitedRun:
    """``python ARGV`` with its address space capped at ``memory_mb`` and its CPU time at
    ``cpu_seconds`` (``resource.setrlimit`` in the child, before it starts)."""

    def limit() -> None:  # runs in the child between fork and exec
        resource.setrlimit(resource.RLIMIT_AS, (memory_mb * MB, memory_mb * MB))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds + 1))

    env = dict(os.environ, NO_COLOR="1", **ONE_THREAD)
    env.pop("RKCHECK_DEBUG", None)
    # the wall-clock timeout only turns a child stuck without using CPU into a failure
    proc = subprocess.run([sys.executable, *argv], input=stdin, capture_output=True, text=True, cwd=cwd, env=env,
                          preexec_fn=limit, timeout=300)
    return LimitedRun(proc.returncode, proc.stdout, proc.stderr)
