"""Text that came from a file, made safe to print on one line.

A key or a method name may hold control characters (a newline, an ANSI escape that clears
the screen or fakes an "OK" line) or, in JSON, a lone surrogate (``"\\ud800"``) that no
terminal encoding accepts.  Everything rkcheck prints that came from a file goes through
:func:`printable` first (defined with the errors, whose one-line messages use it too).
"""

from __future__ import annotations

from rkcheck.errors import printable as printable

__all__ = ["printable"]
