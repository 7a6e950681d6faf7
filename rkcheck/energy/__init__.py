"""Verdicts: what the evaluated numbers say about the method.

Takes: a tableau and check options.  Gives: the three-state verdict of every energy
condition, the energy, classical and quadrature orders, the AVF and line-integral
certificates, Theorem 1, the claims of ``[expect]``, the double-bush map of the seed,
and condition explanations — all as plain data that the reports render.  No I/O.

May import: :mod:`rkcheck.evaluation`, :mod:`rkcheck.trees.rooted`, :mod:`rkcheck.methods`,
:mod:`rkcheck.numbers`, :mod:`rkcheck.options`, :mod:`rkcheck.errors`.
"""
