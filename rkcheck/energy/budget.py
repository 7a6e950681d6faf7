"""What a check will cost, before it starts, and refusing what does not fit.

The counts come from :mod:`rkcheck.trees.counting` (exact, instant); the costs per tree
were measured on the 2-core development machine (docs/performance.md: the benchmark
prints the same figures) and are deliberately on the high side:

* listing: about 0.6 µs per rooted tree (terms with up to N+1 vertices and the factor
  trees with up to N vertices);
* exact evaluation: about 0.06 µs per tree and channel (prime, or prime × root for a
  number field); the channels needed grow with the order and the size of the entries;
* certified balls: about 3.5 µs per tree at 50 digits, growing with the precision; a
  decimal box 0.5 µs more per tree and interval entry (its derivatives);
* from order :data:`~rkcheck.trees.centroid.CENTROID_FROM_ORDER` an exact check
  enumerates its conditions by centroid, with no listing: about 0.12 µs per condition,
  channel and stage (RK4 to order 22: 0.10, a dense 6-stage tableau 0.09), and in
  memory the residues, verdict and record of every condition and the stage vectors of
  the trees that wait (RK4 to order 22: 1.63 GB measured against 1.9 GB modelled);
* many stages (a continuous method's surrogate has hundreds): the products with A, s²
  per factor tree and s per term in every channel (2.5 ns each exact, 150 ns in balls at
  50 digits); making each entry a ball (up to 0.8 ms); the images of the entries in
  every channel (100 ns each; in memory 32 bytes per entry and channel of one pass,
  whose channels hold at most 64 MB of them, and 8 — 24 where the products go through
  float halves — per entry and channel the classical order keeps open); the stage
  vectors beyond 4 stages (16 bytes per factor tree and stage exact, 170 in balls); and
  the entries as written (:func:`entries_size`), which a decimal box first encloses,
  centres and differentiates in its decimals (0.5 ms an entry and 2 µs a character;
  seven times their memory again);
* memory: about 80 MB, plus 24 bytes per tree, plus up to 100 MB of working arrays that
  grow with the listing until 10 million trees (exact); balls count the terms' 24 bytes
  and 150 + 30·s bytes per factor tree at 50 digits (their stored weights: a and w of
  most factor trees, Φ and ψ of the smaller ones), growing as the 0.7th power of the
  precision, and their working arrays from a million trees; a decimal box adds its
  derivatives, a float ball per interval entry beside each stored weight, up to the
  1 GiB that one pass of them may take.

Measured by ``benchmarks/bench_budget.py`` (docs/performance.md), peak against model:
exact 96–111 MB at order 16, 363–369 MB at 18, 1.4 GB at 20 (132 MB, 432 MB, 2.0 GB);
balls, in methods whose conditions hold (no float screen decides them), 167–248 MB,
714–872 MB, and 4.9 GB at order 20 for s = 3 (292–315 MB, 0.94–1.1 GB, 6.4 GB);
HBVM(6, 2) in 60-digit decimals, 42 directions, 519 MB at order 16 (924 MB); kernels
``M = I_k`` through their surrogates of 60–270 stages, 92–776 MB (122–953 MB), exact and
in balls.

The machine's available memory is not read here (this is the core: no I/O); the caller
passes it in a :class:`Budget`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable, Iterable

from rkcheck.errors import ResourceError as ResourceError  # the refusal, named here too
from rkcheck.evaluation.centroid import CENTROID_PASS_VALUES
from rkcheck.evaluation.channels import (
    channels_per_image_pass,
    held_image_bytes,
    image_bytes,
)
from rkcheck.evaluation.slopes import MAX_GRADIENT_BYTES
from rkcheck.numbers.formatting import count_text as count
from rkcheck.numbers.formatting import human_bytes
from rkcheck.trees.centroid import CENTROID_FROM_ORDER
from rkcheck.trees.counting import listing_size

LISTING_SECONDS_PER_TREE = 0.6e-6
EXACT_SECONDS_PER_TREE_CHANNEL = 0.06e-6
BALL_SECONDS_PER_TREE = 3.5e-6
BOX_SECONDS_PER_TREE_DIRECTION = 0.5e-6
BASE_BYTES = 80 * 2**20
EXACT_BYTES_PER_TREE = 24
WORKING_BYTES = 100 * 2**20
BALL_BYTES_PER_FACTOR = 150
BALL_BYTES_PER_FACTOR_STAGE = 30
#: a centroid walk (from CENTROID_FROM_ORDER on, exact), per condition, channel and
#: stage; and the bytes per condition of its record of branches and its verdict
CENTROID_SECONDS_PER_CONDITION_VALUE = 0.12e-6
CENTROID_RECORD_BYTES = 16
#: beyond a few stages, the products with A (s² per factor tree, s per term and
#: channel) and the stage vectors of the stored trees set the cost (a kernel's surrogate
#: has hundreds of stages): about 2.5 ns a product exact (BLAS on float halves), 150 ns
#: in balls at 50 digits; in memory, the images of A in the channels of one pass
#: (:func:`~rkcheck.evaluation.channels.image_bytes`), those the exact classical order
#: keeps in every channel it opens (counted as many as the energy conditions need, a
#: bound), and, per factor tree and stage beyond SMALL_STAGES, 16 bytes exact and 170
#: in balls
EXACT_SECONDS_PER_STAGE_PRODUCT = 2.5e-9
#: and the images of the entries in every channel, about 100 ns each (large rationals)
EXACT_SECONDS_PER_ENTRY_CHANNEL = 100e-9
BALL_SECONDS_PER_STAGE_PRODUCT = 150e-9
#: and each entry made a ball, once per precision the check tries (up to 0.8 ms for the
#: rationals of hundreds of digits a kernel's surrogate has)
BALL_SECONDS_PER_ENTRY = 0.8e-3
EXACT_BYTES_PER_FACTOR_STAGE = 16
BALL_BYTES_PER_LARGE_FACTOR_STAGE = 170
#: the stage counts the per-tree costs above were measured at (RK4, Gauss-3, AVF Gauss-2..4)
SMALL_STAGES = 4
#: a tableau's entries held as written: their text and numbers take about this many
#: bytes per character of their text, and this many besides
ENTRY_BYTES_PER_CHARACTER = 4
ENTRY_BYTES = 1000
#: a decimal box's entries are each enclosed, centred and differentiated in its
#: decimals before the evaluation starts: about 0.5 ms an entry and 2 µs a character
#: of its text (a kernel's surrogate: thousands of entries of hundreds of characters,
#: each the kernel at two nodes, held as a sum over the monomials in its decimals with
#: long rational coefficients), and the entries' numbers, enclosures, centres and slopes
#: take about seven times the entries as written again (measured on kernels of degree
#: 20–40 at order 3: 6–39 s and 132–631 MB, of which 5–35 s the box)
BOX_SECONDS_PER_ENTRY = 0.5e-3
BOX_SECONDS_PER_ENTRY_CHARACTER = 2.0e-6
BOX_ENTRY_COPIES = 8
#: Checks estimated below this many seconds run silently.
QUIET_SECONDS = 5.0


@dataclass(frozen=True)
class Estimate:
    """The predicted size and cost of a check: conditions, terms, factors, seconds and bytes."""

    conditions: int
    terms: int
    factors: int
    seconds: float
    bytes: int

    def text(self) -> str:
        """``3,489,323 conditions (55,469,204 terms): about 1.6 min and 1.9 GB``."""
        secs = self.seconds
        when = f"{secs:.0f} s" if secs < 90 else (f"{secs / 60:.1f} min" if secs < 5400 else f"{secs / 3600:.1f} h")
        return f"{count(self.conditions)} conditions ({count(self.terms)} terms): about {when} and {human_bytes(self.bytes)}"


@dataclass
class Budget:
    """What the caller allows: the memory available (bytes; None = unknown), an explicit
    ``--max-conditions`` (None = derived from the memory), and where to say the estimate
    of a long check (a callable given the text, or None)."""

    available_bytes: int | None = None
    max_conditions: int | None = None
    announce: Callable[[str], None] | None = None
    #: what a refusal for memory tells the user to do (a command without
    #: --max-conditions offers less)
    remedy: str = "lower --order or --degree, or set --max-conditions to run anyway"


def estimate(order: int, degree: int | None, backend: str, channels: int = 16, stages: int = 4,
             dps: int = 50, directions: int = 0, listing: bool = False, entry_bytes: int = 0,
             box_entries: tuple[int, int] | None = None) -> Estimate:
    """The cost of listing and evaluating every condition to ``order`` for ``degree``
    (``directions``: the interval entries of a decimal box, whose derivatives the
    evaluation carries beside the weights; ``entry_bytes``: what the tableau's entries
    take, :func:`entries_size`; ``box_entries``: the count and characters of the entries
    of a decimal box, each enclosed, centred and differentiated first); a check from
    ``CENTROID_FROM_ORDER`` on enumerates them by centroid instead, unless ``listing``
    (what a command that lists the rooted trees itself builds)."""
    if box_entries is not None:
        est = estimate(order, degree, backend, channels, stages, dps, directions, listing,
                       entry_bytes * BOX_ENTRY_COPIES)
        count_, characters = box_entries
        seconds = est.seconds + count_ * BOX_SECONDS_PER_ENTRY + characters * BOX_SECONDS_PER_ENTRY_CHARACTER
        return replace(est, seconds=seconds)
    conditions, terms, factors = listing_size(order, degree)
    if backend == "exact" and order >= CENTROID_FROM_ORDER and not listing:
        by_centroid = _centroid_estimate(conditions, terms, factors, channels, stages)
        return replace(by_centroid, bytes=by_centroid.bytes + entry_bytes)
    trees = terms + factors
    seconds = trees * LISTING_SECONDS_PER_TREE
    products = factors * stages**2 + terms * stages  # per channel
    large = factors * max(0, stages - SMALL_STAGES)
    if backend == "exact":
        seconds += trees * channels * EXACT_SECONDS_PER_TREE_CHANNEL
        seconds += channels * (products * EXACT_SECONDS_PER_STAGE_PRODUCT + stages**2 * EXACT_SECONDS_PER_ENTRY_CHANNEL)
        size = (BASE_BYTES + EXACT_BYTES_PER_TREE * trees + WORKING_BYTES * min(1.0, trees / 1e7)
                + image_bytes(stages) * min(channels, channels_per_image_pass(stages))
                + held_image_bytes(stages) * channels  # the classical order keeps its channels open
                + EXACT_BYTES_PER_FACTOR_STAGE * large)
    else:
        precision = max(1.0, dps / 50)
        seconds += trees * (BALL_SECONDS_PER_TREE * precision**1.2 + BOX_SECONDS_PER_TREE_DIRECTION * directions)
        seconds += products * BALL_SECONDS_PER_STAGE_PRODUCT * precision**1.2 + stages**2 * BALL_SECONDS_PER_ENTRY
        per_factor = (BALL_BYTES_PER_FACTOR + BALL_BYTES_PER_FACTOR_STAGE * stages) * precision**0.7
        size = (BASE_BYTES + EXACT_BYTES_PER_TREE * terms + per_factor * factors
                + WORKING_BYTES * min(1.0, trees / 1e6) + BALL_BYTES_PER_LARGE_FACTOR_STAGE * precision**0.7 * large)
        # a float ball (16 bytes) per direction beside the stored a and w (about 0.7 of a
        # factor tree's) and Φ and ψ (0.25·s): at most MAX_GRADIENT_BYTES at once (more
        # directions take more passes)
        size += min(MAX_GRADIENT_BYTES, factors * directions * (11 + 4 * stages))
    return Estimate(conditions, terms, factors, seconds, int(size + entry_bytes))


def entries_size(texts: Iterable[str]) -> int:
    """About what entries written as ``texts`` take in memory (a kernel's surrogate of
    270 nodes: 73 000 entries of 1 100 characters, 380 MB)."""
    lengths = [len(t) for t in texts]
    return entries_bytes(len(lengths), sum(lengths))


def entries_bytes(count: int, characters: int) -> int:
    """About what ``count`` entries whose texts take ``characters`` in all take in memory."""
    return ENTRY_BYTES * count + ENTRY_BYTES_PER_CHARACTER * characters


def _centroid_estimate(conditions: int, terms: int, factors: int, channels: int, stages: int) -> Estimate:
    """An exact check enumerated by centroid (:mod:`rkcheck.trees.centroid`): a walk per
    pass of channels, its cost per condition and stage entry; in memory every
    condition's residues and record of branches, and the stage vectors of the trees
    that wait, in one pass's channels."""
    per_pass = min(channels, max(1, CENTROID_PASS_VALUES // stages))
    seconds = conditions * channels * stages * CENTROID_SECONDS_PER_CONDITION_VALUE
    size = BASE_BYTES + conditions * (4 * channels + CENTROID_RECORD_BYTES + 2 * per_pass * stages)
    return Estimate(conditions, terms, factors, seconds, int(size))


def check_budget(est: Estimate, budget: Budget | None, order: int) -> None:
    """Refuse (one line, exit 2) a check whose estimate exceeds what the budget allows;
    announce a long one."""
    if budget is None:
        return
    if budget.max_conditions is not None and est.conditions > budget.max_conditions:
        raise ResourceError(
            f"order {order} has {count(est.conditions)} conditions, above --max-conditions "
            f"{count(budget.max_conditions)}; lower --order or --degree, or raise --max-conditions")
    # the estimate is of the whole process, its start (BASE_BYTES) included, which the
    # memory available already leaves out (held, not to come): the check needs the rest
    more = max(0, est.bytes - BASE_BYTES)
    if budget.max_conditions is None and budget.available_bytes is not None and more > budget.available_bytes:
        raise ResourceError(
            f"order {order} needs about {human_bytes(more)} more for {count(est.conditions)} conditions but "
            f"{human_bytes(budget.available_bytes)} is available; {budget.remedy}")
    if budget.announce is not None and est.seconds > QUIET_SECONDS:
        budget.announce(f"estimated {est.text()}")