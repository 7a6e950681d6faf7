"""User-facing errors.

A :class:`UserError` is a problem with what the user gave rkcheck (a file, an entry,
an option).  The CLI prints it as one line ``FILE: PLACE: message`` and exits with
code 2; it never shows a traceback.  Anything else that escapes is a bug.
"""

from __future__ import annotations


class UserError(Exception):
    """An error in the user's input, reported as one line and exit code 2.

    ``place`` says where inside the file (``A[2][3]``, ``line 4``); ``source`` names
    the file.  Both are optional and are filled in by the layer that knows them: the
    expression parser knows the column, the loader knows the entry and the file.
    """

    def __init__(self, message: str, place: str | None = None, source: str | None = None):
        super().__init__(message)
        self.message = message
        self.place = place
        self.source = source

    def located(self, place: str | None = None, source: str | None = None) -> "UserError":
        """Return a copy with the place prefixed (outer places come first) and the source set."""
        if place and self.place:
            new_place = f"{place}: {self.place}"
        else:
            new_place = place or self.place
        return UserError(self.message, new_place, source or self.source)

    def __str__(self) -> str:
        parts = [p for p in (self.source, self.place, self.message) if p]
        return ": ".join(parts)
