"""The ``[continuous]`` table of a method file (definitions §6) ->
:class:`~rkcheck.methods.continuous.ContinuousMethod`.

Either ``A`` (a polynomial in ``tau`` and ``sigma``, ``τ``/``σ`` accepted) with an
optional ``b`` (``B(τ)``, default ``"1"``), or ``M``, the Miyatake–Butcher matrix
(SIAM J. Numer. Anal. 54 (2016), eq. (2.6)).  Coefficients follow the entry grammar and
the ``[constants]`` table; every problem is a one-line error naming the place.
"""

from __future__ import annotations

from typing import Any

from rkcheck.errors import UserError
from rkcheck.io.documents import BareFloat, bare_floats_warning, ignored_keys
from rkcheck.methods.continuous import ContinuousMethod, _unalias, with_written_columns
from rkcheck.methods.tableau import MethodInfo

KEYS = ("A", "b", "M")
def _text(value: Any, place: str) -> str:
    if isinstance(value, bool) or not isinstance(value, (int, str)):
        raise UserError(f"expected a polynomial in tau and sigma (a string), got {type(value).__name__}", place)
    return _unalias(str(value))


def from_document(data: dict[str, Any], name: str, info: MethodInfo, warnings: list[str],
                  parameters: dict[str, Any] | None = None, raw_constants: dict[str, Any] | None = None,
                  definitions: dict[str, Any] | None = None) -> Any:
    """The method of a document with ``[continuous]`` (``info`` carries its constants), or
    with ``parameters`` (the ``[parameters]`` table, the raw ``[constants]`` and their
    parsed definitions) the family of kernels."""
    if parameters is not None:
        return build_kernel_family(data["continuous"], name, info.replace(warnings=tuple(warnings)), parameters,
                                   raw_constants or {}, definitions or {})
    return build_continuous(data["continuous"], name, info, warnings)


def build_continuous(table: Any, name: str, info: MethodInfo, warnings: list[str]) -> ContinuousMethod:
    """The method of a ``[continuous]`` table (``info`` carries the ``[constants]``)."""
    if not isinstance(table, dict):
        raise UserError("[continuous] must be a table", "continuous")
    written = [table.get("A"), table.get("b"), *(x for row in table.get("M") or [] if isinstance(row, list) for x in row)]
    warnings = (warnings + ignored_keys(table, KEYS, "continuous")
                + bare_floats_warning([x for x in written if isinstance(x, BareFloat)]))
    info = info.replace(warnings=tuple(warnings))
    if "M" in table:
        if "A" in table or "b" in table:
            raise UserError("give either A (and b) or M, not both: M defines A and B itself", "continuous")
        return ContinuousMethod.from_matrix(table["M"], name=name, info=info)
    if "A" not in table:
        raise UserError('missing A (the kernel A(τ, σ), e.g. A = "tau") or M', "continuous")
    try:
        return ContinuousMethod(_text(table["A"], "continuous.A"), _text(table.get("b", "1"), "continuous.b"), name, info)
    except UserError as err:
        raise with_written_columns(err, {"continuous.A": str(table["A"]), "continuous.b": str(table.get("b", "1"))}) from None


def build_kernel_family(table: Any, name: str, info: MethodInfo, parameters_table: dict[str, Any],
                        raw_constants: dict[str, Any], definitions: dict[str, Any]) -> Any:
    """A ``[continuous]`` kernel with free ``[parameters]``: a family
    (:func:`~rkcheck.methods.continuous_family.kernel_family`)."""
    from rkcheck.methods.continuous_family import kernel_family
    from rkcheck.methods.parametric import parse_parameters

    if not isinstance(table, dict):
        raise UserError("[continuous] must be a table", "continuous")
    unknown = tuple(ignored_keys(table, ("A", "b"), "continuous"))
    info = info.replace(warnings=info.warnings + unknown)
    if "M" in table:
        raise UserError("a kernel with [parameters] is given by A (and b), not M", "continuous")
    if "A" not in table:
        raise UserError('missing A (the kernel A(τ, σ), e.g. A = "tau")', "continuous")
    parameters = parse_parameters(parameters_table, raw_constants)
    return kernel_family(name, parameters, _text(table["A"], "continuous.A"), _text(table.get("b", "1"), "continuous.b"),
                         definitions, info)
