"""Channels that repeat one another (rkcheck.evaluation.conjugates): a root whose images
are a stage permutation of an earlier root's is not evaluated, its residues copied.

Independent routes: the permutations are checked against a brute force over every
permutation of the stages (itertools), and the copied residues against a pass of their
own at that root (one ModularChannel per prime and root, nothing shared).  Published
fact used: the Galois conjugation of a Gauss–Legendre tableau reverses its nodes
(c ↦ 1 − c), so it is the same tableau with its stages reversed."""

from __future__ import annotations

import itertools
import random

import numpy as np
import pytest
from support.paths import TABLEAUX

import rkcheck.evaluation.scaled as scaled_module
from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.conjugates import repeated_channels
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_field
from rkcheck.io.loader import load
from rkcheck.trees.listing import ConditionListing

P = 1_000_003


def brute_sources(A: np.ndarray, b: np.ndarray) -> list[int]:
    """The same rule as repeated_channels, by trying every permutation of the stages."""
    s, D = b.shape
    source, kept = list(range(D)), []
    for j in range(D):
        for k in kept:
            if any(np.array_equal(A[np.ix_(q, q)][:, :, j], A[:, :, k]) and np.array_equal(b[list(q), j], b[:, k])
                   for q in itertools.permutations(range(s))):
                source[j] = k
                break
        else:
            kept.append(j)
    return source


def random_roots(rng: random.Random, s: int, bases: int, copies: int, values: int):
    """Images at ``bases`` unrelated roots and ``copies`` stage permutations of them, in
    random order; entries from ``values`` distinct residues (few: equal stages, ties)."""
    pool = [rng.randrange(P) for _ in range(values)]
    base = [(np.array([[rng.choice(pool) for _ in range(s)] for _ in range(s)]), np.array([rng.choice(pool) for _ in range(s)]))
            for _ in range(bases)]
    roots = list(base)
    for _ in range(copies):
        A, b = rng.choice(base)
        q = list(range(s))
        rng.shuffle(q)
        inv = np.argsort(q)
        roots.append((A[np.ix_(inv, inv)], b[inv]))  # stage i of the copy is stage q⁻¹(i)
    rng.shuffle(roots)
    return np.stack([A for A, _ in roots], axis=2), np.stack([b for _, b in roots], axis=1)


@pytest.mark.parametrize("seed", range(40))
def test_sources_equal_a_brute_force_over_every_permutation(seed):
    rng = random.Random(seed)
    s = rng.randint(1, 5)
    A, b = random_roots(rng, s, rng.randint(1, 3), rng.randint(0, 4), rng.choice([1, 2, 3, 50]))
    assert repeated_channels(A, b) == brute_sources(A, b)


def test_equal_signatures_without_a_permutation_are_not_copied():
    # two triangles against a hexagon: every stage has the same row, column and weight,
    # and no relabelling maps one digraph on the other
    two_triangles = np.zeros((6, 6), dtype=np.int64)
    hexagon = np.zeros((6, 6), dtype=np.int64)
    for i in range(3):
        two_triangles[i, (i + 1) % 3] = two_triangles[3 + i, 3 + (i + 1) % 3] = 1
    for i in range(6):
        hexagon[i, (i + 1) % 6] = 1
    A = np.stack([two_triangles, hexagon], axis=2)
    b = np.ones((6, 2), dtype=np.int64)
    assert repeated_channels(A, b) == [0, 1] == brute_sources(A, b)


def test_gauss_conjugates_are_the_stages_reversed():
    for name, D in (("gauss-3", 2), ("gauss-5", 8)):
        scaled = scaled_field(load(str(TABLEAUX / "collocation" / f"{name}.toml")).exact_values())
        for p, roots in scaled.primes_for(100):
            assert len(roots) == D
            assert scaled.channel_sources(p) == [0] * D, (name, p)
            A0, b0 = scaled._images(p, roots[0])
            reversed_stages = [(np.array_equal(A[::-1, ::-1], A0) and np.array_equal(b[::-1], b0))
                               for A, b in (scaled._images(p, r) for r in roots[1:])]
            assert any(reversed_stages), (name, p)


@pytest.mark.parametrize("path", ["collocation/gauss-3.toml", "collocation/gauss-5.toml", "avf/avf-gauss-4.toml",
                                  "hbvm/hbvm-4-3.toml"])
@pytest.mark.parametrize("pass_bytes", [0, None])
def test_copied_residues_equal_their_own_pass(path, pass_bytes, monkeypatch):
    # every (prime, root) of the exact sums against one ModularChannel pass at that root,
    # with one channel per pass and with the default width
    if pass_bytes is not None:
        monkeypatch.setattr(scaled_module, "PASS_BYTES", pass_bytes)
    scaled = scaled_field(load(str(TABLEAUX / path)).exact_values())
    listing = ConditionListing(8, None)
    sums = exact_condition_sums(scaled, listing)
    copied = 0
    for n, o in sums.items():
        for i, (p, roots) in enumerate(o.primes):
            copied += sum(k != j for j, k in enumerate(scaled.channel_sources(p)))
            for j, r in enumerate(roots):
                alone = condition_sums(listing, scaled.channel(p, r), scaled.s, [n])[n]
                assert np.array_equal(o.residues[:, i, j], alone), (n, p, r)
    if "gauss" in path:
        assert copied


def test_progress_counts_a_prime_when_all_its_roots_are_done(monkeypatch):
    monkeypatch.setattr(scaled_module, "PASS_BYTES", 0)
    scaled = scaled_field(load(str(TABLEAUX / "collocation" / "gauss-5.toml")).exact_values())
    listing = ConditionListing(8, None)
    seen: list[tuple[int, int]] = []
    sums = exact_condition_sums(scaled, listing, on_pass=lambda done, total: seen.append((done, total)))
    total = max(len(o.primes) for o in sums.values())
    assert seen == [(k, total) for k in range(1, total + 1)]


def test_the_search_is_bounded_and_then_evaluates(monkeypatch):
    # a 12-cycle at both roots, every stage alike in its signature: found with the
    # default budget; with no assignments allowed, the second root is evaluated
    import rkcheck.evaluation.conjugates as conjugates

    s = 12
    cycle = np.zeros((s, s), dtype=np.int64)
    for i in range(s):
        cycle[i, (i + 1) % s] = 1
    A = np.stack([cycle, cycle], axis=2)
    b = np.ones((s, 2), dtype=np.int64)
    assert repeated_channels(A, b) == [0, 0]
    monkeypatch.setattr(conjugates, "MAX_TRIES", 0)
    assert repeated_channels(A, b) == [0, 1]
