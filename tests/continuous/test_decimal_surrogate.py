"""A decimal kernel's surrogate entries as sums over the monomials in its decimals
(``Kernel.surrogate_entries``): each entry is ``Σ_μ v_μ·m_μ`` with the rationals ``v_μ``
formed by FLINT, not the kernel's expression at the nodes.  Checked against that
expression — the slower, obviously correct route, forced by allowing no term — entry by
entry (the value at face value, the enclosure over the box, the derivatives along every
literal) and through whole checks, whose reports must agree to the byte."""

from __future__ import annotations

import json
from fractions import Fraction

import pytest
from support.clirun import run_cli

import rkcheck.methods.kernel as kernel_module
from rkcheck.methods.continuous import ContinuousMethod
from rkcheck.numbers.intervals import Interval
from rkcheck.numbers.literals import literal_box
from rkcheck.numbers.reading import DecimalsMode

KERNELS = [
    # (A, b): decimals multiplying monomials, in powers and products, divided by numbers,
    # shared between A and b only where a matrix M writes them (test below)
    ("tau + 0.250000*tau^5*sigma^5 - 0.333333*tau^4*sigma^2", "1 + 0.142857*tau^5 - 0.142857*tau^4"),
    ("(0.300000*tau + 0.200000*sigma)^3 + tau - 0.5*sigma", "1"),
    ("tau*(1 - 0.123457*sigma)/3 + 0.123457^2*tau^2 - 1.0*sigma*tau", "0.666667 + 0.5*tau/0.25"),
    ("tau - 0.000000*tau^3*sigma + 2.5e-3*(2*sigma - 1)*tau^2", "1"),
    # decimals the expansion cancels, still numbers of the box in every entry
    ("tau + 0.250000*(tau^2 - tau)*(2*sigma - 1)*0", "1"),
    ("tau + (0.300000*tau)^0 - 1 + 0*0.700000*sigma", "1"),
]


def _surrogates(A, b, monkeypatch, vertices):
    """The surrogate by the monomials and by the kernel's expression (``MAX_LITERAL_TERMS``
    0: no kernel is taken apart)."""
    by_monomials = ContinuousMethod.from_kernel(A, b).surrogate(vertices)
    monkeypatch.setattr(kernel_module, "MAX_LITERAL_TERMS", 0)
    by_expression = ContinuousMethod.from_kernel(A, b).surrogate(vertices)
    monkeypatch.undo()
    return by_monomials, by_expression


@pytest.mark.parametrize("A, b", KERNELS)
def test_every_entry_is_the_kernels_expression_at_the_nodes(A, b, monkeypatch):
    fast, slow = _surrogates(A, b, monkeypatch, 4)
    pairs = [(x, y) for rf, rs in zip(fast.A, slow.A) for x, y in zip(rf, rs)] + list(zip(fast.b, slow.b))
    assert len(pairs) == len(fast.b) * (len(fast.b) + 1) and len(fast.b) > 2
    for x, y in pairs:
        assert x.exact == y.exact and x.rounded_digits == y.rounded_digits
        for mode in ("auto", "float64"):
            assert x.enclosure(DecimalsMode(mode)) == y.enclosure(DecimalsMode(mode)), (x.text, y.text)
    # the derivatives along the literals: each decimal one number in every entry
    entries = [x for x, _ in pairs], [y for _, y in pairs]
    boxes = [literal_box(e, 128, DecimalsMode("auto")) for e in entries]
    if boxes[1] is None:
        assert boxes[0] is None
    else:
        # a derivative that is 0 is the literal left out of the row (x^0 keeps no slope)
        def rows(box):
            return [{k: v for k, v in row.items() if v != Interval.point(0)} for row in box.rows]

        assert boxes[0].radii == boxes[1].radii and rows(boxes[0]) == rows(boxes[1])


def test_the_monomials_are_those_of_the_kernel_expanded_by_hand():
    # (0.3τ + 0.2σ)² = 0.3²·τ² + 2·0.3·0.2·τσ + 0.2²·σ², the literals kept as written
    parts = kernel_module.in_literals(ContinuousMethod.from_kernel("(0.300000*tau + 0.200000*sigma)^2").kernel.nodes[0],
                                      {})
    by_text = {kernel_module.xp.to_text(m): {k: Fraction(int(c.p), int(c.q)) for k, c in t.items()} for m, t in parts}
    assert by_text == {"0.300000^2": {(2, 0): 1}, "0.300000*0.200000": {(1, 1): 2}, "0.200000^2": {(0, 2): 1}}


@pytest.mark.parametrize("written, constants", [("sqrt(0.300000)*tau", None), ("k*tau", {"k": "0.700000"}),
                                                 ("(0.300000*tau + 0.200000*sigma + 0.100000)^12", None)])
def test_a_kernel_that_is_no_short_polynomial_in_its_decimals_keeps_its_expression(written, constants):
    # a root of a decimal, a constant (whose decimals its table owns), or more terms than
    # MAX_LITERAL_TERMS = 64 (a trinomial to the 12th has C(14, 2) = 91)
    kernel = ContinuousMethod.from_kernel(written, constants=constants).kernel
    assert kernel_module.MAX_LITERAL_TERMS < 91
    assert kernel_module.in_literals(kernel.nodes[0], {}) is None


@pytest.mark.parametrize("options", [(), ("--decimals", "float64"), ("--decimals", "exact")])
def test_checks_by_either_route_give_the_same_report(tmp_path, capsys, monkeypatch, options):
    path = tmp_path / "k.toml"
    path.write_text(f'[continuous]\nA = "{KERNELS[0][0]}"\nb = "{KERNELS[0][1]}"\n', encoding="utf-8")
    matrix = tmp_path / "m.toml"
    matrix.write_text('[continuous]\nM = [["4", "-6.000000"], ["-6.000000", "12"]]\n', encoding="utf-8")
    cancelled = tmp_path / "z.toml"  # a decimal times 0: still read as rounded, checked over its box
    cancelled.write_text('[continuous]\nA = "tau + 0.250000*(tau^2 - tau)*(2*sigma - 1)*0"\n', encoding="utf-8")

    def reports():
        out = []
        for f in (path, matrix, cancelled):
            r = run_cli(capsys, "verify", str(f), "-N", "4", "-m", "none", "--format", "json", *options)
            doc = json.loads(r.out)
            doc.pop("timings")
            out.append((r.code, doc))
        return out

    fast = reports()
    monkeypatch.setattr(kernel_module, "MAX_LITERAL_TERMS", 0)
    assert reports() == fast


def test_a_long_power_of_decimals_is_given_up_as_it_grows(tmp_path):
    # (l1 + … + l5)^200 has C(204, 4) ≈ 7·10⁷ terms: formed whole before its size was
    # looked at, it took gigabytes and ignored signals inside FLINT; multiplied out factor
    # by factor it passes MAX_LITERAL_TERMS at the fourth, and the kernel keeps its
    # expression (one entry of the kernel's own, as before)
    from support.limits import run_limited

    path = tmp_path / "k.toml"
    path.write_text('[continuous]\nA = "tau + 0.000000*(0.100000+0.200000+0.300000+0.400000+0.500000)^200"\n',
                    encoding="utf-8")
    run = run_limited(["-m", "rkcheck", "verify", str(path), "--order", "3", "--format", "json"], memory_mb=400,
                      cpu_seconds=30)
    assert run.code == 0, (run.code, run.err[-300:])
    assert json.loads(run.out)["summary"]["verdict"] == "holds_to_digits"
