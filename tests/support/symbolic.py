"""An exact algebraic scalar backed by sympy, with the interface rkcheck's tableau-level
algebra expects of an exact number-field element (``+ − × ÷`` with ints and Fractions,
``is_zero()``, ``rational()``, ``enclosure(bits)``, ``text(style)``).

It lets the tests run the generic algebra of rkcheck.energy (reduction, AVF, stability,
symplecticity, symmetry) exactly on algebraic tableaux such as Gauss–Legendre, by an
independent (slow, symbolic) arithmetic.  Imports nothing from rkcheck except the
Interval type that ``enclosure`` must return.
"""

from __future__ import annotations

from fractions import Fraction

import sympy


def _sym(x):
    if isinstance(x, Sym):
        return x.e
    if isinstance(x, Fraction):
        return sympy.Rational(x.numerator, x.denominator)
    if isinstance(x, int):
        return sympy.Integer(x)
    return NotImplemented


class Sym:
    __slots__ = ("e",)

    def __init__(self, e):
        # canonical form in a quadratic field: denominators rationalised, expanded
        # (a + b√d), so that expressions do not grow through long computations
        self.e = sympy.expand(sympy.radsimp(sympy.expand(sympy.sympify(e))))

    def __add__(self, o):
        v = _sym(o)
        return NotImplemented if v is NotImplemented else Sym(self.e + v)

    __radd__ = __add__

    def __sub__(self, o):
        v = _sym(o)
        return NotImplemented if v is NotImplemented else Sym(self.e - v)

    def __rsub__(self, o):
        v = _sym(o)
        return NotImplemented if v is NotImplemented else Sym(v - self.e)

    def __mul__(self, o):
        v = _sym(o)
        return NotImplemented if v is NotImplemented else Sym(self.e * v)

    __rmul__ = __mul__

    def __truediv__(self, o):
        v = _sym(o)
        return NotImplemented if v is NotImplemented else Sym(self.e / v)

    def __rtruediv__(self, o):
        v = _sym(o)
        return NotImplemented if v is NotImplemented else Sym(v / self.e)

    def __neg__(self):
        return Sym(-self.e)

    def __abs__(self):
        return Sym(abs(self.e))

    def is_zero(self) -> bool:
        e = sympy.radsimp(sympy.expand(self.e))
        if e == 0:
            return True
        if e.is_Rational:
            return False
        z = sympy.nsimplify(sympy.simplify(e))
        return z == 0

    def rational(self):
        e = sympy.nsimplify(sympy.simplify(self.e)) if not self.e.is_Rational else self.e
        if e.is_Rational:
            return Fraction(int(e.p), int(e.q))
        return None

    def enclosure(self, bits: int):
        from rkcheck.numbers.intervals import Interval

        digits = bits * 30 // 100 + 10
        mid = sympy.Rational(sympy.N(self.e, digits))
        eps = sympy.Rational(1, 2 ** (bits - 4))
        return Interval(Fraction(int((mid - eps).p), int((mid - eps).q)), Fraction(int((mid + eps).p), int((mid + eps).q)))

    def text(self, style: str = "plain") -> str:
        return str(sympy.simplify(self.e))

    def __repr__(self) -> str:
        return f"Sym({self.e})"


def gauss(s: int):
    """The s-stage Gauss–Legendre collocation tableau over sympy (exact roots, s ≤ 3 in
    closed form): c = zeros of the shifted Legendre polynomial, a_ij = ∫₀^{c_i} ℓ_j,
    b_j = ∫₀¹ ℓ_j."""
    x = sympy.Symbol("x")
    P = sympy.legendre(s, 2 * x - 1)
    c = sorted(sympy.solve(P, x), key=lambda r: float(r))
    ell = []
    for j in range(s):
        p = sympy.Integer(1)
        for k in range(s):
            if k != j:
                p *= (x - c[k]) / (c[j] - c[k])
        ell.append(sympy.expand(p))
    A = [[Sym(sympy.integrate(ell[j], (x, 0, c[i]))) for j in range(s)] for i in range(s)]
    b = [Sym(sympy.integrate(ell[j], (x, 0, 1))) for j in range(s)]
    return A, b
