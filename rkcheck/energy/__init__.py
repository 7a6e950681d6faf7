"""The energy conditions judged: what the evaluated numbers say about energy preservation.

Takes: a tableau (or a family, or a continuous-stage kernel) and check options.  Gives:
the three-state verdict of every energy condition, one per free tree, the energy order,
Theorem 1, the claims of ``[expect]`` (with the method's properties from
:mod:`rkcheck.properties`), the energy error constants, the double-bush map of the seed,
a family's conditions and their solutions, and condition explanations — all as plain
data that the reports render.  No I/O.

May import: :mod:`rkcheck.properties`, :mod:`rkcheck.verdicts`, :mod:`rkcheck.evaluation`,
:mod:`rkcheck.trees`, :mod:`rkcheck.methods`, :mod:`rkcheck.numbers`, :mod:`rkcheck.options`,
:mod:`rkcheck.errors`.
"""
