"""The number model (docs/verdicts.md; docs/definitions.md §5).

Takes: the text of a tableau entry.  Gives: what the entry *is* — an exact rational,
an enclosure with rational end points, or (with the proof-grade work) an element of a
number field — and the certified-number type :class:`~rkcheck.numbers.enclosure.Enclosure`
that every backend returns, plus exact decimal formatting and the polynomials everything
else computes with (:mod:`~rkcheck.numbers.polynomials`: arithmetic over any field, FLINT
over Q, certified real roots).

May import: :mod:`rkcheck.errors` only.  Every other stage builds on it.
"""
