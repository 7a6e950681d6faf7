"""What a check computes from the tableau alone is computed once for a file and its claims,
and the classical order in a number field skips roots whose channels repeat another's.

Independent facts used: Gauss–Legendre with s stages has classical order 2s (Butcher
1964), is symplectic and symmetric, and its stability function is the diagonal Padé
approximant, so R(z)R(−z) = 1 (Hairer–Lubich–Wanner, §IV.3, §VI.4)."""

from __future__ import annotations

import pytest
from support.paths import TABLEAUX

import rkcheck
import rkcheck.energy.check as check_module
import rkcheck.evaluation.scaled as scaled_module
from rkcheck.evaluation.values import TableauValues
from rkcheck.io.loader import load
from rkcheck.numbers.reading import Reading
from rkcheck.properties.orders import classical_order


def test_claim_runs_share_the_properties_of_the_main_run(monkeypatch):
    calls = []
    real = check_module.properties_of_values

    def counted(*scalars, **options):
        calls.append(1)
        return real(*scalars, **options)

    monkeypatch.setattr(check_module, "properties_of_values", counted)
    # gauss-3.toml claims energy orders for degrees 2 and 3 besides its own run: three runs
    result = rkcheck.verify(str(TABLEAUX / "collocation" / "gauss-3.toml"), order=6)
    assert len(calls) == 1
    assert all(c.met for c in result.claims)
    assert result.properties.symplectic.holds and result.properties.symmetric.holds
    assert result.properties.stability.leading_power is None  # R(z)R(−z) ≡ 1


@pytest.mark.parametrize("name, order", [("gauss-3", 6), ("gauss-5", 10)])
def test_classical_order_with_repeated_channels_skipped(name, order, monkeypatch):
    values = TableauValues.of(load(str(TABLEAUX / "collocation" / f"{name}.toml")), Reading())
    found = classical_order(values, order + 2)
    assert found.order == order and found.first_failure is not None
    # the same with every root evaluated: no channel is taken as a copy
    monkeypatch.setattr(scaled_module.ScaledTableau, "channel_sources",
                        lambda self, p: list(range(len(self._roots_of(p)))))
    every = classical_order(TableauValues.of(values.tableau, Reading()), order + 2)
    assert (every.order, every.first_failure) == (found.order, found.first_failure)
