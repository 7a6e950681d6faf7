"""Evaluation of B-series quantities over a number backend.

Takes: a tableau and tree/condition tables.  Gives: certified enclosures
(:class:`~rkcheck.numbers.enclosure.Enclosure`) of elementary weights and of every
energy condition, in one of several number contexts (exact rationals, certified balls,
the float64 screen), as mpmath does with its ``mp``/``iv``/``fp`` contexts.  It does not
judge: turning an enclosure into a verdict is :mod:`rkcheck.energy`'s job.

May import: :mod:`rkcheck.trees.rooted`, :mod:`rkcheck.methods`, :mod:`rkcheck.numbers`,
:mod:`rkcheck.errors`.
"""
