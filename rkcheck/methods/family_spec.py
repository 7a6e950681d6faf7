"""A method family's parameters: the ``[family]`` table and ``rkcheck new``, validated.

A :class:`FamilySpec` names a family (Gauss, Radau, Lobatto, AVF over a rule, HBVM, the
seed's kernel family) and its parameters; :mod:`rkcheck.methods.families` computes its
coefficients and :mod:`rkcheck.methods.closed_forms` writes them exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rkcheck.errors import UserError
from rkcheck.methods.quadrature import Rule, rule
from rkcheck.numbers import grammar as ex
from rkcheck.numbers.entries import Entry
from rkcheck.options import MAX_FAMILY_STAGES, shown_value

FAMILIES = ("avf", "gauss", "lobatto-iiia", "lobatto-iiib", "radau-iia", "radau-ia", "hbvm", "kernel")
TITLES = {
    "gauss": "Gauss–Legendre collocation",
    "lobatto-iiia": "Lobatto IIIA",
    "lobatto-iiib": "Lobatto IIIB",
    "radau-iia": "Radau IIA",
    "radau-ia": "Radau IA",
}
PARAMS = {
    "avf": ("s", "rule"),
    "gauss": ("s",),
    "lobatto-iiia": ("s",),
    "lobatto-iiib": ("s",),
    "radau-iia": ("s",),
    "radau-ia": ("s",),
    "hbvm": ("k", "s"),
    "kernel": ("zeta", "beta"),
}


@dataclass(frozen=True)
class FamilySpec:
    name: str
    s: int
    k: int | None = None
    rule: str = "gauss"
    zeta: Fraction | None = None
    beta: Fraction | None = None

    def title(self) -> str:
        if self.name == "avf":
            return f"AVF over the {self.s}-point {self.rule} rule"
        if self.name == "hbvm":
            return f"HBVM({self.k}, {self.s})"
        if self.name == "kernel":
            return f"Seed kernel family, ζ = {self.zeta}, β = {self.beta}"
        return f"{TITLES[self.name]}, {self.s} stage{'s' if self.s != 1 else ''}"

    def stages(self) -> int:
        return self.s

    def base_rule(self) -> Rule:
        if self.name == "avf":
            return rule(self.rule, self.s)
        if self.name in ("gauss", "hbvm"):
            return rule("gauss", self.k if self.name == "hbvm" else self.s)
        if self.name in ("lobatto-iiia", "lobatto-iiib"):
            return rule("lobatto", self.s)
        if self.name == "radau-iia":
            return rule("radau-ii", self.s)
        if self.name == "radau-ia":
            return rule("radau-i", self.s)
        assert self.name == "kernel"
        assert self.zeta is not None  # the kernel family is given one (parse_spec)
        return rule(f"zeta:{ex.fraction_text(self.zeta)}", 2)  # at any length

    def params(self) -> dict[str, Any]:
        out: dict[str, Any] = {"name": self.name}
        if self.name == "hbvm":
            out.update(k=self.k, s=self.s)
        elif self.name == "kernel":
            out.update(zeta=str(self.zeta), beta=str(self.beta))
        else:
            out["s"] = self.s
            if self.name == "avf":
                out["rule"] = self.rule
        return out


def _exact(text: Any, place: str) -> Fraction:
    if isinstance(text, (int, Fraction)) and not isinstance(text, bool):
        return Fraction(text)  # as it is (str() of a rational past 4 300 digits would raise)
    try:
        e = Entry.parse(str(text))
    except UserError as err:
        raise err.located(place) from None
    if e.exact is None:
        raise UserError(f"expected a rational number, got {shown_value(text)}", place)
    return e.exact


def _positive(value: Any, place: str, minimum: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise UserError(f"expected an integer >= {minimum}, got {value!r}", place)
    if value > MAX_FAMILY_STAGES:
        raise UserError(f"at most {MAX_FAMILY_STAGES}, got {value}", place)
    return value


def parse_spec(table: dict[str, Any]) -> FamilySpec:
    """Validate a ``[family]`` table (``place`` in errors: ``family.k``)."""
    name = table.get("name")
    if name not in FAMILIES:
        raise UserError(f"unknown family {name!r} (known: {', '.join(FAMILIES)})", "family.name")
    known = {"name", "stages", *PARAMS[name]}
    for key in table:
        if key not in known:
            raise UserError(f"unknown parameter for {name} (known: {', '.join(sorted(known - {'name'}))})", f"family.{key}")
    if name == "kernel":
        zeta = _exact(table.get("zeta", "0"), "family.zeta")
        beta = _exact(table.get("beta", "0"), "family.beta")
        return FamilySpec(name, 2, zeta=zeta, beta=beta)
    s_raw = table.get("s", table.get("stages"))
    if s_raw is None:
        raise UserError("missing s (the number of stages)", "family")
    minimum = 2 if name.startswith("lobatto") else 1
    s = _positive(s_raw, "family.s", minimum)
    if name == "hbvm":
        if "k" not in table:
            raise UserError("missing k (the number of Gauss nodes)", "family")
        k = _positive(table["k"], "family.k", s)
        return FamilySpec(name, s, k=k)
    if name == "avf":
        rule_name = table.get("rule", "gauss")
        if not isinstance(rule_name, str):
            raise UserError("expected a rule name", "family.rule")
        if rule_name == "lobatto" and s < 2:
            raise UserError("lobatto needs s >= 2", "family.s")
        rule(rule_name, s)  # validates the name
        return FamilySpec(name, s, rule=rule_name)
    return FamilySpec(name, s)


# ----------------------------------------------------------------- intervals
