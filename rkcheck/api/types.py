"""Data types of the public API that live in the core stages, re-exported."""

from rkcheck.methods.tableau import Tableau
from rkcheck.options import CheckOptions

__all__ = ["CheckOptions", "Tableau"]
