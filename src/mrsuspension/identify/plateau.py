"""Which whole cycles of a harmonic rig test are its steady state: the plateau.

Servo-hydraulic damper rigs (MTS, Instron, Schenck) ramp a sinusoidal test in and out:
the stroke amplitude grows over a few cycles, holds on a plateau, then decays to zero
before the actuator stops, and a record may start or stop anywhere in that envelope.
The steady state to fit is the plateau, wherever it lies in the record.

Each whole cycle is judged by two figures: its stroke amplitude (a least-squares sine
over the cycle's samples, precise to a small fraction of a percent even with sensor
noise) and its force range (peak to peak, which sees 2 % force noise as about 1 % of
scatter and a slow force drift not at all). A run of cycles is *consistent* when all its
cycles agree with each other: the largest stroke amplitude exceeds the smallest by at
most ``stroke_tolerance``, and the largest force range the smallest by at most
``range_tolerance``. The stroke criterion is tight (1 %: a rig holds the amplitude of a
plateau to a fraction of a percent, while the cycles of a ramp differ by the ramp's
step), the force criterion loose (5 %: noise, and a first-cycle transient such as a
Bouc-Wen model's causal start, which leaves the stroke alone but not the force).
Cycles that hardly move (stroke under :data:`REST_FRACTION` of the largest) are the
actuator at rest, never a plateau.

The plateau is the longest consistent run. Ties: the larger stroke amplitude (two
plateaus of the same length at different levels), then the smaller stroke spread (the
same plateau cut at different places: the cut whose cycles lie wholly inside it), then
the later run.

Examples
--------
>>> run = find_plateau([3.0, 6.0, 9.0, 10.0, 10.0, 10.0, 7.0, 4.0], [1, 2, 3, 3.3, 3.3, 3.3, 2, 1])
>>> run.start, run.stop, run.length
(3, 6, 3)
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mrsuspension.identify.readers import TestDataError

__all__ = [
    "REST_FRACTION",
    "PlateauRun",
    "choose_plateau",
    "consistent_runs",
    "find_plateau",
    "no_plateau_message",
]

#: Stroke amplitude, as a fraction of the largest cycle's, below which a cycle is the
#: actuator at rest (before or after a test) and never part of a plateau.
REST_FRACTION = 0.02

#: Edge deviations (:attr:`PlateauRun.edge`) within this many times the best run's
#: scatter, or within :data:`EDGE_FLOOR` times the stroke tolerance, are equally good
#: (their difference is noise, or too small to matter).
EDGE_RESOLUTION = 3.0
EDGE_FLOOR = 0.05


@dataclass(frozen=True)
class PlateauRun:
    """A run of consistent whole cycles ``start`` to ``stop - 1`` (0-based).

    ``amplitude`` is the median stroke amplitude of the run, ``stroke_spread`` and
    ``range_spread`` are ``max / min - 1`` of its stroke amplitudes and force ranges;
    ``edge`` is how far the run's first and last stroke amplitudes are off its median
    (summed, relative: a cut that overlaps a ramp shows there), ``scatter`` the robust
    relative scatter of its stroke amplitudes (1.4826 times their median absolute
    deviation: the noise). ``alignment`` numbers the way the record was cut into cycles
    (0: aligned to its end), ``position`` is where the run starts in periods of the
    record (default: ``start``), and ``whole`` says that the run holds every cycle of
    its cut.
    """

    start: int
    stop: int
    amplitude: float
    stroke_spread: float
    range_spread: float
    edge: float = 0.0
    scatter: float = 0.0
    alignment: int = 0
    position: float = math.nan
    whole: bool = False

    def __post_init__(self) -> None:
        if math.isnan(self.position):
            object.__setattr__(self, "position", float(self.start))

    @property
    def length(self) -> int:
        """Number of cycles in the run."""
        return self.stop - self.start


def _spread(values: npt.NDArray[np.float64]) -> float:
    low = float(np.min(values))
    return float(np.max(values)) / low - 1.0 if low > 0 else float("inf")


def consistent_runs(
    amplitudes: Sequence[float] | npt.ArrayLike,
    ranges: Sequence[float] | npt.ArrayLike,
    *,
    stroke_tolerance: float = 0.01,
    range_tolerance: float = 0.05,
    alignment: int = 0,
    positions: npt.ArrayLike | None = None,
    halves: npt.ArrayLike | None = None,
) -> list[PlateauRun]:
    """Every longest run of consistent cycles (module docstring), in record order.

    ``amplitudes`` and ``ranges`` are the stroke amplitude and force range of each whole
    cycle, ``positions`` where each starts, in periods of the record (default: its
    index). ``halves`` (shape ``(n, 2)``), the stroke amplitude of each half of each
    cycle, makes the stroke criterion apply to them too: a cycle whose stroke changes
    within it (the top of two symmetric ramps around a one-cycle plateau, cut across
    its middle) is not steady even when its neighbour is its mirror image. Runs of
    cycles at rest are not counted; an empty list means that every cycle is at rest.

    Examples
    --------
    >>> [(r.start, r.stop) for r in consistent_runs([5, 5.01, 8, 10, 10.02, 7], [1] * 6)]
    [(0, 2), (3, 5)]
    """
    a = np.asarray(amplitudes, dtype=float)
    r = np.asarray(ranges, dtype=float)
    if a.shape != r.shape or a.ndim != 1:
        raise ValueError("amplitudes and ranges must be 1-D sequences of the same length")
    if a.size == 0:
        return []
    top = float(np.max(a))
    moving = (a > REST_FRACTION * top) & (r > 0) & np.isfinite(a) & np.isfinite(r)
    a_hi, a_lo = a, a  # each cycle's largest and smallest stroke figure
    if halves is not None:
        h = np.asarray(halves, dtype=float)
        if h.shape != (a.size, 2):
            raise ValueError(f"halves must have shape ({a.size}, 2); got {h.shape}")
        a_hi, a_lo = np.maximum(a, h.max(axis=1)), np.minimum(a, h.min(axis=1))
    hi_a: deque[int] = deque()  # indices of decreasing amplitudes (front: max)
    lo_a: deque[int] = deque()  # indices of increasing amplitudes (front: min)
    hi_r: deque[int] = deque()
    lo_r: deque[int] = deque()
    queues = ((hi_a, a_hi, True), (lo_a, a_lo, False), (hi_r, r, True), (lo_r, r, False))
    left, best = 0, 0
    found: list[tuple[int, int]] = []
    for k in range(a.size):
        if not moving[k] or a_hi[k] > a_lo[k] * (1 + stroke_tolerance):
            # at rest, or its stroke changes within it: a run of its own at most
            left = k + 1
            for q, _, _ in queues:
                q.clear()
            if moving[k] and best <= 1:
                best, found = 1, [*found, (k, k + 1)] if best == 1 else [(k, k + 1)]
            continue
        for q, vals, is_max in queues:
            while q and (vals[q[-1]] <= vals[k] if is_max else vals[q[-1]] >= vals[k]):
                q.pop()
            q.append(k)
        while a_hi[hi_a[0]] > a_lo[lo_a[0]] * (1 + stroke_tolerance) or r[hi_r[0]] > r[lo_r[0]] * (
            1 + range_tolerance
        ):
            left += 1
            for q, _, _ in queues:
                while q and q[0] < left:
                    q.popleft()
        length = k - left + 1
        if length > best:
            best, found = length, [(left, k + 1)]
        elif length == best:
            found.append((left, k + 1))
    pos = np.arange(a.size, dtype=float) if positions is None else np.asarray(positions, float)
    return [_run(a, r, i, j, alignment, float(pos[i])) for i, j in found]


def _run(
    a: npt.NDArray[np.float64],
    r: npt.NDArray[np.float64],
    i: int,
    j: int,
    alignment: int,
    position: float,
) -> PlateauRun:
    med = float(np.median(a[i:j]))
    rel = a[i:j] / med - 1.0
    return PlateauRun(
        start=i,
        stop=j,
        amplitude=med,
        stroke_spread=_spread(a[i:j]),
        range_spread=_spread(r[i:j]),
        edge=float(abs(rel[0]) + abs(rel[-1])),
        scatter=float(1.4826 * np.median(np.abs(rel))),
        alignment=alignment,
        position=position,
        whole=i == 0 and j == a.size,
    )


def choose_plateau(runs: Sequence[PlateauRun], *, stroke_tolerance: float = 0.01) -> PlateauRun:
    """The plateau among candidate runs: the longest, then the largest stroke amplitude,
    then the one whose edges deviate least.

    Two amplitudes within ``stroke_tolerance`` are the same level. Runs of the same
    plateau cut in different places differ at their edges: a first or last cycle that
    overlaps a ramp has a smaller stroke. Edge deviations within
    :data:`EDGE_RESOLUTION` times the scatter of the best run (or
    :data:`EDGE_FLOOR` times ``stroke_tolerance``) are noise: among such
    runs of the same plateau (starting within a period of each other) the one holding
    every cycle of the end-aligned cut wins (a record steady throughout is cut as it
    always was), else the middle one (a ramp's undetectable first or last fraction of
    a cycle is left out on both sides alike).

    Examples
    --------
    >>> a = PlateauRun(0, 4, 10.0, 0.004, 0.01)
    >>> b = PlateauRun(6, 10, 20.0, 0.004, 0.01)
    >>> choose_plateau([a, b]).amplitude  # same length: the larger stroke wins
    20.0
    """
    if not runs:
        raise ValueError("no candidate runs")
    longest = max(r.length for r in runs)
    cands = [r for r in runs if r.length == longest]
    top = max(r.amplitude for r in cands)
    cands = [r for r in cands if r.amplitude >= top * (1 - stroke_tolerance)]
    best = min(cands, key=lambda r: (r.edge, r.alignment, -r.start))
    resolution = max(EDGE_RESOLUTION * best.scatter, EDGE_FLOOR * stroke_tolerance)
    ties = sorted(
        (
            r
            for r in cands
            if r.edge <= best.edge + resolution and abs(r.position - best.position) < 1.0
        ),
        key=lambda r: r.position,
    )
    for r in ties:
        if r.whole and r.alignment == 0:
            return r
    return ties[(len(ties) - 1) // 2]


def find_plateau(
    amplitudes: Sequence[float] | npt.ArrayLike,
    ranges: Sequence[float] | npt.ArrayLike,
    *,
    stroke_tolerance: float = 0.01,
    range_tolerance: float = 0.05,
) -> PlateauRun:
    """The plateau of one sequence of whole cycles (:func:`consistent_runs`,
    :func:`choose_plateau`).

    Raises
    ------
    TestDataError
        When every cycle is at rest, or when there are two cycles or more and no two
        of them are consistent (:func:`no_plateau_message`).

    Examples
    --------
    >>> find_plateau([2, 4, 6, 8], [1, 2, 3, 4])
    Traceback (most recent call last):
    ...
    mrsuspension.identify.readers.TestDataError: no two consistent cycles: ...
    """
    runs = consistent_runs(
        amplitudes, ranges, stroke_tolerance=stroke_tolerance, range_tolerance=range_tolerance
    )
    a = np.asarray(amplitudes, dtype=float)
    if not runs:
        raise TestDataError(f"no motion: all {a.size} cycles are at rest")
    best = choose_plateau(runs, stroke_tolerance=stroke_tolerance)
    if best.length < 2 <= a.size:
        raise TestDataError(
            no_plateau_message(
                a, ranges, stroke_tolerance=stroke_tolerance, range_tolerance=range_tolerance
            )
        )
    return best


def no_plateau_message(
    amplitudes: Sequence[float] | npt.ArrayLike,
    ranges: Sequence[float] | npt.ArrayLike,
    *,
    stroke_tolerance: float,
    range_tolerance: float,
    frequency: float | None = None,
) -> str:
    """One line saying why a test has no two consistent cycles, and what was found.

    ``amplitudes`` in m and ``ranges`` in N (the message gives mm and N).

    Examples
    --------
    >>> print(no_plateau_message([0.002, 0.004, 0.006], [100, 200, 300],
    ...                          stroke_tolerance=0.01, range_tolerance=0.05))  # doctest: +NORMALIZE_WHITESPACE
    no two consistent cycles: of 3 whole cycles (strokes 2-6 mm, force ranges 100-300 N),
    no two neighbours agree within 1 % in stroke amplitude and 5 % in force range; the
    closest, cycles 2 and 3, differ by +50 % in stroke and +50 % in force range. A ramped
    test needs a plateau of at least two whole cycles at constant amplitude
    """
    a = np.asarray(amplitudes, dtype=float)
    r = np.asarray(ranges, dtype=float)
    at = f" at {frequency:.4g} Hz" if frequency else ""
    text = (
        f"no two consistent cycles: of {a.size} whole cycles{at} (strokes "
        f"{1e3 * a.min():.3g}-{1e3 * a.max():.3g} mm, force ranges {r.min():.4g}-{r.max():.4g} "
        f"N), no two neighbours agree within {100 * stroke_tolerance:g} % in stroke amplitude "
        f"and {100 * range_tolerance:g} % in force range"
    )
    if a.size >= 2:
        with np.errstate(divide="ignore", invalid="ignore"):
            da = a[1:] / a[:-1] - 1
            dr = r[1:] / r[:-1] - 1
            score = np.maximum(np.abs(da) / stroke_tolerance, np.abs(dr) / range_tolerance)
        score = np.where(np.isfinite(score), score, np.inf)
        k = int(np.argmin(score))
        text += (
            f"; the closest, cycles {k + 1} and {k + 2}, differ by {100 * da[k]:+.0f} % in "
            f"stroke and {100 * dr[k]:+.0f} % in force range"
        )
    return (
        text + ". A ramped test needs a plateau of at least two whole cycles at constant amplitude"
    )
