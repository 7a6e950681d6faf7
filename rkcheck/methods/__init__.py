"""Runge–Kutta methods as data: the tableau, quadrature rules and method families.

Takes: entries (from :mod:`rkcheck.numbers`) or family parameters.  Gives:
:class:`~rkcheck.methods.tableau.Tableau` objects (no file I/O, no B-series).

May import: :mod:`rkcheck.numbers`, :mod:`rkcheck.errors`.
"""
