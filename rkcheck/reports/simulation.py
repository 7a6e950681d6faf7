"""Text renderings of ``simulate`` and ``workprec``."""

from __future__ import annotations

from rich import box
from rich.console import Console, JustifyMethod
from rich.table import Table
from rich.text import Text

from rkcheck.numbers.formatting import count_text, counted
from rkcheck.reports.cells import plain


def _e(x) -> str:
    """``1.234e-05``; an mpmath value past float64's range keeps its own exponent."""
    import math

    f = float(x)
    if math.isinf(f) and not (isinstance(x, float) or str(x) in ("inf", "+inf", "-inf")):
        import mpmath

        return mpmath.nstr(mpmath.mpf(x), 4, min_fixed=0, max_fixed=0)
    return f"{f:.3e}"


def render_energy_fit(tab, ham, fit, agreement, console: Console) -> None:
    console.print(Text(f"{tab.name} on {ham.name} (degree {ham.degree})", style="bold"))
    console.print(f"one step from {fit.points} random points at {fit.dps} digits; |ΔH| per h:")
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    for col in ("h", "|ΔH| (geometric mean)", "min", "max", "fitted"):
        t.add_column(col, justify="right")
    fitted = set(fit.fitted)
    for r in fit.rows:
        t.add_row(*plain(f"2^-{r.h.denominator.bit_length() - 1}", _e(r.delta), _e(r.low), _e(r.high),
                         "•" if r.h in fitted else ""))
    console.print(t)
    if fit.at_solver_precision:
        console.print(f"ΔH at solver precision (every |ΔH| ≤ {_e(fit.floor)}): no slope to fit")
    elif fit.slope is not None:
        console.print(f"slope of log|ΔH| against log h: {fit.slope:.3f}  →  empirical energy order {fit.empirical_order:.2f}")
    style = "bold green" if agreement.agree else "bold red"
    console.print(Text(agreement.message, style=style))
    console.print()


def render_series(tab, ham, h, steps, dps, times, dH, console: Console) -> None:
    console.print(Text(f"{tab.name} on {ham.name}: h = {h}, {counted(steps, 'step')}, "
                       f"{'float64' if not dps else f'{dps} digits'}", style="bold"))
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("t", justify="right")
    t.add_column("|H(y_n) − H(y_0)|", justify="right")
    n = len(times)
    picks = sorted({round(i * (n - 1) / 8) for i in range(9)})
    for i in picks:
        t.add_row(*plain(f"{times[i]:.4g}", _e(dH[i])))
    console.print(t)
    console.print(f"max |ΔH| = {_e(max(dH))}")
    console.print()


def render_workprec(wp, ham, console: Console) -> None:
    console.print(Text(f"work–precision on {ham.name}, T = {wp.T}; reference: {wp.reference}", style="bold"))
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    columns: list[tuple[str, JustifyMethod]] = [("method", "left"), ("steps", "right"), ("h", "right"),
                                                ("time s", "right"), ("error at T", "right"), ("max |ΔH|", "right")]
    for col, just in columns:
        t.add_column(col, justify=just)
    for r in wp.rows:
        t.add_row(*plain(r.name, count_text(r.steps), f"{float(r.h):.4g}", f"{r.seconds:.4f}", _e(r.error), _e(r.energy_error)))
    console.print(t)
