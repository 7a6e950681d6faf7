"""The modular route for a tableau given as polynomials in its nodes
(:class:`~rkcheck.methods.node_form.NodeForm`): its conditions are rational, so they are
computed over Q at primes that split the node polynomial, without the nodes' field.

The conditions of such a tableau are rational (the node form's docstring), and ``e``
(:meth:`NodeForm.integrality_scale`) makes every entry an algebraic integer, so
``N = (n−1)!·e^(n−1)·R`` of a condition R is a rational algebraic integer: an integer,
bounded in absolute value by its bound in any one complex embedding (module docstring
of :mod:`rkcheck.evaluation.modular`, with ``M`` taken there).  Modulo a prime p that
divides no denominator of P, F or W and over which P splits into distinct linear
factors, p is unramified and splits completely in the nodes' field; reducing modulo a
prime ideal above it maps the nodes onto the roots of P modulo p, in some order.  The
entries' images are then ``e·F(r_i, r_j)`` and ``e·W(r_j)`` at those roots, and since N
does not depend on how the stages are numbered, any order gives N modulo p.  One channel
per prime, of ``s`` stages: the tableau is evaluated as a rational one is.

Over the field the same conditions need its degree-48 arithmetic (for the six Gauss-6
nodes) to scale the entries, bound them in every embedding and find their integrality
denominator from their minimal polynomials; here the conditions need none of it (the
field is still built for the properties that are computed in it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from rkcheck.evaluation.scaled import ScaledTableau
from rkcheck.methods.node_form import NodeForm
from rkcheck.numbers.polynomials import integer_coefficients


@dataclass
class SplitNodeTableau(ScaledTableau):
    """A :class:`ScaledTableau` over Q (``minpoly = x``, one channel per prime) whose
    images modulo p come from the roots of the node polynomial (module docstring)."""

    form: NodeForm | None = None

    @property
    def s(self) -> int:
        assert self.form is not None
        return self.form.stages

    def _roots_mod(self, p: int) -> list[int] | None:
        """``[0]`` (the prime's one channel) when p splits the node polynomial into
        distinct linear factors and divides none of the form's denominators."""
        from flint import nmod_poly

        if self._bad % p == 0:
            return None
        P = nmod_poly(self._integer_P, p)  # p divides no denominator: the same roots as P
        x = nmod_poly([0, 1], p)
        if x.pow_mod(p, P) != x:  # P | x^p − x: distinct roots, all in F_p
            return None
        roots = [int(r) for r, _ in P.roots()]
        self.__dict__.setdefault("_node_roots", {})[p] = roots
        return [0]

    @property
    def _integer_P(self) -> list[int]:
        found = self.__dict__.get("_integer_P_value")
        if found is None:
            found = self.__dict__["_integer_P_value"] = integer_coefficients(self._form.P)
        return found

    @property
    def _form(self) -> NodeForm:
        assert self.form is not None
        return self.form

    @property
    def _bad(self) -> int:
        """The product of every denominator of P and of e·F, e·W: a prime dividing it
        is not used."""
        bad = self.__dict__.get("_bad_value")
        if bad is None:
            e = self.d
            dens = [c.denominator for c in self._form.P] + [(e * c).denominator for _, c in self._form.F]
            dens += [(e * c).denominator for _, c in self._form.W]
            bad = self.__dict__["_bad_value"] = math.prod(set(dens)) * e
        return bad

    def _images(self, p: int, root: int) -> tuple[np.ndarray, np.ndarray]:
        """``e·F(r_i, r_j)`` and ``e·W(r_j)`` modulo p at the node roots r."""
        cache = self.__dict__.setdefault("_image_cache", {})
        if p not in cache:
            cache.clear()  # primes are visited one after another: keep one
            roots = self.__dict__.get("_node_roots", {}).get(p)
            if roots is None:
                assert self._roots_mod(p) is not None, "a channel prime must split the node polynomial"
                roots = self.__dict__["_node_roots"][p]
            n, e = self.s, self.d
            powers = [[pow(r, k, p) for k in range(n)] for r in roots]
            G = [[0] * n for _ in range(n)]
            for (row, col), c in self._form.F:
                G[row][col] = _mod(e * c, p)
            w = [0] * n
            for k, c in self._form.W:
                w[k] = _mod(e * c, p)
            # Σ_a r_i^a Σ_b G_ab r_j^b: the inner sums once per node
            inner = [[sum(G[a][k] * pj[k] for k in range(n)) % p for a in range(n)] for pj in powers]
            A = np.array([[sum(pi[a] * inner[j][a] for a in range(n)) % p for j in range(n)] for pi in powers],
                         dtype=np.int64)
            b = np.array([sum(wk * pj[k] for k, wk in enumerate(w)) % p for pj in powers], dtype=np.int64)
            cache[p] = (A, b)
        found: tuple[np.ndarray, np.ndarray] = cache[p]
        return found

    def channel_sources(self, p: int) -> list[int]:
        return [0]


def _mod(q: Fraction, p: int) -> int:
    return q.numerator % p * pow(q.denominator, -1, p) % p


def scaled_nodes(form: NodeForm) -> SplitNodeTableau:
    """The modular data of a tableau in node form (module docstring): ``d = e``, and
    ``log₂ M`` bounded with certified balls at the complex roots of P."""
    e = form.integrality_scale()
    return SplitNodeTableau(A=[], b=[], d=e, minpoly=[0, 1], log2_M=_log2_bound(form, e) + 1e-9, form=form)


def _log2_bound(form: NodeForm, e: int) -> float:
    """An upper bound of ``log₂ max(1, max_i Σ_j |e·A_ij|, Σ_j |e·b_j|)`` at the complex
    roots of P (any numbering: every embedding gives a condition the same value)."""
    from flint import acb, arb, ctx

    from rkcheck.evaluation.field_bounds import log2_upper
    from rkcheck.numbers.polynomials import complex_roots

    integer = integer_coefficients(form.P)
    prec = 128
    while True:
        with ctx.workprec(prec):
            roots = complex_roots(integer, prec)
            powers = [[r**k for k in range(len(form.P))] for r in roots]

            def scaled(terms: Any) -> list[tuple[Any, Any]]:  # e·coefficient as a ball, once per precision
                return [(k if isinstance(k, tuple) else (k,), acb((e * c).numerator) / (e * c).denominator)
                        for k, c in terms]

            F, W = scaled(form.F), scaled(form.W)

            def value(terms: list[tuple[Any, Any]], *at: int) -> Any:
                total = acb(0)
                for ks, c in terms:
                    for i, k in zip(at, ks):
                        c = c * powers[i][k]
                    total += c
                return total

            n = len(roots)
            rows = [sum((abs(value(F, i, j)) for j in range(n)), arb(0)) for i in range(n)]
            rows.append(sum((abs(value(W, j)) for j in range(n)), arb(0)))
            if all(x.is_finite() for x in rows) or prec >= 1 << 12:
                return max(0.0, max(log2_upper(x) for x in rows))
        prec *= 2
