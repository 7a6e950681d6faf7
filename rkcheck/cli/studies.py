"""``bench``, ``perturb``, ``kernel``: studies of the check itself."""

from __future__ import annotations

import click

from rkcheck.cli.common import (
    busy,
    degree_option,
    dps_list,
    flag_values,
    load_tableau,
    guard,
    order_option,
    output_options,
    stdout_console,
)
from rkcheck.errors import UserError
from rkcheck.options import DEFAULT_DPS, resolve_check_options


def _degree_and_order(tab):
    """--degree and --order, else the file's [check], else none and 8 (refused when the
    condition tables would not fit in memory: the resource guard)."""
    options = resolve_check_options(flag_values("degree", "order"), tab.check, {})
    guard(options.order, options.degree, runs=0)
    return options.degree, options.order


@click.command()
@click.argument("file", metavar="FILE")
@degree_option(help="Degree m ('none' = all) [default: file's [check]].")
@order_option(help="Order N [default: file's [check], else 8].")
@click.option("--dps", "dps_text", default="15,30,50,100,200,400", show_default=True, help="Ball precisions to run.")
@click.option("--repeat", type=click.IntRange(1, 50), default=3, show_default=True, help="Best of this many runs.")
@click.option("--chart", metavar="OUT.png|.svg", default=None, help="Draw time against certified digits (needs matplotlib).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@output_options
def bench(file, degree, order, dps_text, repeat, chart, fmt) -> None:
    """Run the same check on every backend: float64 screen, certified balls at each --dps, exact.

    One row per backend: wall time, conditions per second, the weakest certified digits,
    the certified failures, and whether the verdicts agree with the most precise backend.
    """
    from rkcheck.studies.accuracy import bench_backends

    tab = load_tableau(file)
    deg, N = _degree_and_order(tab)
    rows, t_tables = bench_backends(tab, deg, N, dps_list(dps_text), repeat=repeat)
    title = f"{tab.name}: degree {'none' if deg is None else deg}, order {N}, {rows[0].conditions} conditions"
    if chart:
        from rkcheck.reports.charts import bench_chart

        bench_chart(rows, title, chart)
    if fmt == "json":
        from rkcheck.reports.jsondoc import dumps
        from rkcheck.reports.studies import bench_doc

        click.echo(dumps(bench_doc(file, deg, N, rows, t_tables)))
        return
    from rkcheck.reports.studies import render_bench

    render_bench(rows, t_tables, stdout_console(), title)
    if chart:
        click.echo(f"chart written to {chart}")


@click.command()
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
@click.option("--chart", metavar="OUT.png|.svg", default=None, help="Draw max|R| against ε with each backend's floor.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@output_options
def perturb(file, direction, degree, order, eps_text, dps_text, seed, chart, fmt) -> None:
    """Perturb the tableau's A by ε·D and watch the energy conditions fail.

    For each ε: max |R| over the failing conditions, the first failing order, and which
    backends still certify the failure. Prints the fitted slope of log max|R| against
    log ε (1 for generic directions, 2 for kernel directions: the seed's quadratic
    failure) and each backend's detection threshold ε*.
    """
    from rkcheck.studies.accuracy import direction as make_direction
    from rkcheck.studies.accuracy import direction_dps, parse_eps, perturb_sweep

    tab = load_tableau(file)
    deg, N = _degree_and_order(tab)
    eps = parse_eps(eps_text)
    if not eps or any(not 0 < e <= 1 for e in eps):  # log10(ε) and float radii need 0 < ε <= 1
        raise UserError(f"every ε must be in (0, 1], got {eps_text!r}", "--eps")
    with busy("perturbing"):
        D, desc = make_direction(tab, direction, deg, seed, direction_dps(eps, dps_list(dps_text)))
        res = perturb_sweep(tab, D, desc, eps, deg, N, dps_list(dps_text))
    title = f"{tab.name} + ε·D: degree {'none' if deg is None else deg}, order {N}"
    if chart:
        from rkcheck.reports.charts import perturb_chart

        perturb_chart(res, title, chart)
    if fmt == "json":
        from rkcheck.reports.jsondoc import dumps
        from rkcheck.reports.studies import perturb_doc

        click.echo(dumps(perturb_doc(file, deg, N, res)))
        return
    from rkcheck.reports.studies import render_perturb

    render_perturb(res, stdout_console(), title)
    if chart:
        click.echo(f"chart written to {chart}")


@click.command()
@click.option("--stages", "-s", type=click.IntRange(1, 12), default=None, help="Number of stages s.")
@click.option("--degree", "-m", type=click.IntRange(3, 40), required=True, help="Polynomial degree m (>= 3).")
@click.option("--rule", default="gauss", show_default=True, help="gauss | radau-i | radau-ii | lobatto | zeta:<value>.")
@click.option("--tableau", "tableau_file", metavar="FILE", default=None, help="Use this tableau's b and c = A·1 instead of a rule.")
@click.option("--dps", type=click.IntRange(15, 2000), default=DEFAULT_DPS, show_default=True)
@output_options
def kernel(stages, degree, rule, tableau_file, dps) -> None:
    """Rank and kernel of the double-bush map M (seed Lemma 2) on s×s matrices.

    Exact for rational rules; otherwise numerical, with the singular values around the
    cut printed so that the gap is visible. Also the part of ker M with zero row sums
    (seed Lemma "onedim"): the directions A → A + βN that keep every linear condition.

    \b
    Examples:
      rkcheck kernel -s 2 -m 4                  # Gauss, m = 2s: rank s²−1, kernel (1−c)bᵀ
      rkcheck kernel -s 3 -m 5 --rule radau-i   # ζ = −1: rank s²−s−1
      rkcheck kernel -m 3 --tableau tableaux/avf/avf-radau-ii-2.toml
    """
    from rkcheck.energy.double_bush import kernel_of, rule_values, tableau_rule
    from rkcheck.reports.studies import render_kernel

    if tableau_file:
        tab = load_tableau(tableau_file)
        b, c, exact = tableau_rule(tab, dps)
        title = f"double-bush map of {tab.name} (b and c = A·1), degree {degree}"
    else:
        if stages is None:
            raise UserError("give --stages/-s (or --tableau FILE)")
        b, c, exact = rule_values(rule, stages, dps)
        title = f"double-bush map at the {stages}-point {rule} rule, degree {degree}"
    with busy("ranks of the double-bush map"):
        result = kernel_of(b, c, degree, exact, dps)
    render_kernel(result, stdout_console(), title)
