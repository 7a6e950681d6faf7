"""The classical methods a user reaches for first, with exact entries from the literature.

Each :class:`Classic` is plain data: the Butcher tableau as exact entry texts, where it
comes from, and claims derived by hand from theory (not from a run of rkcheck):

* ``classical_order`` p: the order conditions of the cited source;
* ``quadrature_order`` q: the largest q with ``Σ b_i c_i^(k−1) = 1/k`` for k = 1…q
  (definitions §4), worked out from the nodes and weights;
* ``energy_order`` for degree 2 from the stability function: for quadratic H every
  condition is an odd path (definitions §3) and energy is preserved to order n iff
  ``R(z)R(−z) = 1 + O(z^(n+2))`` (for odd n the first term cannot be odd), so the
  energy order is the exponent of the first nonzero term of ``R(z)R(−z) − 1`` minus 1,
  or ``all`` when ``R(z)R(−z) ≡ 1``.  The series are written next to each method.

``rkcheck new NAME`` writes these as TOML files; ``@NAME`` loads them when no shipped
file has that name.  The tests check every claim by a second route (exact brute-force
order conditions, sympy series of the stability function).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rkcheck.methods.tableau import MethodInfo, Tableau


@dataclass(frozen=True)
class Classic:
    """One classical method: exact entries (strings in rkcheck's grammar) and claims."""

    key: str
    name: str
    description: str
    references: tuple[str, ...]
    A: tuple[tuple[str, ...], ...]
    b: tuple[str, ...]
    classical_order: int
    quadrature_order: int
    energy_order_quadratic: int | str  # from R(z)R(−z), see the module docstring
    constants: dict[str, str] = field(default_factory=dict)
    aliases: tuple[str, ...] = ()
    nodes: tuple[str, ...] | None = None  # c as the source writes it, when A is not rational

    @property
    def c(self) -> tuple[str, ...]:
        """The nodes: the row sums ``A·1`` (definitions §1), exact for rational rows."""
        if self.nodes is not None:
            return self.nodes
        return tuple(str(sum((Fraction(x) for x in row), Fraction(0))) for row in self.A)

    def expect(self) -> dict[str, Any]:
        """The ``[expect]`` table of the claims above."""
        return {
            "energy_order": [{"degree": 2, "value": self.energy_order_quadratic}],
            "classical_order": self.classical_order,
            "quadrature_order": self.quadrature_order,
        }

    def document(self) -> dict[str, Any]:
        """The method as a tableau document (the structure of a TOML/JSON tableau file)."""
        doc: dict[str, Any] = {
            "method": {"name": self.name, "description": self.description, "references": list(self.references)},
        }
        if self.constants:
            doc["constants"] = dict(self.constants)
        doc["tableau"] = {"A": [list(r) for r in self.A], "b": list(self.b), "c": list(self.c)}
        doc["expect"] = self.expect()
        return doc


def _c(*rows: tuple[str, ...]) -> tuple[tuple[str, ...], ...]:
    return tuple(rows)


# Butcher, Numerical Methods for ODEs (Wiley 2016), §23 and §32; Hairer–Nørsett–Wanner,
# Solving ODEs I (Springer 1993), §II.1; Hairer–Wanner, Solving ODEs II (1996), §IV.6.
CLASSICS: dict[str, Classic] = {c.key: c for c in (
    Classic(
        "euler", "Explicit Euler", "The forward Euler method: order 1, one stage.",
        ("L. Euler, Institutionum calculi integralis, 1768",),
        _c(("0",)), ("1",), 1, 1, 1, aliases=("forward-euler", "explicit-euler"),
        # R = 1 + z: R(z)R(−z) = 1 − z²
    ),
    Classic(
        "backward-euler", "Implicit (backward) Euler", "Radau IIA with one stage: order 1, L-stable.",
        ("E. Hairer, G. Wanner, Solving ODEs II, Springer 1996, Section IV.5",),
        _c(("1",)), ("1",), 1, 1, 1, aliases=("implicit-euler",),
        # R = 1/(1 − z): R(z)R(−z) = 1/(1 − z²) = 1 + z² + …
    ),
    Classic(
        "midpoint", "Explicit midpoint rule", "Runge's 2-stage, order-2 method (modified Euler).",
        ("C. Runge, Math. Ann. 46 (1895) 167-178",),
        _c(("0", "0"), ("1/2", "0")), ("0", "1"), 2, 2, 3, aliases=("explicit-midpoint", "runge"),
        # R = 1 + z + z²/2: R(z)R(−z) = 1 + z⁴/4
    ),
    Classic(
        "heun", "Heun's method (explicit trapezoidal rule)", "Heun's 2-stage, order-2 method.",
        ("K. Heun, Z. Math. Phys. 45 (1900) 23-38",),
        _c(("0", "0"), ("1", "0")), ("1/2", "1/2"), 2, 2, 3, aliases=("heun2", "explicit-trapezoid"),
    ),
    Classic(
        "ralston", "Ralston's method", "The 2-stage, order-2 method with minimal error bound (c₂ = 2/3).",
        ("A. Ralston, Math. Comp. 16 (1962) 431-437",),
        # quadrature: Σbc = 3/4·2/3 = 1/2, Σbc² = 3/4·4/9 = 1/3, Σbc³ = 2/9 ≠ 1/4 → 3
        _c(("0", "0"), ("2/3", "0")), ("1/4", "3/4"), 2, 3, 3,
    ),
    Classic(
        "rk3", "Kutta's third-order method", "Kutta's 3-stage, order-3 method (Simpson weights).",
        ("W. Kutta, Z. Math. Phys. 46 (1901) 435-453",),
        _c(("0", "0", "0"), ("1/2", "0", "0"), ("-1", "2", "0")), ("1/6", "2/3", "1/6"), 3, 4, 3,
        aliases=("kutta3",),
        # R = 1 + z + z²/2 + z³/6: R(z)R(−z) = 1 − z⁴/12 − z⁶/36
    ),
    Classic(
        "ssprk3", "SSPRK(3,3) (Shu–Osher)", "The optimal 3-stage, order-3 strong-stability-preserving method.",
        ("C.-W. Shu, S. Osher, J. Comput. Phys. 77 (1988) 439-471",),
        _c(("0", "0", "0"), ("1", "0", "0"), ("1/4", "1/4", "0")), ("1/6", "1/6", "2/3"), 3, 4, 3,
    ),
    Classic(
        "rk4", "Classical Runge–Kutta (RK4)", "Kutta's 4-stage, order-4 explicit method.",
        ("W. Kutta, Z. Math. Phys. 46 (1901) 435-453",),
        _c(("0", "0", "0", "0"), ("1/2", "0", "0", "0"), ("0", "1/2", "0", "0"), ("0", "0", "1", "0")),
        ("1/6", "1/3", "1/3", "1/6"), 4, 4, 5,
        # R = Σ_(k≤4) z^k/k!: R(z)R(−z) = 1 + z⁶/72 + …
    ),
    Classic(
        "rk38", "Kutta's 3/8 rule", "Kutta's other 4-stage, order-4 method (Simpson's 3/8 weights).",
        ("W. Kutta, Z. Math. Phys. 46 (1901) 435-453",),
        # quadrature: Simpson 3/8 integrates cubics exactly, Σbc⁴ = 11/54 ≠ 1/5 → 4
        _c(("0", "0", "0", "0"), ("1/3", "0", "0", "0"), ("-1/3", "1", "0", "0"), ("1", "-1", "1", "0")),
        ("1/8", "3/8", "3/8", "1/8"), 4, 4, 5, aliases=("rk4-38", "three-eighths"),
    ),
    Classic(
        "implicit-midpoint", "Implicit midpoint rule", "Gauss collocation with one stage: order 2, symplectic.",
        ("E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration, Springer 2006, Section II.1",),
        _c(("1/2",)), ("1",), 2, 2, "all",
        # R = (1 + z/2)/(1 − z/2): R(z)R(−z) ≡ 1
    ),
    Classic(
        "trapezoid", "Implicit trapezoidal rule", "Lobatto IIIA with two stages (Crank–Nicolson): order 2.",
        ("E. Hairer, G. Wanner, Solving ODEs II, Springer 1996, Section IV.5",),
        _c(("0", "0"), ("1/2", "1/2")), ("1/2", "1/2"), 2, 2, "all", aliases=("crank-nicolson", "trapezoidal"),
        # R = (1 + z/2)/(1 − z/2): R(z)R(−z) ≡ 1
    ),
    Classic(
        "sdirk2", "SDIRK, 2 stages, order 2 (Alexander)",
        "Alexander's L-stable, stiffly accurate SDIRK method with γ = 1 − √2/2.",
        ("R. Alexander, SIAM J. Numer. Anal. 14 (1977) 1006-1021",),
        _c(("g", "0"), ("1 - g", "g")), ("1 - g", "g"), 2, 2, 3, constants={"g": "1 - sqrt(2)/2"}, nodes=("g", "1"),
        # quadrature: Σbc = 2g − g² = 1/2 (g² = 2g − 1/2), Σbc² = (1−g)g² + g ≠ 1/3 → 2
        # order 2 makes R(z)R(−z) = 1 + O(z⁴); its z⁴ coefficient is 3√2 − 17/4 ≠ 0 → 3
    ),
    Classic(
        "sdirk3", "SDIRK, 2 stages, order 3 (Crouzeix, Nørsett)",
        "The 2-stage, order-3 SDIRK method with γ = (3 + √3)/6 (A-stable).",
        ("M. Crouzeix, thesis, Paris 1975; S. P. Nørsett, report, Trondheim 1974",
         "E. Hairer, G. Wanner, Solving ODEs II, Springer 1996, Table IV.6.1"),
        _c(("g", "0"), ("1 - 2*g", "g")), ("1/2", "1/2"), 3, 4, 3, constants={"g": "1/2 + sqrt(3)/6"},
        nodes=("g", "1 - g"),
        # nodes g and 1 − g are the 2-point Gauss nodes: quadrature order 4
    ),
)}

#: every accepted name (keys and aliases) -> key
NAMES: dict[str, str] = {**{c.key: c.key for c in CLASSICS.values()},
                         **{a: c.key for c in CLASSICS.values() for a in c.aliases}}


def classic(name: str) -> Classic | None:
    """The classic called ``name`` (a key or an alias, any case), or None."""
    key = NAMES.get(name.strip().lower())
    return CLASSICS[key] if key else None


def classic_tableau(name: str) -> Tableau:
    """The classic as a :class:`Tableau` with its claims (for ``@name`` and the API)."""
    from rkcheck.methods.claims import parse_claims
    from rkcheck.numbers import grammar as ex
    from rkcheck.numbers.entries import Constants, Entry

    spec = classic(name)
    if spec is None:
        raise KeyError(name)
    constants = Constants({k: ex.parse(v) for k, v in spec.constants.items()})
    A = tuple(tuple(Entry.parse(x, constants) for x in row) for row in spec.A)
    b = tuple(Entry.parse(x, constants) for x in spec.b)
    c = tuple(Entry.parse(x, constants) for x in spec.c)
    expect = spec.expect()
    info = MethodInfo(description=spec.description, references=tuple(spec.references), source=f"@{spec.key}",
                      constants=constants, expect=expect, claims=tuple(parse_claims(expect)))
    return Tableau(A=A, b=b, c=c, name=spec.name, info=info)
