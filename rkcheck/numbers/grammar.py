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
(``1.5e-3``), in ASCII digits.  Besides the ASCII operators, the typographic minus ``−``
(U+2212), the multiplication sign ``×`` (U+00D7) and the middle dot ``·`` (U+00B7) are
read as ``-``, ``*`` and ``*`` (text copied from papers uses them); every other character
outside ASCII letters, digits, ``_ + - * / ^ ( ) , .`` and spaces is refused, naming it.  A decimal literal keeps the number of significant digits it was
written with, which definitions §5 uses as its precision.

Hostile input is refused early and cheaply: entries longer than
:data:`MAX_ENTRY_LENGTH` characters, nesting deeper than :data:`MAX_DEPTH`, exponents
outside ``±MAX_EXPONENT``, and any intermediate value (a power, a product, a sum, an
interval end point) whose exact size would exceed :data:`MAX_BITS` bits — so that chains of
allowed steps (``c1 = "c0*c0"``, ``2^1000*2^1000*…``) cannot grow without bound.  Nothing
here recurses in proportion to the length of an entry: the parser's recursion is bounded by
:data:`MAX_DEPTH`, and evaluation and rendering walk the tree with an explicit stack.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction

from rkcheck.errors import UserError
from rkcheck.numbers.doubles import double_box, rounded_interval
from rkcheck.numbers.formatting import count_text
from rkcheck.numbers.reading import DecimalsMode

MAX_ENTRY_LENGTH = 20_000
MAX_DEPTH = 100
MAX_EXPONENT = 1000
MAX_DECIMAL_EXPONENT = 1000
MAX_BITS = 200_000


def too_large(what: str, size: str | None = None) -> str:
    """The one message of a value past :data:`MAX_BITS`, wherever it is met: ``what``
    and, where known, its ``size`` (``about 256,002 bits``)."""
    return f"{what} is too large ({size + '; ' if size else ''}the limit MAX_BITS is {count_text(MAX_BITS)} bits)"

#: A decimal literal with at least this many significant digits is, by default, read as
#: "rounded to its last digit" (definitions §5).  Shorter decimals such as 0.5, 0.25 or 0.125
#: are read exactly: see docs/decisions.md for why (a literal reading of the definition would make
#: ``0.5`` mean [0.45, 0.55]).
ROUNDED_MIN_DIGITS = 6

# ASCII digits only: ``\d`` would also match other scripts' digits (``١``), which int() accepts.
_NUMBER = re.compile(r"([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_DIGITS = frozenset("0123456789")
_NAME_START = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_")
_SPACES = frozenset(" \t\r\n")
#: Typographic operators read as their ASCII equivalents (docs/file-format.md).
UNICODE_OPERATORS = {"\u2212": "-", "\u00d7": "*", "\u00b7": "*"}
#: Functions and their number of arguments.  ``root(p, k)`` is the k-th smallest real root
#: of the polynomial p in the variable :data:`ROOT_VARIABLE` (rational coefficients).
FUNCTIONS = {"sqrt": 1, "root": 2}
ROOT_VARIABLE = "x"


# --------------------------------------------------------------------------- AST


@dataclass(frozen=True, slots=True)
class Num:
    """A literal.  ``digits`` = significant digits of a decimal literal, None for integers.
    An empty ``text``: an exact number formed by rkcheck, not written (a coefficient of a
    kernel's surrogate entry), which is written out as its value only when shown."""

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

    def interval(self, decimals: DecimalsMode) -> tuple[Fraction, Fraction] | None:
        """The numbers this literal stands for under a decimals mode (definitions §5.2),
        as ``(lo, hi)``; None when it is exact in that mode (:class:`DecimalsMode`).

        In ``auto`` the double's rounding interval is added only when the literal *as
        written* is the double's shortest representation (same value, same number of
        significant digits): ``0.16666666666666666`` then covers 1/6, while
        ``0.500000000000000000000000000000`` says it has 30 digits and is read so.
        """
        decimals = DecimalsMode(decimals)
        if decimals is DecimalsMode.EXACT:
            return None
        if decimals is DecimalsMode.FLOAT64:
            return self._as_double() if self.is_decimal else None
        if not self.is_rounded_decimal:
            return None
        return rounded_interval(self.value, self.digits, self.last_digit_exponent, decimals is DecimalsMode.AUTO)

    def centre(self, decimals: DecimalsMode) -> Fraction:
        """The middle of the numbers this literal stands for: its face value, or, for a
        double's rounding interval (not centred on the decimal that names the double, nor
        on the double below a power of two), the middle of that interval."""
        box = self.interval(decimals)
        return self.value if box is None else (box[0] + box[1]) / 2

    def _as_double(self) -> tuple[Fraction, Fraction]:
        """The rounding interval of the double this literal reads as in ``float64``; a
        literal that rounds past the largest double is refused: it stands for no double."""
        box = double_box(self.value)
        if box is None:
            raise UserError(f"{self.text} is beyond the range of binary64 doubles, and "
                            "--decimals float64 reads every decimal as a double; write it exactly, or check "
                            "with another --decimals")
        return box


@dataclass(frozen=True, slots=True)
class Name:
    """A constant's name, at 1-based ``column`` of the entry."""

    name: str
    column: int


@dataclass(frozen=True, slots=True)
class Unary:
    """Unary minus."""

    op: str  # '-' only; unary '+' is dropped by the parser
    operand: "Expr"


@dataclass(frozen=True, slots=True)
class Binary:
    """``left op right`` for ``+ - * /``."""

    op: str  # '+', '-', '*', '/'
    left: "Expr"
    right: "Expr"
    column: int


@dataclass(frozen=True, slots=True)
class Power:
    """``base ^ exponent`` (or ``**``)."""

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
    """One token of an entry and its 1-based column."""

    kind: str  # 'num', 'name', 'op', '(', ')', 'end'
    text: str
    column: int  # 1-based


def _describe(ch: str) -> str:
    """A character as a message shows it: quoted, escaped when not printable, and with
    its code point when not ASCII (so that ``'π' (U+03C0)`` and a lone surrogate are one
    readable line)."""
    shown = repr(ch) if ch.isprintable() else ascii(ch)
    return shown if ch.isascii() else f"{shown} (U+{ord(ch):04X})"


def _tokenize(text: str) -> list[_Token]:
    tokens: list[_Token] = []
    i, n = 0, len(text)
    depth = 0
    while i < n:
        ch = text[i]
        col = i + 1
        if ch in _SPACES:
            i += 1
            continue
        if ch in _DIGITS or (ch == "." and i + 1 < n and text[i + 1] in _DIGITS):
            m = _NUMBER.match(text, i)
            assert m is not None  # the first character is a digit or '.digit'
            tokens.append(_Token("num", m.group(0), col))
            i = m.end()
            continue
        if ch in _NAME_START:
            m = _NAME.match(text, i)
            assert m is not None  # the first character is a name start
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
        if ch in UNICODE_OPERATORS:
            tokens.append(_Token("op", UNICODE_OPERATORS[ch], col))
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
        raise UserError(f"unexpected character {_describe(ch)} at column {col}")
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
    value = Fraction(int_of_digits(whole + frac or "0")) * Fraction(10) ** (exp10 - len(frac))
    is_decimal = "." in mantissa or exp_part is not None
    if not is_decimal:
        return Num(value, tok.text, None, 0)
    # A written zero (0.000) carries no significant digits: it is exact.
    digits = len(digits_str) if digits_str else None
    return Num(value, tok.text, digits, exp10 - len(frac))


#: int() refuses digit strings longer than this (Python's default int_max_str_digits
#: guard); longer literals are converted in halves, which is bounded by MAX_ENTRY_LENGTH.
_INT_CHUNK = 4000


def int_of_digits(digits: str) -> int:
    """``int(digits)`` for ASCII digit strings of any length (docs/file-format.md promises decimals
    of any length; Python refuses more than 4 300 digits in one conversion)."""
    if len(digits) <= _INT_CHUNK:
        return int(digits)
    low = len(digits) // 2
    value: int = int_of_digits(digits[:-low]) * 10**low + int_of_digits(digits[-low:])
    return value


def fraction_text(q: Fraction | int) -> str:
    """``p/q`` (``p`` for an integer) at any length, as the grammar reads it back exactly."""
    q = Fraction(q)
    return digits_text(q.numerator) if q.denominator == 1 else f"{digits_text(q.numerator)}/{digits_text(q.denominator)}"


def digits_text(n: int) -> str:
    """``str(n)`` for integers of any length (the inverse of :func:`int_of_digits`)."""
    if -10**_INT_CHUNK < n < 10**_INT_CHUNK:
        return str(n)
    if n < 0:
        return "-" + digits_text(-n)
    half = int(n.bit_length() * 0.30103) // 2
    high, low = divmod(n, 10**half)
    return digits_text(high) + digits_text(low).zfill(half)


def parse(text: str, limit: int | None = MAX_ENTRY_LENGTH) -> Expr:
    """Parse one entry.  Raises :class:`UserError` with the column of the problem.
    ``limit``: None for a text rkcheck wrote from entries each within the limit (a
    kernel from its matrix M: the terms of up to 40 × 40 entries)."""
    if limit is not None and len(text) > limit:
        raise UserError(f"entry too long ({count_text(len(text))} characters; the limit is {count_text(limit)})")
    return _Parser(text).parse()
