"""Many files at once: ``scan`` (a worker pool with one outcome per file, in a fixed
order, interrupt-safe), ``catalog`` (one row per file and degree), and ``executors``:
where a batch of independent jobs runs (this process, local processes or a Dask
cluster), behind one interface that sweeps can use as well.

Takes: file lists and options.  Gives: outcomes and catalogue rows as plain data.

May import: :mod:`rkcheck.io`, :mod:`rkcheck.energy` and every stage below it,
:mod:`rkcheck.options`, :mod:`rkcheck.errors`.
"""
