"""Check options: their names, values, defaults, and where they come from.

Options reach rkcheck from four places — command-line flags, a tableau file's
``[check]`` table, the project's ``[tool.rkcheck]`` table, and the Python API — and are
resolved by one rule, most specific first: flags, then ``[check]``, then
``[tool.rkcheck]``, then the defaults below (:func:`resolve_check_options`).  Every
source is validated by the same functions, so a value means the same everywhere and is
refused with the same one-line message.

This module is shared vocabulary: it imports nothing from rkcheck but the errors and
the number model's reading (:mod:`rkcheck.numbers.reading`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from rkcheck.errors import UserError
from rkcheck.numbers.formatting import count_text
from rkcheck.numbers.reading import DEFAULT_DPS, Arithmetic, DecimalsMode, Reading

DEFAULT_ORDER = 8
#: the energy order of a family's conditions as polynomials when neither the command
#: line nor the file's [check] gives one (they grow quickly with the order)
DEFAULT_FAMILY_ORDER = 6
DEFAULT_DECIMALS = DecimalsMode.AUTO
DEFAULT_MAX_STAGES = 64
#: What --max-stages (and the API's max_stages) accepts: an importer allocates the s×s
#: matrix of the highest stage index it reads, so the bound bounds its memory too.
MAX_STAGES_RANGE = (1, 1000)

#: The highest energy order any source may ask for.  What actually fits is decided by the
#: resource guard from exact condition counts (rkcheck.energy.budget): order 20 needs
#: about 2 GB, order 24 about 140 GB.
MAX_ORDER = 30
#: The highest degree bound m any source accepts.  Conditions up to order N never need
#: m > N (a free tree with N+1 vertices has degrees <= N); the AVF and line-integral
#: certificates build quadrature rules exact to degree about m, whose cost grows
#: quadratically (m = 5000 took 40 s).
MAX_DEGREE = 200
#: The most stages of a generated family (``rkcheck new``, ``[family]``): beyond it the
#: quadrature nodes take minutes (Gauss s = 20: about 50 s) or fail (s = 60).
MAX_FAMILY_STAGES = 20
#: Working precisions any source accepts (decimal digits).
DPS_RANGE = (10, 5000)
#: Energy orders any source accepts.
ORDER_RANGE = (1, MAX_ORDER)
#: Worker processes of ``scan`` any source accepts (never more than the files to check).
JOBS_RANGE = (1, 256)
#: Decimal digits ``rkcheck new --digits`` writes.
DIGITS_RANGE = (1, 5000)
#: ``kernel``: stages s of a named rule, degrees m of the double-bush map (m >= 3: it has
#: conditions), working precisions of its numerical ranks (also ``simulate --dps``).
KERNEL_STAGES_RANGE = (1, 12)
KERNEL_DEGREE_RANGE = (3, 40)
STUDY_DPS_RANGE = (15, 2000)
#: ``kernel``: the most elimination work on M, counted as rows × columns² (columns = s²),
#: times (dps/50)^1.5 when the rank is numerical; about a minute on one core at the limit
#: (-s 8 -m 16 is 430 080; -s 12 -m 12 took 72 s at 1 140 480, -s 6 -m 40 over 400 s).
MAX_KERNEL_WORK = 500_000
#: ``bench --repeat``: best of this many runs.
REPEAT_RANGE = (1, 50)
#: ``simulate --steps`` and ``simulate --energy-order --points``.
STEPS_RANGE = (1, 10_000_000)
POINTS_RANGE = (1, 100)

#: Decimals modes (definitions §5), as the CLI, the files and the JSON spell them.
DECIMALS_MODES = tuple(m.value for m in DecimalsMode)
#: Arithmetics of the conditions (``--arithmetic``).
ARITHMETICS = tuple(a.value for a in Arithmetic)
#: What makes a checked file count as failed (exit code 1).
FAIL_ON = ("auto", "conditions", "claims", "never")
#: Output formats of ``rkcheck scan``.
SCAN_FORMATS = ("text", "json", "csv", "junit", "github")
#: Words that mean "no degree bound: all Hamiltonians".
NO_DEGREE = ("none", "all", "any")
#: Keys of a tableau file's ``[check]`` table.
CHECK_KEYS = ("degree", "order", "dps", "decimals", "require")
#: What ``load`` reads: TOML and JSON documents, delimited Butcher arrays, nodepy text.
INPUT_FORMATS = ("toml", "json", "csv", "nodepy")
#: What ``scan --sort`` orders rows by.
SCAN_SORTS = ("path", "energy")


@dataclass(frozen=True)
class CheckOptions:
    """What one check runs: degree bound m (None = all Hamiltonians), energy order N,
    working precision, decimals mode, arithmetic, the proof gate, and whether to stop
    after the first failing order.  The number options travel below as one
    :class:`~rkcheck.numbers.reading.Reading` (:attr:`reading`)."""

    degree: int | None = None
    order: int = DEFAULT_ORDER
    dps: int = DEFAULT_DPS
    decimals: DecimalsMode = DEFAULT_DECIMALS
    fail_fast: bool = False
    require: str = "any"  # the gate of definitions §5.3: "any", "proof" or "digits:D"
    arithmetic: Arithmetic = Arithmetic.AUTO

    @property
    def required_digits(self) -> int | None:
        """D of ``digits:D`` (None for ``any`` and ``proof``)."""
        return int(self.require.split(":", 1)[1]) if self.require.startswith("digits:") else None

    @property
    def reading(self) -> Reading:
        """How the check reads and computes numbers."""
        return Reading(self.decimals, self.dps, self.arithmetic)

    def __post_init__(self) -> None:
        # the API is a source of options too: the same ranges and messages as the CLI
        parse_degree(self.degree, "degree")
        parse_int_in(self.order, ORDER_RANGE, "order")
        parse_int_in(self.dps, DPS_RANGE, "dps")
        object.__setattr__(self, "decimals", DecimalsMode(parse_choice(self.decimals, DECIMALS_MODES, "decimals")))
        object.__setattr__(self, "arithmetic", Arithmetic(parse_choice(self.arithmetic, ARITHMETICS, "arithmetic")))


# ------------------------------------------------------------------ single values


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def parse_degree(value: Any, place: str, source: str | None = None) -> int | None:
    """A degree bound: a positive integer, or ``none``/``all``/``any``/None for no bound."""
    if value is None or (isinstance(value, str) and value.strip().lower() in NO_DEGREE):
        return None
    if isinstance(value, str) and value.strip().isascii() and value.strip().isdigit():  # '²'.isdigit() too
        value = int(value)
    if _is_int(value) and 1 <= value <= MAX_DEGREE:
        return value
    if _is_int(value) and value > MAX_DEGREE:
        raise UserError(f"expected a degree from 1 to {MAX_DEGREE} or 'none', got {shown_value(value)}", place, source)
    raise UserError(f"expected a positive integer or 'none', got {shown_value(value)}", place, source)


def parse_positive(value: Any, place: str, source: str | None = None) -> int:
    """A positive integer (an order, a precision, a number of jobs)."""
    if _is_int(value) and value >= 1:
        return value
    raise UserError(f"expected a positive integer, got {shown_value(value)}", place, source)


def parse_int_in(value: Any, bounds: tuple[int, int], place: str, source: str | None = None) -> int:
    """An integer within ``bounds`` (inclusive): an order, a precision, a number of jobs."""
    lo, hi = bounds
    if _is_int(value) and lo <= value <= hi:
        return value
    raise UserError(f"expected an integer from {lo} to {hi}, got {shown_value(value)}", place, source)


def parse_integer(value: Any, place: str, source: str | None = None) -> int:
    """Any integer (a seed)."""
    if _is_int(value):
        return value
    raise UserError(f"expected an integer, got {shown_value(value)}", place, source)


def parse_dps_list(value: Any, place: str = "--dps", source: str | None = None) -> list[int]:
    """Working precisions: ``"15,50"`` (the CLI's text) or a sequence of integers, each
    within :data:`DPS_RANGE` (``bench --dps``, ``perturb --dps``)."""
    values = _integer_list(value, "a comma-separated list of integers", place, source)
    lo, hi = DPS_RANGE
    if not values or any(d < lo or d > hi for d in values):
        raise UserError(f"each dps must be between {lo} and {hi}", place, source)
    return values


def parse_step_counts(value: Any, place: str = "--steps", source: str | None = None) -> list[int]:
    """Numbers of steps: ``"20,40,80"`` (the CLI's text) or a sequence of positive integers
    (``workprec --steps``)."""
    counts = _integer_list(value, "comma-separated integers", place, source)
    if not counts:
        raise UserError("expected at least one step count", place, source)
    if min(counts) < 1:
        raise UserError("step counts must be positive", place, source)
    if max(counts) > STEPS_RANGE[1]:  # the same bound as simulate's: a run of that many steps
        raise UserError(f"expected step counts from 1 to {count_text(STEPS_RANGE[1])}, got {shown_value(max(counts))}",
                        place, source)
    return counts


def _integer_list(value: Any, expected: str, place: str, source: str | None) -> list[int]:
    """Integers from the CLI's comma-separated text or from a sequence (the API's form)."""
    if isinstance(value, str):
        try:
            return [int(x) for x in value.split(",") if x.strip()]
        except ValueError:
            raise UserError(f"expected {expected}, got {value!r}", place, source) from None
    if isinstance(value, (list, tuple)) and all(_is_int(x) for x in value):
        return list(value)
    raise UserError(f"expected {expected}, got {shown_value(value)}", place, source)


def shown_value(value: Any) -> str:
    """A value for a message: short, one line (repr of a huge integer is refused by Python
    past 4 300 digits, and would not be one line anyway)."""
    if _is_int(value) and value.bit_length() > 128:
        return f"an integer of about {count_text(int(value.bit_length() * 0.30103) + 1)} digits"
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def nearest(name: str, known: tuple[str, ...]) -> str:
    """`` (did you mean 'order'?)`` for a misspelt key, else ``""``."""
    import difflib  # only for a misspelt key: not at start-up

    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def parse_choice(value: Any, choices: tuple[str, ...], place: str, source: str | None = None) -> str:
    if value in choices:
        return value
    names = ", ".join(f"'{c}'" for c in choices)
    raise UserError(f"expected one of {names}, got {shown_value(value)}", place, source)


def parse_flag(value: Any, place: str, source: str | None = None) -> bool:
    """True or False, and nothing that merely reads as one (``'no'`` is a true string)."""
    if isinstance(value, bool):
        return value
    raise UserError(f"expected True or False, got {shown_value(value)}", place, source)


def parse_callback(value: Any, place: str) -> Any:
    """A function to call, or None."""
    if value is None or callable(value):
        return value
    raise UserError(f"expected a function or None, got {shown_value(value)}", place)


def parse_require(value: Any, place: str, source: str | None = None) -> str:
    """The proof gate (definitions §5.3): ``any`` (every ``holds to D digits`` with D ≥ 1
    passes: one with no certain digit decides nothing), ``proof`` (only exact ``holds``
    and exact certificates pass) or ``digits:D`` (a numerical holds passes only with at
    least D digits), returned normalised."""
    text = value.strip().lower() if isinstance(value, str) else None
    if text in ("any", "proof"):
        return text
    if text and text.startswith("digits:") and text[7:].strip().isdigit():
        d = int(text[7:].strip())
        if 1 <= d <= DPS_RANGE[1]:
            return f"digits:{d}"
    raise UserError(f"expected 'any', 'proof' or 'digits:D' with 1 <= D <= {DPS_RANGE[1]}, got {value!r}", place, source)


def parse_strings(value: Any, place: str, source: str | None = None) -> list[str]:
    """A string or a list of strings (paths, globs, references)."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(x, str) for x in value):
        return list(value)
    raise UserError("expected a string or a list of strings", place, source)


# ------------------------------------------------------------------ tables


def validate_check_table(table: Mapping[str, Any], prefix: str = "check", source: str | None = None,
                         extra_keys: tuple[str, ...] = ()) -> dict[str, Any]:
    """Validate the check options of a ``[check]`` (or ``[tool.rkcheck]``) table.

    Returns the recognised options with their parsed values; keys in ``extra_keys`` are
    left to the caller; any other key is an error naming ``prefix.key``."""
    out: dict[str, Any] = {}
    for key, value in table.items():
        place = f"{prefix}.{key}"
        name = key.replace("-", "_")
        if name == "degree":
            out[name] = parse_degree(value, place, source)
        elif name == "order":
            out[name] = parse_int_in(value, ORDER_RANGE, place, source)
        elif name == "dps":
            out[name] = parse_int_in(value, DPS_RANGE, place, source)
        elif name == "decimals":
            out[name] = DecimalsMode(parse_choice(value, DECIMALS_MODES, place, source))
        elif name == "require":
            out[name] = parse_require(value, place, source)
        elif name not in extra_keys:
            known = ", ".join(CHECK_KEYS + extra_keys)
            raise UserError(f"unknown key{nearest(name, CHECK_KEYS + extra_keys)} (known: {known})", place, source)
    return out


def resolve_check_options(flags: Mapping[str, Any], file: Mapping[str, Any],
                          project: Mapping[str, Any]) -> CheckOptions:
    """The options of one check: flags, else the file's ``[check]``, else
    ``[tool.rkcheck]``, else the defaults.  Each mapping holds parsed values."""

    def pick(key: str, default: Any) -> Any:
        for source in (flags, file, project):
            if key in source:
                return source[key]
        return default

    return CheckOptions(
        degree=pick("degree", None),
        order=pick("order", DEFAULT_ORDER),
        dps=pick("dps", DEFAULT_DPS),
        decimals=pick("decimals", DEFAULT_DECIMALS),
        require=pick("require", "any"),
        fail_fast=bool(flags.get("fail_fast", False)),
        arithmetic=flags.get("arithmetic", Arithmetic.AUTO),
    )
