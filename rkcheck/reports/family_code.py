"""A family's conditions as code: each condition an exact polynomial in the parameters
(``rkcheck conditions FAMILY --emit python|sympy|julia|latex``).

Unlike the conditions of a general tableau (:mod:`rkcheck.reports.code`: functions of A
and b), these are the family's own polynomials, expanded: one function of the
parameters returning every residual.  Coefficients are exact rationals in every
language; the field generator θ of a family over Q(θ) is written as its closed form where
the language has one (``sympy.sqrt(3)``, ``\\sqrt{3}``) and as a keyword argument in
Python and Julia (a float by default: pass an exact value for exact residuals).
"""

from __future__ import annotations

import re
from fractions import Fraction
from typing import Any

from rkcheck.errors import UserError
from rkcheck.numbers.parametric import THETA
from rkcheck.version import __version__

#: The languages a family's conditions are written in.
FAMILY_LANGUAGES = ("python", "sympy", "julia", "latex")


def _terms(p: Any) -> list[tuple[Fraction, tuple[int, ...]]]:
    return [(Fraction(int(c.p), int(c.q)), tuple(int(e) for e in m)) for m, c in p.to_dict().items()]


def _monomial(names: list[str], m: tuple[int, ...], power: str, times: str) -> str:
    return times.join(n if e == 1 else f"{n}{power}{e}" for n, e in zip(names, m) if e)


def _number(q: Fraction, lang: str) -> str:
    if q.denominator == 1:
        return str(abs(q.numerator))
    a, d = abs(q.numerator), q.denominator
    return {"python": f"Fraction({a}, {d})", "sympy": f"sympy.Rational({a}, {d})", "julia": f"{a}//{d}",
            "latex": f"\\tfrac{{{a}}}{{{d}}}"}[lang]


def polynomial_code(p: Any, names: list[str], lang: str) -> str:
    """``p`` (an fmpq_mpoly whose variables are ``names`` as written) in ``lang``."""
    if p.is_zero():
        return "0"
    power, times = {"python": ("**", "*"), "sympy": ("**", "*"), "julia": ("^", "*"), "latex": ("^", " ")}[lang]
    out = ""
    for q, m in _terms(p):
        mono = _monomial(names, m, power, times)
        if lang == "latex":
            mono = " ".join(f"{n}^{{{e}}}" if e > 1 else n for n, e in zip(names, m) if e)
        num = _number(q, lang)
        body = mono if abs(q) == 1 and mono else (f"{num}{times}{mono}" if mono else num)
        sign = "-" if q < 0 else "+"
        out += f" {sign} {body}" if out else (f"-{body}" if q < 0 else body)
    return out


_GREEK = {"alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "iota", "kappa", "lambda", "mu",
          "nu", "xi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega"}  # not theta (the field's θ), pi


_CAPITAL_GREEK = {"Gamma", "Delta", "Lambda", "Xi", "Sigma", "Upsilon", "Phi", "Psi", "Omega"}


def latex_name(name: str) -> str:
    """A parameter's name in LaTeX: trailing digits as a subscript (``a11`` → ``a_{11}``,
    ``b_2`` → ``b_{2}``), a Greek letter's name as the letter (``beta`` → ``\\beta``,
    ``Gamma`` → ``\\Gamma``); any other name upright, its underscores escaped
    (``lambda_`` → ``\\mathrm{lambda\\_}``), so that every name compiles."""
    m = re.fullmatch(r"([A-Za-z]+)(?:_?(\d+))?", name)
    if m is None:
        return "\\mathrm{" + name.replace("_", "\\_") + "}"
    stem, sub = m.group(1), m.group(2)
    stem = f"\\{stem}" if stem in _GREEK or stem in _CAPITAL_GREEK else stem
    return f"{stem}_{{{sub}}}" if sub is not None else stem


def _theta_names(fc: Any, lang: str) -> tuple[list[str], list[str]]:
    """The variables as written, and the lines defining θ (if any)."""
    fam = fc.family
    field = fam.ring.field
    params = [latex_name(p) for p in fam.parameters] if lang == "latex" else list(fam.parameters)
    if field is None:
        return params, []
    name = field.name
    if lang == "sympy":
        if field.sqrt_of:
            return ["theta"] + params, [f"theta = sympy.sqrt({field.sqrt_of})"]
        coeffs = ", ".join(str(Fraction(c)) for c in reversed(field.minpoly))
        return ["theta"] + params, [f"theta = sympy.CRootOf(sympy.Poly([{coeffs}], sympy.Symbol('x')), "
                                    f"{field.index - 1})  # {name}"]
    if lang == "latex":
        shown = f"\\sqrt{{{field.sqrt_of}}}" if field.sqrt_of else "\\theta"
        return [shown] + params, ([] if field.sqrt_of else [f"% \\theta = {name}"])
    return ["theta"] + params, []


#: names the emitted code itself uses, besides each language's keywords
_TAKEN = {"python": {"Fraction", "residuals", "theta"}, "sympy": {"sympy", "residuals", "theta"},
          "julia": {"residuals", "theta", "sqrt", "Rational", "big"}, "latex": set()}
_JULIA_KEYWORDS = {"baremodule", "begin", "break", "catch", "const", "continue", "do", "else", "elseif", "end",
                   "export", "false", "finally", "for", "function", "global", "if", "import", "let", "local", "macro",
                   "module", "quote", "return", "struct", "true", "try", "using", "while", "abstract", "mutable",
                   "primitive", "type", "where", "in", "isa"}


def _check_names(fc: Any, lang: str) -> None:
    """Refuse a parameter whose name the emitted code could not use: a keyword of the
    language, or a name the code defines itself (θ, the function, an import)."""
    import keyword

    for name in fc.family.parameters:
        taken = (keyword.iskeyword(name) or keyword.issoftkeyword(name) if lang in ("python", "sympy")
                 else name in _JULIA_KEYWORDS if lang == "julia" else False)
        if taken or name in _TAKEN[lang]:
            raise UserError(f"the parameter {name!r} cannot be a name in {lang} code (a keyword, or a name the "
                            "code uses itself): rename it in the family file", "--emit")


def emit_family(fc: Any, lang: str) -> str:
    """The conditions of a :class:`~rkcheck.energy.family_conditions.FamilyConditions` as
    source text."""
    if lang not in FAMILY_LANGUAGES:
        raise ValueError(f"unknown language {lang!r}")
    _check_names(fc, lang)
    names, theta_lines = _theta_names(fc, lang)
    conds = fc.energy + (fc.classical or [])
    ring_names = list(fc.family.ring.variables)
    assert len(ring_names) == len(names) and (THETA not in ring_names or ring_names[0] == THETA)
    rows = [(c, polynomial_code(c.polynomial, names, lang)) for c in conds]
    title = (f"The conditions of the family {fc.family.name!r} (degree m = {fc.degree}, order {fc.order}) "
             f"as polynomials in {', '.join(fc.family.parameters)}")
    head = f"Generated by rkcheck {__version__} (`rkcheck conditions FAMILY --emit {lang}`)"
    if lang in ("python", "sympy"):
        return _python(rows, names, theta_lines, fc, lang, title, head)
    if lang == "julia":
        return _julia(rows, names, fc, title, head)
    return _latex(rows, theta_lines, title, head)


def _python(rows, names, theta_lines, fc, lang, title, head) -> str:
    params = ", ".join(fc.family.parameters)
    field = fc.family.ring.field
    lines = [f'"""{title}.', "", f"{head}: each residual is zero exactly when its condition holds.", '"""', "",
             "import sympy" if lang == "sympy" else "from fractions import Fraction", ""]
    if lang == "sympy":
        lines += [f"{', '.join(fc.family.parameters)}, = sympy.symbols({list(fc.family.parameters)!r})"]
        lines += theta_lines + [""]
        sig = params
    else:
        sig = params + (f", theta={float(field.theta_enclosure(64).lo)!r}" if field is not None else "")
        if field is not None:
            lines += [f"# theta = {field.name}: the default is a float; pass an exact value for exact residuals", ""]
    lines += ["", f"def residuals({sig}):", "    return ["]
    lines += [f"        {code},  # {c.kind} {c.id} {c.bracket}" for c, code in rows]
    lines += ["    ]", ""]
    if lang == "sympy":
        lines += ["", f"conditions = residuals({params})", ""]
    return "\n".join(lines)


def _julia(rows, names, fc, title, head) -> str:
    field = fc.family.ring.field
    sig = ", ".join(fc.family.parameters) + (f"; theta=sqrt({field.sqrt_of})" if field is not None and field.sqrt_of
                                            else (f"; theta={float(field.theta_enclosure(64).lo)!r}"
                                                  if field is not None else ""))
    lines = [f"# {title}.", f"# {head}. Rational inputs give exact residuals.", "",
             f"function residuals({sig})", "    return ["]
    lines += [f"        {code},  # {c.kind} {c.id} {c.bracket}" for c, code in rows]
    lines += ["    ]", "end", ""]
    return "\n".join(lines)


def _latex(rows, theta_lines, title, head) -> str:
    lines = [f"% {title}.", f"% {head}. Each R must vanish."] + theta_lines + ["\\begin{align*}"]
    for k, (c, code) in enumerate(rows):
        end = " \\\\" if k < len(rows) - 1 else ""
        lines.append(f"R_{{{c.id}}} &= {code}{end}  % {c.kind} {c.bracket}")
    lines.append("\\end{align*}")
    return "\n".join(lines) + "\n"
