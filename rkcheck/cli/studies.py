"""``bench``, ``perturb``, ``kernel``: studies of the check itself."""

from __future__ import annotations

import click

from rkcheck.cli.common import (
    busy,
    chart_file,
    degree_option,
    echo_json,
    exit_codes,
    flag_values,
    load_tableau,
    order_option,
    output_options,
    stdout_console,
)
from rkcheck.options import (
    DEFAULT_DPS,
    KERNEL_DEGREE_RANGE,
    KERNEL_STAGES_RANGE,
    REPEAT_RANGE,
    STUDY_DPS_RANGE,
)


@click.command(epilog=exit_codes())
@click.argument("file", metavar="FILE")
@degree_option(help="Degree m ('none' = all) [default: file's [check]].")
@order_option(help="Order N [default: file's [check], else 8].")
@click.option("--dps", "dps_text", default="15,30,50,100,200,400", show_default=True, help="Ball precisions to run.")
@click.option("--repeat", type=click.IntRange(*REPEAT_RANGE), default=3, show_default=True, help="Best of this many runs.")
@click.option("--chart", metavar="OUT.png|.svg", default=None, callback=chart_file, help="Draw time against certified digits (needs matplotlib).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@output_options
def bench(file, degree, order, dps_text, repeat, chart, fmt) -> None:
    """Run the same check on every backend: float64 screen, certified balls at each --dps, exact.

    One row per backend: wall time, conditions per second, the weakest certified digits,
    the certified failures, and whether the verdicts agree with the most precise backend.
    """
    from rkcheck.api.studies import bench as run_bench

    tab = load_tableau(file)
    result = run_bench(tab, **flag_values("degree", "order"), dps=dps_text, repeat=repeat)
    rows, t_tables, deg, N = result.rows, result.tables_seconds, result.degree, result.order
    from rkcheck.reports.console import count_text

    title = f"{tab.name}: degree {'none' if deg is None else deg}, order {N}, {count_text(rows[0].conditions)} conditions"
    if chart:
        from rkcheck.reports.charts import bench_chart

        bench_chart(rows, title, chart)
    if fmt == "json":
        from rkcheck.reports.studies import bench_doc

        echo_json(bench_doc(file, deg, N, rows, t_tables))
        return
    from rkcheck.reports.studies import render_bench

    render_bench(rows, t_tables, stdout_console(), title)
    if chart:
        click.echo(f"chart written to {chart}")


@click.command(epilog=exit_codes())
@click.argument("file", metavar="FILE")
@click.option("--direction", required=True, metavar="random|kernel|entry:i,j",
              help="Perturb A along a fixed-seed random matrix, the zero-row-sum kernel direction of the "
              "double-bush map (needs --degree >= 3), or one entry.")
@degree_option(help="Degree m [default: file's [check]].")
@order_option(help="Order N [default: file's [check], else 8].")
@click.option("--eps", "eps_text", default="1e-1..1e-30", show_default=True,
              help="ε values: 1e-1..1e-40 (every decade), 1e-2..1e-30:2 (every 2nd), or a list 1e-3,1e-6.")
@click.option("--dps", "dps_text", default="15,50", show_default=True, help="Ball precisions whose detection is reported.")
@click.option("--seed", type=int, default=2024, show_default=True, help="Seed of the random direction.")
@click.option("--chart", metavar="OUT.png|.svg", default=None, callback=chart_file, help="Draw max|R| against ε with each backend's floor.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@output_options
def perturb(file, direction, degree, order, eps_text, dps_text, seed, chart, fmt) -> None:
    """Perturb the tableau's A by ε·D and watch the energy conditions fail.

    For each ε: max |R| over the failing conditions, the first failing order, and which
    backends still certify the failure. Prints the fitted slope of log max|R| against
    log ε (1 for generic directions, 2 for kernel directions: the seed's quadratic
    failure) and each backend's detection threshold ε*.
    """
    from rkcheck.api.studies import perturb as run_perturb

    tab = load_tableau(file)
    with busy("perturbing"):
        result = run_perturb(tab, direction, **flag_values("degree", "order"), eps=eps_text, dps=dps_text, seed=seed)
    res, deg, N = result, result.degree, result.order
    title = f"{tab.name} + ε·D: degree {'none' if deg is None else deg}, order {N}"
    if chart:
        from rkcheck.reports.charts import perturb_chart

        perturb_chart(res, title, chart)
    if fmt == "json":
        from rkcheck.reports.studies import perturb_doc

        echo_json(perturb_doc(file, deg, N, res))
        return
    from rkcheck.reports.studies import render_perturb

    render_perturb(res, stdout_console(), title)
    if chart:
        click.echo(f"chart written to {chart}")


@click.command(epilog=exit_codes())
@click.option("--stages", "-s", type=click.IntRange(*KERNEL_STAGES_RANGE), default=None, help="Number of stages s.")
@click.option("--degree", "-m", type=click.IntRange(*KERNEL_DEGREE_RANGE), required=True, help="Polynomial degree m (>= 3).")
@click.option("--rule", default="gauss", show_default=True, help="gauss | radau-i | radau-ii | lobatto | zeta:<value>.")
@click.option("--tableau", "tableau_file", metavar="FILE", default=None, help="Use this tableau's b and c = A·1 instead of a rule.")
@click.option("--dps", type=click.IntRange(*STUDY_DPS_RANGE), default=DEFAULT_DPS, show_default=True)
@output_options
def kernel(stages, degree, rule, tableau_file, dps) -> None:
    """Rank and kernel of the double-bush map M (seed Lemma 2) on s×s matrices.

    The rank is exact for every named rule (a basis too while the nodes' field is
    small); for a tableau with inexact entries it is bracketed by a certified lower
    bound and marked "not determined at this precision" unless the bounds meet, with
    the singular values around the numerical cut printed. Also the part of ker M with zero row sums
    (seed Lemma "onedim"): the directions A → A + βN that keep every linear condition.

    \b
    Examples:
      rkcheck kernel -s 2 -m 4                  # Gauss, m = 2s: rank s²−1, kernel (1−c)bᵀ
      rkcheck kernel -s 3 -m 5 --rule radau-i   # ζ = −1: rank s²−s−1
      rkcheck kernel -m 3 --tableau tableaux/avf/avf-radau-ii-2.toml
    """
    from rkcheck.api.studies import kernel as double_bush_kernel
    from rkcheck.reports.studies import render_kernel

    given = flag_values("stages", "rule")
    if tableau_file and given:  # the tableau's own b and c are the rule
        from rkcheck.errors import UserError, not_applying
        flags = [{"stages": "-s", "rule": "--rule"}[name] for name in given]
        raise UserError(f"--tableau takes the tableau's own b and c = A·1: {not_applying(flags)}")
    tab = load_tableau(tableau_file) if tableau_file else None
    with busy("ranks of the double-bush map"):
        result = double_bush_kernel(degree, stages, rule=rule, tableau=tab, dps=dps)
    if tab is not None:
        title = f"double-bush map of {tab.name} (b and c = A·1), degree {degree}"
    else:
        title = f"double-bush map at the {stages}-point {rule} rule, degree {degree}"
    render_kernel(result, stdout_console(), title)
