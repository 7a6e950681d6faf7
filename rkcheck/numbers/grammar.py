"""The entry grammar: a small recursive-descent parser of arithmetic expressions (definitions §5).

File content never reaches ``eval``/``exec``: entries are tokenised and parsed here into
a tiny AST that only knows numbers, named constants, ``+ - * / ^ **``, unary signs,
parentheses, ``sqrt(...)`` and ``root(p, k)`` (the k-th smallest real root of a
polynomial p in ``x`` with rational coefficients).  Grammar (``^`` and ``**`` are the same operator, right
associative, binding tighter than unary minus, so ``-2^2 = -4`` and ``2^-1 = 1/2``)::

    expr   := term  (('+' | '-') term)*
    term   := unary (('*' | '/') unary)*
    unary  := ('+' | '-') unary | power
    power  := atom (('^' | '**') unary)?
    atom   := NUMBER | NAME | FUNC '(' expr (',' expr)* ')' | '(' expr ')'
    FUNC   := 'sqrt' (one argument) | 'root' (two: root(p, k))

Numbers are integers, decimals (``0.25``, ``.5``, ``2.``) and scientific notation
(``1.5e-3``).  A decimal literal keeps the number of significant digits it was
written with, which definitions §5 uses as its precision.

Hostile input is refused early and cheaply: entries longer than
:data:`MAX_ENTRY_LENGTH` characters, nesting deeper than :data:`MAX_DEPTH`, exponents
outside ``±MAX_EXPONENT`` and powers whose exact result would exceed
:data:`MAX_BITS` bits.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Mapping

from rkcheck.errors import UserError
from rkcheck.numbers.intervals import Interval, exact_sqrt

MAX_ENTRY_LENGTH = 20_000
MAX_DEPTH = 100
MAX_EXPONENT = 1000
MAX_DECIMAL_EXPONENT = 1000
MAX_BITS = 200_000

#: A decimal literal with at least this many significant digits is, by default, read as
#: "rounded to its last digit" (definitions §5).  Shorter decimals such as 0.5, 0.25 or 0.125
#: are read exactly: see README "Decimals" for why (a literal reading of the definition would make
#: ``0.5`` mean [0.45, 0.55]).
ROUNDED_MIN_DIGITS = 6

_NUMBER = re.compile(r"(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
#: Functions and their number of arguments.  ``root(p, k)`` is the k-th smallest real root
#: of the polynomial p in the variable :data:`ROOT_VARIABLE` (rational coefficients).
FUNCTIONS = {"sqrt": 1, "root": 2}
ROOT_VARIABLE = "x"


# --------------------------------------------------------------------------- AST


@dataclass(frozen=True, slots=True)
class Num:
    """A literal.  ``digits`` = significant digits of a decimal literal, None for integers."""

    value: Fraction
    text: str
    digits: int | None
    last_digit_exponent: int  # the written number is an integer multiple of 10**this

    @property
    def is_rounded_decimal(self) -> bool:
        return self.digits is not None and self.digits >= ROUNDED_MIN_DIGITS

    @property
    def half_unit(self) -> Fraction:
        """Half a unit in the last written digit: the rounding radius of definitions §5."""
        return Fraction(1, 2) * Fraction(10) ** self.last_digit_exponent

    @property
    def is_decimal(self) -> bool:
        """A nonzero decimal literal (``0.5``, ``1.0``, ``2e-3``): in ``--decimals float64``
        it stands for a double.  Zero stays exact in every mode (it carries structure:
        explicit methods, diagonal blocks)."""
        return self.digits is not None and self.value != 0

    def interval(self, decimals: str) -> tuple[Fraction, Fraction] | None:
        """The numbers this literal stands for under a decimals mode (definitions §5.2),
        as ``(lo, hi)``; None when it is exact in that mode.

        * ``exact``: every literal at face value;
        * ``rounded``: a decimal with at least :data:`ROUNDED_MIN_DIGITS` significant
          digits is within half a unit of its last digit;
        * ``float64``: every nonzero decimal is the double nearest to it, and stands for
          that double's rounding interval (every real that rounds to it);
        * ``auto``: as ``rounded``, widened to the double's rounding interval when the
          literal is the shortest representation of a double (what Python, numpy and
          Julia print): ``0.16666666666666666`` then covers 1/6.
        """
        if decimals == "exact":
            return None
        if decimals == "float64":
            return double_interval(self.value) if self.is_decimal else None
        if not self.is_rounded_decimal:
            return None
        h = self.half_unit
        lo, hi = self.value - h, self.value + h
        if decimals == "auto":
            d = double_interval(self.value, shortest_only=True)
            if d is not None:
                lo, hi = min(lo, d[0]), max(hi, d[1])
        return lo, hi


def double_interval(value: Fraction, shortest_only: bool = False) -> tuple[Fraction, Fraction] | None:
    """The rounding interval of the binary64 double nearest to ``value``: the closed
    interval of reals that round to it (half an ulp each side; the spacing below a power
    of two is half the spacing above).  None when ``value`` is outside the range of
    doubles, or, with ``shortest_only``, when ``value`` is not the shortest decimal
    representation of that double (``repr``)."""
    try:
        f = float(value)  # correctly rounded (Fraction.__float__ divides exactly)
    except OverflowError:
        return None
    if not math.isfinite(f) or f == 0:
        return None
    if shortest_only and Fraction(repr(f)) != value:
        return None
    x = Fraction(f)
    lo = (x + Fraction(math.nextafter(f, -math.inf))) / 2
    hi = (x + Fraction(math.nextafter(f, math.inf))) / 2
    return lo, hi


@dataclass(frozen=True, slots=True)
class Name:
    name: str
    column: int


@dataclass(frozen=True, slots=True)
class Unary:
    op: str  # '-' only; unary '+' is dropped by the parser
    operand: "Expr"


@dataclass(frozen=True, slots=True)
class Binary:
    op: str  # '+', '-', '*', '/'
    left: "Expr"
    right: "Expr"
    column: int


@dataclass(frozen=True, slots=True)
class Power:
    base: "Expr"
    exponent: "Expr"
    column: int


@dataclass(frozen=True, slots=True)
class Call:
    """``sqrt(a)`` or ``root(p, k)``: a function of one or more arguments."""

    func: str
    args: tuple["Expr", ...]
    column: int

    @property
    def arg(self) -> "Expr":
        """The first argument (the only one of ``sqrt``)."""
        return self.args[0]


Expr = Num | Name | Unary | Binary | Power | Call


# ----------------------------------------------------------------------- tokens


@dataclass(frozen=True, slots=True)
class _Token:
    kind: str  # 'num', 'name', 'op', '(', ')', 'end'
    text: str
    column: int  # 1-based


def _tokenize(text: str) -> list[_Token]:
    tokens: list[_Token] = []
    i, n = 0, len(text)
    depth = 0
    while i < n:
        ch = text[i]
        col = i + 1
        if ch.isspace():
            i += 1
            continue
        if ch.isdigit() or (ch == "." and i + 1 < n and text[i + 1].isdigit()):
            m = _NUMBER.match(text, i)
            assert m is not None
            tokens.append(_Token("num", m.group(0), col))
            i = m.end()
            continue
        if ch.isalpha() or ch == "_":
            m = _NAME.match(text, i)
            assert m is not None
            tokens.append(_Token("name", m.group(0), col))
            i = m.end()
            continue
        if text.startswith("**", i):
            tokens.append(_Token("op", "^", col))
            i += 2
            continue
        if ch in "+-*/^":
            tokens.append(_Token("op", ch, col))
            i += 1
            continue
        if ch == "(":
            depth += 1
            if depth > MAX_DEPTH:
                raise UserError(f"parentheses nested deeper than {MAX_DEPTH} at column {col}")
            tokens.append(_Token("(", ch, col))
            i += 1
            continue
        if ch == ")":
            depth -= 1
            tokens.append(_Token(")", ch, col))
            i += 1
            continue
        if ch == ",":
            tokens.append(_Token(",", ch, col))
            i += 1
            continue
        raise UserError(f"unexpected character {ch!r} at column {col}")
    tokens.append(_Token("end", "", n + 1))
    return tokens


# ----------------------------------------------------------------------- parser


class _Parser:
    def __init__(self, text: str):
        self.text = text
        self.tokens = _tokenize(text)
        self.pos = 0
        self.depth = 0

    def peek(self) -> _Token:
        return self.tokens[self.pos]

    def take(self) -> _Token:
        tok = self.tokens[self.pos]
        self.pos += 1
        return tok

    def fail(self, tok: _Token) -> UserError:
        if tok.kind == "end":
            return UserError(f"unexpected end of expression at column {tok.column}")
        return UserError(f"unexpected {tok.text!r} at column {tok.column}")

    def descend(self, tok: _Token) -> None:
        # Unary chains ('- - - 1') nest without parentheses; bound them too.
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise UserError(f"expression nested deeper than {MAX_DEPTH} at column {tok.column}")

    def parse(self) -> Expr:
        if self.peek().kind == "end":
            raise UserError("empty expression")
        node = self.expr()
        tok = self.peek()
        if tok.kind != "end":
            raise self.fail(tok)
        return node

    def expr(self) -> Expr:
        node = self.term()
        while self.peek().kind == "op" and self.peek().text in "+-":
            tok = self.take()
            node = Binary(tok.text, node, self.term(), tok.column)
        return node

    def term(self) -> Expr:
        node = self.unary()
        while self.peek().kind == "op" and self.peek().text in "*/":
            tok = self.take()
            node = Binary(tok.text, node, self.unary(), tok.column)
        return node

    def unary(self) -> Expr:
        tok = self.peek()
        if tok.kind == "op" and tok.text in "+-":
            self.take()
            self.descend(tok)
            operand = self.unary()
            self.depth -= 1
            return operand if tok.text == "+" else Unary("-", operand)
        return self.power()

    def power(self) -> Expr:
        base = self.atom()
        tok = self.peek()
        if tok.kind == "op" and tok.text == "^":
            self.take()
            self.descend(tok)
            exponent = self.unary()
            self.depth -= 1
            return Power(base, exponent, tok.column)
        return base

    def atom(self) -> Expr:
        tok = self.take()
        if tok.kind == "num":
            return _number(tok)
        if tok.kind == "name":
            if self.peek().kind == "(":
                if tok.text not in FUNCTIONS:
                    known = ", ".join(FUNCTIONS)
                    raise UserError(f"unknown function {tok.text!r} at column {tok.column} (known: {known})")
                self.take()
                args = [self.expr()]
                while self.peek().kind == ",":
                    self.take()
                    args.append(self.expr())
                close = self.take()
                if close.kind != ")":
                    raise self.fail(close)
                want = FUNCTIONS[tok.text]
                if len(args) != want:
                    shape = "sqrt(a)" if tok.text == "sqrt" else "root(p, k)"
                    raise UserError(f"{tok.text} takes {want} argument{'s' if want > 1 else ''} ({shape}) "
                                    f"at column {tok.column}")
                return Call(tok.text, tuple(args), tok.column)
            if tok.text in FUNCTIONS:
                raise UserError(f"{tok.text} needs parentheses at column {tok.column}")
            return Name(tok.text, tok.column)
        if tok.kind == "(":
            node = self.expr()
            close = self.take()
            if close.kind != ")":
                raise self.fail(close)
            return node
        raise self.fail(tok)


def _number(tok: _Token) -> Num:
    m = _NUMBER.fullmatch(tok.text)
    assert m is not None
    mantissa, exp_part = m.group(1), m.group(2)
    exp10 = 0
    if exp_part:
        exp10 = int(exp_part[1:])
        if abs(exp10) > MAX_DECIMAL_EXPONENT:
            raise UserError(
                f"exponent {exp10} of {tok.text!r} is out of range (|e| <= {MAX_DECIMAL_EXPONENT}) "
                f"at column {tok.column}"
            )
    if "." in mantissa:
        whole, frac = mantissa.split(".")
    else:
        whole, frac = mantissa, ""
    digits_str = (whole + frac).lstrip("0")
    value = Fraction(int(whole + frac or "0")) * Fraction(10) ** (exp10 - len(frac))
    is_decimal = "." in mantissa or exp_part is not None
    if not is_decimal:
        return Num(value, tok.text, None, 0)
    # A written zero (0.000) carries no significant digits: it is exact.
    digits = len(digits_str) if digits_str else None
    return Num(value, tok.text, digits, exp10 - len(frac))


def parse(text: str) -> Expr:
    """Parse one entry.  Raises :class:`UserError` with the column of the problem."""
    if len(text) > MAX_ENTRY_LENGTH:
        raise UserError(f"entry too long ({len(text):,} characters; the limit is {MAX_ENTRY_LENGTH:,})")
    return _Parser(text).parse()


# ------------------------------------------------------------------- traversals


def walk(node: Expr):
    """Every node of ``node`` in pre-order, left to right."""
    stack = [node]
    while stack:
        n = stack.pop()
        yield n
        if isinstance(n, Unary):
            stack.append(n.operand)
        elif isinstance(n, Call):
            # root's polynomial is not part of the expression: its x is a bound variable
            # and its coefficients are exact (see :func:`root_polynomial`)
            stack.extend(reversed(n.args[1:] if n.func == "root" else n.args))
        elif isinstance(n, Binary):
            stack.extend((n.right, n.left))
        elif isinstance(n, Power):
            stack.extend((n.exponent, n.base))


# ------------------------------------------------------------------- root(p, k)

MAX_ROOT_DEGREE = 100


def root_polynomial(call: Call) -> list[Fraction]:
    """The coefficients (ascending) of the polynomial of ``root(p, k)``: ``p`` may use the
    variable ``x``, numbers (taken exactly), ``+ - *``, division by a nonzero number and
    powers with integer exponents >= 0."""
    from rkcheck.numbers.polynomials import trim

    def padd(a: list[Fraction], b: list[Fraction]) -> list[Fraction]:
        n = max(len(a), len(b))
        return [(a[i] if i < len(a) else 0) + (b[i] if i < len(b) else 0) for i in range(n)]

    def pmul(a: list[Fraction], b: list[Fraction]) -> list[Fraction]:
        out = [Fraction(0)] * (len(a) + len(b) - 1)
        for i, x in enumerate(a):
            if x:
                for j, y in enumerate(b):
                    out[i + j] += x * y
        if len(out) - 1 > MAX_ROOT_DEGREE:
            raise UserError(f"root's polynomial has degree above {MAX_ROOT_DEGREE} at column {call.column}")
        return out

    def const(node: Expr, what: str) -> Fraction:
        p = trim(go(node))
        if len(p) > 1:
            raise UserError(f"{what} in root's polynomial must not depend on x (column {call.column})")
        return p[0]

    def go(node: Expr) -> list[Fraction]:
        if isinstance(node, Num):
            return [node.value]
        if isinstance(node, Name):
            if node.name != ROOT_VARIABLE:
                raise UserError(f"root's polynomial may use only the variable {ROOT_VARIABLE!r} and numbers, "
                                f"not {node.name!r} (column {node.column})")
            return [Fraction(0), Fraction(1)]
        if isinstance(node, Unary):
            return [-c for c in go(node.operand)]
        if isinstance(node, Call):
            raise UserError(f"no function inside root's polynomial (column {node.column})")
        if isinstance(node, Power):
            n = _check_exponent(const(node.exponent, "an exponent"), node.column)
            if n < 0:
                raise UserError(f"negative power in root's polynomial at column {node.column}")
            base, out = go(node.base), [Fraction(1)]
            for _ in range(n):
                out = pmul(out, base)
            return out
        assert isinstance(node, Binary)
        left, right = go(node.left), go(node.right)
        if node.op == "+":
            return padd(left, right)
        if node.op == "-":
            return padd(left, [-c for c in right])
        if node.op == "*":
            return pmul(left, right)
        divisor = const(node.right, "a divisor")
        if divisor == 0:
            raise UserError(f"division by zero at column {node.column}")
        return [c / divisor for c in left]

    coeffs = trim(go(call.args[0]))
    if len(coeffs) < 2:
        raise UserError(f"root's polynomial must have degree >= 1 (column {call.column})")
    return coeffs


def root_enclosure(call: Call, k_value: Fraction | None, bits: int) -> Interval:
    """The k-th smallest real root of root(p, k), enclosed to ``2^-bits`` (exact when
    rational).  ``k_value`` is the exact value of k."""
    from rkcheck.numbers.polynomials import real_root_intervals

    if k_value is None or k_value.denominator != 1 or k_value < 1:
        raise UserError(f"root(p, k): k must be a positive integer, got {k_value} (column {call.column})")
    coeffs = root_polynomial(call)
    roots = real_root_intervals(coeffs, bits)
    k = int(k_value)
    if k > len(roots):
        raise UserError(f"root(p, {k}): the polynomial has only {len(roots)} real root"
                        f"{'s' if len(roots) != 1 else ''} (column {call.column})")
    return roots[k - 1]


def names(node: Expr) -> list[Name]:
    """All names used in ``node`` (with repetition), left to right."""
    return [n for n in walk(node) if isinstance(n, Name)]


def literals(node: Expr) -> list[Num]:
    """All number literals in ``node``."""
    return [n for n in walk(node) if isinstance(n, Num)]


# ------------------------------------------------------------------- evaluation


def _check_exponent(value: Fraction, column: int) -> int:
    if value.denominator != 1:
        raise UserError(f"exponent {value} at column {column} is not an integer")
    if abs(value) > MAX_EXPONENT:
        raise UserError(f"exponent {value} at column {column} is out of range (|n| <= {MAX_EXPONENT})")
    return int(value)


def _check_size(base: Fraction, n: int, column: int) -> None:
    bits = (base.numerator.bit_length() + base.denominator.bit_length()) * abs(n)
    if bits > MAX_BITS:
        raise UserError(f"power at column {column} is too large (about {bits:,} bits)")


def evaluate_exact(node: Expr, constants: Mapping[str, Fraction | None]) -> Fraction | None:
    """The exact rational value of ``node`` at face value, or None when it is irrational.

    ``constants`` maps names to their exact values (None = irrational).  Square roots of
    rational squares are exact (``sqrt(9/4) = 3/2``).  Raises :class:`UserError` for a
    division by zero or the root of a negative number.
    """
    if isinstance(node, Num):
        return node.value
    if isinstance(node, Name):
        return constants[node.name]
    if isinstance(node, Unary):
        v = evaluate_exact(node.operand, constants)
        return None if v is None else -v
    if isinstance(node, Call):
        if node.func == "root":
            iv = root_enclosure(node, evaluate_exact(node.args[1], constants), 64)
            return iv.lo if iv.is_point else None
        v = evaluate_exact(node.arg, constants)
        if v is None:
            return None
        if v < 0:
            raise UserError(f"square root of a negative number ({v}) at column {node.column}")
        return exact_sqrt(v)
    if isinstance(node, Power):
        e = evaluate_exact(node.exponent, constants)
        if e is None:
            raise UserError(f"exponent at column {node.column} is not an integer")
        n = _check_exponent(e, node.column)
        b = evaluate_exact(node.base, constants)
        if b is None:
            return None
        if b == 0 and n < 0:
            raise UserError(f"division by zero (0 to a negative power) at column {node.column}")
        _check_size(b, n, node.column)
        return b**n
    assert isinstance(node, Binary)
    left = evaluate_exact(node.left, constants)
    right = evaluate_exact(node.right, constants)
    if node.op == "/" and right == 0:
        raise UserError(f"division by zero at column {node.column}")
    if left is None or right is None:
        return None
    if node.op == "+":
        return left + right
    if node.op == "-":
        return left - right
    if node.op == "*":
        return left * right
    return left / right


def enclose(
    node: Expr,
    bits: int,
    rounded: bool | str,
    constants: Mapping[str, Interval],
) -> Interval:
    """A rigorous enclosure of ``node`` (definitions §5).

    ``rounded``: the decimals mode (``auto``, ``rounded``, ``float64``, ``exact``; see
    :meth:`Num.interval`); ``True``/``False`` mean ``rounded``/``exact``.  Square roots
    of non-squares are rounded outwards to ``bits`` bits.  ``constants`` maps names to
    their enclosures.
    """
    if isinstance(node, Num):
        mode = rounded if isinstance(rounded, str) else ("rounded" if rounded else "exact")
        box = node.interval(mode)
        return Interval(*box) if box is not None else Interval.point(node.value)
    if isinstance(node, Name):
        return constants[node.name]
    if isinstance(node, Unary):
        return -enclose(node.operand, bits, rounded, constants)
    if isinstance(node, Call) and node.func == "root":
        k = enclose(node.args[1], bits, rounded, constants)
        return root_enclosure(node, k.lo if k.is_point else None, bits)
    if isinstance(node, Call):
        v = enclose(node.arg, bits, rounded, constants)
        if v.hi < 0:
            raise UserError(f"square root of a negative number at column {node.column}")
        if v.lo < 0:
            raise UserError(
                f"square root at column {node.column}: the argument cannot be shown to be >= 0 "
                f"(it lies in [{float(v.lo):.3g}, {float(v.hi):.3g}])"
            )
        return v.sqrt(bits)
    if isinstance(node, Power):
        e = enclose(node.exponent, bits, rounded, constants)
        if not e.is_point:
            raise UserError(f"exponent at column {node.column} is not an exact integer")
        n = _check_exponent(e.lo, node.column)
        b = enclose(node.base, bits, rounded, constants)
        if n < 0 and b.contains_zero():
            raise UserError(f"division by zero (0 to a negative power) at column {node.column}")
        _check_size(max(abs(b.lo), abs(b.hi)) or Fraction(1), n, node.column)
        return b.power(n)
    assert isinstance(node, Binary)
    left = enclose(node.left, bits, rounded, constants)
    right = enclose(node.right, bits, rounded, constants)
    if node.op == "+":
        return left + right
    if node.op == "-":
        return left - right
    if node.op == "*":
        return left * right
    if right.contains_zero():
        if right.is_point:
            raise UserError(f"division by zero at column {node.column}")
        raise UserError(
            f"division at column {node.column}: the divisor cannot be shown to be nonzero"
        )
    return left / right


def to_text(node: Expr) -> str:
    """A canonical, fully parenthesised-where-needed rendering (used for constants inlined in output)."""
    prec = {"+": 1, "-": 1, "*": 2, "/": 2}

    def go(n: Expr, parent: int) -> str:
        if isinstance(n, Num):
            return n.text
        if isinstance(n, Name):
            return n.name
        if isinstance(n, Call):
            return f"{n.func}({', '.join(go(a, 0) for a in n.args)})"
        if isinstance(n, Unary):
            s = "-" + go(n.operand, 3)
            return f"({s})" if parent >= 3 else s
        if isinstance(n, Power):
            s = f"{go(n.base, 4)}^{go(n.exponent, 3)}"
            return f"({s})" if parent >= 4 else s
        assert isinstance(n, Binary)
        p = prec[n.op]
        right_parent = p + 1 if n.op in "-/" else p
        s = f"{go(n.left, p)} {n.op} {go(n.right, right_parent)}" if p == 1 else f"{go(n.left, p)}{n.op}{go(n.right, right_parent)}"
        return f"({s})" if parent > p else s

    return go(node, 0)

