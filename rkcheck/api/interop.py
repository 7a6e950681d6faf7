"""nodepy interoperability: its ``RungeKuttaMethod`` objects in and out.

nodepy (optional: ``pip install "rkcheck[nodepy]"``, never a core dependency) keeps a
method's ``A`` and ``b`` as numpy arrays of sympy numbers (exact: ``1/6``,
``1/4 - sqrt(3)/6``) or of floats.  :func:`from_nodepy` reads them with the rules of
:func:`~rkcheck.api.tableaux.from_arrays` (sympy numbers exactly, floats as the decimals
they print as — what ``rkcheck verify`` reads in a JSON file of the same floats —, or
with ``floats="exact"`` at their exact binary values); :func:`to_nodepy` builds a
nodepy method whose entries are exact sympy numbers, constructed from rkcheck's parsed
entries node by node (no string is ever evaluated).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from rkcheck.api.tableaux import from_arrays
from rkcheck.errors import TableauError
from rkcheck.methods.arrays import FloatMode
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers import grammar as ex


def from_nodepy(method: Any, *, floats: FloatMode = "shortest") -> Tableau:
    """A tableau from a nodepy ``RungeKuttaMethod`` (or anything with ``A``, ``b`` and
    optionally ``c`` and ``name``); for an embedded pair, its main method ``b``."""
    for attribute in ("A", "b"):
        if not hasattr(method, attribute):
            raise TableauError(f"expected a Runge–Kutta method with A and b, got {type(method).__name__}")
    c = getattr(method, "c", None)
    name = str(getattr(method, "name", None) or "nodepy method")
    return from_arrays(method.A, method.b, c, name=name, floats=floats)


def to_sympy(node: ex.Expr, constants: dict[str, ex.Expr]) -> Any:
    """An entry's expression as an exact sympy number, built node by node."""
    import sympy

    def go(n: ex.Expr) -> Any:
        if isinstance(n, ex.Num):
            return sympy.Rational(n.value.numerator, n.value.denominator)
        if isinstance(n, ex.Name):
            return go(constants[n.name])
        if isinstance(n, ex.Unary):
            return -go(n.operand)
        if isinstance(n, ex.Power):
            return go(n.base) ** go(n.exponent)
        if isinstance(n, ex.Call):
            if n.func == "sqrt":
                return sympy.sqrt(go(n.arg))
            raise TableauError(f"{n.func}(…) has no exact sympy form here; use the tableau file")
        assert isinstance(n, ex.Binary)
        left, right = go(n.left), go(n.right)
        return {"+": left + right, "-": left - right, "*": left * right}[n.op] if n.op != "/" else left / right

    return go(node)


def to_nodepy(tableau: Tableau) -> Any:
    """A nodepy ``RungeKuttaMethod`` (``ExplicitRungeKuttaMethod`` when A is strictly
    lower triangular) with exact sympy entries.  Needs nodepy installed."""
    try:
        import numpy as np
        from nodepy import runge_kutta_method as rk
    except ImportError as err:
        raise TableauError(f"nodepy is not installed ({err}); pip install 'rkcheck[nodepy]'") from None
    if tableau.info.family is not None and not tableau.is_rational:
        raise TableauError("a family computed at the working precision has no exact entries; write it with "
                           "rkcheck new first")
    consts = tableau.info.constants.definitions

    def value(e: Any) -> Any:
        import sympy

        if e.exact is not None:
            q = Fraction(e.exact)
            return sympy.Rational(q.numerator, q.denominator)
        return to_sympy(e.node, consts)

    A = np.array([[value(e) for e in row] for row in tableau.A], dtype=object)
    b = np.array([value(e) for e in tableau.b], dtype=object)
    cls = rk.ExplicitRungeKuttaMethod if tableau.structure == "explicit" else rk.RungeKuttaMethod
    return cls(A=A, b=b, name=tableau.name)


__all__ = ["from_nodepy", "to_nodepy"]
