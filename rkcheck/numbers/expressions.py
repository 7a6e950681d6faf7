"""What a parsed entry means: traversals of the AST of :mod:`rkcheck.numbers.grammar`,
its exact value, its enclosure, ``root(p, k)``'s polynomial, and its text.

Every walk uses an explicit stack (:func:`walk`, :func:`fold`), so a sum of 10 000 terms
needs no recursion; every intermediate value is held to the size budget
(:data:`rkcheck.numbers.grammar.MAX_BITS`) before it is computed.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Callable, Iterator, Mapping

from rkcheck.errors import UserError
from rkcheck.numbers import polynomials
from rkcheck.numbers.formatting import count_text, exact_string
from rkcheck.numbers.grammar import (
    MAX_BITS,
    MAX_EXPONENT,
    ROOT_VARIABLE,
    Binary,
    Call,
    Expr,
    Name,
    Num,
    Power,
    Unary,
    parse,
    too_large,
)
from rkcheck.numbers.intervals import Interval, exact_sqrt
from rkcheck.numbers.reading import DecimalsMode

# ------------------------------------------------------------------- traversals


def walk(node: Expr) -> Iterator[Expr]:
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


def operands(node: Expr) -> tuple[Expr, ...]:
    """The sub-expressions whose values an evaluation of ``node`` combines, in order
    (root's polynomial is not one: its x is a bound variable, see :func:`root_polynomial`)."""
    if isinstance(node, Unary):
        return (node.operand,)
    if isinstance(node, (Binary,)):
        return (node.left, node.right)
    if isinstance(node, Power):
        return (node.base, node.exponent)
    if isinstance(node, Call):
        return node.args[1:] if node.func == "root" else node.args
    return ()


def children(node: Expr) -> tuple[Expr, ...]:
    """Every direct sub-expression of ``node``, root's polynomial too: its structure."""
    return node.args if isinstance(node, Call) else operands(node)


def polynomial_operands(node: Expr) -> tuple[Expr, ...]:
    """The operands of ``node`` read as a polynomial in its names: a power's base only (its
    exponent is a whole number, read on its own), and none of a call's (a call is a number)."""
    if isinstance(node, Power):
        return (node.base,)
    return () if isinstance(node, Call) else operands(node)


def fold(node: Expr, combine: Callable[[Expr, list[Any]], Any],
         operands: Callable[[Expr], tuple[Expr, ...]] = operands) -> Any:
    """``combine(n, [values of n's operands])`` for every node, operands first, left to
    right: a post-order evaluation with an explicit stack, so that a sum of 10 000 terms
    (a left-leaning tree 10 000 deep) needs no recursion."""
    values: list[Any] = []
    stack: list[tuple[Expr, bool]] = [(node, False)]
    while stack:
        n, expanded = stack.pop()
        kids = operands(n)
        if expanded or not kids:
            k = len(kids)
            args = values[len(values) - k:] if k else []
            if k:
                del values[len(values) - k:]
            values.append(combine(n, args))
        else:
            stack.append((n, True))
            stack.extend((kid, False) for kid in reversed(kids))
    return values[0]


def rebuilt(node: Expr, leaf: Callable[[Num | Name], Expr],
            call: Callable[[Call, list[Expr]], list[Expr]] | None = None) -> Expr:
    """``node`` rebuilt bottom-up with each literal and name ``n`` replaced by
    ``leaf(n)`` — in a root's polynomial too, unless ``call(n, args)`` (told each call
    with its rebuilt arguments) gives other arguments."""

    def combine(n: Expr, vals: list[Expr]) -> Expr:
        if isinstance(n, (Num, Name)):
            return leaf(n)
        if isinstance(n, Unary):
            return Unary(n.op, vals[0])
        if isinstance(n, Binary):
            return Binary(n.op, vals[0], vals[1], n.column)
        if isinstance(n, Power):
            return Power(vals[0], vals[1], n.column)
        return Call(n.func, tuple(vals if call is None else call(n, vals)), n.column)

    out: Expr = fold(node, combine, children)
    return out


def substituted(node: Expr, values: Mapping[str, Expr]) -> Expr:
    """``node`` with every name in ``values`` replaced by its expression — except the
    ``x`` of a root's polynomial, which is that polynomial's own bound variable."""
    inner = {k: v for k, v in values.items() if k != ROOT_VARIABLE}

    def root_bound(n: Call, vals: list[Expr]) -> list[Expr]:
        if n.func == "root" and n.args and ROOT_VARIABLE in values:
            vals[0] = substituted(n.args[0], inner)
        return vals

    return rebuilt(node, lambda n: values.get(n.name, n) if isinstance(n, Name) else n, root_bound)


def _bits(q: Fraction) -> int:
    return q.numerator.bit_length() + q.denominator.bit_length()


def _check_value_bits(values: tuple[Fraction, ...], column: int) -> None:
    """Refuse an intermediate value larger than :data:`MAX_BITS` (the size budget)."""
    bits = max(_bits(v) for v in values)
    if bits > MAX_BITS:
        raise UserError(too_large(f"value at column {column}", f"about {count_text(bits)} bits"))


def _check_operand_bits(values: tuple[Fraction, ...], column: int) -> None:
    """Refuse before computing a sum, product or quotient whose operands together exceed
    twice the budget (the result could not fit, and computing it would cost time)."""
    bits = sum(_bits(v) for v in values)
    if bits > 2 * MAX_BITS:
        raise UserError(too_large(f"value at column {column}", f"about {count_text(bits)} bits"))


# ------------------------------------------------------------------- root(p, k)

MAX_ROOT_DEGREE = 100


def root_polynomial(call: Call) -> list[Fraction]:
    """The coefficients (ascending) of the polynomial of ``root(p, k)``: ``p`` may use the
    variable ``x``, numbers (taken exactly), ``+ - *``, division by a nonzero number and
    powers with integer exponents >= 0."""
    reader = _RootPolynomial(call.column)
    coeffs = polynomials.trim(fold(call.args[0], reader.combine, reader.inside))
    if len(coeffs) < 2:
        raise UserError(f"root's polynomial must have degree >= 1 (column {call.column})")
    return coeffs


class _RootPolynomial:
    """The polynomial in ``x`` of a ``root`` call's first argument, node by node, with the
    limits on its degree and size (errors name the call's column)."""

    def __init__(self, column: int):
        self.column = column

    def mul(self, a: list[Fraction], b: list[Fraction]) -> list[Fraction]:
        out = polynomials.mul(a, b)
        if len(out) - 1 > MAX_ROOT_DEGREE:
            raise UserError(f"root's polynomial has degree above {MAX_ROOT_DEGREE} at column {self.column}")
        return out

    def constant(self, poly: list[Fraction], what: str) -> Fraction:
        p = polynomials.trim(poly)
        if len(p) > 1:
            raise UserError(f"{what} in root's polynomial must not depend on x (column {self.column})")
        value: Fraction = p[0]
        return value

    @staticmethod
    def inside(node: Expr) -> tuple[Expr, ...]:
        return () if isinstance(node, Call) else operands(node)  # a call is refused in combine

    def combine(self, node: Expr, vals: list[list[Fraction]]) -> list[Fraction]:
        if isinstance(node, Num):
            return [node.value]
        if isinstance(node, Name):
            if node.name != ROOT_VARIABLE:
                raise UserError(f"root's polynomial may use only the variable {ROOT_VARIABLE!r} and numbers, "
                                f"not {node.name!r} (column {node.column})")
            return [Fraction(0), Fraction(1)]
        if isinstance(node, Unary):
            return [-c for c in vals[0]]
        if isinstance(node, Call):
            raise UserError(f"no function inside root's polynomial (column {node.column})")
        if isinstance(node, Power):
            return self.power(node, vals[0], vals[1])
        assert isinstance(node, Binary)
        left, right = vals
        if node.op == "+":
            return polynomials.add(left, right)
        if node.op == "-":
            return polynomials.sub(left, right)
        if node.op == "*":
            out = self.mul(left, right)
            _check_value_bits(tuple(out), node.column)
            return out
        divisor = self.constant(right, "a divisor")
        if divisor == 0:
            raise UserError(f"division by zero at column {node.column}")
        return [c / divisor for c in left]

    def power(self, node: Power, base: list[Fraction], exponent: list[Fraction]) -> list[Fraction]:
        n = check_exponent(self.constant(exponent, "an exponent"), node.column)
        if n < 0:
            raise UserError(f"negative power in root's polynomial at column {node.column}")
        out = [Fraction(1)]
        for _ in range(n):
            out = self.mul(out, base)
            _check_value_bits(tuple(out), node.column)
        return out


def root_enclosure(call: Call, k_value: Fraction | None, bits: int) -> Interval:
    """The k-th smallest real root of root(p, k), enclosed to ``2^-bits`` (exact when
    rational).  ``k_value`` is the exact value of k."""
    if k_value is None or k_value.denominator != 1 or k_value < 1:
        raise UserError(f"root(p, k): k must be a positive integer, got {k_value} (column {call.column})")
    coeffs = root_polynomial(call)
    roots = polynomials.real_root_intervals(coeffs, bits)
    k = int(k_value)
    if k > len(roots):
        raise UserError(f"root(p, {k}): the polynomial has only {len(roots)} real root"
                        f"{'s' if len(roots) != 1 else ''} (column {call.column})")
    return roots[k - 1]


def root_decimals(node: Expr) -> list[Num]:
    """The decimal literals inside the polynomials of ``node``'s ``root(p, k)`` calls
    (whose numbers are read exactly, :func:`root_polynomial`)."""
    out: list[Num] = []
    for n in walk(node):
        if isinstance(n, Call) and n.func == "root" and n.args:
            stack = [n.args[0]]
            while stack:
                m = stack.pop()
                if isinstance(m, Num) and m.is_decimal:
                    out.append(m)
                stack.extend(children(m))
    return out


def names(node: Expr) -> list[Name]:
    """All names used in ``node`` (with repetition), left to right."""
    return [n for n in walk(node) if isinstance(n, Name)]


def literals(node: Expr) -> list[Num]:
    """All number literals in ``node``."""
    return [n for n in walk(node) if isinstance(n, Num)]


# ------------------------------------------------------------------- evaluation


def check_exponent(value: Fraction, column: int) -> int:
    # a short exponent as written (1/2), a long one by its leading digits (2^1000^1000 has 3 001)
    shown = str(value) if value.numerator.bit_length() + value.denominator.bit_length() < 200 else exact_string(value)
    if value.denominator != 1:
        raise UserError(f"exponent {shown} at column {column} is not an integer")
    if abs(value) > MAX_EXPONENT:
        raise UserError(f"exponent {shown} at column {column} is out of range (|n| <= {MAX_EXPONENT})")
    return int(value)


def check_power_size(base: Fraction, n: int, column: int) -> None:
    bits = (base.numerator.bit_length() + base.denominator.bit_length()) * abs(n)
    if bits > MAX_BITS:
        raise UserError(too_large(f"power at column {column}", f"about {count_text(bits)} bits"))


def rational_power(base: Fraction, k: int, column: int) -> Fraction:
    """``base**k`` (``k`` from :func:`check_exponent`) within the size budget."""
    if base == 0 and k < 0:
        raise UserError(f"division by zero (0 to a negative power) at column {column}")
    check_power_size(base, k, column)
    return base**k


def rational_text_value(text: str) -> Fraction | None:
    """The exact value of a number written in the entries' grammar without names (an
    option's ``1e-3``, ``3/4``, ``2^-4``), None when it is irrational or names something;
    a text that does not parse, or a value past the limits, raises :class:`UserError`."""
    node = parse(text)
    if any(True for _ in names(node)):
        return None
    return evaluate_exact(node, {})


def evaluate_exact(node: Expr, constants: Mapping[str, Fraction | None]) -> Fraction | None:
    """The exact rational value of ``node`` at face value, or None when it is irrational.

    ``constants`` maps names to their exact values (None = irrational).  Square roots of
    rational squares are exact (``sqrt(9/4) = 3/2``).  Raises :class:`UserError` for a
    division by zero, the root of a negative number, or a value past :data:`MAX_BITS`.
    """

    def combine(n: Expr, vals: list[Fraction | None]) -> Fraction | None:
        if isinstance(n, Num):
            return n.value
        if isinstance(n, Name):
            return constants[n.name]
        if isinstance(n, Unary):
            v = vals[0]
            return None if v is None else -v
        if isinstance(n, Call):
            if n.func == "root":
                iv = root_enclosure(n, vals[0], 64)
                return iv.lo if iv.is_point else None
            v = vals[0]
            if v is None:
                return None
            if v < 0:
                raise UserError(f"square root of a negative number ({v}) at column {n.column}")
            return exact_sqrt(v)
        if isinstance(n, Power):
            b, e = vals
            if e is None:
                raise UserError(f"exponent at column {n.column} is not an integer")
            k = check_exponent(e, n.column)
            return None if b is None else rational_power(b, k, n.column)
        assert isinstance(n, Binary)
        left, right = vals
        if n.op == "/" and right == 0:
            raise UserError(f"division by zero at column {n.column}")
        if left is None or right is None:
            return None
        _check_operand_bits((left, right), n.column)
        out: Fraction = binary(n.op, left, right)
        _check_value_bits((out,), n.column)
        return out

    value: Fraction | None = fold(node, combine)
    return value


def binary(op: str, left: Any, right: Any) -> Any:
    """``left op right`` for any numbers (Fractions, Intervals, field elements, FLINT
    polynomials); the division checks are the caller's."""
    if op == "+":
        return left + right
    if op == "-":
        return left - right
    if op == "*":
        return left * right
    return left / right


def enclose(
    node: Expr,
    bits: int,
    decimals: DecimalsMode,
    constants: Mapping[str, Interval],
    centre: bool = False,
) -> Interval:
    """A rigorous enclosure of ``node`` (definitions §5) under the decimals mode (see
    :meth:`Num.interval`).  Square roots of non-squares are rounded outwards to ``bits``
    bits.  ``constants`` maps names to their enclosures.  ``centre``: each literal at the
    middle of what it stands for (:meth:`Num.centre`), the centre of the box of inputs.
    """
    mode = DecimalsMode(decimals)

    def combine(n: Expr, vals: list[Interval]) -> Interval:
        if isinstance(n, Num):
            if centre:
                return Interval.point(n.centre(mode))
            box = n.interval(mode)
            return Interval(*box) if box is not None else Interval.point(n.value)
        if isinstance(n, Name):
            return constants[n.name]
        if isinstance(n, Unary):
            return -vals[0]
        if isinstance(n, Call) and n.func == "root":
            index = vals[0]
            return root_enclosure(n, index.lo if index.is_point else None, bits)
        if isinstance(n, Call):
            v = vals[0]
            if v.hi < 0:
                raise UserError(f"square root of a negative number at column {n.column}")
            if v.lo < 0:
                raise UserError(
                    f"square root at column {n.column}: the argument cannot be shown to be >= 0 "
                    f"(it lies in [{_short(v.lo)}, {_short(v.hi)}])"
                )
            return v.sqrt(bits)
        if isinstance(n, Power):
            b, e = vals
            if not e.is_point:
                raise UserError(f"exponent at column {n.column} is not an exact integer")
            k = check_exponent(e.lo, n.column)
            if k < 0 and b.contains_zero():
                raise UserError(f"division by zero (0 to a negative power) at column {n.column}")
            check_power_size(max(abs(b.lo), abs(b.hi)) or Fraction(1), k, n.column)
            out = b.power(k)
            _check_value_bits((out.lo, out.hi), n.column)
            return out
        assert isinstance(n, Binary)
        left, right = vals
        _check_operand_bits((left.lo, left.hi, right.lo, right.hi), n.column)
        if n.op == "/" and right.contains_zero():
            if right.is_point:
                raise UserError(f"division by zero at column {n.column}")
            raise UserError(f"division at column {n.column}: the divisor cannot be shown to be nonzero")
        result: Interval = binary(n.op, left, right)
        _check_value_bits((result.lo, result.hi), n.column)
        return result

    value: Interval = fold(node, combine)
    return value


def _short(q: Fraction) -> str:
    """A rational for a message, as ``1.23e+45`` (float() overflows past 1e308, and str()
    of a huge integer is refused past 4 300 digits)."""
    try:
        return f"{float(q):.3g}"
    except OverflowError:
        exponent = round((q.numerator.bit_length() - q.denominator.bit_length()) * 0.30103)
        return f"{'-' if q < 0 else ''}about 1e{exponent:+d}"


def to_text(node: Expr) -> str:
    """A canonical, fully parenthesised-where-needed rendering (used for constants inlined in output)."""
    prec = {"+": 1, "-": 1, "*": 2, "/": 2}

    def wrap(child: Expr, text: str, context: int) -> str:
        # context: how tightly the parent binds this operand (0 = not at all)
        if isinstance(child, Binary):
            return f"({text})" if context > prec[child.op] else text
        if isinstance(child, Unary):
            return f"({text})" if context >= 3 else text
        if isinstance(child, Power):
            return f"({text})" if context >= 4 else text
        return text

    def combine(n: Expr, texts: list[str]) -> str:
        if isinstance(n, Num):
            return n.text or (str(n.value) if n.value.denominator == 1 and n.value >= 0 else f"({n.value})")
        if isinstance(n, Name):
            return n.name
        if isinstance(n, Call):
            return f"{n.func}({', '.join(texts)})"
        if isinstance(n, Unary):
            return "-" + wrap(n.operand, texts[0], 3)
        if isinstance(n, Power):
            return f"{wrap(n.base, texts[0], 4)}^{wrap(n.exponent, texts[1], 3)}"
        assert isinstance(n, Binary)
        p = prec[n.op]
        left = wrap(n.left, texts[0], p)
        right = wrap(n.right, texts[1], p + 1 if n.op in "-/" else p)
        return f"{left} {n.op} {right}" if p == 1 else f"{left}{n.op}{right}"

    text: str = fold(node, combine, children)
    return text
