"""Rich text reports for people (``verify``, ``show``, ``conditions``, ``explain``)."""

from __future__ import annotations

from fractions import Fraction
from typing import Sequence

from rich import box
from rich.console import Console, Group
from rich.table import Table
from rich.text import Text

from rkcheck.energy.check import CheckResult, inconsistent, overall
from rkcheck.energy.gate import requirement_shortfall
from rkcheck.energy.results import Condition
from rkcheck.evaluation.values import Backend, TableauValues
from rkcheck.io.printable import printable
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.formatting import (
    count_text,
    counted,
    decimal_string,
    digits_text,
)
from rkcheck.numbers.precision import bits_for_dps
from rkcheck.numbers.reading import DecimalsMode, Reading
from rkcheck.reports.cells import enclosure_text, plain, state_text
from rkcheck.reports.properties import property_rows, stability_line, tableau_stability
from rkcheck.reports.trees import tree_text
from rkcheck.verdicts import FAILS, HOLDS, HOLDS_TO_DIGITS

MAX_FAILURES_SHOWN = 20


def _kv_table() -> Table:
    t = Table(box=None, show_header=False, pad_edge=False, padding=(0, 2, 0, 0))
    t.add_column(style="bold", no_wrap=True)
    t.add_column()
    return t


def header(values: TableauValues) -> Group:
    tab = values.tableau
    title = Text(tab.name, style="bold")
    source = tab.info.source
    if source and source not in ("<memory>", "<string>"):
        title.append(f"  ({printable(source)})", style="dim")
    if tab.info.continuous is not None:
        return Group(title, Text(continuous_facts(tab.info.continuous, values)))
    facts = f"{tab.stages} stage{'s' if tab.stages != 1 else ''}, {tab.structure}, {values.describe()}"
    return Group(title, Text(facts))


def continuous_facts(surrogate, values: TableauValues) -> str:
    """The header of a continuous-stage method: its kernel and how its B-series is exact."""
    m = surrogate.method
    return (f"continuous-stage method: A(τ, σ) = {m.A}, B(τ) = {m.b}\n{values.describe()}; elementary weights exact "
            f"for trees up to {surrogate.vertices} vertices (an exact {surrogate.nodes}-node rational rule)")


def conditions_table(results: Sequence[Condition], title: str) -> Table:
    t = Table(title=Text(title), title_justify="left", box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("id", no_wrap=True)
    t.add_column("bracket", no_wrap=True)
    t.add_column("vertices", justify="right")
    t.add_column("max deg", justify="right")
    t.add_column("residual")
    t.add_column("state", no_wrap=True)
    for r in results:
        t.add_row(*plain(
            r.id, r.bracket, r.vertices, r.max_degree,
            enclosure_text(r.enclosure, r.verdict, value=r.residual), state_text(r.verdict),
        ))
    return t


def per_order_table(res: CheckResult) -> Table:
    t = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("order", justify="right")
    t.add_column("vertices", justify="right")
    t.add_column("conditions", justify="right")
    t.add_column("checked", justify="right")
    t.add_column("held", justify="right")
    t.add_column("failed", justify="right")
    # exact arithmetic proves or refutes every condition: a digits column would only say
    # "exact" on every row, so it is shown for balls alone
    show_digits = res.backend is not Backend.EXACT
    if show_digits:
        t.add_column("min digits", justify="right")
    for p in res.per_order:
        failed = Text(count_text(p.failed), style="bold red" if p.failed else "")
        digits = "exact" if p.checked and p.min_digits is None and p.held else (str(p.min_digits) if p.min_digits is not None else "")
        t.add_row(*plain(p.order, p.order + 1, *map(count_text, (p.conditions, p.checked, p.held)), failed,
                         *([digits] if show_digits else [])))
    return t


def _backend_text(res: CheckResult) -> str:
    if res.backend is Backend.EXACT:
        exact = res.values.exact
        if exact is not None and exact.algebra is not None:  # a family's conditions over Q, and no field built
            return f"exact arithmetic over Q (entries polynomials in the roots of a degree-{res.values.stages} node polynomial)"
        if exact is None or exact.field is None:
            return "exact rational arithmetic"
        where = f"Q({exact.field.name})" if exact.field.sqrt_of else f"a number field of degree {exact.field.degree}"
        return f"exact arithmetic over Q (entries in {where})" if exact.nodes is not None else f"exact arithmetic in {where}"
    return f"certified ball arithmetic at {res.options.dps} digits"


def claims_table(claim_results, title: str = "Claims ([expect])") -> Table:
    t = Table(title=Text(title), title_justify="left", box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("claim", no_wrap=True)
    t.add_column("claimed")
    t.add_column("found")
    t.add_column("", no_wrap=True)
    t.add_column("note")
    for r in claim_results:
        # a claim on what nothing decides is not met, but not shown false either
        ok = (Text("ok", style="green") if r.met else Text("NOT SHOWN", style="bold yellow")
              if r.found == "undecided" else Text("BROKEN", style="bold red"))
        t.add_row(*plain(r.claim.label(), r.claimed, r.found, ok, r.note or ""))
    return t


def render_check(
    res: CheckResult, console: Console, show_all: bool = False, quiet: bool = False,
    verbose: bool = False, fail_on: str = "auto", draw: bool = False,
) -> None:
    """The ``verify`` report: header, facts, AVF, energy order, per-order counts, failures
    (``draw``: with the free tree of each failing condition shown, drawn)."""
    o = res.options
    deg = "all Hamiltonians" if o.degree is None else f"degree ≤ {o.degree}"
    total = sum(p.conditions for p in res.per_order)
    if quiet:  # the warnings that matter (c ≠ A·1, Σb ≠ 1, bare floats) survive --quiet
        for w in res.warnings:
            console.print(Text(f"warning: {w}", style="yellow"))
    if not quiet:
        console.print(header(res.values))
        console.print(f"{deg}, order ≤ {o.order}: {counted(total, 'condition')}, {_backend_text(res)}")
        for w in res.warnings:
            console.print(Text(f"warning: {w}", style="yellow"))
        console.print()
        console.print(_facts_table(res))
        console.print()
        console.print(per_order_table(res))
        if verbose:
            console.print(_timings_line(res), style="dim")
    if show_all:
        console.print(conditions_table(res.conditions, f"All conditions ({count_text(len(res.conditions))} checked)"))
    elif res.failures and (not quiet or judged_by_conditions(res, fail_on)):
        # --quiet prints problems only: failing conditions are one when they decide the verdict
        shown = res.failures[:MAX_FAILURES_SHOWN]
        title = f"Failing conditions ({count_text(len(res.failures))} of {count_text(len(res.conditions))} checked"
        title += f"; the first {len(shown)}, --all lists every one)" if len(shown) < len(res.failures) else ")"
        console.print(conditions_table(shown, title))
        if draw:
            draw_conditions(shown, console)
    if res.claims and not quiet:
        console.print(claims_table(res.claims))
    elif res.claims and any(not r.met for r in res.claims):  # --quiet: the broken claims only
        console.print(claims_table([r for r in res.claims if not r.met], "Broken claims ([expect])"))
    # one line however long: CI jobs read it with tail -1 or grep
    console.print(verdict_line(res, res.claims, fail_on), soft_wrap=True)


def _facts_table(res: CheckResult) -> Table:
    """The check's facts, one per row: orders, AVF, certificate, energy order, properties."""
    kv = _kv_table()
    kv.add_row(*plain("quadrature order", _order_text(res.quadrature, "quadrature",
                                                      res.tableau.info.continuous is not None)))
    kv.add_row(*plain("classical order", _order_text(res.classical, "classical")))
    if res.avf is not None:
        a = res.avf
        style = "red" if a.verdict.state == FAILS else "green" if a.verdict.state == HOLDS else "yellow"
        label = Text(a.verdict.answer(), style=style)
        label.append(f" — {a.reason}", style="")
        kv.add_row(*plain("AVF" if a.degree is None else f"AVF (degree {a.degree})", label))
        for note in a.notes:
            kv.add_row(*plain("", note))
    if res.certificate is not None and res.certificate.certified and res.certificate.kind != "avf":
        kv.add_row(*plain("certificate", res.certificate.reason))
    kv.add_row(*plain("energy order", _energy_text(res)))
    if res.theorem1:
        kv.add_row(*plain("Theorem 1", res.theorem1.removeprefix("Theorem 1: ")))
    for name, value in property_rows(res):  # error constant, symplectic, symmetric, R(z)
        kv.add_row(*plain(name, value))
    return kv


def _timings_line(res: CheckResult) -> str:
    """``--verbose``: where the check's time went, and in which arithmetic."""
    t = res.timings
    return (f"timings: tree and condition tables {t.get('trees', 0):.3f} s, evaluation "
            f"{t.get('evaluation', 0):.3f} s, orders and certificates {t.get('orders_and_avf', 0):.3f} s; "
            f"backend {res.backend}"
            + (f" at {bits_for_dps(res.options.dps)} bits" if res.backend != "exact" else ""))


def draw_conditions(conditions: Sequence[Condition], console: Console) -> None:
    """The free trees of some conditions, drawn from their centres, side by side."""
    from rich.columns import Columns

    console.print(Text("Their free trees, drawn from the centre:"))
    console.print(Columns([Group(Text(r.id, style="bold"), tree_text(r.tree.level_sequence, mark_root=False))
                           for r in conditions], padding=(1, 4)))
    console.print()


def judged_by_conditions(res: CheckResult, fail_on: str) -> bool:
    """Whether failing conditions decide the file's verdict under ``--fail-on``: always
    with ``conditions``, with ``auto`` when the file makes no claims."""
    return fail_on == "conditions" or (fail_on == "auto" and not res.claims)


def _order_text(r, what: str, continuous: bool = False) -> str:
    """``4  (Σ b_i c_i^4 = 1/5 fails)``; an order reached only to digits says so:
    ``0, holds to 15 digits beyond order 0 up to order 4  (…)`` (definitions §5)."""
    # a continuous method's quadrature order is checked as far as its exact B-series goes
    open_ended = (what == "classical" or (what == "quadrature" and continuous)) and not r.first_failure
    text = (f"≥ {r.to_digits}" if open_ended else f"{r.to_digits}") if r.digits is None else (
        beyond_digits(r.order, r.digits, r.to_digits))
    if r.first_failure:
        text += f"  ({r.first_failure} fails)"
    elif what == "classical" or open_ended:
        text += f"  (checked up to {r.checked})"
    return text


def _degree_words(degree: int | None) -> str:
    return "every Hamiltonian" if degree is None else f"degree ≤ {degree}"


def beyond_digits(proven: int, digits: int, reach: int | str) -> str:
    """``1, holds to 15 digits beyond order 1 up to order 4``: a proven order and how far
    the conditions beyond it hold to digits."""
    return f"{proven}, holds to {digits_text(digits)} beyond order {proven} up to order {reach}"


def energy_order_phrase(res: CheckResult) -> str:
    """The energy order as the headline says it: ``4``, or qualified when conditions
    beyond the proven order hold only to digits."""
    digits = res.energy_order_digits
    if digits is None:
        return str(res.energy_order)
    reach: int | str = f"{res.checked_through}, the order checked" if not len(res.failures) else (
        res.energy_order_to_digits)
    return beyond_digits(res.energy_order, digits, reach)


def _certificate_name(res: CheckResult) -> str:
    """The certificate's name; one that holds only numerically is not called a
    certificate (definitions §5.3): ``line-integral criterion, to 5 digits``."""
    cert = res.certificate
    if cert is None:
        return "certificate"
    name = cert.name
    if cert.verdict.state == HOLDS_TO_DIGITS:
        name = name.replace("certificate", "criterion") + f", to {digits_text(cert.verdict.digits)}"
    return name


def _numeric_certificate(res: CheckResult) -> int | None:
    return res.energy_order_all_digits


def _energy_text(res: CheckResult) -> Text:
    o = res.options
    if res.certified_all:
        digits = _numeric_certificate(res)
        if digits is not None:
            return Text(f"to {digits_text(digits)}: all orders for {_degree_words(o.degree)} ({_certificate_name(res)}, "
                        f"not a proof); {res.checked_through} verified", style="yellow")
        return Text(f"all orders for {_degree_words(o.degree)} ({_certificate_name(res)}); {res.checked_through} verified", style="green")
    first = res.first_failure
    if first is None:
        if res.energy_order_digits is not None:
            return Text(f"{energy_order_phrase(res)} (not a proof)", style="yellow")
        if res.interrupted:
            done = res.checked_through
            if done < 2:
                return Text("≥ 1 (interrupted before every condition of order 2 was checked)", style="yellow")
            return Text(f"≥ {res.energy_order} (interrupted: every condition up to order {done} holds; "
                        f"order {done + 1} was not finished)", style="yellow")
        return Text(f"≥ {res.energy_order} (every condition up to order {o.order} holds; not proven beyond)", style="green")
    return Text(
        f"{energy_order_phrase(res)} (first failing condition at order {first.order}: "
        f"{first.id} {first.bracket})",
        style="red",
    )


def verdict_line(res: CheckResult, claims, fail_on: str) -> Text:
    """The last line: the verdict that decides the exit code first (claims or conditions,
    by ``--fail-on``), the other one in parentheses."""
    conditions = final_line(res)
    if not claims:
        return conditions
    broken = [r for r in claims if not r.met]
    # the file fails, whatever its claims, when --require is not met; under --fail-on
    # conditions the conditions' line says so, after any condition that fails
    shortfall = requirement_shortfall(res, claims) if fail_on not in ("never", "conditions") else None
    if shortfall is not None:
        met = "the claim is met" if len(claims) == 1 else f"all {len(claims)} claims met"
        head = Text(f"FAIL: {shortfall.text()}", style="bold red")
        head.append(Text(f"  ({f'claims broken: {len(broken)} of {len(claims)}' if broken else met})", style=""))
        return head
    unshown = all(r.found == "undecided" for r in broken)
    what = "CLAIMS NOT SHOWN" if unshown else "CLAIMS BROKEN"
    claims_text = (Text(f"{what}: {len(broken)} of {len(claims)}", style="bold red") if broken
                   else Text("OK: the claim is met" if len(claims) == 1 else f"OK: all {len(claims)} claims met",
                             style="bold green"))
    if fail_on == "conditions":
        head, other = conditions, claims_text.plain
    else:
        head, other = claims_text, conditions.plain
    head = head.copy()
    head.append(Text(f"  ({other})", style=""))
    return head


def final_line(res: CheckResult) -> Text:
    """The verdict line (definitions §5.3): a proof says OK; a numerical result says
    "to D digits" first and never "certificate"; ``--require`` turns a shortfall into
    FAIL; a certain ``Σb ≠ 1`` fails the method."""
    v = overall(res)
    count = len(res.conditions)
    n = counted(count, "condition")
    every = f"the {n}" if count == 1 else f"all {n}"  # "the 1 condition holds", "all 4 conditions hold"
    holds = "holds" if count == 1 else "hold"
    if len(res.failures):
        failing = len(res.failures)
        also = "; Σb ≠ 1 (certain): the method is inconsistent" if inconsistent(res) else ""
        return Text(f"FAIL: {count_text(failing)} of {n} {'fails' if failing == 1 else 'fail'}; "
                    f"energy order {energy_order_phrase(res)}{also}", style="bold red")
    if res.interrupted:  # no failure among the orders that finished: no verdict either
        return Text(f"INTERRUPTED: {n} checked before Ctrl-C, none failing; no verdict", style="bold yellow")
    if inconsistent(res):
        return Text(f"FAIL: Σb ≠ 1 (certain): the method is inconsistent, whatever its {counted(count, 'energy condition')} "
                    f"say{'s' if count == 1 else ''}", style="bold red")
    shortfall = requirement_shortfall(res)
    if shortfall is not None:
        return Text(f"FAIL: {shortfall.text()}", style="bold red")
    if res.certified_all:
        digits = _numeric_certificate(res)
        if digits is not None:
            return Text(
                f"OK to {digits_text(digits)} (not a proof): energy preserved to all orders for "
                f"{_degree_words(res.options.degree)} ({_certificate_name(res)}); {n} checked",
                style="bold yellow",
            )
        return Text(
            f"OK: energy preserved to all orders for {_degree_words(res.options.degree)} ({_certificate_name(res)}); "
            f"{n} checked",
            style="bold green",
        )
    if count == 0:  # order 1: the first energy condition has three vertices (order 2)
        return Text(f"OK: no energy condition up to order {res.options.order} (the first is of order 2)",
                    style="bold green")
    if v.state == HOLDS:
        return Text(f"OK: {every} {holds} exactly", style="bold green")
    return Text(f"OK to {digits_text(v.digits)} (not a proof): {every} {holds} to at least {digits_text(v.digits)}",
                style="bold yellow")


def render_tableau(tab: Tableau, console: Console, decimals: DecimalsMode = DecimalsMode.AUTO,
                   warnings: list[str] | None = None) -> None:
    """``show``: the Butcher table ``c | A`` over ``| bᵀ`` with the entries as written."""
    values = TableauValues(tab, Reading(decimals))
    console.print(header(values))
    if tab.info.description:
        console.print(Text(tab.info.description, style="dim"))
    for ref in tab.info.references:
        console.print(Text(f"reference: {ref}", style="dim"))
    if tab.info.constants.definitions:
        from rkcheck.numbers.expressions import to_text

        consts = ", ".join(f"{k} = {to_text(v)}" for k, v in tab.info.constants.definitions.items())
        console.print(f"constants: {consts}")
    t = Table(box=box.SIMPLE, show_header=False, pad_edge=False)
    t.add_column(style="cyan")
    for _ in range(tab.stages):
        t.add_column()
    c_entries = tab.c
    for i, row in enumerate(tab.A):
        c_text = c_entries[i].text if c_entries is not None else Text(_row_sum_text(tab, i), style="dim")
        t.add_row(*plain(c_text, *[e.text for e in row]), end_section=i == tab.stages - 1)
    t.add_row(*plain("", *[e.text for e in tab.b]), style="bold")
    console.print(t)
    if c_entries is None:
        console.print(Text("c not given: the row sums A·1 are shown (dim) and used", style="dim"))
    console.print(Text(stability_line(tableau_stability(values))))  # R(z), R(z)R(−z) − 1
    for w in warnings or []:
        console.print(Text(f"warning: {w}", style="yellow"))


def _row_sum_text(tab: Tableau, i: int) -> str:
    row = tab.A[i]
    exact = [e.exact for e in row if e.exact is not None]
    if len(exact) == len(row):
        return str(sum(exact, Fraction(0)))
    enc = sum((e.enclosure(80, DecimalsMode.EXACT) for e in row[1:]), row[0].enclosure(80, DecimalsMode.EXACT))
    return "≈ " + decimal_string(enc.mid, 12)
