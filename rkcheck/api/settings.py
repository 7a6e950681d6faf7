"""What the project and the machine allow a run: ``[tool.rkcheck]`` of the nearest
``pyproject.toml``, the memory available, and the resource guard.

These are the helpers the public functions (and the CLI, for ``verify``) use so that
every command reads the project's settings and refuses oversized work the same way.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

from rkcheck.io.config import Config as ProjectConfig

if TYPE_CHECKING:
    from rkcheck.energy.budget import Budget


def project_config() -> ProjectConfig:
    """``[tool.rkcheck]`` of the nearest ``pyproject.toml`` above the working directory
    (empty when there is none); a bad table raises :class:`~rkcheck.errors.UserError`
    naming the file and the key (docs/commands/scan.md, "Configuration")."""
    from rkcheck.io.config import load_config

    return load_config()


def budget(max_conditions: int | None = None, announce: Callable[[str], None] | None = None) -> "Budget":
    """The resource budget of a check on this machine: the memory available to this
    process (cgroup limits included), an explicit limit on the number of conditions
    (``--max-conditions``; it replaces the memory test), and where to say the estimate of
    a check longer than 5 s (``announce(text)``; None: say nothing)."""
    from rkcheck.energy.budget import Budget
    from rkcheck.io.machine import available_memory

    return Budget(available_memory(), max_conditions, announce)


def guard(order: int, degree: int | None) -> None:
    """Refuse (:class:`~rkcheck.energy.budget.ResourceError`, the CLI's one line) an order
    whose condition tables would not fit in the memory available: the guard of the
    commands that build the tables without a budget of their own (bench, perturb,
    catalog)."""
    from rkcheck.energy.budget import check_budget, estimate

    check_budget(estimate(order, degree, "exact"), budget(), order)


__all__ = ["ProjectConfig", "budget", "guard", "project_config"]
