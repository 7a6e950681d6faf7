"""All rooted trees up to an order as flat arrays, with O(1) Butcher-product lookups.

This is the listing behind the energy check (definitions §2–§3).  Conventions:

* Every rooted tree ``t ≠ τ`` is the **Butcher product** ``t = u ∘ v``: ``v`` is its
  child with the *largest* id and ``u`` is ``t`` with (one copy of) that child removed.
  So ``children(t) = children(u) ∪ {v}`` and the elementary weights follow
  ``Φ(t) = Φ(u) ⊙ AΦ(v)`` and ``a(B₋(t)) = a(B₋(u)) · a(v)`` (definitions §2).
* Ids grow with the number of vertices: the trees with ``n`` vertices are
  ``first[n] <= id < first[n+1]``, so both factors of a tree have smaller ids.
* Within an order, ids follow the **generation order**: by the order ``r`` of ``v``,
  then by ``v``, then by ``u`` in the order of the left factors sorted by their largest
  child.  That makes the id of a product a sum of table entries::

      id(u ∘ v) = first[n] + base[n, r] + offset[n, v] + rank[u]        (n = |u| + |v|)

  — a few array reads, never a search.  (A sorted-key search costs about 1.6 µs per
  lookup in a table of 35 million trees, from cache misses; the sum costs a few reads.)
* Degree bounds: every vertex other than the root has at most ``inner_bound`` children
  and the root at most ``root_bound``.  For Hamiltonians of degree ≤ m the energy
  conditions need ``inner_bound = m − 1`` and ``root_bound = m`` (a vertex's degree is its
  children plus its parent edge); trees outside the bounds are never built.

Per tree the table keeps: ``left``/``right`` (the factors ``u``, ``v``; −1 for τ),
``nchild``, ``sigma`` (symmetry σ), ``mult`` (copies of ``v`` among the children), the
depths of the two deepest branches ``h1 ≥ h2`` (``height = h1``), the child ``tall`` that
alone reaches depth ``h1`` (when ``h1 > h2``) and ``rest = t − tall``; these locate the
centre of every tree's free tree without building it (:mod:`rkcheck.trees.classes`).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

TAU = 0
_NONE = -1

IdArray: TypeAlias = npt.NDArray[np.int32]  # tree ids (and −1 for "none")
IndexArray: TypeAlias = npt.NDArray[np.integer[Any]]  # positions or ids of any integer type
#: one block of an order's generation: the order r of the right factors, those factors
#: (None: every tree of order r) and the running total of the left factors each takes
Block: TypeAlias = tuple[int, "IdArray | None", IdArray]


_FIELDS = {  # per-tree arrays and their dtypes
    "left": np.int32, "right": np.int32, "nchild": np.int8, "h1": np.int8, "h2": np.int8,
    "tall": np.int32, "rest": np.int32, "sigma": np.int64, "mult": np.int8, "order": np.int8,
    "rank": np.int32, "inner_max": np.int8,
}
_CHUNK = 1 << 20  # rows per vectorised step: bounds the temporaries
#: σ from here on is kept in :attr:`TreeTable.sigma` as a key of its exact value
#: (:meth:`TreeTable.sigma_value`): 21!, σ of the bush with 22 vertices, exceeds int64
SIGMA_LIMIT = 1 << 62


class TreeTable:
    """Every rooted tree with at most ``max_order`` vertices within the degree bounds
    (``None`` = unbounded), generated order by order into preallocated arrays."""

    # the per-tree arrays of _FIELDS (set through setattr); after release() only
    # left/right remain and the others are None
    left: IdArray
    right: IdArray
    nchild: npt.NDArray[np.int8]
    h1: npt.NDArray[np.int8]
    h2: npt.NDArray[np.int8]
    tall: IdArray
    rest: IdArray
    sigma: npt.NDArray[np.int64]
    mult: npt.NDArray[np.int8]
    order: npt.NDArray[np.int8]
    rank: IdArray
    inner_max: npt.NDArray[np.int8]

    def __init__(self, max_order: int, root_bound: int | None = None, inner_bound: int | None = None,
                 capacity: int = 1, factors: tuple[IdArray, IdArray] | None = None):
        """``capacity``: rows to allocate at once (the trees of every order the table will
        hold, when known: growing then never copies); ``factors``: the arrays to keep
        ``left``/``right`` in (at least ``capacity`` rows; a listing's own, so that they
        are not copied when the table is released)."""
        if max_order < 1:
            raise ValueError("max_order must be at least 1")
        if root_bound is not None and inner_bound is not None and inner_bound > root_bound:
            raise ValueError("the root may not have fewer children than an inner vertex")
        self.root_bound = root_bound
        self.inner_bound = inner_bound
        self.first = [0, 0, 1]  # first[n] for n = 0, 1, 2 (order 1 is τ alone)
        self._capacity = max(capacity, 1)
        # without a root bound a tree's rank among the left factors follows from its id
        # (:meth:`_prepare_lefts`): no array of them (4 bytes a tree)
        self._fields = {k: t for k, t in _FIELDS.items() if k != "rank" or root_bound is not None}
        self.rank = np.empty(0, dtype=np.int32)
        for name, dtype in self._fields.items():
            # np.empty: pages are only touched (and counted as resident) once written
            setattr(self, name, np.empty(self._capacity, dtype=dtype))
        if factors is not None:
            if min(len(factors[0]), len(factors[1])) < self._capacity:
                raise ValueError("the factor arrays are shorter than the capacity")
            self.left, self.right = factors
        for name in self._fields:
            getattr(self, name)[0] = 0
        self.left[0] = self.right[0] = self.tall[0] = self.rest[0] = _NONE
        self.sigma[0] = self.order[0] = 1
        # lookup tables: base[n][r]; offset[n] covers the ids of orders < n
        self._base: dict[int, np.ndarray] = {}
        self._offset: dict[int, np.ndarray] = {}
        self._lefts_sorted: dict[int, IdArray] = {}  # order -> left-factor ids sorted by largest child
        self._block_cache: dict[int, list[Block]] = {}
        self._count: dict[int, int] = {}
        # the exact σ of at least SIGMA_LIMIT, by key (sigma_value), and the keys by value
        self._big_sigma: list[int] = []
        self._big_sigma_keys: dict[int, int] = {}
        self._prepare_lefts(1)
        self.max_order = 1
        self.grow_to(max_order)

    def grow_to(self, max_order: int) -> None:
        """Add the orders up to ``max_order`` (a table grows; it never shrinks)."""
        for n in range(self.max_order + 1, max_order + 1):
            self._grow(n)
            self.max_order = n

    def __len__(self) -> int:
        return self.first[-1]

    def ids_of_order(self, n: int) -> range:
        if n < 1 or n > self.max_order:
            return range(0)
        return range(self.first[n], self.first[n + 1])

    def count(self, n: int) -> int:
        return len(self.ids_of_order(n))

    def _inner_ok(self, ids: IndexArray) -> npt.NDArray[np.bool_]:
        if self.inner_bound is None:
            return np.ones(len(ids), dtype=bool)
        return self.nchild[ids] <= self.inner_bound

    def _reserve(self, size: int, used: int) -> None:
        """Grow every per-tree array to hold ``size`` trees, keeping the first ``used``."""
        if size <= self._capacity:
            return
        cap = size
        for name, dtype in self._fields.items():
            arr = np.empty(cap, dtype=dtype)
            arr[:used] = getattr(self, name)[:used]
            setattr(self, name, arr)
        self._capacity = cap

    def release(self) -> None:
        """Keep only the factors ``left``/``right`` (all that evaluating weights needs)
        and what :meth:`pairs` needs to generate a prepared order again; lookups and new
        orders are no longer possible afterwards."""
        for name in _FIELDS:
            if name not in ("left", "right"):
                setattr(self, name, None)
        self._base.clear()
        self._offset.clear()

    # -------------------------------------------------------------- generation

    def _prepare_lefts(self, k: int) -> None:
        """The trees of order k that can be left factors (room for one more child at the
        root), sorted by their largest child (τ's is −1), and each one's rank there.

        The right factors of an order never decrease in id order (generation order), so
        the sort keeps the id order; without a root bound every tree of the order is a
        left factor and its rank is ``id − first[k]``: neither the list nor the ranks
        are stored then (:meth:`_lefts_of`, :meth:`_ranks`)."""
        if self.root_bound is None:
            return
        ids = np.arange(self.first[k], self.first[k + 1], dtype=np.int32)
        ids = ids[self.nchild[ids] < self.root_bound]
        order = np.argsort(self.right[ids], kind="stable")
        lefts = ids[order]
        self._lefts_sorted[k] = lefts
        self.rank[self.first[k]:self.first[k + 1]] = _NONE
        self.rank[lefts] = np.arange(len(lefts), dtype=np.int32)

    def _left_count(self, k: int) -> int:
        """How many trees of order k are left factors."""
        if self.root_bound is None:
            return self.first[k + 1] - self.first[k]
        return len(self._lefts_sorted[k])

    def _left_rights(self, k: int) -> IdArray:
        """The largest child of each left factor of order k, in rank order (never
        decreasing)."""
        if self.root_bound is None:
            return self.right[self.first[k]:self.first[k + 1]]
        return self.right[self._lefts_sorted[k]]

    def _lefts_of(self, k: int, local: IndexArray) -> IdArray:
        """The left factors of order k with the ranks ``local``."""
        if self.root_bound is None:
            return (local + self.first[k]).astype(np.int32)
        return self._lefts_sorted[k][local]

    def _ranks(self, u: IndexArray) -> npt.NDArray[np.integer[Any]]:
        """The rank of each left factor ``u`` among those of its order."""
        if self.root_bound is None:
            return u - np.asarray(self.first, dtype=np.int64)[self.order[u]]
        return self.rank[u]

    def _blocks(self, n: int) -> Iterator[Block]:
        """For each order r of the right factor: ``(r, v_ids, ends)`` with ``v_ids`` the
        inner-valid right factors v of order r (None: all of them, ``first[r] …
        first[r+1] − 1``) and ``ends`` the running total (int32) of how many left factors
        each one takes, counted in chunks (no int64 array of a whole order's factors)."""
        for r in range(1, n):
            v_ids = None
            if self.inner_bound is not None:
                v_ids = np.arange(self.first[r], self.first[r + 1], dtype=np.int32)
                v_ids = v_ids[self._inner_ok(v_ids)]
            size = self.first[r + 1] - self.first[r] if v_ids is None else len(v_ids)
            if size == 0 or self._left_count(n - r) == 0:
                yield r, np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.int32)
                continue
            rights = self._left_rights(n - r)
            ends = np.empty(size, dtype=np.int32)
            total = 0
            for a in range(0, size, _CHUNK):
                b = min(size, a + _CHUNK)
                v = np.arange(self.first[r] + a, self.first[r] + b, dtype=np.int32) if v_ids is None else v_ids[a:b]
                part = np.cumsum(np.searchsorted(rights, v, side="right"))
                part += total
                if int(part[-1]) >= 2**31:  # pragma: no cover - far beyond 24 vertices
                    raise OverflowError("too many trees in one block for int32 positions")
                ends[a:b] = part
                total = int(part[-1])
            yield r, v_ids, ends

    @staticmethod
    def _block_ids(r_first: int, v_ids: np.ndarray | None, i: int, j: int) -> np.ndarray:
        """The right factors ``i … j − 1`` of a block (``v_ids`` None: consecutive ids
        from ``r_first``)."""
        if v_ids is None:
            return np.arange(r_first + i, r_first + j, dtype=np.int32)
        return v_ids[i:j]

    def prepare_order(self, n: int) -> int:
        """Build the lookup tables of order ``n`` (``base``, ``offset``) and return how
        many trees it has.  ``n`` may be one above the stored orders: its trees can then be
        looked up and generated in chunks (:meth:`pairs`) without being stored."""
        if n in self._block_cache:
            return int(self._count[n])
        bases = np.zeros(n + 1, dtype=np.int64)
        offset = np.full(self.first[n], _NONE, dtype=np.int32)
        total = 0
        blocks = []
        for r, v_ids, ends in self._blocks(n):
            bases[r] = total
            for a in range(0, len(ends), _CHUNK):  # starts = ends − counts, a chunk at a time
                b = min(len(ends), a + _CHUNK)
                starts = np.empty(b - a, dtype=np.int32)
                starts[1:] = ends[a:b - 1]
                starts[0] = ends[a - 1] if a else 0
                if v_ids is None:
                    offset[self.first[r] + a:self.first[r] + b] = starts
                else:
                    offset[v_ids[a:b]] = starts
            blocks.append((r, v_ids, ends))
            total += int(ends[-1]) if len(ends) else 0
        self._base[n] = bases
        self._offset[n] = offset
        self._block_cache[n] = blocks
        self._count[n] = total
        return total

    def pairs(self, n: int) -> Iterator[tuple[IdArray, IdArray]]:
        """The factors ``(U, V)`` of the trees of order ``n`` in id order, in chunks of
        about ``_CHUNK`` rows (generation order, see the module docstring)."""
        self.prepare_order(n)
        for r, v_ids, ends in self._block_cache[n]:
            size = len(ends)
            if size == 0 or int(ends[-1]) == 0:  # no left factor takes these right ones
                continue
            # chunk boundaries on the right factors: about _CHUNK pairs each (one factor
            # with more partners than that is a chunk of its own)
            marks = np.arange(_CHUNK, int(ends[-1]) + _CHUNK, _CHUNK)
            cuts = np.searchsorted(ends, marks.astype(ends.dtype) if int(marks[-1]) < 2**31 else marks, side="right")
            i = 0
            # sorted already: dict.fromkeys drops the repeats (np.unique would also import
            # numpy.ma, 15 ms of start-up)
            for j in [*dict.fromkeys(cuts.tolist()), size]:
                j = min(max(j, i + 1), size)
                if j <= i:
                    continue
                before = int(ends[i - 1]) if i else 0
                c = np.diff(ends[i:j], prepend=np.int32(before)).astype(np.int64)
                m = int(ends[j - 1]) - before
                if m:
                    V = np.repeat(self._block_ids(self.first[r], v_ids, i, j), c)
                    local = np.arange(m, dtype=np.int64) - np.repeat(np.cumsum(c) - c, c)
                    yield self._lefts_of(n - r, local), V
                i = j

    def _grow(self, n: int) -> None:
        total = self.prepare_order(n)
        lo = self.first[-1]
        self._reserve(lo + total, lo)
        self.first.append(lo + total)
        pos = lo
        for U, V in self.pairs(n):
            hi = pos + len(U)
            for name, values in self.attributes(n, U, V).items():
                if name in self._fields:
                    getattr(self, name)[pos:hi] = values
            pos = hi
        del self._block_cache[n]
        self._prepare_lefts(n)

    def attributes(self, n: int, U: np.ndarray, V: np.ndarray) -> dict[str, npt.NDArray[Any] | int]:
        """The per-tree attributes of the trees ``U ∘ V`` (all of order ``n``; ``order``
        and ``rank`` are the same for all of them, given as one int)."""
        h1u = self.h1[U].astype(np.int16)
        dv = self.h1[V].astype(np.int16) + 1
        taller = dv > h1u
        tie = dv == h1u
        h1 = np.maximum(h1u, dv)
        h2 = np.where(taller, h1u, np.where(tie, dv, np.maximum(self.h2[U], dv)))
        tall = np.where(taller | tie, V, self.tall[U])
        mult = np.where(self.right[U] == V, self.mult[U] + 1, 1)
        # rest = t − tall: u when the tall child is v, else (u − tall) ∘ v; only where the
        # tallest branch is unique (h1 > h2), which is where the centre lies off the root
        rest = np.full(len(U), _NONE, dtype=np.int32)
        unique = h1 > h2
        via_v = unique & (tall == V)
        rest[via_v] = U[via_v]
        via_u = np.flatnonzero(unique & ~via_v)
        if len(via_u):  # (u − tall) has fewer vertices: its product is already in the table
            rest[via_u] = self.product(self.rest[U[via_u]], V[via_u])
        return {
            "left": U, "right": V, "nchild": self.nchild[U] + 1, "h1": h1, "h2": h2, "tall": tall,
            "rest": rest, "mult": mult, "sigma": self._sigma_product(U, V, mult), "order": n,
            "rank": _NONE,
            "inner_max": np.maximum(self.inner_max[U], np.maximum(self.inner_max[V], self.nchild[V] + 1)),
        }

    def _sigma_product(self, U: IndexArray, V: IndexArray, mult: npt.NDArray[np.integer[Any]]) -> npt.NDArray[np.int64]:
        """``σ(u ∘ v) = σ(u)·σ(v)·mult`` as :attr:`sigma` keeps it: the value itself below
        :data:`SIGMA_LIMIT`, else a key of the exact value (:meth:`sigma_value`).  21!, the
        bush with 22 vertices, exceeds int64: multiplied there, it wrapped around."""
        su, sv = self.sigma[U], self.sigma[V]
        out = su * sv * mult
        # a float estimate flags the products that may reach the limit (its error is far
        # below the factor 2 between the limit and int64's range)
        big = np.flatnonzero((su < 0) | (sv < 0) | (su.astype(np.float64) * sv * mult >= SIGMA_LIMIT))
        if len(big):
            out[big] = [self._sigma_key(self.sigma_value(a) * self.sigma_value(b) * m)
                        for a, b, m in zip(su[big].tolist(), sv[big].tolist(), mult[big].tolist())]
        return out

    def _sigma_key(self, value: int) -> int:
        """What :attr:`sigma` keeps for the exact σ ``value``: itself when below the
        limit, else ``−1 − i`` for the i-th such value (the same key for the same value)."""
        if value < SIGMA_LIMIT:
            return value
        key = self._big_sigma_keys.get(value)
        if key is None:
            key = self._big_sigma_keys[value] = -1 - len(self._big_sigma)
            self._big_sigma.append(value)
        return key

    def sigma_value(self, key: int) -> int:
        """The exact σ of an entry of :attr:`sigma`."""
        return key if key >= 0 else self._big_sigma[-1 - key]

    # ----------------------------------------------------------------- lookups

    def product(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """``id(u ∘ v)`` for arrays of factors; requires ``v >= largest child of u``, ``u``
        with room for one more child and ``v`` within the inner bound (every caller
        guarantees this by construction)."""
        u = np.asarray(u)
        v = np.asarray(v)
        order = self.order
        r = order[v]
        n = order[u] + r
        out = np.empty(len(u), dtype=np.int32)
        lo_n, hi_n = (int(n.min()), int(n.max())) if len(n) else (0, -1)
        for nn in range(lo_n, hi_n + 1):
            sel = np.flatnonzero(n == nn) if lo_n != hi_n else slice(None)
            vs = v[sel]
            out[sel] = self._base[nn][r[sel]] + self._offset[nn][vs] + self._ranks(u[sel]) + self.first[nn]
        return out

    def insert(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """``id`` of the tree whose root carries ``children(x) ∪ {y}`` (``y`` any id within
        the inner bound): strip the children of ``x`` larger than ``y``, attach ``y``,
        re-attach the stripped ones, largest last."""
        x = np.array(x, dtype=np.int32)
        y = np.asarray(y)
        right, left = self.right, self.left
        stripped: list[tuple[np.ndarray, np.ndarray]] = []  # (rows, child) per level
        active = np.flatnonzero(right[x] > y)
        while len(active):
            stripped.append((active, right[x[active]]))
            x[active] = left[x[active]]
            active = active[right[x[active]] > y[active]]
        cur = self.product(x, y)
        for rows, child in reversed(stripped):
            cur[rows] = self.product(cur[rows], child)
        return cur

    def gamma(self, ids: np.ndarray) -> np.ndarray:
        """The density γ of each tree (definitions §2): ``γ(u ∘ v) = γ(u)·γ(v)·|t|/|u|``,
        as exact Python ints (object array; 21! exceeds int64)."""
        cache = self.__dict__.setdefault("_gamma", {0: 1})
        out = []
        for t in (int(x) for x in ids):
            stack = [t]
            while stack:
                x = stack[-1]
                if x in cache:
                    stack.pop()
                    continue
                u, v = int(self.left[x]), int(self.right[x])
                missing = [y for y in (u, v) if y not in cache]
                if missing:
                    stack.extend(missing)
                    continue
                cache[x] = cache[u] * cache[v] * int(self.order[x]) // int(self.order[u])
                stack.pop()
            out.append(cache[t])
        return np.array(out, dtype=object)

    def id_of_children(self, children: Iterable[int]) -> int:
        """The id of the tree whose root carries ``children`` (ids, any order); KeyError
        when that tree is not in the table (too many vertices, or outside the bounds)."""
        kids = sorted(int(c) for c in children)
        n = 1 + sum(int(self.order[c]) for c in kids)
        if n > self.max_order or (self.root_bound is not None and len(kids) > self.root_bound):
            raise KeyError(tuple(children))
        if self.inner_bound is not None and any(self.nchild[c] > self.inner_bound for c in kids):
            raise KeyError(tuple(children))
        cur = TAU
        for c in kids:  # attaching children in increasing id order: each is the largest so far
            cur = int(self.product(np.array([cur]), np.array([c]))[0])
        return cur

    def id_of_level_sequence(self, seq: Sequence[int]) -> int:
        """The id of the tree with level sequence ``seq`` (any valid one)."""
        from rkcheck.trees.rooted import children_of_level_sequence

        return self.id_of_children([self.id_of_level_sequence(sub) for sub in children_of_level_sequence(tuple(seq))])

    def bracket(self, t: int) -> str:
        """Butcher's bracket notation of ``t`` (``[[τ]τ²]``)."""
        from rkcheck.trees.rooted import bracket_of_forest

        return bracket_of_forest([self.level_sequence(c) for c in self.children(t)])

    @property
    def height(self) -> np.ndarray:
        """Edges from the root to the deepest leaf (τ: 0)."""
        return self.h1

    def children(self, t: int) -> list[int]:
        """The children of ``t`` (ids), largest first."""
        out = []
        right, left = self.right, self.left
        while t != TAU:
            out.append(int(right[t]))
            t = int(left[t])
        return out

    def level_sequence(self, t: int, _cache: dict[int, tuple[int, ...]] | None = None) -> tuple[int, ...]:
        """Canonical (lexicographically largest) level sequence of ``t``, definitions §2."""
        cache = self.__dict__.setdefault("_ls_cache", {}) if _cache is None else _cache
        seq = cache.get(t)
        if seq is None:
            subs = sorted((self.level_sequence(c, cache) for c in self.children(t)), reverse=True)
            out = [1]
            for sub in subs:
                out.extend(d + 1 for d in sub)
            seq = cache[t] = tuple(out)
        return seq
