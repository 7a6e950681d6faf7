"""Entry expressions rendered as code: LaTeX, Julia and Python, each exact
(:mod:`rkcheck.io.formats` writes whole tableaux with them)."""

from __future__ import annotations

from typing import Iterable

from rkcheck.errors import UserError
from rkcheck.numbers import grammar as ex


class NoExactForm(UserError):
    """A function of the entries that the output format cannot write exactly."""

    def __init__(self, func: str):
        super().__init__(f"{func}(…) has no exact form in this output format; write the tableau as TOML or JSON"
                         + (" (or as Python: sympy's CRootOf)" if func == "root" else ""))
        self.func = func


_PREC = {"+": 1, "-": 1, "*": 2, "/": 2}


class Code:
    """Renders an entry expression in another language; subclasses say how."""

    sqrt = "sqrt"

    def number(self, n: ex.Num) -> str:
        return str(n.value) if n.value.denominator == 1 else f"{n.value.numerator}/{n.value.denominator}"

    #: names the written code defines or uses itself, besides the language's keywords
    reserved: frozenset[str] = frozenset({"A", "b", "c"})
    names: dict[str, str] = {}

    def identifiers(self, constants: Iterable[str]) -> dict[str, str]:
        """Each constant's name in the written code: a keyword (``None``, ``import``,
        ``end``) or a name the code uses (``Fraction``, ``A``) gets underscores appended
        until it is free."""
        taken = set(constants)
        out = {}
        for name in constants:
            new = name
            while new in self.reserved or self.is_keyword(new) or (new != name and new in taken):
                new += "_"
            taken.add(new)
            out[name] = new
        self.names = out
        return out

    def is_keyword(self, name: str) -> bool:
        return False

    def name(self, n: ex.Name) -> str:
        return self.names.get(n.name, n.name)

    def div(self, left: str, right: str) -> str:
        return f"{left}/{right}"

    def power(self, base: str, exponent: str) -> str:
        return f"{base}^{exponent}"

    def call(self, func: str, args: list[str]) -> str:
        if func != "sqrt":
            raise NoExactForm(func)
        return f"{self.sqrt}({args[0]})"

    def paren(self, text: str) -> str:
        return f"({text})"

    def mul(self, left: str, right: str) -> str:
        return f"{left}*{right}"

    def render(self, node: ex.Expr, parent: int = 0) -> str:
        node = _fold_fraction(node)
        if isinstance(node, ex.Num):
            text = self.number(node)
            return self.paren(text) if parent >= 2 and "/" in text else text
        if isinstance(node, ex.Name):
            return self.name(node)
        if isinstance(node, ex.Call):
            return self.call(node.func, [self.render(a, 0) for a in node.args])
        if isinstance(node, ex.Unary):
            text = "-" + self.render(node.operand, 3)
            return self.paren(text) if parent >= 2 else text
        if isinstance(node, ex.Power):
            text = self.power(self.render(node.base, 4), self.render(node.exponent, 3))
            return self.paren(text) if parent >= 4 else text
        assert isinstance(node, ex.Binary)
        p = _PREC[node.op]
        left = self.render(node.left, p)
        # a negative right operand is parenthesised: 1 + (-1), x*(-y), never 1 + -1
        right = self.render(node.right, 2 if isinstance(node.right, ex.Unary) else (p + 1 if node.op in "-/" else p))
        text = self.div(left, right) if node.op == "/" else (
            f"{left} {node.op} {right}" if p == 1 else self.mul(left, right))
        return self.paren(text) if parent > p else text


_JULIA_KEYWORDS = frozenset(
    "baremodule begin break catch const continue do else elseif end export false finally for function global if "
    "import let local macro module quote return struct true try using while abstract mutable primitive type where "
    "outer".split())


def _is_integer(node: ex.Expr) -> bool:
    return isinstance(node, ex.Num) and node.digits is None and node.value.denominator == 1


def _fold_fraction(node: ex.Expr) -> ex.Expr:
    """``p/q`` of two integer literals is one rational literal (``Fraction(1, 4)``); so is
    ``-p/q`` (the parser reads it as ``(-p)/q``)."""
    if (isinstance(node, ex.Binary) and node.op == "/" and isinstance(node.left, ex.Unary)
            and _is_integer(node.left.operand) and _is_integer(node.right)):
        folded = _fold_fraction(ex.Binary("/", node.left.operand, node.right, node.column))
        if isinstance(folded, ex.Num):
            return ex.Num(-folded.value, str(-folded.value), None, 0)
    if (isinstance(node, ex.Binary) and node.op == "/" and _is_integer(node.left) and _is_integer(node.right)
            and isinstance(node.right, ex.Num) and node.right.value != 0 and isinstance(node.left, ex.Num)):
        value = node.left.value / node.right.value
        return ex.Num(value, str(value), None, 0)
    return node


class Julia(Code):
    """Julia: exact ``Rational{BigInt}`` literals (``big(1)//6``), ``sqrt(big(3))``."""

    reserved = frozenset({"A", "b", "c", "big", "sqrt", "pi", "im", "true", "false", "nothing", "missing", "Inf",
                          "NaN"})

    def is_keyword(self, name: str) -> bool:
        return name in _JULIA_KEYWORDS

    def number(self, n: ex.Num) -> str:
        v = n.value
        return f"big({v.numerator})" if v.denominator == 1 else f"big({v.numerator})//{v.denominator}"

    def div(self, left: str, right: str) -> str:
        return f"{left}/{right}"

    def call(self, func: str, args: list[str]) -> str:
        if func == "sqrt":
            return f"sqrt({args[0]})" if args[0].startswith("big(") else f"sqrt(big({args[0]}))"
        return super().call(func, args)


class Python(Code):
    """Python: ``Fraction`` literals; ``sympy.sqrt`` keeps square roots exact."""

    reserved = frozenset({"A", "b", "c", "Fraction", "sympy"})

    def is_keyword(self, name: str) -> bool:
        import keyword

        return keyword.iskeyword(name)

    sqrt = "sympy.sqrt"

    def call(self, func: str, args: list[str]) -> str:
        if func == "sqrt" and args[0].startswith("Fraction(") and "," not in args[0]:
            return f"sympy.sqrt({args[0][9:-1]})"  # an integer: sympy.sqrt(3)
        return super().call(func, args)

    def number(self, n: ex.Num) -> str:
        v = n.value
        return f"Fraction({v.numerator})" if v.denominator == 1 else f"Fraction({v.numerator}, {v.denominator})"

    def power(self, base: str, exponent: str) -> str:
        return f"{base}**{exponent}"

    def render(self, node: ex.Expr, parent: int = 0) -> str:
        if isinstance(node, ex.Call) and node.func == "root":
            # sympy's CRootOf indexes the real roots first, from the smallest: the k-th
            # smallest real root is CRootOf(p, k − 1), exact; the polynomial's x is its own
            saved, self.names = self.names, {**self.names, "x": 'sympy.Symbol("x")'}
            try:
                poly = super().render(node.args[0], 0)
            finally:
                self.names = saved
            k = node.args[1]
            index = f"{int(k.value) - 1}" if isinstance(k, ex.Num) else f"{super().render(k, 0)} - 1"
            return f"sympy.CRootOf({poly}, {index})"
        return super().render(node, parent)


class Latex(Code):
    """LaTeX math: ``\\frac``, ``\\sqrt``, powers with braces; constants inlined."""

    def __init__(self, constants: dict[str, ex.Expr]):
        self.constants = constants

    def number(self, n: ex.Num) -> str:
        v = n.value
        if n.digits is not None:  # a decimal stays the decimal it was
            return n.text
        sign = "-" if v < 0 else ""
        return str(v) if v.denominator == 1 else rf"{sign}\frac{{{abs(v.numerator)}}}{{{v.denominator}}}"

    def render(self, node: ex.Expr, parent: int = 0) -> str:
        node = _fold_fraction(node)
        if isinstance(node, ex.Name) and node.name in self.constants:
            return self.render(self.constants[node.name], parent)
        if isinstance(node, ex.Num) and node.digits is None:
            return self.number(node)  # \frac needs no parentheses
        if isinstance(node, ex.Binary) and node.op == "/":
            return rf"\frac{{{self.render(node.left, 0)}}}{{{self.render(node.right, 0)}}}"
        return super().render(node, parent)

    def paren(self, text: str) -> str:
        return rf"\left({text}\right)"

    def power(self, base: str, exponent: str) -> str:
        return f"{base}^{{{exponent}}}"

    def call(self, func: str, args: list[str]) -> str:
        if func == "sqrt":
            return rf"\sqrt{{{args[0]}}}"
        return rf"\operatorname{{{func}}}\left({', '.join(args)}\right)"

    def div(self, left: str, right: str) -> str:
        return rf"\frac{{{left}}}{{{right}}}"

    def mul(self, left: str, right: str) -> str:
        # a number before a command or a letter is written beside it (7\sqrt{6}), as in print
        if left.isdigit() and not right[:1].isdigit() and not right.startswith("\\frac"):
            return f"{left}{right}" if right.startswith("\\") else f"{left} {right}"
        return rf"{left} \cdot {right}"
