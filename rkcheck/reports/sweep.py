"""Reports of ``rkcheck sweep``: a table for people (the grid as a map of energy orders
for one or two swept parameters, and the count per order), JSON for machines, and a
chart (matplotlib, ``rkcheck[plot]``)."""

from __future__ import annotations

from collections import Counter
from typing import Any

from rich.console import Console
from rich.text import Text

from rkcheck.numbers.formatting import counted
from rkcheck.reports.families import FAMILY_SCHEMA
from rkcheck.version import __version__

#: The map is drawn in text only up to this many values per axis (JSON has every point).
MAX_MAP_SIDE = 60


def _text(q: Any) -> str:
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def _cell(order: int, cap: int) -> str:
    return "*" if order >= cap else (str(order) if order < 10 else "+")


def sweep_doc(sw: Any, lazy: bool = False) -> dict[str, Any]:
    """``rkcheck sweep --format json`` (``lazy``: the points a generator, made as they
    are written)."""
    points = ({"values": {k: _text(v) for k, v in p.items()}, "energy_order": o}
              for p, o in zip(sw.points(), sw.orders))
    return {
        "rkcheck": __version__,
        "schema": FAMILY_SCHEMA,
        "family": {"name": sw.family.name, "source": sw.family.info.source, "parameters": list(sw.family.parameters)},
        "degree": sw.degree,
        "order_checked": sw.order,
        "energy_order_generic": sw.generic,
        "grid": {name: [_text(v) for v in values] for name, values in sw.axes},
        "points": points if lazy else list(points),
    }


def render_sweep(sw: Any, console: Console) -> None:
    deg = "none" if sw.degree is None else sw.degree
    console.print(Text(f"{sw.family.name}: energy order over {counted(len(sw.orders), 'grid point')} "
                       f"(degree m = {deg}, checked to order {sw.order}; exact at every point)", style="bold"))
    # an order that reaches the one checked is a lower bound: every condition checked held
    label = lambda o: f"≥ {o}" if o >= sw.order else str(o)  # noqa: E731
    console.print(f"energy order for generic parameter values: {label(sw.generic)}")
    counts = Counter(sw.orders)
    for o in sorted(counts):
        console.print(f"  energy order {label(o)}: {counts[o]} point{'s' if counts[o] != 1 else ''}")
    swept = [(n, v) for n, v in sw.axes if len(v) > 1]
    if len(swept) == 2 and all(len(v) <= MAX_MAP_SIDE for _, v in swept):
        _map(sw, swept, console)
    special = [(p, o) for p, o in zip(sw.points(), sw.orders) if o != sw.generic]
    if special and len(special) <= 40:
        console.print("points where the order is not the generic one:")
        for p, o in special:
            console.print(f"  {', '.join(f'{k} = {_text(v)}' for k, v in p.items())}: {label(o)}")


def _map(sw: Any, swept: list, console: Console) -> None:
    """Rows: the first swept parameter (top = largest), columns: the second; each cell
    the energy order (``*``: at least the order checked)."""
    (n1, v1), (n2, v2) = swept
    grid: dict[tuple, int] = {}
    for p, o in zip(sw.points(), sw.orders):
        grid[(p[n1], p[n2])] = o  # other axes hold one value each
    console.print(f"map: rows {n1} from {_text(v1[-1])} down to {_text(v1[0])}, columns {n2} from "
                  f"{_text(v2[0])} to {_text(v2[-1])} ('*': order ≥ {sw.order})")
    for a in reversed(v1):
        console.print("  " + "".join(_cell(grid[(a, b)], sw.order) for b in v2), highlight=False)


def sweep_chart(sw: Any, out: str) -> None:
    """The energy order over the grid: a coloured map for two swept parameters, a step
    line for one."""
    from rkcheck.errors import UserError
    from rkcheck.reports.charts import pyplot

    if not out.lower().endswith((".png", ".svg", ".pdf")):
        raise UserError("the chart file must end in .png, .svg or .pdf", "--plot")
    swept = [(n, v) for n, v in sw.axes if len(v) > 1]
    if not 1 <= len(swept) <= 2:
        raise UserError("--plot charts one or two swept parameters", "--plot")
    plt = pyplot("--plot")
    fig, ax = plt.subplots(figsize=(6.5, 5))
    if len(swept) == 1:
        (name, values), = swept
        ax.step([float(v) for v in values], sw.orders, where="mid")
        ax.set_xlabel(name)
        ax.set_ylabel("energy order")
    else:
        import numpy as np

        (n1, v1), (n2, v2) = swept
        Z = np.array(sw.orders, dtype=float).reshape(len(v1), len(v2))
        mesh = ax.pcolormesh([float(v) for v in v2], [float(v) for v in v1], Z, shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=f"energy order (capped at {sw.order})")
        ax.set_xlabel(n2)
        ax.set_ylabel(n1)
    ax.set_title(f"{sw.family.name}\n(degree m = {sw.degree}, exact at every grid point)", fontsize=9)
    fig.savefig(out, dpi=130, bbox_inches="tight")
    plt.close(fig)
