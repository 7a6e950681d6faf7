"""Studies of the check itself: accuracy against speed over the backends (``bench``) and
perturbation sweeps (``perturb``).

Takes: tableaux and study parameters.  Gives: rows of measurements as plain data.

May import: :mod:`rkcheck.energy`, :mod:`rkcheck.evaluation`, :mod:`rkcheck.trees.rooted`,
:mod:`rkcheck.methods`, :mod:`rkcheck.numbers`, :mod:`rkcheck.errors`.
"""
