"""The error hierarchy of the public API (re-exported from :mod:`rkcheck.errors`).

``RkcheckError`` ⊃ ``UserError`` (alias ``InputError``) ⊃ ``TableauError``,
``OptionError``, ``UnknownMethodError``; ``str(err)`` is the CLI's one-line message.
"""

from rkcheck.errors import (
    OptionError,
    RkcheckError,
    TableauError,
    UnknownMethodError,
    UserError,
)

InputError = UserError

__all__ = ["InputError", "OptionError", "RkcheckError", "TableauError", "UnknownMethodError", "UserError"]
