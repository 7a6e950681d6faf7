"""An experiment: the conditions of one order evaluated by centroid decomposition, with
no listing of rooted trees.  Measures what that route costs for RK4 up to order 22, and
checks it against the engine at small orders.

    python benchmarks/bench_centroid.py --vertices 23     # RK4 to order 22 (23 939 311 conditions), 5 primes
    python benchmarks/bench_centroid.py --check 14        # every condition up to 14 vertices against the engine

It prints, per number of vertices, the CPU time so far and the conditions that are
nonzero at some prime (they fail), then the peak memory.  ``--check`` compares the
residue of every condition's designated rooting, named by its canonical id, with the
engine's (``exact_condition_sums``) at the engine's own primes.

The route (not yet the engine's: docs/performance.md, *Order 22*).  Every
free tree with n vertices has one centroid (a vertex whose branches have at most
(n−1)/2 vertices each) or, for even n, two adjacent ones whose halves have n/2 vertices.
Rooted at its centroid it is a multiset of rooted trees of at most ⌊(n−1)/2⌋ vertices
(plus, with two centroids, one more of n/2), and those are few: 3 047 rooted trees up to
11 vertices.  Summing over vertices instead of distinct rootings (the orbit–stabiliser
count turns 1/σ(u) into 1/|Aut t̄|, and |Aut t̄| = σ(T) for the centroid rooting T of a
non-superfluous tree),

    R(t̄)·σ(T) = ± Σ_v (−1)^{d(v)} a(B₋(rooting at v)),

and the vertices of a branch c contribute a *linear* function of the stage vector x of
the rest of the tree seen from c's root: mᵀx, with

    m(τ) = b,     m(c) = w(c)·b − Aᵀ Q(c),     Q(c) = Σ_{children u} m(u) ⊙ Π_{siblings u'} ψ(u').

So a free tree costs a few vector products per branch, built incrementally as its
multiset of branches is enumerated (P = Πψ, α = Πa, Q as above), whatever its number of
rootings; the tables of m, Q, ψ, a and w cover the 3 047 small rooted trees only.  The
sign ± is that of the centroid's distance to the centre (the designated rooting).
"""

from __future__ import annotations

import argparse
import math
import resource
import sys
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

RK4 = ([[0, 0, 0, 0], [Fraction(1, 2), 0, 0, 0], [0, Fraction(1, 2), 0, 0], [0, 0, 1, 0]],
       [Fraction(1, 6), Fraction(1, 3), Fraction(1, 3), Fraction(1, 6)])

#: rows of one block of new states: the temporaries of a block stay small
BLOCK = 1 << 17

#: partial multisets with at most this many vertices left are completed at once, not held
SHALLOW = 4


class SmallTrees:
    """Every rooted tree with at most ``top`` vertices, ids by size: tree ``c = u ∘ v``
    (``v`` attached to ``u``'s root, ``v`` the child with the largest id)."""

    def __init__(self, top: int):
        self.left, self.right, self.size, self.maxchild, self.run, self.sigma = [-1], [-1], [1], [-1], [0], [1]
        self.first = [0, 0, 1]  # first id with 1, 2, … vertices
        for z in range(2, top + 1):
            for v in range(len(self.size)):  # v: the largest child
                zu = z - self.size[v]
                if zu < 1:
                    continue
                for u in range(self.first[zu], self.first[zu + 1] if zu + 1 < len(self.first) else len(self.size)):
                    if self.size[u] != zu or self.maxchild[u] > v:
                        continue
                    run = self.run[u] + 1 if self.maxchild[u] == v else 1
                    self.left.append(u)
                    self.right.append(v)
                    self.size.append(z)
                    self.maxchild.append(v)
                    self.run.append(run)
                    self.sigma.append(self.sigma[u] * self.sigma[v] * run)
            self.first.append(len(self.size))
        self.count = len(self.size)

    def upto(self, z: int) -> int:
        """The number of trees with at most z vertices."""
        return self.first[z + 1] if z + 1 < len(self.first) else self.count

    def children(self, c: int) -> list[int]:
        out = []
        while c > 0:
            out.append(self.right[c])
            c = self.left[c]
        return out

    def level_sequence(self, c: int) -> tuple[int, ...]:
        seq = [1]
        for child in self.children(c):
            seq += [d + 1 for d in self.level_sequence(child)]
        return tuple(seq)


def weight_tables(trees: SmallTrees, A: list[list[int]], b: list[int], primes: list[int]) -> dict[str, np.ndarray]:
    """Φ, ψ, a, w, Q, m and 1/σ of every small tree modulo each prime (Â, b̂ integer),
    stacked on a channel axis after the tree axis."""
    tables = [_weight_tables(trees, A, b, p) for p in primes]
    keys = ("phi", "psi", "a", "w", "Q", "m", "sigma_inv", "run_inv")
    out = {key: np.stack([x[key] for x in tables], axis=1) for key in keys}
    out["size"] = tables[0]["size"]
    out["p"] = np.array(primes, dtype=np.int64)
    return out


def _weight_tables(trees: SmallTrees, A_int: list[list[int]], b_int: list[int], p: int) -> dict[str, np.ndarray]:
    s, n = len(b_int), trees.count
    A = np.array([[x % p for x in row] for row in A_int], dtype=np.int64)
    b = np.array([x % p for x in b_int], dtype=np.int64)
    phi, psi, m, Q = (np.zeros((n, s), dtype=np.int64) for _ in range(4))
    a, w = np.zeros(n, dtype=np.int64), np.zeros(n, dtype=np.int64)
    At = A.T.copy()
    for c in range(n):
        if c == 0:
            phi[0] = 1
            w[0] = 1
        else:
            u, v = trees.left[c], trees.right[c]
            phi[c] = phi[u] * psi[v] % p
            w[c] = w[u] * a[v] % p
            Q[c] = (Q[u] * psi[v] + m[v] * phi[u]) % p
        psi[c] = A @ phi[c] % p
        a[c] = int(b @ phi[c] % p)
        m[c] = (w[c] * b - (At @ Q[c]) % p) % p
    sigma_inv = np.array([pow(x, -1, p) for x in trees.sigma], dtype=np.int64)
    return {"phi": phi, "psi": psi, "a": a, "w": w, "Q": Q, "m": m, "sigma_inv": sigma_inv,
            "size": np.array(trees.size, dtype=np.int64),
            "run_inv": np.array([0] + [pow(k, -1, p) for k in range(1, 64)], dtype=np.int64)}


def centroid_sums(trees: SmallTrees, t: dict[str, np.ndarray], n: int, keep: bool = False):
    """``(n−1)!·σ(T)⁻¹·Σ_v (−1)^{d(v)} ŵ`` of every non-superfluous free tree with n
    vertices rooted at its centroid, modulo each prime; with ``keep`` also each tree's
    branches.  A multiset of branches is built largest first; partial multisets wait by
    the vertices still to place, except those with at most ``SHALLOW`` left, which are
    completed at once: they are most of the partial multisets (at 23 vertices, held,
    they would take some 3 GB)."""
    cap = (n - 1) // 2 if n % 2 else n // 2 - 1
    p = t["p"]
    pv = p[:, None]
    fact = np.array([math.factorial(n - 1) % q for q in p.tolist()], dtype=np.int64)
    out, branches = [], []
    C, s = t["phi"].shape[1:]
    # partial multisets by vertices still to place: (P, Q, alpha, sigma_inv, last id, run, path)
    pending: dict[int, list[tuple]] = {r: [] for r in range(n)}

    def expand(r: int, state: tuple) -> None:
        P, Q, alpha, sinv, last, run, path = state
        count = np.minimum(last, trees.upto(min(r, cap)) - 1) + 1
        ends = np.cumsum(count)
        lo = 0
        while lo < len(count):
            start = ends[lo - 1] if lo else 0
            hi = max(int(np.searchsorted(ends, start + BLOCK, side="right")), lo + 1)
            k = count[lo:hi]
            parent = np.repeat(np.arange(lo, hi), k)
            c = np.arange(len(parent)) - np.repeat(np.cumsum(k) - k, k)
            psi_c = t["psi"][c]
            Pp = P[parent].astype(np.int64)
            P2 = (Pp * psi_c % pv).astype(np.int32)
            Q2 = ((Q[parent] * psi_c + t["m"][c] * Pp) % pv).astype(np.int32)
            del Pp, psi_c
            alpha2 = (alpha[parent] * t["a"][c] % p).astype(np.int32)
            run2 = np.where(last[parent] == c, run[parent] + 1, 1)
            sinv2 = (sinv[parent] * t["sigma_inv"][c] % p * t["run_inv"][run2] % p).astype(np.int32)
            rem = r - t["size"][c]
            for r2 in np.unique(rem).tolist():
                sel = rem == r2
                paths = [path[i] + (int(x),) for i, x in zip(parent[sel], c[sel])] if keep else None
                if r2 == 0:
                    S = (alpha2[sel] - Q2[sel].sum(axis=2, dtype=np.int64)) % p
                    out.append((fact * sinv2[sel] % p * S % p).astype(np.int32))
                    if keep:
                        branches.extend(paths)
                    continue
                child = (P2[sel], Q2[sel], alpha2[sel], sinv2[sel], c[sel], run2[sel], paths)
                if r2 <= SHALLOW:
                    expand(r2, child)
                else:
                    pending[r2].append(child)
            lo = hi

    root = (np.ones((1, C, s), dtype=np.int32), np.zeros((1, C, s), dtype=np.int32), np.ones((1, C), dtype=np.int32),
            np.ones((1, C), dtype=np.int32), np.array([trees.count]), np.zeros(1, dtype=np.int64), [()])
    pending[n - 1].append(root)
    for r in range(n - 1, 0, -1):
        if pending[r]:
            parts, pending[r] = pending[r], []
            state = tuple(np.concatenate([x[i] for x in parts]) for i in range(6))
            expand(r, state + ([q for x in parts for q in x[6]] if keep else None,))
    if n % 2 == 0:  # two centroids: halves c > c' with n/2 vertices each, rooted at c's root
        lo_id, hi_id = trees.first[n // 2], trees.upto(n // 2)
        ids = np.arange(lo_id, hi_id)
        big, small = np.triu_indices(len(ids), 1)  # c' < c: the equal pairs are superfluous
        c1, c2 = ids[small], ids[big]
        S = (t["w"][c2] * t["a"][c1] - ((t["Q"][c2] * t["psi"][c1] + t["m"][c1] * t["phi"][c2]) % pv).sum(axis=2)) % p
        out.append(fact * t["sigma_inv"][c2] % p * t["sigma_inv"][c1] % p * S % p)
        if keep:
            branches.extend(("pair", int(x), int(y)) for x, y in zip(c2, c1))
    return np.concatenate(out) if out else np.zeros((0, C), dtype=np.int64), branches


def designated(trees: SmallTrees, branches) -> tuple[tuple[int, ...], int]:
    """The canonical id of a free tree given by its centroid branches, and the sign
    (−1)^distance from the centroid to the designated centre."""
    from rkcheck.trees.graph import adjacency, centres, distances, rooted_at

    if branches and branches[0] == "pair":
        forest = trees.children(branches[1]) + [branches[2]]
    else:
        forest = list(branches)
    seq = [1]
    for c in forest:
        seq += [d + 1 for d in trees.level_sequence(c)]
    adj = adjacency(tuple(seq))
    best = max((rooted_at(adj, v), v) for v in centres(adj))
    return best[0], (-1) ** distances(adj, 0)[best[1]]


def scaled(tableau) -> tuple[list[list[int]], list[int]]:
    """``Â = d·A`` and ``b̂ = d·b`` as integers, d the entries' common denominator."""
    A, b = [[Fraction(x) for x in row] for row in tableau[0]], [Fraction(x) for x in tableau[1]]
    d = math.lcm(*(x.denominator for x in [*b, *(x for row in A for x in row)]))
    return [[int(x * d) for x in row] for row in A], [int(x * d) for x in b]


def check_against_engine(tableau, top: int) -> None:
    """Every condition with 3 … top vertices: the engine's residue of its designated
    rooting at the prime p against this route's."""
    from rkcheck.evaluation.modular import exact_condition_sums
    from rkcheck.evaluation.scaled import scaled_rational
    from rkcheck.trees.listing import ConditionListing

    listing = ConditionListing(top - 1, None)
    exact = [[Fraction(x) for x in row] for row in tableau[0]], [Fraction(x) for x in tableau[1]]
    sums = exact_condition_sums(scaled_rational(*exact), listing)
    trees = SmallTrees(top // 2)
    for n in range(3, top + 1):
        order = sums[n]
        primes = [q for q, _ in order.primes]
        residues = order.residues
        engine = {listing.record(n, k).level_sequence: tuple(listing.flip(n, k) * int(residues[k, i, 0]) % q
                                                              for i, q in enumerate(primes))
                  for k in range(len(order))}
        t = weight_tables(trees, *scaled(tableau), primes)
        values, branches = centroid_sums(trees, t, n, keep=True)
        mine = {}
        for v, br in zip(values.tolist(), branches):
            seq, sign = designated(trees, br)
            mine[seq] = tuple(sign * x % q for x, q in zip(v, primes))
        assert mine == engine, (n, len(mine), len(engine))
        print(f"{n:3d} vertices: {len(engine):6d} conditions agree at {len(primes)} primes")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vertices", type=int, default=23)
    ap.add_argument("--primes", type=int, default=5)
    ap.add_argument("--check", type=int, metavar="TOP")
    ap.add_argument("--dense", action="store_true", help="a dense 6-stage rational tableau instead of RK4")
    args = ap.parse_args()
    if args.dense:
        from bench_arith import DENSE6 as tableau
    else:
        tableau = RK4
    if args.check:
        check_against_engine(tableau, args.check)
        return
    from rkcheck.evaluation.scaled import scaled_rational

    primes = [q for q, _ in scaled_rational(*RK4).primes_for(30 * args.primes)][:args.primes]
    trees = SmallTrees(args.vertices // 2)
    t0 = time.process_time()
    t = weight_tables(trees, *scaled(tableau), primes)
    conditions = failing = 0
    for n in range(3, args.vertices + 1):
        values, _ = centroid_sums(trees, t, n)
        nonzero = int(np.count_nonzero(np.any(values != 0, axis=1)))
        conditions, failing = conditions + len(values), failing + nonzero
        print(f"{n:3d} vertices: {time.process_time() - t0:6.1f} s CPU so far, {len(values)} conditions, "
              f"{nonzero} nonzero at some prime")
    total = time.process_time() - t0
    print(f"{conditions} conditions, {failing} nonzero at some prime (fail)")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"{len(primes)} primes: {total:.1f} s CPU, peak {peak:.0f} MiB")


if __name__ == "__main__":
    main()
