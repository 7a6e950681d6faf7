"""One order of a condition listing as plain named arrays, for a store that keeps it
between runs (the listing cache of :mod:`rkcheck.io.cache`), and back — checked.

The listing of the conditions with ``n`` vertices for degree ≤ m depends on nothing but
``(n, m)``: a record of it is the factors ``left``/``right`` of the rooted trees with
``n`` vertices (in id order) and the arrays of its :class:`~rkcheck.trees.terms.OrderTerms`.
This module does no I/O: a *store* (:class:`ListingStore`) does, and what it returns is
data from outside the process — whatever it claims, a record is accepted only when every
array has the expected type and length and every index lies in its range; otherwise the
order is built again.
"""

from __future__ import annotations

import math
import re
from typing import Any, Protocol

import numpy as np

from rkcheck.trees.terms import OrderTerms

#: What a record's arrays are: any change of the listing's id order, of the
#: classification or of these arrays must raise it (a stored record of another format is
#: then not read).
RECORD_FORMAT = 1

#: name -> dtype; the arrays of length ``terms`` (one per rooted tree) and ``conditions``
TERM_ARRAYS = {"left": np.int32, "right": np.int32, "condition": np.int32, "coefficient_index": np.int16}
CONDITION_ARRAYS = {"counts": np.int32, "rep_left": np.int32, "rep_right": np.int32, "tall": np.int32,
                    "rest": np.int32, "max_degree": np.int16}


class ListingStore(Protocol):
    """Where listings are kept between runs: ``load`` returns the arrays and metadata
    saved under ``key`` (None when there are none, or they are damaged); ``save`` keeps
    them (a store may decline: a cache is only an optimisation) and returns None, or,
    when it declines for a reason the user can change, one line saying so, which the
    check passes on as a warning.  Orders with fewer than ``min_terms`` terms are neither
    loaded nor saved (cheaper to build).

    ``into``: arrays that ``load`` may fill in place of allocating its own (by name, when
    type and length match) and then return as those arrays; whatever is returned, their
    contents are unspecified afterwards unless they are the ones returned."""

    min_terms: int

    def load(self, key: dict[str, Any],
             into: dict[str, np.ndarray] | None = None) -> tuple[dict[str, np.ndarray], dict[str, Any]] | None: ...

    def save(self, key: dict[str, Any], arrays: dict[str, np.ndarray], meta: dict[str, Any]) -> str | None: ...


def record_key(vertices: int, degree: int | None) -> dict[str, Any]:
    """What identifies the record of an order: its kind, format and parameters."""
    return {"kind": "condition-listing", "format": RECORD_FORMAT, "vertices": vertices, "degree": degree}


def to_record(left: np.ndarray, right: np.ndarray,
              terms: OrderTerms) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """The arrays and metadata of one order (``left``/``right``: its trees' factors)."""
    arrays = {"left": left, "right": right}
    condition, index = terms.block(0, terms.rows)  # the file keeps them apart
    arrays["condition"], arrays["coefficient_index"] = condition, index.astype(np.int16, copy=False)
    arrays.update({name: getattr(terms, name) for name in CONDITION_ARRAYS})
    # exact integers beyond int64 at high orders: kept as decimal strings
    meta = {"superfluous": int(terms.superfluous), "coefficients": [str(c) for c in terms.coefficients]}
    return arrays, meta


def from_record(vertices: int, first_id: int, terms: int, conditions: int, arrays: dict[str, np.ndarray],
                meta: dict[str, Any]) -> tuple[np.ndarray, np.ndarray, OrderTerms] | None:
    """``(left, right, terms)`` of the order with ``vertices`` vertices from a record, or
    None when the record is not exactly what such an order must be (its counts are
    known in advance: ``terms`` rooted trees, ``conditions`` conditions)."""
    coefficients = _coefficients(meta.get("coefficients"))
    superfluous = meta.get("superfluous")
    if coefficients is None or type(superfluous) is not int or superfluous < 0:
        return None
    expected = {**{k: (t, terms) for k, t in TERM_ARRAYS.items()},
                **{k: (t, conditions) for k, t in CONDITION_ARRAYS.items()}}
    if set(arrays) != set(expected):
        return None
    for name, (dtype, length) in expected.items():
        x = arrays[name]
        if not isinstance(x, np.ndarray) or x.dtype != np.dtype(dtype) or x.shape != (length,):
            return None
    a = arrays
    # the factors index trees with fewer vertices; a class index ``conditions`` is the
    # superfluous trees' bin; the designated-rooting data are ids or −1
    ok = (_within(a["left"], 0, first_id) and _within(a["right"], 0, first_id)
          and _within(a["condition"], 0, conditions + 1)
          and _within(a["coefficient_index"], 0, len(coefficients))
          and _within(a["rep_left"], 0, first_id) and _within(a["rep_right"], 0, first_id)
          and _within(a["tall"], -1, first_id) and _within(a["rest"], -1, first_id)
          and _within(a["max_degree"], 1, vertices) and _within(a["counts"], 1, terms + 1)
          and int(a["counts"].sum(dtype=np.int64)) <= terms
          and all(math.factorial(vertices - 1) % c == 0 for c in coefficients[::2]))
    # every class has exactly the terms it claims
    if not ok or not np.array_equal(_class_sizes(a["condition"], conditions + 1)[:conditions], a["counts"]):
        return None
    order = OrderTerms(
        vertices=vertices, first_id=first_id, left=None, right=None, condition=a["condition"],
        coefficient_index=a["coefficient_index"], coefficients=coefficients, counts=a["counts"],
        rep_left=a["rep_left"], rep_right=a["rep_right"], tall=a["tall"], rest=a["rest"],
        max_degree=a["max_degree"], superfluous=superfluous,
    )
    return a["left"], a["right"], order


#: terms counted at once by :func:`_class_sizes`
_COUNT_CHUNK = 1 << 22


def _class_sizes(condition: np.ndarray, bins: int) -> np.ndarray:
    """The terms per class, counted in chunks: ``np.bincount`` widens its input to intp,
    which for the 35 million terms of a large order is a copy of 280 MB."""
    sizes = np.zeros(bins, dtype=np.int64)
    for i in range(0, len(condition), _COUNT_CHUNK):
        sizes += np.bincount(condition[i:i + _COUNT_CHUNK], minlength=bins)
    return sizes


def _within(a: np.ndarray, lo: int, hi: int) -> bool:
    """Every entry in ``[lo, hi)`` (an empty array trivially)."""
    return len(a) == 0 or (int(a.min()) >= lo and int(a.max()) < hi)


_MAX_COEFFICIENT_DIGITS = 40  # (n−1)!/σ for n ≤ 31 vertices has at most 33 digits
_INTEGER = re.compile(r"-?[0-9]+")  # ASCII: str.isdigit() is also true of '²', which int() refuses


def _coefficients(raw: Any) -> list[int] | None:
    """The signed coefficients ``±(n−1)!/σ`` (index 2i positive, 2i + 1 its negative)."""
    if not isinstance(raw, list) or len(raw) % 2:
        return None
    out = []
    for x in raw:
        if not isinstance(x, str) or not 0 < len(x) <= _MAX_COEFFICIENT_DIGITS or not _INTEGER.fullmatch(x):
            return None
        out.append(int(x))
    if any(out[i] <= 0 or out[i + 1] != -out[i] for i in range(0, len(out), 2)):
        return None
    return out
