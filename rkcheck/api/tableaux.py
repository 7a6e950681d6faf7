"""Tableaux in and out: files, text, ``@name``, arrays (:mod:`rkcheck.methods.arrays`
says what each kind of value means), and written forms."""

from __future__ import annotations

import os
from typing import Any

from rkcheck.errors import OptionError, TableauError, UserError
from rkcheck.methods.tableau import Tableau

#: ``rkcheck.from_arrays``: :meth:`Tableau.from_arrays`
from_arrays = Tableau.from_arrays
from rkcheck.numbers.reading import DecimalsMode
from rkcheck.options import DEFAULT_MAX_STAGES


def load(source: str | os.PathLike[str], *, max_stages: int = DEFAULT_MAX_STAGES,
         format: str | None = None) -> Tableau:
    """A tableau from a file (TOML, JSON, ``.csv``/``.tsv``, nodepy ``.txt``; ``format``
    overrides the guess by suffix) or ``"@name"`` (a shipped tableau such as ``@gauss-3``,
    or a classical method such as ``@rk4``).  A file with a ``[continuous]`` table gives a
    :class:`ContinuousMethod` (definitions §6), which ``verify`` takes like a tableau.
    Raises :class:`~rkcheck.errors.UserError` subclasses with the CLI's one-line message."""
    from rkcheck.io.loader import load as load_file

    if not isinstance(source, (str, os.PathLike)):
        raise UserError(f"expected a path (str or os.PathLike) or '@name', got {type(source).__name__}", "source")
    return load_file(os.fsdecode(source), max_stages=max_stages, fmt=format)


def loads(text: str, *, format: str = "toml", name: str = "<string>",
          max_stages: int = DEFAULT_MAX_STAGES) -> Tableau:
    """A tableau from the text of a tableau file (``format``: toml, json, csv, nodepy)."""
    from rkcheck.io.loader import loads as load_text

    if not isinstance(name, str):
        raise OptionError(f"expected the name its errors give the text (str), got {type(name).__name__}", "name")
    if isinstance(text, (bytes, bytearray)):
        try:
            text = bytes(text).decode("utf-8")
        except UnicodeDecodeError as err:
            raise UserError(f"not UTF-8 text (byte {err.start})", source=name) from None
    if not isinstance(text, str):
        raise UserError(f"expected the text of a tableau file (str), got {type(text).__name__}", source=name)
    return load_text(text, source=name, fmt=format, max_stages=max_stages)


def library() -> list[str]:
    """The names ``@name`` accepts: every shipped tableau (``collocation/gauss-3``) and
    every classical method of ``rkcheck new`` (``rk4``), sorted."""
    from rkcheck.io.library import entries
    from rkcheck.methods.classics import CLASSICS

    return sorted({e.key for e in entries()} | set(CLASSICS))


def write(tableau: Tableau, format: str = "toml") -> str:
    """The tableau as text: ``toml``/``json`` (a file rkcheck reads back exactly),
    ``latex`` (a Butcher array), ``julia`` or ``python`` (code with exact entries)."""
    from rkcheck.io.formats import write as write_tableau

    if getattr(tableau, "is_continuous", False):
        as_tableau(tableau)  # refused in one line, with the way to a tableau (discretize)
    if not isinstance(tableau, Tableau):
        raise UserError(f"expected a Tableau (rkcheck.load, rkcheck.from_arrays), got {type(tableau).__name__}")
    if not isinstance(format, str):
        raise OptionError(f"expected a format name (toml, json, latex, julia, python), got {format!r}", "format")
    return write_tableau(tableau, format)


def tableau_warnings(tableau: Tableau, decimals: str = "auto") -> list[str]:
    """Everything ``rkcheck show`` warns about: the warnings made while reading the
    tableau, then the consistency warnings of definitions §1 (a given ``c`` that certainly
    differs from ``A·1``, a certain ``Σb ≠ 1``), judged at the default precision with
    decimals read as ``decimals`` says (definitions §5)."""
    from rkcheck.errors import OptionError, UserError
    from rkcheck.evaluation.values import TableauValues
    from rkcheck.numbers.reading import Reading
    from rkcheck.options import DECIMALS_MODES, parse_choice

    try:
        decimals = parse_choice(decimals, DECIMALS_MODES, "decimals")
    except UserError as err:
        raise OptionError(err.message, err.place) from None
    return list(tableau.info.warnings) + TableauValues(tableau, Reading(DecimalsMode(decimals))).consistency_warnings()


#: What the API functions accept for a tableau: the object, a path or ``@name``.
TableauLike = Tableau | str | os.PathLike[str]


def as_tableau(tableau: "TableauLike | ContinuousMethod", max_stages: int = DEFAULT_MAX_STAGES, *,
               continuous: bool = False) -> Tableau:
    """A tableau given as itself, a path or ``@name`` (files read with ``max_stages``).
    ``continuous``: a continuous-stage method is welcome too (the checks take one, and
    then it is returned as it is; the commands that need stages refuse it in one line)."""
    if isinstance(tableau, (str, os.PathLike)):
        tableau = load(tableau, max_stages=max_stages)
    if getattr(tableau, "is_continuous", False):
        if continuous:
            method: Any = tableau  # checked like a tableau (definitions §6)
            return method
        raise TableauError("a continuous-stage method has no stages of its own, and this needs a tableau; "
                           "`rkcheck discretize FILE --rule gauss-K` (rkcheck.discretize) writes one",
                           source=tableau.info.source)
    if isinstance(tableau, Tableau):
        return tableau
    raise TableauError(f"expected a Tableau, a path or '@name', got {type(tableau).__name__}", "tableau")


from rkcheck.methods.continuous import ContinuousMethod  # noqa: E402 - a public name


def discretize(method: "ContinuousMethod | str | os.PathLike[str]", rule: "str | Tableau", *,
               command: str = "") -> tuple[str, str]:
    """The tableau file (TOML text) of a continuous-stage method on a quadrature rule
    (``gauss-3``, ``radau-ii-2``, ``lobatto-4``, ``newton-cotes-5``, or a tableau — or its
    file — whose b and c are the rule), and a sentence on the degree of Hamiltonian it keeps."""
    from rkcheck.energy.discretize import RULE_PATTERN
    from rkcheck.energy.discretize import discretize as build

    m = as_tableau(method, continuous=True)
    if not getattr(m, "is_continuous", False):
        raise TableauError("discretize takes a continuous-stage method ([continuous] A, b or M), not a tableau")
    if isinstance(rule, (str, os.PathLike)) and not RULE_PATTERN.fullmatch(os.fspath(rule).strip().lower()):
        rule = as_tableau(rule)  # a tableau file: its b and c
    elif not isinstance(rule, (str, Tableau)):
        raise UserError(f"expected a rule name, a tableau or its file, got {type(rule).__name__}", "rule")
    kernel: Any = m
    d = build(kernel, rule if isinstance(rule, Tableau) else os.fspath(rule))
    return _discretized_toml(m, d, command), d.reason


def _discretized_toml(method: Any, d: Any, command: str = "") -> str:
    """The tableau file (TOML) of a discretisation, through the one writer."""
    from rkcheck.io.writers import document_toml

    desc = (f"{method.name} discretised with the {d.rule} rule (quadrature order {d.quadrature_order}): "
            f"a_ij = b_j A(c_i, c_j), b_i = b_i B(c_i). {d.reason[0].upper()}{d.reason[1:]}.")
    if command:
        desc += f" Written by `{command}`."
    doc: dict[str, dict[str, Any]] = {"method": {"name": f"{method.name}, {d.rule}", "description": desc}}
    if d.constants:
        doc["constants"] = d.constants
    doc["tableau"] = {"A": d.A, "b": d.b, "c": d.c}
    if d.kept_degree is not None:
        doc["check"] = {"degree": d.kept_degree}
        doc["expect"] = {"energy_order": [{"degree": d.kept_degree, "value": "all"}]}
    return document_toml(doc, block_matrix=True)


__all__ = ["ContinuousMethod", "discretize", "from_arrays", "library", "load", "loads", "write"]