"""Studies of the check itself: the double-bush map's rank and kernel (``rkcheck
kernel``), perturbation sweeps (``rkcheck perturb``) and backends compared (``rkcheck
bench``), for Python callers.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Sequence

from rkcheck.api.settings import guard
from rkcheck.api.tableaux import TableauLike
from rkcheck.api.verification import UNSET, _option, check_flags
from rkcheck.energy.double_bush import Kernel
from rkcheck.errors import OptionError
from rkcheck.methods.tableau import Tableau
from rkcheck.numbers.grammar import fraction_text
from rkcheck.options import (
    DEFAULT_DPS,
    KERNEL_DEGREE_RANGE,
    KERNEL_STAGES_RANGE,
    MAX_KERNEL_WORK,
    REPEAT_RANGE,
    STUDY_DPS_RANGE,
    parse_dps_list,
    parse_int_in,
    parse_integer,
    resolve_check_options,
)
from rkcheck.studies.accuracy import Perturbation

if TYPE_CHECKING:
    from rkcheck.studies.accuracy import BenchRow


#: The working precisions ``bench`` compares by default, and those ``perturb`` reports.
BENCH_DPS: tuple[int, ...] = (15, 30, 50, 100, 200, 400)
PERTURB_DPS: tuple[int, ...] = (15, 50)
#: The ε values ``perturb`` sweeps by default: every decade from 10⁻¹ to 10⁻³⁰.
PERTURB_EPS = "1e-1..1e-30"


def _degree_and_order(tab: Tableau, degree: Any, order: Any) -> tuple[int | None, int]:
    """``degree`` and ``order`` when given, else the tableau's ``[check]``, else none and
    8; refused when the condition tables would not fit in memory (the resource guard)."""
    options = resolve_check_options(check_flags(degree, order), tab.info.check, {})
    guard(options.order, options.degree)
    return options.degree, options.order


# ------------------------------------------------------------------ kernel


def kernel(degree: int, stages: int | None = None, *, rule: str = "gauss", tableau: TableauLike | None = None,
           dps: int = DEFAULT_DPS) -> Kernel:
    """Rank and kernel of the double-bush map M for polynomial degree ``degree`` (m ≥ 3)
    at a quadrature rule — the ``stages``-point ``rule`` (``gauss``, ``radau-i``,
    ``radau-ii``, ``lobatto``, ``zeta:<value>``) or the ``b`` and ``c = A·1`` of
    ``tableau`` (a Tableau, path or ``"@name"``) — as ``rkcheck kernel`` prints it.

    M maps A to the double-bush conditions ``p bᵀC^(p−1)Ac^q − q bᵀC^(q−1)Ac^p``,
    1 ≤ p < q ≤ m−1 (definitions §3–4, seed Lemma 2): for Gauss and m = 2s, rank M = s²−1
    with kernel ``(1−c)bᵀ``; for m = 2s−1 and nodes the zeros of ``P_s − ζP_{s−1}``,
    s²−3 (ζ ≠ −1) or s²−s−1 (ζ = −1, Radau I).  Exact for rational and algebraic rules,
    else numerical at ``dps`` digits."""
    from rkcheck.api.tableaux import as_tableau
    from rkcheck.energy.double_bush import kernel_of, rule_kernel, tableau_rule

    degree = _option(lambda: parse_int_in(degree, KERNEL_DEGREE_RANGE, "degree"))
    if not isinstance(rule, str):
        raise OptionError(f"expected a rule name (gauss, radau-i, radau-ii, lobatto, zeta:<value>), got {rule!r}",
                          "rule")
    if stages is not None:
        stages = _option(lambda: parse_int_in(stages, KERNEL_STAGES_RANGE, "stages"))
    dps = _option(lambda: parse_int_in(dps, STUDY_DPS_RANGE, "dps"))
    if tableau is not None:
        tab = as_tableau(tableau)
        b, c, exact = tableau_rule(tab, dps)
        _kernel_work_guard(len(b), degree, exact, dps)
        return replace(kernel_of(b, c, degree, exact, dps), tableau=tab)
    if stages is None:
        raise OptionError("give --stages/-s (or --tableau FILE)")
    # named rules need no guard: their rank is exact over Q from the node polynomial, in
    # seconds even at s = 12, m = 40
    return replace(rule_kernel(rule, stages, degree, dps), rule=rule)


def _kernel_work_guard(s: int, degree: int, exact: bool, dps: int) -> None:
    """Refuse a map M whose elimination would run for minutes (MAX_KERNEL_WORK)."""
    rows, columns = (degree - 1) * (degree - 2) // 2 + s, s * s
    work = rows * columns**2 * (1 if exact else max(1.0, dps / 50) ** 1.5)
    if work > MAX_KERNEL_WORK:
        raise OptionError(f"M for s = {s}, m = {degree} is {rows} × {columns}: about {round(work):,} units of "
                          f"elimination work (rows × columns²{'' if exact else ' × (dps/50)^1.5'}), beyond the limit "
                          f"MAX_KERNEL_WORK = {MAX_KERNEL_WORK:,}; lower -m, -s or --dps", "kernel")


# ------------------------------------------------------------------ perturb


def _eps_list(eps: str | Sequence[Any]) -> list[Fraction]:
    from rkcheck.studies.accuracy import parse_eps

    if isinstance(eps, (int, float, Fraction)) and not isinstance(eps, bool):
        eps = [eps]  # one value
    if not isinstance(eps, str) and not (isinstance(eps, Sequence) and not isinstance(eps, (bytes, bytearray))):
        raise OptionError(f"expected ε values: a text such as \"1e-1..1e-40\", a number or a list, "
                          f"got {type(eps).__name__}", "eps")
    # a float as its shortest decimal, as Tableau.from_arrays reads one
    text = eps if isinstance(eps, str) else ",".join(
        fraction_text(x) if isinstance(x, (int, Fraction)) and not isinstance(x, bool) else str(x) for x in eps)
    values: list[Fraction] = _option(lambda: parse_eps(text))
    if not values or any(not 0 < e <= 1 for e in values):  # log10(ε) and float radii need 0 < ε <= 1
        raise OptionError(f"every ε must be in (0, 1], got {text!r}", "--eps")
    return values


def perturb(tableau: TableauLike, direction: str, *, degree: int | str | None = UNSET, order: int = UNSET,
            eps: str | Sequence[Any] = PERTURB_EPS, dps: str | Sequence[int] = PERTURB_DPS,
            seed: int = 2024) -> Perturbation:
    """Perturb the tableau's A by ε·D and watch the energy conditions fail, as
    ``rkcheck perturb`` does.

    ``direction``: ``"random"`` (fixed-seed random matrix, ``seed``), ``"kernel"`` (the
    zero-row-sum kernel direction of the double-bush map: the seed's §2.3–2.4 direction
    that keeps every linear condition; needs ``degree`` ≥ 3) or ``"entry:i,j"`` (1-based).
    D is scaled to max |d_ij| = 1, b stays.  ``eps``: ``"1e-1..1e-30"`` (every decade),
    ``"1e-2..1e-30:2"``, ``"1e-3,1e-6"`` or a list of numbers, each in (0, 1];
    ``dps``: the ball precisions whose detection is reported.  ``degree`` and ``order``
    default to the tableau's ``[check]``, then none and 8 (definitions §3).  The residuals
    are judged as definitions §5 says; the reference backend is exact for exact tableaux."""
    from rkcheck.api.tableaux import as_tableau
    from rkcheck.studies.accuracy import direction as make_direction
    from rkcheck.studies.accuracy import direction_dps, perturb_sweep

    if not isinstance(direction, str):
        raise OptionError(f"expected 'random', 'kernel' or 'entry:i,j', got {direction!r}", "direction")
    tab = as_tableau(tableau)
    deg, N = _degree_and_order(tab, degree, order)
    eps_values = _eps_list(eps)
    dps_values = _option(lambda: parse_dps_list(dps))
    seed = _option(lambda: parse_integer(seed, "seed"))
    D, desc = _option(lambda: make_direction(tab, direction, deg, seed, direction_dps(eps_values, dps_values)))
    return perturb_sweep(tab, D, desc, eps_values, deg, N, dps_values)


# ------------------------------------------------------------------ bench


@dataclass(frozen=True)
class Bench:
    """What :func:`bench` gives: one row per backend (``float64``, ``dps:D``, ``exact``)
    with ``seconds`` (best of the repeats), ``conditions``, ``per_second``,
    ``min_digits`` (the weakest certified digits of the conditions that hold),
    ``failures`` (certified) and ``agrees`` (same failures as the last, most precise
    backend); and the time to build the shared condition tables."""

    tableau: Tableau
    degree: int | None
    order: int
    rows: "list[BenchRow]"
    tables_seconds: float

    def __repr__(self) -> str:
        return f"<Bench of {self.tableau.name!r}: {', '.join(r.backend for r in self.rows)}>"


def bench(tableau: TableauLike, *, degree: int | str | None = UNSET, order: int = UNSET,
          dps: str | Sequence[int] = BENCH_DPS, repeat: int = 3) -> Bench:
    """The same check on every backend — float64 screen, certified balls at each of
    ``dps`` digits, exact when the tableau is — timed (best of ``repeat``), as
    ``rkcheck bench`` runs it.  ``degree`` and ``order`` default to the tableau's
    ``[check]``, then none and 8 (definitions §3); verdicts as definitions §5."""
    from rkcheck.api.tableaux import as_tableau
    from rkcheck.studies.accuracy import bench_backends

    tab = as_tableau(tableau)
    deg, N = _degree_and_order(tab, degree, order)
    dps_values = _option(lambda: parse_dps_list(dps))
    repeat = _option(lambda: parse_int_in(repeat, REPEAT_RANGE, "repeat"))
    rows, t_tables = bench_backends(tab, deg, N, dps_values, repeat=repeat)
    return Bench(tab, deg, N, rows, t_tables)


__all__ = ["Bench", "Kernel", "Perturbation", "bench", "kernel", "perturb"]