"""What the tableau itself says, by algebra on its s×s entries: its properties as a method.

Takes: a tableau (its entries as exact numbers or certified intervals, through
:mod:`rkcheck.evaluation.values`).  Gives, each as a three-state verdict
(:mod:`rkcheck.verdicts`): the irreducible form (stage reduction), the stability function
and the certificate it gives for quadratic Hamiltonians, symplecticity and symmetry, the
quadrature and classical orders, and the two certificates of energy preservation at
every order that need no trees (the tableau is the AVF method; the line-integral
identity of HBVMs) — for a tableau entry by entry (:mod:`.tableau`) or for a family from
its node form (:mod:`.from_nodes`).  The energy conditions themselves, one per free
tree, are :mod:`rkcheck.energy`'s.  No I/O.

May import: :mod:`rkcheck.verdicts`, :mod:`rkcheck.evaluation`, :mod:`rkcheck.trees`,
:mod:`rkcheck.methods`, :mod:`rkcheck.numbers`, :mod:`rkcheck.errors`.
"""
