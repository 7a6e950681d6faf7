"""The error hierarchy of the public API (re-exported from :mod:`rkcheck.errors`).

``RkcheckError`` ⊃ ``UserError`` (alias ``InputError``) ⊃ ``TableauError``,
``OptionError``, ``UnknownMethodError``, ``ResourceError`` (a check that would not
fit in the memory available); ``str(err)`` is the CLI's one-line message.
``RkcheckWarning`` (a ``UserWarning``) is what the API warns with, e.g. when it reads floats.
"""

from rkcheck.errors import (
    OptionError,
    ResourceError,
    RkcheckError,
    RkcheckWarning,
    TableauError,
    UnknownMethodError,
    UserError,
)

InputError = UserError

__all__ = ["InputError", "OptionError", "ResourceError", "RkcheckError", "RkcheckWarning", "TableauError", "UnknownMethodError",
           "UserError"]
