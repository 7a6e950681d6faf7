"""Energy in practice: one-step energy errors, energy drift, work–precision.

* :func:`fit_energy_order` — one step from several random points at ``h = 2⁻³ … 2⁻¹⁰`` in
  mpmath; the slope of log|ΔH| against log h is n + 1 for a method of energy order n
  (``H(y₁) − H(y₀) = O(h^(n+1))``), so the empirical energy order is slope − 1.  At each
  h the |ΔH| of the points are combined by their geometric mean; the slope is fitted on
  the asymptotic range of small steps (:func:`asymptotic_window`).  If every |ΔH| is at
  the level of the stage solver (10^-(dps−10) relative), there is no slope to fit: the
  method preserves this H ("ΔH at solver precision").
* :func:`energy_order_agreement` — ``verify``'s energy order for the problem's degree
  first, then the fit at a precision chosen from it (a failure of size 10⁻²⁴ needs more
  than 40 digits to be seen in one step), and the comparison: they agree when they round
  to the same integer (|difference| ≤ 0.5), or when both say the energy is preserved.
* :func:`energy_series` and :func:`work_precision` — long runs in float64.
"""

from __future__ import annotations

import dataclasses
import math
import random
import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rkcheck.dynamics.integrator import (
    H_ADVICE,
    MP,
    Float64,
    RKMethod,
    StepAdvice,
    integrate,
    step,
)
from rkcheck.errors import UserError
from rkcheck.numbers.formatting import decimal_string
from rkcheck.numbers.reading import DecimalsMode

H_EXPONENTS = tuple(range(3, 11))  # h = 2^-3 ... 2^-10


@dataclass
class FitRow:
    h: Fraction
    delta: Any  # geometric mean of |ΔH| over the points
    low: Any
    high: Any


@dataclass
class EnergyFit:
    rows: list[FitRow]
    slope: float | None
    empirical_order: float | None
    at_solver_precision: bool
    floor: Any
    dps: int
    points: int
    fitted: list[Fraction] = field(default_factory=list)  # the steps h the slope was fitted on


def random_points(dim: int, count: int, seed: int, ctx) -> list[list[Any]]:
    """``count`` points with coordinates uniform on a 1/1000 grid in [−1/2, 1/2]."""
    rng = random.Random(seed)
    return [[ctx.num(Fraction(rng.randint(-500, 500), 1000)) for _ in range(dim)] for _ in range(count)]


def _log10(x) -> float:
    import mpmath

    return float(mpmath.log10(x))


def fit_energy_order(tableau, ham, dps: int = 40, points: int = 4, seed: int = 7,
                     exponents=H_EXPONENTS) -> EnergyFit:
    import mpmath

    with mpmath.workdps(dps):
        ctx = MP(dps)
        method = RKMethod.from_tableau(tableau, ctx)
        ys = random_points(ham.dim, points, seed, ctx)
        H0 = [ham.energy(y) for y in ys]
        scale = max(abs(x) for x in H0) + 1
        floor = scale * mpmath.mpf(10) ** (-(dps - 10))
        rows = []
        for e in exponents:
            h = mpmath.mpf(2) ** (-e)
            deltas = []
            for y, h0 in zip(ys, H0):
                y1 = step(method, ham, y, h, ctx, f" (one step from a random point, h = 2^-{e})")
                deltas.append(abs(ham.energy(y1) - h0))
            logs = [mpmath.log(max(d, mpmath.mpf(10) ** (-2 * dps))) for d in deltas]
            rows.append(FitRow(Fraction(1, 2**e), mpmath.exp(sum(logs) / len(logs)), min(deltas), max(deltas)))
        at_floor = all(r.high <= floor for r in rows)
        slope, window = None, []
        if not at_floor:
            pts = [(math.log10(float(r.h)), _log10(r.delta), r.h) for r in rows if r.delta > floor * 1000]
            window = asymptotic_window(pts)
            if len(window) >= 2:
                mx = sum(p[0] for p in window) / len(window)
                my = sum(p[1] for p in window) / len(window)
                sxx = sum((p[0] - mx) ** 2 for p in window)
                slope = sum((p[0] - mx) * (p[1] - my) for p in window) / sxx
        return EnergyFit(rows, slope, None if slope is None else slope - 1, at_floor, floor, dps, points,
                         [p[2] for p in window])


def asymptotic_window(pts: list[tuple[float, float, Fraction]], tolerance: float = 0.25):
    """The points (log h, log|ΔH|, h), sorted by decreasing h, on which the slope is fitted:
    start from the three smallest steps and extend toward larger h while each new local
    slope stays within ``tolerance`` of the median of the local slopes already taken.
    Larger steps are pre-asymptotic: there the next term of the error, h^(n+2), can
    nearly cancel the leading one at a starting point and bend the curve."""
    if len(pts) < 3:
        return pts
    local = [(pts[i][1] - pts[i + 1][1]) / (pts[i][0] - pts[i + 1][0]) for i in range(len(pts) - 1)]
    start = len(pts) - 3  # the window is pts[start:]
    taken = local[start:]
    while start > 0:
        candidate = local[start - 1]
        median = sorted(taken)[len(taken) // 2]
        if abs(candidate - median) > tolerance:
            break
        taken.append(candidate)
        start -= 1
    return pts[start:]


@dataclass
class Agreement:
    degree: int | None
    algebraic: str  # "all", "≥ N" or "n"
    empirical: str
    agree: bool
    message: str
    certificate: str | None = None
    dps: int = 0  # the precision the one-step errors were computed at


def needed_dps(result, exponents=H_EXPONENTS, floor: int = 40) -> int:
    """Digits needed to see the energy error of the smallest step: the size of the first
    failing residual, times h^(n+1) at h = 2^-max(exponents), plus 20 guard digits."""
    first = result.first_failure
    if first is None:
        return floor
    r = abs(first.enclosure.mid)
    size = -_log10_abs(r) if r else 0.0
    n = result.energy_order_to_digits  # where the residuals start to be nonzero, proven or not
    return max(floor, math.ceil(size + (n + 1) * max(exponents) * math.log10(2) + 20))


def energy_order_agreement(tableau, ham, dps: int | None = None, points: int = 4, seed: int = 7,
                           exponents=H_EXPONENTS, order: int = 10) -> tuple[EnergyFit, Agreement]:
    """verify's energy order for the problem's degree, then the one-step fit at a precision
    chosen from it (or ``dps`` if larger), and whether the two agree.

    The integrator steps with the entries' face values, so ``verify`` is asked with
    ``decimals = exact`` too: a 16-digit AVF tableau is compared as what it is."""
    from rkcheck.energy.check import CheckOptions, check

    res = check(tableau, CheckOptions(degree=ham.degree, order=order, decimals=DecimalsMode.EXACT))
    sizes = magnitudes(tableau, res)
    use = max(dps or 40, needed_dps(sizes, exponents))
    fit = fit_energy_order(tableau, ham, dps=use, points=points, seed=seed, exponents=exponents)
    return fit, compare_with_verify(tableau, ham.degree, fit, order, result=res, sizes=sizes)


def magnitudes(tableau, result):
    """A check whose failing residuals' sizes are cheap to read, with the same verdicts:
    ``result`` itself, or for a tableau in a number field of degree > 2 the same check in
    30-digit balls.  The sizes only choose a precision and the order whose residuals
    dominate; an exact residual in a field of degree 48 needs its 48 coefficients'
    prime budget (a minute for the failing conditions of HBVM(6, 2) to order 10)."""
    from rkcheck.energy.check import check

    exact = result.values.exact
    # a family in node form has rational residuals, whatever its field
    field = exact.field if exact is not None and exact.nodes is None and result.backend == "exact" else None
    if field is None or field.degree <= 2 or not len(result.failures):
        return result
    return check(tableau, dataclasses.replace(result.options, dps=30, arithmetic="ball"))


def _max_residual(result, k: int):
    return max((abs(r.enclosure.mid) for r in result.failures if r.order == k + 1), default=0)


def dominant_order(result, fit: EnergyFit) -> int:
    """The failing order n whose one-step contribution max|R|·h^(n+1) is largest at the
    smallest fitted step: what the slope should show.  It is the energy order unless the
    first failing conditions fail by very little (a decimal tableau read at face value)."""
    if not fit.fitted:
        return result.energy_order_to_digits
    log_h = _log10_abs(min(fit.fitted))
    best, best_size = result.energy_order_to_digits, -math.inf
    for r in result.failures:
        n = r.order - 1
        if not r.enclosure.mid:
            continue
        size = _log10_abs(r.enclosure.mid) + (n + 1) * log_h  # log10 of |R|·h^(n+1): no overflow
        if size > best_size:
            best, best_size = n, size
    return best


def _log10_abs(x) -> float:
    """log10 |x| of a nonzero rational or float, at any magnitude (math.log10 takes
    integers of any size; a float of 1e400 does not exist)."""
    if isinstance(x, Fraction):
        return math.log10(abs(x.numerator)) - math.log10(x.denominator)
    return math.log10(abs(x))


def compare_with_verify(tableau, degree: int | None, fit: EnergyFit, order: int = 10, result=None,
                        sizes=None) -> Agreement:
    """Does the fitted one-step order agree with verify's energy order?  ``sizes``: the
    check to read residual sizes from (:func:`magnitudes`; ``result`` by default)."""
    from rkcheck.energy.check import CheckOptions, check

    res = result or check(tableau, CheckOptions(degree=degree, order=order, decimals=DecimalsMode.EXACT))
    sizes = sizes or res
    emp = "ΔH at solver precision" if fit.at_solver_precision else (
        "—" if fit.empirical_order is None else f"{fit.empirical_order:.2f}")
    cert = None
    alg = res.energy_order_label
    if res.certified_all:
        agree = fit.at_solver_precision
        cert = res.certificate.reason if res.certificate else None
    elif res.first_failure is None:
        agree = fit.at_solver_precision or (fit.empirical_order is not None and fit.empirical_order >= order - 0.5)
    else:
        expected = dominant_order(sizes, fit)
        agree = fit.empirical_order is not None and abs(fit.empirical_order - expected) <= 0.5
        if agree and expected != res.energy_order_to_digits:
            h_min = min(fit.fitted)
            return Agreement(degree, alg, emp, True,
                             f"agree: empirical {emp} is order {expected}, the failing order whose residuals dominate "
                             f"for h ≥ {h_min}; the energy order is {alg}, but its conditions fail by only "
                             f"{decimal_string(Fraction(_max_residual(sizes, res.energy_order_to_digits)), 2)} and dominate at smaller steps",
                             cert, fit.dps)
    if agree:
        msg = f"agree: algebraic energy order {alg}, empirical {emp}"
    else:
        msg = (f"DISAGREE: verify says energy order {alg} for degree {degree if degree else 'none'}, "
               f"but one step gives {emp}")
    return Agreement(degree, alg, emp, agree, msg, cert, fit.dps)


def _reportable(x, what: str) -> float:
    """An mpmath value as the float the table and the chart use; mpmath has no overflow,
    so a value past float64's range is refused here instead of printed as ``inf``."""
    import mpmath

    f = float(x)
    if math.isinf(f):
        raise UserError(f"{what} reaches about {mpmath.nstr(x, 3)}, beyond float64's range (about 1.8e308) that the "
                        "report and the chart use; the step is probably too large: try a smaller --h", "--h")
    return f


def energy_series(tableau, ham, y0: list[Fraction], h: Fraction, steps: int, dps: int | None = None,
                  record: int = 200):
    """(times, |H(y_n) − H(y_0)|) as floats, float64 unless ``dps`` is given."""
    import mpmath

    every = max(1, steps // record)
    ctx: MP | Float64
    if dps:
        with mpmath.workdps(dps):
            ctx = MP(dps)
            method = RKMethod.from_tableau(tableau, ctx)
            t, _, E = integrate(method, ham, [ctx.num(x) for x in y0], ctx.num(h), steps, ctx, every)
            return [_reportable(x, "t") for x in t], [_reportable(abs(e - E[0]), "|ΔH|") for e in E]
    ctx = Float64()
    method = RKMethod.from_tableau(tableau, ctx)
    t, _, E = integrate(method, ham, [ctx.num(x) for x in y0], ctx.num(h), steps, ctx, every)
    return [float(x) for x in t], [abs(e - E[0]) for e in E]


DEFAULT_START = {
    "harmonic": [Fraction(1), Fraction(0)],
    "quartic": [Fraction(1), Fraction(0)],
    "henon-heiles": [Fraction(1, 10), Fraction(-1, 10), Fraction(3, 10), Fraction(1, 5)],  # energy ≈ 0.068 < 1/6
    "fpu": [Fraction(1, 2), Fraction(0), Fraction(0), Fraction(1, 2)],
}


def start_point(ham) -> list[Fraction]:
    if ham.name in DEFAULT_START:
        return DEFAULT_START[ham.name]
    rng = random.Random(11)
    return [Fraction(rng.randint(-300, 300), 1000) for _ in range(ham.dim)]


@dataclass
class WorkRow:
    name: str
    h: Fraction
    steps: int
    seconds: float
    error: float
    energy_error: float


@dataclass
class WorkPrecision:
    """Work against precision: one row per tableau and step count with ``name``,
    ``steps``, ``h``, ``seconds``, ``error`` (max norm at T against the reference
    solution) and ``energy_error`` (max |ΔH| over the run); ``reference`` says how the
    reference solution was computed."""

    rows: list[WorkRow] = field(default_factory=list)
    T: Fraction = Fraction(1)
    reference: str = ""
    problem: Any = None

    def __repr__(self) -> str:
        name = getattr(self.problem, "name", "a problem")
        return f"<WorkPrecision on {name}, T = {self.T}: {len(self.rows)} runs>"


def reference_solution(ham, y0, T: Fraction, dps: int = 20, steps: int = 160, advice: StepAdvice = H_ADVICE):
    """y(T) with 6-stage Gauss collocation (order 12) in mpmath: error ≈ (T/steps)^12."""
    import mpmath

    from rkcheck.methods.families import FamilySpec, family_tableau

    gauss6 = family_tableau(FamilySpec("gauss", 6))
    with mpmath.workdps(dps):
        ctx = MP(dps)
        method = RKMethod.from_tableau(gauss6, ctx)
        y = [ctx.num(x) for x in y0]
        h = ctx.num(T) / steps
        for k in range(steps):
            y = step(method, ham, y, h, ctx, f" (reference solution, step {k + 1})", advice=advice)
        return [float(x) for x in y]


#: the steps of ``workprec``: T/N, chosen through its --T and --steps
T_ADVICE = StepAdvice("a smaller --T or more --steps", "a larger --T or fewer --steps", "--T/--steps")


def work_precision(tableaux: list, ham, T: Fraction, step_counts: list[int], y0=None,
                   ref_steps: int = 160) -> WorkPrecision:
    y0 = y0 or start_point(ham)
    ref = reference_solution(ham, y0, T, steps=ref_steps, advice=T_ADVICE)
    out = WorkPrecision(T=T, reference=f"6-stage Gauss (order 12) at 20 digits with {ref_steps} steps", problem=ham)
    ctx = Float64()
    for tab in tableaux:
        method = RKMethod.from_tableau(tab, ctx)
        for n in step_counts:
            h = T / n
            t0 = time.perf_counter()
            _, states, E = integrate(method, ham, [ctx.num(x) for x in y0], ctx.num(h), n, ctx, 1, T_ADVICE)
            secs = time.perf_counter() - t0
            err = max(abs(a - b) for a, b in zip(states[-1], ref))
            de = max(abs(e - E[0]) for e in E)
            out.rows.append(WorkRow(tab.name, h, n, secs, err, de))
    return out
