"""The gate of a check (definitions §5.3): whether its holds meet ``--require``, and
whether its conditions pass at all."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from rkcheck.energy.check import CheckResult, inconsistent
from rkcheck.numbers.formatting import count_text, digits_text
from rkcheck.verdicts import DECIDING_DIGITS, HOLDS_TO_DIGITS


@dataclass(frozen=True)
class Shortfall:
    """Why the holds of a check do not meet ``--require`` (definitions §5.3)."""

    require: str
    count: int  # conditions that hold only to too few digits (0: the certificate alone)
    examples: list[str]  # their ids, first ones in presentation order
    certificate: bool  # the certificate of every order holds only numerically
    claims: tuple[str, ...] = ()  # why each claim met only to too few digits (or orders) falls short

    def text(self) -> str:
        if self.require == "any":  # the shortfall of any is holds to 0 digits
            held, ending = "to 0 digits", ": not one digit is certain"
        else:
            held = "only to digits"
            ending = ", which is not " + ("a proof" if self.require == "proof"
                                          else digits_text(int(self.require.split(":")[1])))
        parts = []
        if self.count:
            ids = "; ".join(self.examples) + ("; …" if self.count > len(self.examples) else "")
            parts.append(f"{count_text(self.count)} condition{'s' if self.count != 1 else ''} hold"
                         f"{'s' if self.count == 1 else ''} {held} ({ids})")
        if self.certificate:
            parts.append(f"the certificate of every order holds {held}")
        parts.extend(self.claims)
        return f"--require {self.require}: " + "; ".join(parts) + ending


def requirement_shortfall(result: CheckResult, claims: list[Any] | None = None) -> Shortfall | None:
    """What keeps the holds of ``result`` from meeting its ``options.require``: conditions
    that hold only to digits (``proof``) or to fewer than D (``digits:D``), a certificate
    that is only numerical, or claims (``claims``, else the result's own) met only that
    way — or, for ``proof``, met by the orders checked without a proof beyond them.  None
    when the requirement is met, as it is by an exact certificate of every order (but
    for the claims on other properties).  Even
    ``any`` asks one certain digit of every holds (:data:`DECIDING_DIGITS`): a holds to 0
    digits decides nothing."""
    require = result.options.require
    need = DECIDING_DIGITS if require == "any" else result.options.required_digits
    claims = result.claims if claims is None else claims
    unmet = tuple(_claim_shortfall(r, need) for r in claims or () if r.met and _claim_short(r, need))
    # an exact certificate of every order proves each checked condition exactly, whatever
    # arithmetic evaluated the conditions themselves (definitions §5: a proof); it proves
    # nothing of a claim on another property (a classical order met to digits)
    if result.energy_order_all:
        return Shortfall(require, 0, [], False, unmet) if unmet else None

    def short(digits: np.ndarray) -> np.ndarray:
        return np.ones(len(digits), dtype=bool) if need is None else digits < need

    orders = result.conditions.orders.values()
    count = sum(int(np.count_nonzero((o.state == HOLDS_TO_DIGITS.code) & short(o.digits))) for o in orders)
    examples = []
    if count:
        for r in result.conditions.with_state(HOLDS_TO_DIGITS):
            if need is None or (r.verdict.digits or 0) < need:
                examples.append(r.id)
                if len(examples) == 3:
                    break
    cert_digits = result.energy_order_all_digits
    cert_short = cert_digits is not None and (need is None or cert_digits < need)
    if not count and not cert_short and not unmet:
        return None
    return Shortfall(require, count, examples, cert_short, unmet)


def _claim_short(r: Any, need: int | None) -> bool:
    """A met claim whose evidence falls short of ``proof`` (``need`` None) or of ``need``
    digits: it holds only to digits, or (for a proof) only to the orders checked."""
    if need is None:
        return r.digits is not None or not r.proven
    return r.digits is not None and r.digits < need


def _claim_shortfall(r: Any, need: int | None) -> str:
    if r.digits is not None:
        return f"the claim {r.name} holds only to {digits_text(r.digits)}"
    return f"the claim {r.name} is {r.note}"


def conditions_ok(result: CheckResult) -> bool:
    """Every checked condition holds, or a certificate proves them all; the method is
    consistent (``Σb = 1`` not certainly false); and the holds meet ``--require``."""
    if inconsistent(result):
        return False
    if not (result.all_hold or result.certified_all):
        return False
    return requirement_shortfall(result) is None
