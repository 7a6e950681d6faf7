"""New tableaux: the method families (Gauss, Radau, Lobatto, AVF, HBVM, the seed's kernel
family) at any number of stages, and the classical methods (RK4, Heun, SDIRK, ...) —
``rkcheck new``, for Python callers.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any, Callable, Sequence

from rkcheck.errors import OptionError, as_option, not_applying
from rkcheck.methods.classics import NAMES as _CLASSIC_NAMES
from rkcheck.methods.family_spec import FAMILIES as _FAMILIES
from rkcheck.methods.tableau import Tableau
from rkcheck.options import (
    DIGITS_RANGE,
    MAX_FAMILY_STAGES,
    parse_choice,
    parse_flag,
    parse_int_in,
)

if TYPE_CHECKING:
    from rkcheck.methods.family_spec import FamilySpec

#: The families ``new`` computes (``[family]`` tables name them too).
FAMILIES: tuple[str, ...] = _FAMILIES
#: Every name of a classical method ``new`` accepts (keys and aliases: ``rk4``, ``rk38``,
#: ``heun``, ``backward-euler``, ``crank-nicolson``, ...).
CLASSICAL_METHODS: tuple[str, ...] = tuple(_CLASSIC_NAMES)


_option = as_option


def _spec(method: str, stages: int | None, k: int | None, rule: str, zeta: Any, beta: Any) -> "FamilySpec":
    """The family's parameters, validated with the CLI's messages."""
    from rkcheck.methods.family_spec import parse_spec

    table: dict[str, Any] = {"name": method}
    if method == "kernel":
        table.update(zeta=zeta, beta=beta)
    else:
        if stages is None:
            raise OptionError(f"{method} needs --stages/-s")
        table["s"] = stages
        if method == "hbvm":
            if k is None:
                raise OptionError("hbvm needs -k (the number of Gauss nodes, k >= s)")
            table["k"] = k
        if method == "avf":
            table["rule"] = rule
    return parse_spec(table)


#: the parameters a family reads besides ``stages`` alone (a classical method reads none);
#: ``digits`` and ``exact``, how a family's entries are written, apply to every family
_FAMILY_READS = {"kernel": ("zeta", "beta"), "avf": ("stages", "rule"), "hbvm": ("stages", "k")}
_WRITING = ("digits", "exact")


def family_reads(method: str) -> tuple[str, ...]:
    """The parameters ``method`` reads (by the API's names; none for a classical method)."""
    return _FAMILY_READS.get(method, ("stages",)) if method in FAMILIES else ()


def unused_options(method: str, given: Sequence[str]) -> list[str]:
    """The parameters among ``given`` (by the API's names) that ``method`` does not read."""
    reads = family_reads(method) + (_WRITING if method in FAMILIES else ())
    return [g for g in given if g not in reads]


def unused_refusal(method: str, given: Sequence[str], shown: Callable[[str], str] = str) -> str | None:
    """Why the parameters among ``given`` that ``method`` does not read are refused (each
    written as ``shown`` names it: the CLI's flags), or None when it reads them all."""
    unused = unused_options(method, given)
    if not unused:
        return None
    what = (f"a family that reads {', '.join(shown(n) for n in family_reads(method))}" if method in FAMILIES
            else "a classical method (written exactly as published)")
    return f"{method} is {what}: {not_applying([shown(n) for n in unused])}"


def _is(value: Any, default: Fraction) -> bool:
    """``value`` is the default number, as a string or a number (``str()`` of a rational
    past Python's 4 300 digits would raise)."""
    if isinstance(value, (int, Fraction)) and not isinstance(value, bool):
        return value == default
    return isinstance(value, str) and value.strip() == str(default)


def _refuse_unused(method: str, stages: int | None, k: int | None, rule: str, zeta: Any, beta: Any,
                   digits: int | None = None, exact: bool = False) -> None:
    """An OptionError for the parameters given away from their defaults that ``method``
    does not read."""
    given = {"stages": stages is not None, "k": k is not None, "rule": rule != "gauss",
             "zeta": not _is(zeta, Fraction(0)), "beta": not _is(beta, Fraction(1, 10)), "digits": digits is not None,
             "exact": bool(exact)}
    refusal = unused_refusal(method, [g for g, on in given.items() if on])
    if refusal is not None:
        raise OptionError(refusal, "method")


def _validate(method: str, stages: int | None, k: int | None) -> str:
    method = _option(lambda: parse_choice(method, FAMILIES + CLASSICAL_METHODS, "method"))
    if stages is not None:
        _option(lambda: parse_int_in(stages, (1, MAX_FAMILY_STAGES), "stages"))
    if k is not None:
        _option(lambda: parse_int_in(k, (1, MAX_FAMILY_STAGES), "k"))
    return method


def new(method: str, *, stages: int | None = None, k: int | None = None, rule: str = "gauss",
        zeta: str | int | Fraction = "0", beta: str | int | Fraction = "1/10", name: str | None = None) -> Tableau:
    """A tableau of a method family or a classical method (backs ``rkcheck new``).

    ``method`` is a family — ``gauss``, ``radau-iia``, ``radau-ia``, ``lobatto-iiia``,
    ``lobatto-iiib`` (``stages`` = s), ``avf`` (``stages`` and ``rule``: ``gauss``,
    ``radau-i``, ``radau-ii``, ``lobatto`` or ``zeta:<value>``; definitions §4),
    ``hbvm`` (``k`` Gauss nodes, ``stages`` = s ≤ k), ``kernel`` (the seed's ``c bᵀ +
    βN`` with s = 2, nodes the zeros of ``P_2 − ζP_1``; definitions §4) — or a classical
    method (:data:`CLASSICAL_METHODS`: ``rk4``, ``heun``, ``sdirk2``, ...; it reads no
    parameter).

    A family's entries are computed at whatever precision a check asks for, and held
    exactly in their number field when the nodes have a closed form in roots (the same
    tableau as a file's ``[family]`` table); a classical method has exact entries from
    the literature and the claims of ``rkcheck new NAME``.  ``name`` replaces the method's
    name.  Bad parameters, and parameters the method does not read, raise
    :class:`~rkcheck.errors.OptionError`."""
    method = _validate(method, stages, k)
    _refuse_unused(method, stages, k, rule, zeta, beta)
    if method not in FAMILIES:
        from rkcheck.methods.classics import classic_tableau

        tab = classic_tableau(_CLASSIC_NAMES[method])
    else:
        from rkcheck.methods.families import family_tableau

        tab = family_tableau(_option(lambda: _spec(method, stages, k, rule, zeta, beta)))
    return tab.replace(name=name) if name else tab


def _command_line(spec: "FamilySpec", mode: str, digits: int | None) -> str:
    """The ``rkcheck new`` command that writes ``spec`` (recorded in the file's description)."""
    parts = ["rkcheck new", spec.name]
    params = spec.params()
    if spec.name == "kernel":
        parts += [f"--zeta {params['zeta']}", f"--beta {params['beta']}"]
    else:
        parts.append(f"-s {spec.s}")
        if spec.name == "hbvm":
            parts.append(f"-k {spec.k}")
        if spec.name == "avf" and spec.rule != "gauss":
            parts.append(f"--rule {spec.rule}")
    if mode == "exact":
        parts.append("--exact")
    elif digits is not None:
        parts.append(f"--digits {digits}")
    return " ".join(parts)


def new_toml(method: str, *, stages: int | None = None, k: int | None = None, rule: str = "gauss",
             zeta: str | int | Fraction = "0", beta: str | int | Fraction = "1/10", digits: int | None = None,
             exact: bool = False, name: str | None = None) -> str:
    """The tableau file ``rkcheck new`` writes (TOML), with the parameters of :func:`new`.

    A family's entries are exact expressions when its nodes have a closed form (square
    roots, or ``root(p, k)`` of their polynomial up to ``MAX_EXACT_NODES`` = 8 nodes;
    ``[constants]`` for the nodes), plain fractions when they are rational, else 60-digit
    decimals (read back as rounded to their last digit, definitions §5);
    ``digits=D`` writes D-digit decimals instead, ``exact=True`` refuses to write
    decimals.  A classical method is written with its ``[expect]`` claims.  Parameters the
    method does not read raise :class:`~rkcheck.errors.OptionError`."""
    method = _validate(method, stages, k)
    exact = _option(lambda: parse_flag(exact, "exact"))
    _refuse_unused(method, stages, k, rule, zeta, beta, digits, exact)
    if method not in FAMILIES:
        from rkcheck.io.writers import document_toml
        from rkcheck.methods.classics import CLASSICS

        doc = CLASSICS[_CLASSIC_NAMES[method]].document()
        if name:
            doc["method"]["name"] = name
        return document_toml(doc)
    if exact and digits is not None:
        raise OptionError("give either --exact or --digits, not both")
    if digits is not None:
        _option(lambda: parse_int_in(digits, DIGITS_RANGE, "digits"))
    from rkcheck.io.writers import render_toml

    spec = _option(lambda: _spec(method, stages, k, rule, zeta, beta))
    mode = "exact" if exact else ("digits" if digits is not None else "auto")
    return render_toml(spec, mode, digits or 60, name, _command_line(spec, mode, digits))


__all__ = ["new", "new_toml"]