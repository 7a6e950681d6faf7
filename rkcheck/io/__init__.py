"""Files in and out: tableau files → :class:`~rkcheck.methods.tableau.Tableau`, the
project configuration (``[tool.rkcheck]``), finding tableau files in folders, and
writing tableaux as files.

Takes: paths and text.  Gives: tableaux, configuration, file lists, file text.  The only
stage that touches the file system for tableaux.

May import: :mod:`rkcheck.methods`, :mod:`rkcheck.numbers`, :mod:`rkcheck.options`,
:mod:`rkcheck.errors`.
"""
