"""Text renderings of ``bench``, ``perturb`` and ``kernel``."""

from __future__ import annotations

from fractions import Fraction

from rich import box
from rich.console import Console, JustifyMethod
from rich.table import Table
from rich.text import Text

from rkcheck.io.printable import printable
from rkcheck.numbers.formatting import count_text, decimal_string
from rkcheck.reports.cells import plain


def _eps(x: Fraction | None) -> str:
    return "—" if x is None else decimal_string(x, 3)


def render_bench(rows, t_tables: float, console: Console, title: str) -> None:
    from rkcheck.studies.accuracy import label

    console.print(Text(title, style="bold"))
    console.print(f"tree and condition tables: {t_tables:.3f} s (shared by all backends)")
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    columns: list[tuple[str, JustifyMethod]] = [("backend", "left"), ("time s", "right"), ("conditions/s", "right"),
                                                ("min certified digits", "right"), ("certified failures", "right"),
                                                ("agrees", "center")]
    for col, just in columns:
        t.add_column(col, justify=just, no_wrap=True)
    for r in rows:
        digits = "exact" if r.min_digits is None and r.backend == "exact" else ("—" if r.min_digits is None else str(r.min_digits))
        agrees = Text("yes", style="green") if r.agrees else Text("no", style="bold red")
        t.add_row(*plain(label(r.backend), f"{r.seconds:.4f}", count_text(round(r.per_second)), digits, r.failures, agrees))
    console.print(t)
    console.print("agrees = the same set of certified failures as the most precise backend (last row)")


def render_perturb(res, console: Console, title: str) -> None:
    from rkcheck.studies.accuracy import label

    console.print(Text(title, style="bold"))
    console.print(f"direction: {res.direction}")
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("ε", justify="right")
    t.add_column("max |R|", justify="right")
    t.add_column("first failing order", justify="right")
    t.add_column("failing", justify="right")
    for name in res.backends:
        t.add_column(label(name), justify="center")
    for r in res.rows:
        cells = [_eps(r.eps), "—" if r.max_residual is None else decimal_string(r.max_residual, 3),
                 "—" if r.first_failing_order is None else r.first_failing_order, r.failing]
        cells += [Text("detects", style="green") if r.detected[n] else Text("—", style="dim") for n in res.backends]
        t.add_row(*plain(*cells))
    console.print(t)
    slope = "—" if res.slope is None else f"{res.slope:.3f}"
    console.print(f"slope of log max|R| against log ε: {slope} (1 for a generic direction, 2 along the kernel)")
    th = ", ".join(f"{label(n)}: {_eps(v)}" for n, v in res.thresholds.items())
    console.print(f"detection threshold ε* (smallest ε certified to fail): {th}")
    for w in res.warnings:
        console.print(Text(f"warning: {w}", style="yellow"))


def bench_doc(file: str, degree, order: int, rows, t_tables: float) -> dict:
    """``rkcheck bench --format json``."""
    from rkcheck.reports.jsondoc import SCHEMA
    from rkcheck.version import __version__

    return {
        "schema": SCHEMA, "rkcheck": __version__, "file": printable(file), "degree": degree, "order": order,
        "tables_seconds": t_tables,
        "backends": [
            {"backend": r.backend, "seconds": r.seconds, "conditions": r.conditions,
             "conditions_per_second": r.per_second, "min_digits": r.min_digits, "failures": r.failures,
             "agrees": r.agrees}
            for r in rows
        ],
    }


def perturb_doc(file: str, degree, order: int, res) -> dict:
    """``rkcheck perturb --format json``."""
    from rkcheck.reports.jsondoc import SCHEMA
    from rkcheck.version import __version__

    return {
        "schema": SCHEMA, "rkcheck": __version__, "file": printable(file), "direction": res.direction, "degree": degree, "order": order,
        "slope": res.slope,
        "thresholds": {k: None if v is None else str(v) for k, v in res.thresholds.items()},
        "floors": res.floors,
        "rows": [{"eps": str(r.eps),
                  "max_residual": None if r.max_residual is None else decimal_string(r.max_residual, 12),
                  "first_failing_order": r.first_failing_order, "failing": r.failing, "detected": r.detected}
                 for r in res.rows],
        "warnings": res.warnings,
    }


def _fmt(x) -> str:
    if isinstance(x, Fraction):
        return str(x)
    if hasattr(x, "text"):  # an exact number-field element
        return x.text()
    import mpmath

    return mpmath.nstr(x, 8, min_fixed=-3, max_fixed=3) if x != 0 else "0"


def render_kernel(res, console: Console, title: str) -> None:
    console.print(Text(title, style="bold"))
    s = res.s
    console.print(f"M: R^({s}×{s}) → R^{res.conditions} (double-bush conditions 1 ≤ p < q ≤ {res.degree - 1})")
    console.print(_rank_line(res))
    if res.tableau is not None and res.tableau.rounded_digits is not None and res.exact:
        console.print(f"decimals taken at face value ({res.tableau.rounded_digits}+ significant digits): the rank of "
                      "this exact rule, not of every rule within the rounding of its decimals")
    if res.singular_values:
        around = ", ".join(f"σ_{i} = {_fmt(v)}" for i, v in res.singular_values)
        console.print(f"singular values around the cut: {around}")
    for k, N in enumerate(res.basis, start=1):
        console.print(Text(f"ker M basis N_{k}:", style="bold"))
        _matrix(N, console)
    lo, hi = res.zero_row_sum_bounds
    dim = f"{len(res.zero_row_sum)}" if lo == hi else (
        f"{len(res.zero_row_sum)}? (not determined at this precision: certainly {lo} to {hi})")
    console.print(f"ker M ∩ {{N·1 = 0}}: dimension {dim}")
    if res.zero_row_sum_singular_values:
        around = ", ".join(f"σ_{i} = {_fmt(v)}" for i, v in res.zero_row_sum_singular_values)
        console.print(f"(stacked with the row sums) singular values around the cut: {around}")
    for N in res.zero_row_sum:
        _matrix(N, console)


def _rank_line(res) -> str:
    """``rank M = r  dim ker M = d  [how]``: exact, or the certain bracket and the numerical cut."""
    s2 = res.s * res.s
    if res.exact:
        return f"rank M = {res.rank}   dim ker M = {s2 - res.rank}   \\[exact: rational or number-field arithmetic]"
    if res.rank_certain:
        how = ("exact rank: rational elimination on the node polynomial; basis numerical"
               if res.singular_values is None else "certified: ball arithmetic; basis numerical")
        return f"rank M = {res.rank}   dim ker M = {s2 - res.rank}   \\[{how}]"
    lo, hi = res.rank_bounds
    return (f"rank M = {res.rank}?   dim ker M = {s2 - res.rank}?   \\[not determined at this precision: "
            f"certainly {lo} ≤ rank M ≤ {hi}; numerical cut at {res.rank}]")


def _matrix(N, console: Console) -> None:
    t = Table(box=box.SIMPLE, show_header=False, pad_edge=False)
    for _ in N[0]:
        t.add_column(justify="right")
    for row in N:
        t.add_row(*plain(*[_fmt(x) for x in row]))
    console.print(t)
