"""Charts (matplotlib, the optional extra ``rkcheck[plot]``); imported only when drawing."""

from __future__ import annotations

from rkcheck.errors import UserError

INSTALL_HINT = "charts need matplotlib: pip install 'rkcheck[plot]' (or pip install matplotlib)"


def pyplot(option: str = "--chart"):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise UserError(INSTALL_HINT.replace("charts", "pictures") if option == "--draw" else INSTALL_HINT,
                        option) from None
    return plt


def _save(fig, out: str) -> None:
    if not out.lower().endswith((".png", ".svg", ".pdf")):
        raise UserError("the chart file must end in .png, .svg or .pdf", "--chart")
    fig.savefig(out, dpi=130, bbox_inches="tight")


def bench_chart(rows, title: str, out: str) -> None:
    """Time (log x) against certified digits (y), one labelled point per backend."""
    from rkcheck.studies.accuracy import label

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for r in rows:
        digits = r.min_digits if r.min_digits is not None else None
        y = digits if digits is not None else max((x.min_digits or 0) for x in rows) + 20
        marker = "*" if digits is None else "o"
        ax.scatter([r.seconds], [y], s=60, marker=marker, color="tab:red" if r.backend == "float64" else "tab:blue")
        text = label(r.backend) + (" (exact: ∞ digits)" if digits is None else "")
        ax.annotate(text, (r.seconds, y), textcoords="offset points", xytext=(6, 4), fontsize=8)
    ax.set_xscale("log")
    ax.set_xlabel("wall time of the check (s, log scale)")
    ax.set_ylabel("certified digits (weakest held condition)")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    _save(fig, out)
    plt.close(fig)


def perturb_chart(result, title: str, out: str) -> None:
    """max |R| against ε (log–log) with one horizontal line per backend's detection floor."""
    from rkcheck.studies.accuracy import label

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    pts = [(float(r.eps), float(r.max_residual)) for r in result.rows if r.max_residual]
    if pts:
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", color="black",
                  label=f"max |R| (slope {result.slope:.2f})" if result.slope is not None else "max |R|")
    colours = ["tab:red", "tab:orange", "tab:green", "tab:blue", "tab:purple", "tab:brown", "tab:gray"]
    for (name, floor), colour in zip(result.floors.items(), colours):
        if floor > 0:
            ax.axhline(floor, color=colour, linestyle="--", linewidth=1,
                       label=f"{label(name)} floor ≈ {floor:.0e}")
    ax.set_xlabel("ε (perturbation size)")
    ax.set_ylabel("max |R| over failing conditions")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ax.invert_xaxis()
    _save(fig, out)
    plt.close(fig)


def energy_chart(series: list[tuple[str, list[float], list[float]]], title: str, out: str,
                 xlabel: str = "t", ylabel: str = "|H(y_n) − H(y_0)|", loglog: bool = False) -> None:
    """Energy error over time (or any x), one line per series (semilog-y)."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    positive = [y for _, _, ys in series for y in ys if y > 0]
    floor = min(positive) / 2 if positive else 1e-300  # exact zeros drawn just below the data
    for name, xs, ys in series:
        ys_pos = [max(y, floor) for y in ys]
        if loglog:
            ax.loglog(xs, ys_pos, "o-", label=name, markersize=3)
        else:
            ax.semilogy(xs, ys_pos, label=name, linewidth=1)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, out)
    plt.close(fig)


def workprec_chart(wp, title: str, out: str) -> None:
    """Final error and energy error against wall time (log–log), one line per tableau."""
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    names = list(dict.fromkeys(r.name for r in wp.rows))
    for name in names:
        rows = [r for r in wp.rows if r.name == name]
        t = [max(r.seconds, 1e-6) for r in rows]
        ax1.loglog(t, [max(r.error, 1e-300) for r in rows], "o-", label=name, markersize=4)
        ax2.loglog(t, [max(r.energy_error, 1e-300) for r in rows], "o-", label=name, markersize=4)
    ax1.set_xlabel("wall time (s)")
    ax1.set_ylabel(f"error at T = {float(wp.T):g}")
    ax2.set_xlabel("wall time (s)")
    ax2.set_ylabel("max |H(y_n) − H(y_0)|")
    for ax in (ax1, ax2):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    _save(fig, out)
    plt.close(fig)


def tree_picture(drawing, title: str, out: str) -> None:
    """The free tree of a :class:`~rkcheck.trees.drawing.TreeDrawing` as a picture: the
    designated centre on top, each vertex above its children, centres filled red, the
    root of the rooting given ringed.  Every vertex and edge carries an id (``vertex-3``,
    ``edge-1-3``; SVG keeps them) so that a reader, or a test, can tell what was drawn."""
    if not out.lower().endswith((".png", ".svg", ".pdf")):
        raise UserError("the picture file must end in .png, .svg or .pdf", "--draw")
    plt = pyplot("--draw")
    n = drawing.vertices
    width = max(drawing.x, default=0) + 1
    height = max(drawing.depth, default=0) + 1
    fig, ax = plt.subplots(figsize=(max(2.5, 0.7 * width + 1.5), max(2.0, 0.8 * height + 1.2)))
    for p, v in drawing.edges:
        (line,) = ax.plot([drawing.x[p], drawing.x[v]], [-drawing.depth[p], -drawing.depth[v]], color="0.35",
                          linewidth=1.5, zorder=1)
        line.set_gid(f"edge-{p}-{v}")
    for v in range(n):
        centre = v in drawing.centres
        dot = ax.scatter([drawing.x[v]], [-drawing.depth[v]], s=140 if centre else 90, zorder=2,
                         color="tab:red" if centre else "0.15", edgecolors="black")
        dot.set_gid(f"vertex-{v}" + ("-centre" if centre else ""))
    ring = ax.scatter([drawing.x[drawing.root]], [-drawing.depth[drawing.root]], s=420, zorder=3,
                      facecolors="none", edgecolors="tab:blue", linewidths=2)
    ring.set_gid(f"root-{drawing.root}")
    from matplotlib.lines import Line2D

    ax.legend(handles=[
        Line2D([], [], marker="o", linestyle="", color="tab:red", markeredgecolor="black", label="centre"),
        Line2D([], [], marker="o", linestyle="", markerfacecolor="none", markeredgecolor="tab:blue",
               markersize=12, markeredgewidth=2, label="root of the rooting given"),
    ], loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2, frameon=False, fontsize=8)
    ax.set_title(title, fontsize=10)
    ax.set_xlim(-0.7, width - 0.3)
    ax.set_ylim(-height + 0.4, 0.6)
    ax.axis("off")
    fig.savefig(out, dpi=130, bbox_inches="tight")
    plt.close(fig)
