"""Claims: the ``[expect]`` table of a tableau file, as data.

A method's author states the published properties of the method::

    [expect]
    energy_order = {degree = 4, order = 8, value = "all"}   # or value = 4; degree = "none"
    avf = {degree = 4, value = true}
    classical_order = 4
    quadrature_order = 4
    symplectic = true                                        # BA + AᵀB − bbᵀ = 0
    symmetric = true                                         # adjoint = method
    stability_defect = 0                                     # R(z)R(−z) ≡ 1, or the leading
    # term of R(z)R(−z) − 1: stability_defect = {power = 6, coefficient = "1/72"}

``energy_order`` and ``avf`` may also be lists of such tables (one per degree).  This
module validates the table into :class:`Claim` values; what each claim means and how it
is judged is :mod:`rkcheck.energy.claims`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rkcheck.errors import UserError
from rkcheck.options import MAX_ORDER, parse_degree

CLAIM_KINDS = ("energy_order", "avf", "classical_order", "quadrature_order", "symplectic", "symmetric",
               "stability_defect")
BOOLEAN_KINDS = ("symplectic", "symmetric")


@dataclass(frozen=True)
class Claim:
    """One claim of a tableau's ``[expect]`` table: its kind, the claimed value and where it was written."""

    kind: str
    value: int | str | bool
    degree: int | None = None
    order: int | None = None
    place: str = ""  # "expect.energy_order" or "expect.energy_order[2]"
    power: int | None = None  # stability_defect: the power of the leading term (None: R(z)R(−z) ≡ 1)
    coefficient: str | None = None  # stability_defect: its coefficient, as an entry text

    def label(self) -> str:
        if self.kind in ("energy_order", "avf"):
            deg = "all H" if self.degree is None else f"degree {self.degree}"
            return f"{self.kind} ({deg})"
        return self.kind


#: The highest ``classical_order`` claim: judging p checks the rooted trees of p + 1
#: vertices (87 811 at 15, seconds; each vertex more about 2.7 times the trees, time
#: and memory: 17 vertices took 70 s and 2.3 GB).  Feagin's order-14 methods fit.
MAX_CLASSICAL_CLAIM = 14


def _is_count(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _int(value: Any, place: str, minimum: int = 0, maximum: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise UserError(f"expected an integer >= {minimum}, got {value!r}"[:120], place)
    if maximum is not None and value > maximum:
        # judging the claim checks one order beyond it: keep that within MAX_ORDER
        raise UserError(f"expected an integer from {minimum} to {maximum}, got {value}"[:120], place)
    return value


def _stability_defect(raw: Any, place: str) -> Claim:
    """``0`` (R(z)R(−z) ≡ 1) or ``{power = 2k, coefficient = "p/q"}`` (its leading term)."""
    if raw == 0 or raw == "0":
        return Claim("stability_defect", "0", place=place)
    if not isinstance(raw, dict):
        raise UserError('expected 0 or a table like {power = 6, coefficient = "1/72"}', place)
    unknown = set(raw) - {"power", "coefficient"}
    if unknown:
        raise UserError(f"unknown key {sorted(unknown)[0]!r} (known: power, coefficient)", place)
    for key in ("power", "coefficient"):
        if key not in raw:
            raise UserError(f"missing {key}", place)
    power = _int(raw["power"], f"{place}.power", 2)
    if power % 2:
        raise UserError("R(z)R(−z) − 1 is even: the power must be even", f"{place}.power")
    coef = raw["coefficient"]
    if isinstance(coef, bool) or not isinstance(coef, (str, int)):
        raise UserError(f"expected a number as a string, got {coef!r}", f"{place}.coefficient")
    from rkcheck.numbers.entries import Entry

    try:
        entry = Entry.parse(str(coef))
    except UserError as err:
        raise UserError(err.message, f"{place}.coefficient") from None
    if entry.exact == 0:
        raise UserError("the leading coefficient is nonzero (claim 0 for R(z)R(−z) ≡ 1)", f"{place}.coefficient")
    return Claim("stability_defect", f"{coef} z^{power}", place=place, power=power, coefficient=str(coef))


def _one(kind: str, raw: Any, place: str) -> Claim:
    if kind in BOOLEAN_KINDS:
        if isinstance(raw, dict):
            unknown = set(raw) - {"value"}
            if unknown:
                raise UserError(f"unknown key {sorted(unknown)[0]!r} (known: value)", place)
            raw = raw.get("value")
        if not isinstance(raw, bool):
            raise UserError(f"expected true or false, got {raw!r}", place)
        return Claim(kind, raw, place=place)
    if kind == "stability_defect":
        return _stability_defect(raw, place)
    if kind in ("classical_order", "quadrature_order"):
        if isinstance(raw, dict):
            raw = raw.get("value")
        if kind == "classical_order" and _is_count(raw) and raw > MAX_CLASSICAL_CLAIM:
            raise UserError(f"expected an integer from 0 to {MAX_CLASSICAL_CLAIM}, got {raw} (the limit "
                            "MAX_CLASSICAL_CLAIM: judging it checks every rooted tree of one more vertex)", place)
        return Claim(kind, _int(raw, place, 0), place=place)
    if not isinstance(raw, dict):
        raise UserError("expected a table like {degree = 4, value = ...}", place)
    unknown = set(raw) - {"degree", "order", "value"}
    if unknown:
        raise UserError(f"unknown key {sorted(unknown)[0]!r} (known: degree, order, value)", place)
    if "value" not in raw:
        raise UserError("missing value", place)
    if kind == "avf" and "degree" not in raw:
        raise UserError("missing degree (AVF is defined for a polynomial degree m)", place)
    degree = parse_degree(raw.get("degree"), f"{place}.degree")
    order = _int(raw["order"], f"{place}.order", 1, MAX_ORDER) if "order" in raw else None
    value = raw["value"]
    if kind == "avf":
        if not isinstance(value, bool):
            raise UserError(f"expected true or false, got {value!r}", f"{place}.value")
        if degree is None:
            raise UserError("AVF needs a polynomial degree", f"{place}.degree")
    elif value != "all":
        value = _int(value, f"{place}.value", 1, MAX_ORDER - 1)
    return Claim(kind, value, degree, order, place)


def parse_claims(expect: dict[str, Any]) -> list[Claim]:
    """Validate an ``[expect]`` table; errors name the claim (``expect.avf.value``)."""
    claims: list[Claim] = []
    for kind, raw in expect.items():
        place = f"expect.{kind}"
        if kind not in CLAIM_KINDS:
            raise UserError(f"unknown claim (known: {', '.join(CLAIM_KINDS)})", place)
        if isinstance(raw, list) and kind in ("energy_order", "avf"):
            if not raw:  # a gate that reads this file would check nothing it seems to
                raise UserError("an empty list claims nothing: give one table per degree, or leave the key out", place)
            claims.extend(_one(kind, item, f"{place}[{i}]") for i, item in enumerate(raw, start=1))
        else:
            claims.append(_one(kind, raw, place))
    return claims
