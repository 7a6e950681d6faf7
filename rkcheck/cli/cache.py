"""``cache info`` and ``cache clear``: the listing cache (condition listings kept between
runs in the user cache directory)."""

from __future__ import annotations

import click

from rkcheck.cli.common import exit_codes, output_options, settings


def _short(n: int) -> str:
    for unit, scale in (("GiB", 1024**3), ("MiB", 1024**2), ("KiB", 1024)):
        if n >= scale:
            return f"{n / scale:.1f} {unit}"
    return f"{n:,} bytes"


def _size(n: int) -> str:
    return f"{_short(n)} ({n:,} bytes)" if n >= 1024 else _short(n)


@click.group(epilog=exit_codes())
@output_options
def cache() -> None:
    """The listing cache: condition listings (which depend only on the order and the
    degree, never on the tableau) kept between runs, so that a check of a high order
    does not build them again.  Where: RKCHECK_CACHE_DIR, else the user cache directory
    (~/.cache/rkcheck, $XDG_CACHE_HOME/rkcheck, ~/Library/Caches/rkcheck on macOS,
    %LOCALAPPDATA%\\rkcheck\\Cache on Windows).  Bounded by RKCHECK_MAX_CACHE_BYTES
    (default 2 GiB; the least recently used files go first).  The checking commands
    take --no-cache (also RKCHECK_NO_CACHE=1)."""


@cache.command(epilog=exit_codes())
@output_options
def info() -> None:
    """Where the listing cache is, its files, their size, and the limit."""
    from rkcheck.api.settings import listing_cache

    state = listing_cache().info()
    click.echo(f"path   {state.path}")
    click.echo(f"files  {state.files}")
    click.echo(f"size   {_size(state.bytes)}")
    import os

    source = ("set by RKCHECK_MAX_CACHE_BYTES" if os.environ.get("RKCHECK_MAX_CACHE_BYTES")
              else "the default; RKCHECK_MAX_CACHE_BYTES changes it")
    click.echo(f"limit  {_size(state.limit)}, {source}")
    blocking = _not_a_directory(str(state.path))
    if blocking is not None:
        click.echo(f"{blocking} is not a directory: no listing can be saved or read at {state.path} "
                   "(RKCHECK_CACHE_DIR names the cache's directory)")
    if state.disabled:
        click.echo("RKCHECK_NO_CACHE is set: the checking commands neither read nor save listings")


@cache.command(epilog=exit_codes())
@output_options
def clear() -> None:
    """Remove the listing files (nothing else in the cache's directory)."""
    from rkcheck.api.settings import listing_cache

    store = listing_cache()
    before = store.info()
    removed = store.clear()
    if not settings().quiet:
        click.echo(f"removed {removed} listing file{'s' if removed != 1 else ''} ({_short(before.bytes)}) "
                   f"from {before.path}")


def _not_a_directory(path: str) -> str | None:
    """The path itself or the nearest of its folders that exists, when that is not a
    directory (the cache could never be made there); None otherwise."""
    import os

    current = os.path.abspath(path)
    while not os.path.exists(current):
        parent = os.path.dirname(current)
        if parent == current:
            return None
        current = parent
    return None if os.path.isdir(current) else current
