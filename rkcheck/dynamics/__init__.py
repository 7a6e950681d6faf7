"""Energy in practice: polynomial Hamiltonians and a Runge–Kutta integrator, to measure
what the algebraic verdicts predict (``rkcheck simulate``, ``workprec``).

Takes: tableaux and Hamiltonians.  Gives: trajectories, energy errors, fitted orders,
and their agreement with :mod:`rkcheck.energy`.

May import: :mod:`rkcheck.energy`, :mod:`rkcheck.methods`, :mod:`rkcheck.numbers`,
:mod:`rkcheck.errors`.
"""
