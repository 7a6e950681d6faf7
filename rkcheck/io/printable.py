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
    return "".join(ch if ch.isprintable() else _escape(ch) for ch in text)


def _escape(ch: str) -> str:
    # U+DC80..U+DCFF is how Python keeps a byte that is not UTF-8 in a file name or an
    # argument (surrogateescape): show the byte itself, as ls and git do
    if "\udc80" <= ch <= "\udcff":
        return f"\\x{ord(ch) - 0xDC00:02x}"
    return ascii(ch)[1:-1]
