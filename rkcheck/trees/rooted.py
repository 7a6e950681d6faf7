"""Rooted trees as level sequences: canonical forms and bracket notation (definitions §2).

Conventions (the same as RootedTrees.jl, so ids can be pasted between tools):

* A rooted tree is written as its **level sequence**: the depth of every vertex in
  depth-first order, the root at depth 1.  The **canonical** level sequence is the
  lexicographically largest one, obtained by listing the subtrees of every vertex in
  non-increasing lexicographic order of their own canonical sequences
  (``[[τ]τ]`` is ``(1, 2, 3, 2)``).
* Bracket notation: ``τ``, ``[τ]``, ``[τ²]``, ``[[τ]τ]``, ... with the subtrees in
  canonical order and repeats written as powers.
* ``σ(τ) = 1``, ``σ([t1^r1 … tp^rp]) = Π r_i! σ(t_i)^r_i`` (symmetry);
  ``γ(τ) = 1``, ``γ(t) = |t| Π γ(t_i)`` (density, for the classical order conditions).

These are the small, exact functions people use on one tree at a time (parsing an id,
printing a bracket); the bulk tables of trees with integer ids are
:mod:`rkcheck.trees.table`.
"""

from __future__ import annotations

from functools import lru_cache
from itertools import groupby
from typing import Iterable, Sequence

_SUPERSCRIPTS = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


# ---------------------------------------------------------- free functions


def level_sequence_of_forest(subtrees: Sequence[tuple[int, ...]]) -> tuple[int, ...]:
    """Canonical level sequence of the tree whose root carries ``subtrees``
    (each a canonical level sequence with root depth 1)."""
    out = [1]
    for sub in sorted(subtrees, reverse=True):
        out.extend(d + 1 for d in sub)
    return tuple(out)


def bracket_of_forest(subtrees: Sequence[tuple[int, ...]]) -> str:
    """Bracket notation of the tree whose root carries ``subtrees`` (level sequences)."""
    return _bracket_of_forest(tuple(sorted(subtrees, reverse=True)))


@lru_cache(maxsize=1 << 16)
def _bracket_of_forest(subtrees: tuple[tuple[int, ...], ...]) -> str:
    ordered = sorted(subtrees, reverse=True)
    return bracket_of_runs((bracket_of_forest(_split_children(seq)), len(list(run))) for seq, run in groupby(ordered))


def bracket_of_runs(runs: Iterable[tuple[str, int]]) -> str:
    """The bracket of a root carrying, in order, each subtree (its bracket) as many times
    as its count — ``[τ²]`` — and τ when it carries none."""
    parts = [text + (str(count).translate(_SUPERSCRIPTS) if count > 1 else "") for text, count in runs]
    return "[" + "".join(parts) + "]" if parts else "τ"


def bracket(seq: Sequence[int]) -> str:
    """Bracket notation of a level sequence (any valid one: it is canonicalised first,
    so every rooting of the same tree prints the same way)."""
    return bracket_of_forest(_split_children(canonical_level_sequence(seq)))


def _split_children(seq: tuple[int, ...]) -> list[tuple[int, ...]]:
    """The subtrees of the root of a level sequence, each re-based to root depth 1."""
    if not seq or seq[0] < 1:
        raise ValueError("a level sequence starts at the root, whose level is 1 or more")
    root = seq[0]
    subs: list[tuple[int, ...]] = []
    start = None
    for i in range(1, len(seq)):
        if seq[i] <= root:
            raise ValueError("a level sequence has exactly one vertex at the root's depth")
        if seq[i] == root + 1:
            if start is not None:
                subs.append(tuple(d - root for d in seq[start:i]))
            start = i
        elif seq[i] > seq[i - 1] + 1:
            raise ValueError("a level sequence can go down only one level at a time")
    if start is not None:
        subs.append(tuple(d - root for d in seq[start:]))
    return subs


def children_of_level_sequence(seq: Sequence[int]) -> list[tuple[int, ...]]:
    """Public form of the subtree split: ``B₋(t)`` as level sequences (definitions §2)."""
    return _split_children(tuple(seq))


def canonical_level_sequence(seq: Sequence[int]) -> tuple[int, ...]:
    """The canonical form of any valid level sequence."""
    return _canonical(tuple(seq))


@lru_cache(maxsize=1 << 16)
def _canonical(seq: tuple[int, ...]) -> tuple[int, ...]:
    # the same subtrees recur in tree after tree (emitting the conditions of order 12
    # asked for 700 000 of them): each is put in canonical form once
    return level_sequence_of_forest([_canonical(s) for s in _split_children(seq)])


def parse_level_sequence(text: str) -> tuple[int, ...]:
    """Parse ``"1,2,3,2"``, ``"[1, 2, 3, 2]"`` or ``"1 2 3 2"``; raises ValueError."""
    cleaned = text.strip().strip("[]()")
    if "," in cleaned:  # commas separate: an empty place (``1,,2``) is a typo, not a skip
        parts = [p.strip() for p in cleaned.split(",")]
    else:
        parts = cleaned.split()
    if not parts or not all(p.isascii() and p.isdigit() for p in parts):
        raise ValueError(f"not a level sequence: {text!r} (expected e.g. 1,2,3,2)")
    seq = tuple(int(p) for p in parts)
    _split_children(seq)  # validates
    if seq[0] != 1:
        raise ValueError("a level sequence starts with the root at depth 1")
    return seq
