"""The declared interfaces of the number contexts.

One algorithm (:mod:`rkcheck.evaluation.algorithm`) runs over several contexts — exact
residues modulo primes (:mod:`~rkcheck.evaluation.modular`), certified balls
(:mod:`~rkcheck.evaluation.balls`, :mod:`~rkcheck.evaluation.limbs`) and the float
screen — as mpmath runs one algorithm over ``mp``, ``iv`` and ``fp``.  Each context owns
its precision and storage; the algorithm sees only the calls declared here, so mypy checks
every context against them where it is passed in.

Values a context stores are opaque to the algorithm (numpy arrays of residues, of digits,
of floats): they are typed ``Any`` on purpose, the one thing a context may choose freely.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Iterator, Protocol

if TYPE_CHECKING:
    import numpy as np

    from rkcheck.numbers.enclosure import Enclosure
    from rkcheck.trees.terms import OrderTerms


class WeightContext(Protocol):
    """Arithmetic on whole arrays of elementary weights (definitions §2).

    ``vectors``/``scalars`` allocate storage for n values (vectors have s components);
    ``ones``/``one`` are the weights of the single-vertex tree; ``take`` gathers rows,
    ``put`` stores a block at row ``lo``; ``mul`` multiplies elementwise; ``matvec``
    and ``dot`` are ``x Aᵀ`` and ``x b`` row by row."""

    def vectors(self, n: int, s: int) -> Any: ...
    def scalars(self, n: int) -> Any: ...
    def ones(self, k: int, s: int) -> Any: ...
    def one(self, k: int) -> Any: ...
    def take(self, x: Any, idx: np.ndarray) -> Any: ...
    def put(self, store: Any, lo: int, x: Any) -> None: ...
    def mul(self, x: Any, y: Any) -> Any: ...
    def matvec(self, x: Any) -> Any: ...
    def dot(self, x: Any) -> Any: ...


class NumberContext(WeightContext, Protocol):
    """Weights and the energy conditions' sums: ``sums``, ``add_terms`` and
    ``finish_sums`` accumulate ``Σ ±w/σ`` over the terms of one order into its condition
    sums and report them in the context's own terms."""

    def sums(self, k: int, n: int) -> Any: ...
    def add_terms(self, acc: Any, w_terms: Any, terms: OrderTerms, n: int, i0: int, i1: int) -> None: ...
    def finish_sums(self, acc: Any, k: int, n: int) -> Any: ...


class EnclosingContext(NumberContext, Protocol):
    """A context whose values can be read back as certified enclosures (balls, floats):
    what the classical order conditions need."""

    def enclosures(self, x: Any) -> list[Enclosure]: ...


class SubsetContext(NumberContext, Protocol):
    """A context that also sums the selected conditions of a
    :class:`~rkcheck.evaluation.subset.Subset`, whose terms come in any order: ``part``
    is one order's selected terms (their coefficient indices, their conditions
    renumbered among the selected); ``add_selected`` bins its terms ``t0 … t1−1``."""

    def selected_sums(self, part: Any) -> Any: ...
    def add_selected(self, acc: Any, w_terms: Any, part: Any, t0: int, t1: int) -> None: ...
    def finish_selected(self, acc: Any, part: Any) -> Any: ...


class BoundedSums(Protocol):
    """The condition sums of one order from an inexact context: each an enclosure,
    which ones certainly exclude zero, and a bound on the magnitude of the others."""

    def __len__(self) -> int: ...
    def enclosure(self, k: int) -> Enclosure: ...
    def excludes_zero(self) -> np.ndarray: ...
    def magnitude_bound(self) -> np.ndarray: ...


class ExactSums(Protocol):
    """The condition sums of one order decided exactly: which are zero, and each value
    (a ``Fraction`` or a number-field element) on demand."""

    def __len__(self) -> int: ...
    def is_zero(self) -> np.ndarray: ...
    def value(self, k: int) -> Any: ...


class PassRunner(Protocol):
    """Runs the channel passes of an exact evaluation somewhere else (the workers of a
    cluster): ``jobs`` are ``(channels, orders)`` — the ``(p, root)`` pairs of one pass
    and the numbers of vertices it is for — and every job's
    ``scaled.residues_at(listing, channels, orders)`` is yielded once as ``(index, sums)``,
    in any order."""

    def __call__(self, scaled: Any, listing: Any,
                 jobs: list[tuple[list[tuple[int, int]], list[int]]]) -> Iterator[tuple[int, dict[int, np.ndarray]]]: ...
