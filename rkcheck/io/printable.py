"""Text that came from a file, made safe to print on one line.

A key or a method name may hold control characters (a newline, an ANSI escape that clears
the screen or fakes an "OK" line) or, in JSON, a lone surrogate (``"\\ud800"``) that no
terminal encoding accepts.  Everything rkcheck prints that came from a file goes through
:func:`printable` first.
"""

from __future__ import annotations


def printable(text: str) -> str:
    """``text`` with every non-printable character (controls, line breaks, lone
    surrogates, format characters) written as its Python escape (``\\n``, ``\\x1b``,
    ``\\ud800``); printable text, including non-ASCII letters, is unchanged."""
    if text.isprintable():
        return text
    return "".join(ch if ch.isprintable() else ascii(ch)[1:-1] for ch in text)
