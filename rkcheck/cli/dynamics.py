"""``simulate`` and ``workprec``: integrate polynomial Hamiltonians and watch the energy."""

from __future__ import annotations

import sys

import click

from rkcheck.cli.common import (
    EXIT_FAIL,
    EXIT_OK,
    busy,
    chart_file,
    exit_codes,
    load_tableau,
    max_stages_option,
    output_options,
    stdout_console,
)
from rkcheck.options import POINTS_RANGE, STEPS_RANGE, STUDY_DPS_RANGE


@click.command(epilog=exit_codes("--energy-order: the empirical energy order disagrees with the algebraic one"))
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--problem", "-p", "problem_spec", required=True,
              help="harmonic | henon-heiles | quartic | fpu | random:degree=m[,dim=d][,seed=S].")
@click.option("--h", "h_text", default="1/10", show_default=True, help="Step size (a rational: 0.1, 1/16).")
@click.option("--steps", type=click.IntRange(*STEPS_RANGE), default=1000, show_default=True)
@click.option("--dps", type=click.IntRange(*STUDY_DPS_RANGE), default=None,
              help="Integrate in mpmath at this precision [default: float64; --energy-order: 40, or more "
              "when verify's first failing residual is too small to be seen in one step].")
@click.option("--energy-order", is_flag=True,
              help="One step from random points at h = 2^-3..2^-10: fit the empirical energy order and "
              "compare it with verify's algebraic one (exit 1 when they disagree).")
@click.option("--points", type=click.IntRange(*POINTS_RANGE), default=4, show_default=True, help="--energy-order: starting points.")
@click.option("--seed", type=int, default=7, show_default=True, help="--energy-order: seed of the starting points.")
@click.option("--chart", metavar="OUT.png|.svg", default=None, callback=chart_file, help="Draw |ΔH| over time (or against h).")
@max_stages_option
@output_options
def simulate(files, problem_spec, h_text, steps, dps, energy_order, points, seed, chart, max_stages) -> None:
    """Integrate a polynomial Hamiltonian with each tableau and watch the energy.

    \b
    Without --energy-order: |H(y_n) − H(y_0)| over time, a short table per tableau.
    With --energy-order: the empirical energy order (slope − 1 of log|ΔH| against
    log h, fitted on the asymptotic small steps) against verify's algebraic energy
    order for the problem's degree; an energy-preserving method shows "ΔH at solver
    precision". Exit 1 on a disagreement.

    \b
    Examples:
      rkcheck simulate tableaux/explicit/rk4.toml --problem random:degree=4 --energy-order
      rkcheck simulate tableaux/collocation/gauss-2.toml tableaux/avf/avf-gauss-2.toml \\
          --problem henon-heiles --h 1/10 --steps 2000 --chart drift.png
    """
    from rkcheck.api.dynamics import empirical_energy_order, hamiltonian
    from rkcheck.api.dynamics import simulate as run_simulation
    from rkcheck.reports.simulation import render_energy_fit, render_series

    ham = hamiltonian(problem_spec)
    tabs = [load_tableau(f, max_stages) for f in files]
    console = stdout_console()
    if energy_order:
        disagree = 0
        series = []
        for tab in tabs:
            measured = empirical_energy_order(tab, ham, dps=dps, points=points, seed=seed)
            fit, agreement = measured.fit, measured.agreement
            render_energy_fit(tab, ham, fit, agreement, console)
            disagree += not agreement.agree
            series.append((tab.name, [float(r.h) for r in fit.rows], [float(r.delta) for r in fit.rows]))
        if chart:
            from rkcheck.reports.charts import energy_chart

            energy_chart(series, f"one-step energy error on {ham.name}", chart, xlabel="h",
                         ylabel="|ΔH| (geometric mean)", loglog=True)
            click.echo(f"chart written to {chart}")
        sys.exit(EXIT_FAIL if disagree else EXIT_OK)
    all_series = []
    h = None
    for tab in tabs:
        run = run_simulation(tab, ham, h=h_text, steps=steps, dps=dps)
        h = run.h
        render_series(tab, ham, h, steps, dps, run.times, run.energy_errors, console)
        all_series.append((tab.name, run.times, run.energy_errors))
    if chart:
        from rkcheck.reports.charts import energy_chart

        energy_chart(all_series, f"energy error on {ham.name}, h = {h}, {'float64' if not dps else f'{dps} digits'}", chart)
        click.echo(f"chart written to {chart}")


@click.command(epilog=exit_codes())
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--problem", "-p", "problem_spec", required=True, help="As for simulate.")
@click.option("--T", "T_text", default="10", show_default=True, help="Final time.")
@click.option("--steps", "steps_text", default="20,40,80,160,320,640", show_default=True,
              help="Comma-separated numbers of steps (step sizes T/N).")
@click.option("--chart", metavar="OUT.png|.svg", default=None, callback=chart_file, help="Draw error and energy error against time.")
@max_stages_option
@output_options
def workprec(files, problem_spec, T_text, steps_text, chart, max_stages) -> None:
    """Work–precision: error at T and energy error against wall time, one line per tableau.

    Each tableau runs in float64 over the step counts; the error is measured against a
    reference solution computed with 6-stage Gauss collocation (order 12) at 20 digits.
    """
    from rkcheck.api.dynamics import work_precision
    from rkcheck.reports.simulation import render_workprec

    with busy("work–precision runs"):
        wp = work_precision(files, problem_spec, T=T_text, steps=steps_text, max_stages=max_stages)
    render_workprec(wp, wp.problem, stdout_console())
    if chart:
        from rkcheck.reports.charts import workprec_chart

        workprec_chart(wp, f"work–precision on {wp.problem.name}, T = {wp.T}", chart)
        click.echo(f"chart written to {chart}")
