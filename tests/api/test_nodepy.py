"""nodepy interop (skipped cleanly without nodepy): every method of nodepy's own library
is read, exactly where nodepy is exact; nodepy's own order() (its independent order
conditions) agrees with rkcheck's classical order on the exact ones; rkcheck → nodepy →
rkcheck gives the same exact tableau."""

from __future__ import annotations

from fractions import Fraction

import pytest

import rkcheck

rk = pytest.importorskip("nodepy.runge_kutta_method")
sp = pytest.importorskip("sympy")

LIBRARY = rk.loadRKM("All")


def _is_float(x) -> bool:
    return isinstance(x, (float, sp.Float))


@pytest.mark.filterwarnings("ignore::rkcheck.RkcheckWarning")
@pytest.mark.parametrize("key", sorted(LIBRARY))
def test_every_nodepy_method_reads(key):
    method = LIBRARY[key]
    tab = rkcheck.from_nodepy(method)
    exact = rkcheck.from_nodepy(method, floats="exact")
    assert tab.stages == len(method.b)
    for row, erow, nrow in zip(tab.A, exact.A, method.A):
        for e, f, x in zip(row, erow, nrow):
            if isinstance(x, sp.Rational):
                assert e.exact == f.exact == Fraction(int(x.p), int(x.q))
            elif _is_float(x):
                assert e.text == repr(float(x))  # the decimal it prints as, by default
                assert f.exact == Fraction(float(x))  # the exact binary value, on request


#: nodepy's methods with entries stored as floats (numpy floats or sympy Floats)
FLOATS = [k for k in sorted(LIBRARY) if any(_is_float(x) for x in list(LIBRARY[k].A.flat) + list(LIBRARY[k].b))]


def _json_number(x):
    if isinstance(x, sp.Rational):
        return f"{x.p}/{x.q}"
    return float(x) if _is_float(x) else str(x)


@pytest.mark.parametrize("key", FLOATS)
def test_float_methods_read_as_verify_reads_their_json(key, tmp_path, capsys):
    # the same floats written to JSON (json.dumps writes each float's repr) and checked by
    # the CLI: the API reading must give the same document, condition for condition
    import json

    from support.clirun import run_cli

    method = LIBRARY[key]
    doc = {"A": [[_json_number(x) for x in row] for row in method.A], "b": [_json_number(x) for x in method.b],
           "c": [_json_number(x) for x in method.c]}
    path = tmp_path / f"{key}.json"
    path.write_text(json.dumps(doc))
    cli = json.loads(run_cli(capsys, "verify", str(path), "--order", "6", "--format", "json").out)
    with pytest.warns(rkcheck.RkcheckWarning):
        api = rkcheck.verify(rkcheck.from_nodepy(method), order=6).to_dict()
    assert api["summary"] == cli["summary"] and api["conditions"] == cli["conditions"]


def test_tsit5_reaches_order_5_to_digits():
    # Tsitouras (2011) designed Tsit5 with classical order 5; nodepy stores it in
    # doubles, so order 5 is reached to digits only, and order 6 certainly fails
    with pytest.warns(rkcheck.RkcheckWarning):
        result = rkcheck.verify(rkcheck.from_nodepy(LIBRARY["Tsit5"]), order=6)
    assert result.classical.to_digits == 5 and result.classical.first_failure is not None
    assert result.classical_order < 5 and result.classical.digits is not None


EXACT = [k for k in sorted(LIBRARY) if all(isinstance(x, sp.Rational) for x in list(LIBRARY[k].A.flat)
                                           + list(LIBRARY[k].b))]


@pytest.mark.parametrize("key", [k for k in EXACT if len(LIBRARY[k].b) <= 7])
def test_classical_order_agrees_with_nodepy(key):
    method = LIBRARY[key]
    p = method.order()
    result = rkcheck.verify(rkcheck.from_nodepy(method), order=min(p + 1, 7), degree=2)
    assert result.classical_order == min(p, result.classical.checked)


@pytest.mark.parametrize("name", ["@rk4", "@gauss-3", "@sdirk2", "@radau-iia-2"])
def test_round_trip_through_nodepy(name):
    tab = rkcheck.load(name)
    back = rkcheck.from_nodepy(rkcheck.to_nodepy(tab))
    for row, brow in zip(tab.A, back.A):
        for e, f in zip(row, brow):
            if e.exact is not None:
                assert f.exact == e.exact
            else:
                a, b = e.enclosure(300), f.enclosure(300)
                assert abs(a.mid - b.mid) <= a.rad + b.rad and a.rad < Fraction(1, 10**80)
    assert back.name == tab.name


def test_not_a_method():
    with pytest.raises(rkcheck.TableauError):
        rkcheck.from_nodepy(object())


def test_algebraic_entries_beyond_square_roots_stay_exact():
    # SDIRK34 (Crouzeix/Alexander): γ = 1/2 + √3 cos(π/18)/3, a root of 24x³ − 36x² + 12x − 1
    method = LIBRARY["SDIRK34"]
    tab = rkcheck.from_nodepy(method)
    g = tab.A[0][0]
    assert g.text.startswith("root(") and g.exact is None
    gamma = sp.Rational(1, 2) + sp.sqrt(3) * sp.cos(sp.pi / 18) / 3
    assert sp.expand(24 * gamma**3 - 36 * gamma**2 + 12 * gamma - 1).equals(0)
    enc = g.enclosure(200)
    assert abs(sp.Rational(enc.mid.numerator, enc.mid.denominator) - gamma).evalf(70) <= enc.rad + sp.Rational(1, 10**55)
    assert rkcheck.verify(tab, order=5, degree=2).classical_order == method.order() == 4
