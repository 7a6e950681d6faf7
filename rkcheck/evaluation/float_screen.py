"""The float64 screen: the same check in numpy double precision, with its own error bound.

Every quantity is a ball ``mid ± rad`` of float64 arrays.  Operations are vectorised
over all trees of one order (weights) and over all terms of all conditions (residuals).
Rounding is bounded in the standard way for IEEE round-to-nearest arithmetic without
overflow: a product or a length-n dot product of floats has relative error at most
``γ_n = n·u/(1 − n·u)`` (``u = 2⁻⁵³``, Higham, *Accuracy and Stability of Numerical
Algorithms*, §3.1), radii are propagated as for exact balls, and every computed radius is
inflated by ``(1 + 16u)`` and the smallest subnormal to cover the rounding of the bound
itself.  So the screen may say ``fails`` only when its own bound excludes 0 (definitions §5);
otherwise its enclosures give ``holds to D digits`` with D ≈ 15 at best, and ``verify``
never uses it for a verdict — it exists for speed comparisons (``rkcheck bench``) and
screens.  Like every backend it returns enclosures; the verdicts are
:mod:`rkcheck.energy.verdicts`' job.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Sequence

import numpy as np

from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.intervals import Interval
from rkcheck.trees.rooted import RootedTreeTable

U = 2.0**-53
ETA = 2.0**-1074  # smallest subnormal: covers underflow in the bounds
INFLATE = 1.0 + 16 * U


def gamma(n: int) -> float:
    return n * U / (1 - n * U)


def _up(x: np.ndarray) -> np.ndarray:
    return x * INFLATE + ETA


def _ball(x: Interval) -> tuple[float, float]:
    m = float(x.mid)
    r = float(x.rad) + abs(m) * U  # the rounding of mid to a double, and of rad
    return m, r * INFLATE + ETA


class FloatBackend:
    """float64 ball arithmetic with rigorous (inflated) rounding bounds."""

    name = "float64"
    exact = False

    def __init__(self, A: Sequence[Sequence[Interval]], b: Sequence[Interval]):
        self.s = len(b)
        Am = np.array([[_ball(x)[0] for x in row] for row in A], dtype=float)
        Ar = np.array([[_ball(x)[1] for x in row] for row in A], dtype=float)
        self.Am, self.Ar, self.Aabs = Am, Ar, np.abs(Am)
        self.bm = np.array([_ball(x)[0] for x in b])
        self.br = np.array([_ball(x)[1] for x in b])
        self._caches: dict[RootedTreeTable, dict] = {}

    def _matvec(self, xm: np.ndarray, xr: np.ndarray, Mm: np.ndarray, Mr: np.ndarray, Mabs: np.ndarray):
        """Rows of x times Mᵀ: (n, s) @ (s, k) as balls."""
        mid = xm @ Mm.T
        absx = np.abs(xm)
        rad = absx @ Mr.T + xr @ Mabs.T + xr @ Mr.T + gamma(self.s + 1) * (absx @ Mabs.T)
        return mid, _up(rad)

    def tree_weights(self, table: RootedTreeTable, upto: int | None = None):
        """(a_mid, a_rad) arrays over all ids of ``table`` up to order ``upto``."""
        upto = table.max_order if upto is None else upto
        c = self._caches.get(table)
        n_total = len(table)
        if c is None:
            s = self.s
            c = {
                "phi_m": np.zeros((n_total, s)), "phi_r": np.zeros((n_total, s)),
                "psi_m": np.zeros((n_total, s)), "psi_r": np.zeros((n_total, s)),
                "a_m": np.zeros(n_total), "a_r": np.zeros(n_total), "done": 1,
            }
            c["phi_m"][0] = 1.0
            pm, pr = self._matvec(c["phi_m"][:1], c["phi_r"][:1], self.Am, self.Ar, self.Aabs)
            c["psi_m"][0], c["psi_r"][0] = pm[0], pr[0]
            am, ar = self._matvec(c["phi_m"][:1], c["phi_r"][:1], self.bm[None, :], self.br[None, :], np.abs(self.bm)[None, :])
            c["a_m"][0], c["a_r"][0] = am[0, 0], ar[0, 0]
            self._caches[table] = c
        if len(c["a_m"]) < n_total:  # a growable table gained orders
            for key in ("phi_m", "phi_r", "psi_m", "psi_r"):
                c[key] = np.vstack([c[key], np.zeros((n_total - len(c[key]), self.s))])
            for key in ("a_m", "a_r"):
                c[key] = np.concatenate([c[key], np.zeros(n_total - len(c[key]))])
        babs = np.abs(self.bm)[None, :]
        left_all, right_all = table.factor_arrays()
        for n in range(c["done"] + 1, upto + 1):
            lo, hi = table.first_id[n], table.first_id[n + 1]
            if hi == lo:
                c["done"] = n
                continue
            ids = np.arange(lo, hi)
            left, right = left_all[lo:hi], right_all[lo:hi]
            um, ur = c["phi_m"][left], c["phi_r"][left]
            vm, vr = c["psi_m"][right], c["psi_r"][right]
            pm = um * vm
            pr = _up(np.abs(um) * vr + np.abs(vm) * ur + ur * vr + U * np.abs(pm))
            c["phi_m"][ids], c["phi_r"][ids] = pm, pr
            qm, qr = self._matvec(pm, pr, self.Am, self.Ar, self.Aabs)
            c["psi_m"][ids], c["psi_r"][ids] = qm, qr
            am, ar = self._matvec(pm, pr, self.bm[None, :], self.br[None, :], babs)
            c["a_m"][ids], c["a_r"][ids] = am[:, 0], ar[:, 0]
            c["done"] = n
        return c["a_m"], c["a_r"]

    def enclose_table(self, ctable) -> list[Enclosure]:
        """Every condition of a condition table at once, from its cached term arrays."""
        arr = ctable.term_arrays
        a_m, a_r = self.tree_weights(ctable.trees)
        # index -1 (padding) reads the appended exact 1
        am = np.append(a_m, 1.0)
        ar = np.append(a_r, 0.0)
        br = arr["branches"]
        n_terms = br.shape[0]
        pm = np.ones(n_terms)
        pr = np.zeros(n_terms)
        for k, n_k in enumerate(arr["needs"]):  # factor k: only the first n_k terms have it
            idx = br[:n_k, k]
            qm, qr = am[idx], ar[idx]
            xm, xr = pm[:n_k], pr[:n_k]
            new_m = xm * qm
            pr[:n_k] = _up(np.abs(xm) * qr + np.abs(qm) * xr + xr * qr + U * np.abs(new_m))
            pm[:n_k] = new_m
        cf = arr["coef"]
        tm = cf * pm
        tr = _up(np.abs(cf) * pr + U * np.abs(cf) * np.abs(pm) + U * np.abs(tm))
        n = len(ctable.conditions)
        owner = arr["owner"]
        mid = np.bincount(owner, weights=tm, minlength=n)
        absum = np.bincount(owner, weights=np.abs(tm), minlength=n)
        rad = np.bincount(owner, weights=tr, minlength=n)
        counts = arr["counts"]
        g = counts * U / (1 - counts * U)
        rad = _up(rad + g * absum)
        # floats are exact dyadic rationals: no Fraction objects on this fast path
        return [Enclosure(m, r, False) for m, r in zip(mid.tolist(), rad.tolist())]

    def enclose_terms(self, table: RootedTreeTable, terms, scale: int) -> Enclosure:
        """One condition (the per-condition path of the backend protocol), in scalar
        floats with the same bounds as :meth:`enclose_table`."""
        a_m, a_r = self.tree_weights(table)
        mid = rad = absum = 0.0
        for term in terms:
            pm, pr = 1.0, 0.0
            for t in term.branches:
                qm, qr = float(a_m[t]), float(a_r[t])
                new_m = pm * qm
                pr = (abs(pm) * qr + abs(qm) * pr + pr * qr + U * abs(new_m)) * INFLATE + ETA
                pm = new_m
            cf = term.sign / term.sigma
            tm = cf * pm
            rad += (abs(cf) * pr + U * abs(cf) * abs(pm) + U * abs(tm)) * INFLATE + ETA
            mid += tm
            absum += abs(tm)
        rad = (rad + gamma(len(terms)) * absum) * INFLATE + ETA
        return Enclosure(mid, rad, False)

    def weight_minus(self, table: RootedTreeTable, t: int, value: Fraction) -> Enclosure:
        a_m, a_r = self.tree_weights(table, table.order[t])
        v = float(value)
        m = a_m[t] - v
        r = (a_r[t] + U * abs(v) + U * abs(m)) * INFLATE + ETA
        return Enclosure(Fraction(float(m)), Fraction(float(r)), False)


def make_float_backend(tableau, decimals: str = "rounded") -> FloatBackend:
    A, b = tableau.enclosures(128, decimals)
    return FloatBackend(A, b)
