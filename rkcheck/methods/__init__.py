"""Runge–Kutta methods as data: the tableau, quadrature rules and method families.

Takes: entries (from :mod:`rkcheck.numbers`) or family parameters.  Gives:
:class:`~rkcheck.methods.tableau.Tableau` objects and their ``[expect]`` claims as data
(no file I/O, no B-series).

May import: :mod:`rkcheck.numbers`, :mod:`rkcheck.options`, :mod:`rkcheck.errors`.
"""
