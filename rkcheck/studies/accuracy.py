"""Accuracy against speed: the same check over several backends, and perturbation sweeps.

* :func:`bench_backends` — one row per backend (float64 screen, certified balls at each
  dps, exact when rational): time, conditions per second, the weakest certified digits of
  the conditions that hold, the number of certified failures, and whether the verdicts
  agree with the most precise backend.
* :func:`perturb_sweep` — ``A + εD`` for a direction D (random, the zero-row-sum kernel
  direction of the double-bush map, or one entry), for each ε: max |R| over failing
  conditions, first failing order, which backends still detect the failure; the fitted
  slope of log max|R| against log ε (1 for generic directions, 2 for kernel directions,
  seed §2.4) and each backend's detection threshold ε*.
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rkcheck.energy.results import classify_sums
from rkcheck.errors import UserError
from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.backends import ball_context, float_context
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.values import TableauValues
from rkcheck.methods.tableau import MethodInfo, Tableau
from rkcheck.numbers.enclosure import Enclosure
from rkcheck.numbers.entries import Entry
from rkcheck.numbers.reading import DEFAULT_READING, Reading
from rkcheck.trees.listing import condition_listing
from rkcheck.verdicts import (
    FAILS,
    HOLDS,
    HOLDS_TO_DIGITS,
    Verdict,
)

DEFAULT_DPS_LIST = (15, 30, 50, 100, 200, 400)


def evaluate_backend(listing, values: TableauValues, name: str):
    """Every condition of ``listing`` on one backend — ``float64``, ``exact`` or
    ``dps:<D>`` — as ``{(vertices, k): (enclosure, verdict)}`` in listing order (the
    enclosure is the class representative's: sizes and verdicts do not depend on it)."""
    if name == "exact":
        # backend_names offers "exact" only for exact values
        out = {}
        for n, o in exact_condition_sums(values.scaled, listing).items():
            zero = o.is_zero()
            for k in range(len(zero)):
                v = o.value(k)
                if not isinstance(v, Fraction):  # a number-field element: a tight enclosure of it
                    iv = v.enclosure(256)
                    enc = Enclosure(iv.mid, iv.rad, v.rational() is not None)
                else:
                    enc = Enclosure.of(v)
                out[(n, k)] = (enc, Verdict(HOLDS) if zero[k] else Verdict(FAILS))
        return out
    ctx = float_context(values) if name == "float64" else ball_context(values.at(int(name[4:])))
    sums = condition_sums(listing, ctx, values.stages)
    out = {}
    for n, order_sums in sums.items():
        states, digits = classify_sums(order_sums)
        for k in range(len(order_sums)):
            v = Verdict(FAILS) if states[k] == FAILS.code else Verdict(HOLDS_TO_DIGITS, int(digits[k]))
            out[(n, k)] = (order_sums.enclosure(k), v)
    return out


def backend_names(values: TableauValues, dps_list) -> list[str]:
    names = ["float64"] + [f"dps:{d}" for d in dps_list]
    if values.kind.is_exact:
        names.append("exact")
    return names


def label(name: str) -> str:
    return f"balls dps {name[4:]}" if name.startswith("dps:") else name


@dataclass
class BenchRow:
    backend: str
    seconds: float
    conditions: int
    min_digits: int | None  # weakest certified digits among the held conditions (None: all exact)
    failures: int
    agrees: bool
    failing_ids: frozenset = field(default_factory=frozenset, repr=False)

    @property
    def per_second(self) -> float:
        return self.conditions / self.seconds if self.seconds > 0 else math.inf


def bench_backends(tableau: Tableau, degree: int | None, order: int, dps_list=DEFAULT_DPS_LIST,
                   reading: Reading = DEFAULT_READING, repeat: int = 1) -> tuple[list[BenchRow], float]:
    """Rows per backend, and the time to build the (shared) condition table."""
    t0 = time.perf_counter()
    listing = condition_listing(order, degree)
    t_tables = time.perf_counter() - t0
    values = TableauValues.of(tableau, reading)
    rows: list[BenchRow] = []
    for name in backend_names(values, dps_list):
        best = math.inf
        results = None
        for _ in range(max(1, repeat)):
            t1 = time.perf_counter()
            results = evaluate_backend(listing, values, name)
            best = min(best, time.perf_counter() - t1)
        assert results is not None
        digits = [v.digits for _, v in results.values() if v.state == HOLDS_TO_DIGITS]
        failing = frozenset(key for key, (_, v) in results.items() if v.state == FAILS)
        rows.append(BenchRow(name, best, len(results), min(digits) if digits else None, len(failing), True, failing))
    reference = rows[-1]  # exact when rational, else the highest dps
    for r in rows:
        r.agrees = r.failing_ids == reference.failing_ids
    return rows, t_tables


# ------------------------------------------------------------------ perturbation


def parse_eps(text: str) -> list[Fraction]:
    """``1e-1..1e-40`` (every decade), ``1e-2..1e-30:2`` (every 2nd decade) or ``1e-3,1e-6``:
    each value a rational number in the entries' grammar, read exactly (its exponent
    bounded as an entry's, ``MAX_DECIMAL_EXPONENT``)."""
    text = text.strip()
    try:
        if ".." in text:
            lo, _, rest = text.partition("..")
            hi, _, step = rest.partition(":")
            ea, eb = _decade(_eps_value(lo)), _decade(_eps_value(hi))
            if ea is None or eb is None:
                raise UserError(f"a range's ends are powers of ten (1e-1..1e-40), got {text!r}", "--eps")
            k = int(step) if step.strip() else 1
            if k < 1:
                raise ValueError
            sign = -1 if eb < ea else 1
            return [Fraction(10) ** e for e in range(ea, eb + sign, sign * k)]
        return [_eps_value(x) for x in text.split(",") if x.strip()]
    except (ValueError, ZeroDivisionError):
        raise UserError(f"cannot read {text!r} (examples: 1e-1..1e-40, 1e-2..1e-30:2, 1e-3,1e-6)", "--eps") from None


def _eps_value(text: str) -> Fraction:
    from rkcheck.numbers.expressions import rational_text_value

    try:
        value = rational_text_value(text)
    except UserError as err:
        raise UserError(f"{text.strip()!r}: {err.message}", "--eps") from None
    if value is None:
        raise ValueError(text)
    return value


def _decade(x: Fraction) -> int | None:
    """e where x = 10^e exactly, else None."""
    if x <= 0 or 1 not in (x.numerator, x.denominator):
        return None
    power = x.denominator if x.numerator == 1 else x.numerator
    e = len(str(power)) - 1
    if 10**e != power:
        return None
    return -e if x.numerator == 1 else e


def mpf_fraction(x) -> Fraction:
    """The exact value of an mpmath number as a Fraction (mantissa · 2^exponent): every
    bit kept, whatever the current mpmath precision (``str()`` would round it to the
    global ``mp.dps``, 15 digits by default)."""
    import mpmath

    if not isinstance(x, mpmath.mpf):  # mpf(x) of an mpf would round it to the global precision
        x = mpmath.mpf(x)
    if not mpmath.isfinite(x):
        raise ValueError(f"not a finite number: {x}")
    sign, man, exp, _ = x._mpf_  # (sign, |mantissa|, exponent, bits); zero is (0, 0, 0, 0)
    man = -int(man) if sign else int(man)  # int(): gmpy2 mantissas would leak into Fraction
    return Fraction(man * 2 ** exp) if exp >= 0 else Fraction(man, 2 ** -exp)


def direction_dps(eps_list, dps_list=(15, 50), dps: int = 60) -> int:
    """The precision at which a numerical kernel direction is computed for a sweep.

    With D = N + η (N in the kernel, |η| ≈ 10^-P at P digits), the perturbed tableau
    has R(ε) = K ε² + O(ε|η|): the conditions linear in A really fail, at about
    ε·10^-P.  Computing D 20 digits beyond the reference backend
    (:func:`reference_dps`) keeps that part inside every backend's radius for all
    ε ≤ 1, so that what the sweep certifies is the kernel direction's own quadratic
    failure (seed §2.4), not the rounding of D."""
    return max(dps, reference_dps(eps_list, dps_list) + 20)


def direction(tableau: Tableau, kind: str, degree: int | None, seed: int = 2024, dps: int | None = None):
    """(D as a matrix of Fractions with max |d_ij| = 1, a description).

    The kernel direction (seed §2.4, §3–4: ker M ∩ {N·1 = 0} of the double-bush map) is
    exact when the tableau is rational (elimination over Q); otherwise it is computed at
    ``dps`` digits and every bit of that numerical vector is kept (:func:`mpf_fraction`),
    so that D is within ~10^-dps of the kernel: choose ``dps`` with
    :func:`direction_dps` for the sweep (default: the CLI's default sweep, ε down to
    10^-30 with balls at 15 and 50 digits)."""
    if dps is None:
        dps = direction_dps(parse_eps("1e-1..1e-30"))
    s = tableau.stages
    if kind == "random":
        rng = random.Random(seed)
        D = [[Fraction(rng.randint(-10**6, 10**6), 10**6) for _ in range(s)] for _ in range(s)]
        desc = f"random (seed {seed}, entries uniform in [-1, 1] on a 10^-6 grid)"
    elif kind.startswith("entry:"):
        try:
            i, j = (int(x) for x in kind[6:].split(","))
        except ValueError:
            raise UserError(f"expected entry:i,j, got {kind!r}", "--direction") from None
        if not (1 <= i <= s and 1 <= j <= s):
            raise UserError(f"entry ({i},{j}) is outside the {s}x{s} tableau", "--direction")
        D = [[Fraction(int(r == i - 1 and c == j - 1)) for c in range(s)] for r in range(s)]
        desc = f"the entry a_{i}{j}"
    elif kind == "kernel":
        if degree is None or degree < 3:
            raise UserError("the kernel direction needs --degree m >= 3 (the double-bush map)", "--direction")
        from rkcheck.energy.double_bush import kernel_of, tableau_rule

        b, c, exact = tableau_rule(tableau, dps)
        k = kernel_of(b, c, degree, exact, dps)
        if not k.zero_row_sum:
            raise UserError(
                f"the double-bush map for degree {degree} has no kernel direction with zero row sums at this rule "
                f"(rank {k.rank} of {s * s})", "--direction")
        N = k.zero_row_sum[0]
        if exact:  # Fractions, or exact number-field elements (their text parses back)
            D = [[x if hasattr(x, "field") else Fraction(x) for x in row] for row in N]
        else:  # the numerical kernel vector, exactly as computed (no rounding to a short decimal),
            # with the row sums then made exactly zero: that constraint is rational, so
            # only the double-bush part M(D) = 0 is left at ~10^-dps
            D = [[mpf_fraction(x) for x in row] for row in N]
            D = [[x - sum(row, Fraction(0)) / s for x in row] for row in D]
        desc = (f"the zero-row-sum kernel direction of the double-bush map for degree {degree} "
                f"({'exact' if exact else f'to {dps} digits'}; {len(k.zero_row_sum)}-dimensional)")
    else:
        raise UserError(f"unknown direction {kind!r} (random, kernel, entry:i,j)", "--direction")
    big = max(abs(x) for row in D for x in row)
    if big == 0:
        raise UserError("the direction is zero", "--direction")
    return [[x / big for x in row] for row in D], desc


def perturbed(tableau: Tableau, D, eps: Fraction) -> Tableau:
    """A + εD with b unchanged; entries stay exact expressions over the same constants."""
    A = tuple(
        tuple(
            e if D[i][j] == 0 else Entry.parse(f"({e.text}) + ({eps * D[i][j]})", tableau.info.constants)
            if not getattr(e, "computed", False) else e
            for j, e in enumerate(row)
        )
        for i, row in enumerate(tableau.A)
    )
    if any(getattr(e, "computed", False) for row in tableau.A for e in row):
        raise UserError("perturb needs explicit entries; write the family out with `rkcheck new` first")
    return Tableau(A=A, b=tableau.b, c=None, name=f"{tableau.name} + {eps}·D",
                   info=MethodInfo(constants=tableau.info.constants))


@dataclass
class PerturbRow:
    eps: Fraction
    max_residual: Fraction | None  # over certified failures of the reference backend
    first_failing_order: int | None
    failing: int
    detected: dict[str, bool]


@dataclass
class Perturbation:
    """What a perturbation sweep gives: for each ε, max |R| over the failing conditions
    of ``A + εD``, the first failing order and which backends certify a failure; the
    fitted slope of log max|R| against log ε (1 for a generic direction, 2 along the
    kernel: the seed's quadratic failure); each backend's detection threshold ε*."""

    rows: list[PerturbRow]
    slope: float | None
    thresholds: dict[str, Fraction | None]  # smallest ε at which each backend certifies a failure
    floors: dict[str, float]  # each backend's detection floor: its radius level at ε = 0
    direction: str  # the direction D, described
    backends: list[str]
    warnings: list[str] = field(default_factory=list)
    tableau: Any = None
    degree: int | None = None
    order: int = 0

    def __repr__(self) -> str:
        slope = "—" if self.slope is None else f"{self.slope:.3f}"
        name = getattr(self.tableau, "name", "a tableau")
        return f"<Perturbation of {name!r}: {len(self.rows)} ε values, slope {slope}>"


def fit_slope(xs: list[float], ys: list[float]) -> float | None:
    if len(xs) < 2:
        return None
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0:
        return None
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def _log10(x: Fraction) -> float:
    return math.log10(x.numerator) - math.log10(x.denominator)


def reference_dps(eps_list, dps_list) -> int:
    """The precision of the reference backend of a non-exact sweep: beyond every backend
    compared (2·max + 20), and fine enough to certify a quadratic residual K ε² at the
    smallest ε (its radius ≈ 10^-dps must be far below ε²; 30 digits of margin)."""
    smallest = min((e for e in eps_list if e > 0), default=None)
    need = 0 if smallest is None else math.ceil(-2 * _log10(smallest)) + 30
    return max(max(dps_list) * 2 + 20, need)


def base_failure_warning(results, degree: int | None, order: int) -> str | None:
    """A warning when the unperturbed tableau already certainly fails a condition at
    this degree and order: then max|R| does not vanish as ε → 0 and the slope measures
    nothing (definitions §3: the conditions of the check asked for)."""
    fails = [key for key, (_, v) in results.items() if v.state == FAILS]
    if not fails:
        return None
    first = min(key[0] for key in fails) - 1
    return (f"the unperturbed tableau already fails {len(fails)} of {len(results)} conditions at degree "
            f"{'none' if degree is None else degree}, order {order} (the first at order {first}): "
            f"max|R| does not tend to 0 with ε, so the slope means nothing; lower --order or --degree")


def perturb_sweep(tableau: Tableau, D, desc: str, eps_list: list[Fraction], degree: int | None, order: int,
                  dps_list=(15, 50), reading: Reading = DEFAULT_READING) -> Perturbation:
    """The sweep of the module docstring.  The reference backend (exact when the tableau
    is, else balls at :func:`reference_dps`) gives max|R| and the first failing order."""
    listing = condition_listing(order, degree)

    def run(tab: Tableau, name: str):
        return evaluate_backend(listing, TableauValues.of(tab, reading), name)

    names = backend_names(TableauValues.of(tableau, reading), dps_list)
    if "exact" not in names:
        names.append(f"dps:{reference_dps(eps_list, dps_list)}")  # the reference: well beyond the others
    reference = names[-1]
    warnings = []
    base_reference = run(tableau, reference)
    warning = base_failure_warning(base_reference, degree, order)
    if warning:
        warnings.append(warning)
    rows: list[PerturbRow] = []
    for eps in eps_list:
        tab = perturbed(tableau, D, eps)
        detected = {}
        ref_results = None
        for name in names:
            res = run(tab, name)
            detected[name] = any(v.state == FAILS for _, v in res.values())
            if name == reference:
                ref_results = res
        assert ref_results is not None
        fails = [(key, e) for key, (e, v) in ref_results.items() if v.state == FAILS]
        rows.append(PerturbRow(
            eps, max((abs(Fraction(e.mid)) for _, e in fails), default=None),
            min((key[0] - 1 for key, _ in fails), default=None), len(fails), detected,
        ))
    pts = [(_log10(r.eps), _log10(r.max_residual)) for r in rows if r.max_residual]
    slope = fit_slope([p[0] for p in pts], [p[1] for p in pts])
    thresholds = {n: min((r.eps for r in rows if r.detected[n]), default=None) for n in names}
    base = run(perturbed(tableau, D, Fraction(0)), names[0])
    floors = {}
    for name in names:
        if name == "exact":
            continue
        res = base if name == names[0] else (
            base_reference if name == reference else run(tableau, name))
        floors[name] = max(float(abs(e.mid) + e.rad) for e, _ in res.values()) if res else 0.0
    return Perturbation(rows, slope, thresholds, floors, desc, names, warnings, tableau, degree, order)
