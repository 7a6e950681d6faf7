"""Remembered products and inverses in large number fields give exactly the products
and inverses computed afresh (polynomial arithmetic modulo the minimal polynomial, and
for the inverse the defining identity x·x⁻¹ = 1), also when two keys collide."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest
from support.heavy import heavy
from support.paths import TABLEAUX

import rkcheck.numbers.algebraic as alg
from rkcheck.numbers.algebraic import NumberField


@pytest.fixture
def field():
    # x^16 − 2 is irreducible (Eisenstein at 2): a field of degree 16 remembers
    return NumberField([-2] + [0] * 15 + [1], 2)


def _element(K, rng):
    return K([Fraction(rng.randint(-50, 50), rng.randint(1, 9)) for _ in range(K.degree)])


def _fresh_product(x, y):
    return (x.poly * y.poly) % x.field.g


def test_products_and_inverses_are_those_computed_afresh(field):
    assert field.degree >= alg.MEMO_MIN_DEGREE
    rng = random.Random(3)
    xs = [_element(field, rng) for _ in range(12)]
    for _ in range(3):  # the second and third rounds come from the memo
        for x in xs:
            for y in xs:
                assert (x * y).poly == _fresh_product(x, y)
            assert (x * x.inverse()).poly == 1
    assert len(field._products) > 0


def test_a_hash_collision_is_never_a_wrong_answer(field, monkeypatch):
    monkeypatch.setattr(alg._PolyKey, "__init__", lambda self, poly: (setattr(self, "poly", poly),
                                                                      setattr(self, "h", 0))[0])
    rng = random.Random(5)
    xs = [_element(field, rng) for _ in range(6)]
    for x in xs:
        for y in xs:
            assert (x * y).poly == _fresh_product(x, y)


def test_the_memo_is_bounded(field, monkeypatch):
    monkeypatch.setattr(alg, "MEMO_SIZE", 5)
    rng = random.Random(7)
    xs = [_element(field, rng) for _ in range(8)]
    for x in xs:
        for y in xs:
            assert (x * y).poly == _fresh_product(x, y)
            assert len(field._products) <= 5


def test_small_fields_do_not_remember():
    K = NumberField([-2, 0, 1], 2)
    x = K([1, 1])
    assert (x * x).poly == _fresh_product(x, x) and not K._products


@heavy
def test_an_hbvm_6_check_is_the_same_without_the_memo(monkeypatch):
    # the degree-48 field of HBVM(6, 3): every verdict, residual and order as without
    # remembering (each run builds its own field, so nothing is shared between them)
    from rkcheck.api import load
    from rkcheck.energy.check import check
    from rkcheck.options import CheckOptions

    def report():
        t = load(str(TABLEAUX / "hbvm" / "hbvm-6-3.toml"))
        t = getattr(t, "tableau", t)
        r = check(t, CheckOptions(degree=5, order=7))
        return ([(c.id, str(c.verdict), str(c.residual)) for c in r.conditions], r.energy_order,
                r.quadrature, r.classical, str(r.certificate))

    remembered = report()
    monkeypatch.setattr(alg, "MEMO_MIN_DEGREE", 10**9)
    assert report() == remembered
