"""rkcheck's version: one place, importable from every stage without importing the package."""

__version__ = "0.2.0"
