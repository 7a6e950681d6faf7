"""Rich text of the condition listing and of one condition's free tree (``conditions``,
``explain``)."""

from __future__ import annotations

from typing import Sequence

from rich import box
from rich.console import Console
from rich.table import Table
from rich.text import Text

from rkcheck.energy.explain import EnergyCondition
from rkcheck.numbers.formatting import count_text, counted
from rkcheck.reports.cells import enclosure_text, plain, state_text
from rkcheck.verdicts import FAILS, HOLDS, Verdict


def render_condition_list(listing, console: Console, count_only: bool) -> None:
    """``conditions``: counts per order, and the list of condition trees."""
    deg = "no degree bound" if listing.degree is None else f"max degree ≤ {listing.degree}"
    console.print(f"Energy conditions up to order {listing.order} ({deg}): {count_text(len(listing))}")
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("order", justify="right")
    t.add_column("vertices", justify="right")
    t.add_column("conditions", justify="right")
    for k, v in listing.counts_by_order().items():
        t.add_row(*plain(k, k + 1, count_text(v)))
    console.print(t)
    if count_only:
        return
    lst = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    lst.add_column("id", no_wrap=True)
    lst.add_column("bracket", no_wrap=True)
    lst.add_column("vertices", justify="right")
    lst.add_column("max deg", justify="right")
    lst.add_column("rootings", justify="right")
    for c in listing.sorted_records():
        lst.add_row(*plain(c.id, c.bracket, c.vertices, c.max_degree, c.rootings))
    console.print(lst)


def tree_drawing(seq: Sequence[int]):
    """The :class:`~rkcheck.trees.drawing.TreeDrawing` of a level sequence (for pictures)."""
    from rkcheck.trees.drawing import draw

    return draw(tuple(seq))


def tree_text(seq: Sequence[int], mark_root: bool = True) -> Text:
    """The free tree of a level sequence drawn in Unicode (:mod:`rkcheck.trees.drawing`):
    one ``●`` per vertex, centres and the root of the rooting given labelled."""
    from rkcheck.trees.drawing import draw

    out = Text()
    for k, line in enumerate(draw(tuple(seq)).lines(mark_root)):
        dot = line.index("●")
        out.append(line[:dot], style="dim")
        out.append(line[dot:dot + 1], style="bold magenta" if "centre" in line[dot:] else "bold")
        out.append(line[dot + 1:], style="cyan")
        if k < len(seq) - 1:
            out.append("\n")
    return out


def render_explanation(ex: EnergyCondition, console: Console) -> None:
    """``explain``: the free tree (drawn), its rootings with signs and σ, and the weights."""
    given = ",".join(map(str, ex.given))
    tableau = ex.tableau
    drawn = f"The free tree of {given}, drawn from its centre (root: the root of {given}):"
    if ex.tree is None:
        # a tree with one vertex has no edge, so it is not superfluous: it is below the
        # conditions, which start at 3 vertices (definitions §3)
        what = ("superfluous free tree: a rooting u∘u exists (equal halves across the central edge)"
                if ex.superfluous else "fewer than 3 vertices")
        console.print(f"{given}: {counted(ex.vertices, 'vertex', 'vertices')} — {what}; no energy condition")
        console.print(drawn)
        console.print(tree_text(ex.given))
        return
    c = ex.tree
    console.print(Text(f"Energy condition {c.id}  {c.bracket}", style="bold"))
    if c.id != given:
        console.print(f"(given as {given}: canonical id = level sequence of the rooting at the centre)")
    console.print(
        f"{ex.vertices} vertices (order {c.order}), max degree {ex.max_degree}: "
        f"a condition for every degree m ≥ {ex.max_degree}"
    )
    console.print(drawn)
    console.print(tree_text(ex.given))
    console.print("R = Σ_u (−1)^κ / σ(u) · a(B₋(u)) over the distinct rootings u:")
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("rooting u", no_wrap=True)
    t.add_column("sign", justify="center")
    t.add_column("σ(u)", justify="right")
    t.add_column("a(B₋(u)) = product of")
    if tableau is not None:
        t.add_column("term value")
    for term in ex.terms:
        forest = " · ".join(f"({w})" for w in term.weights) or "1"
        row = [f"{term.bracket}  {','.join(map(str, term.level_sequence))}", "+" if term.sign > 0 else "−", str(term.sigma), forest]
        if tableau is not None and term.value is not None:
            row.append(enclosure_text(term.value, Verdict(FAILS) if not term.value.exact else Verdict(HOLDS)))
        t.add_row(*plain(*row))
    console.print(t)
    if tableau is not None and ex.enclosure is not None and ex.verdict is not None:
        line = Text(f"R = {enclosure_text(ex.enclosure, ex.verdict, 20)}   ")
        line.append_text(state_text(ex.verdict))
        console.print(line)
