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

#: Stroke spreads closer than this fraction of the stroke tolerance are equally good
#: (their difference is noise): then the earlier alignment / later run wins.
SPREAD_RESOLUTION = 0.1


@dataclass(frozen=True)
class PlateauRun:
    """A run of consistent whole cycles ``start`` to ``stop - 1`` (0-based).

    ``amplitude`` is the median stroke amplitude of the run, ``stroke_spread`` and
    ``range_spread`` are ``max / min - 1`` of its stroke amplitudes and force ranges;
    ``alignment`` numbers the way the record was cut into cycles (0: aligned to its end).
    """

    start: int
    stop: int
    amplitude: float
    stroke_spread: float
    range_spread: float
    alignment: int = 0

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
) -> list[PlateauRun]:
    """Every longest run of consistent cycles (module docstring), in record order.

    ``amplitudes`` and ``ranges`` are the stroke amplitude and force range of each whole
    cycle. Runs of cycles at rest are not counted; an empty list means that every cycle
    is at rest.

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
    hi_a: deque[int] = deque()  # indices of decreasing amplitudes (front: max)
    lo_a: deque[int] = deque()  # indices of increasing amplitudes (front: min)
    hi_r: deque[int] = deque()
    lo_r: deque[int] = deque()
    queues = ((hi_a, a, True), (lo_a, a, False), (hi_r, r, True), (lo_r, r, False))
    left, best = 0, 0
    found: list[tuple[int, int]] = []
    for k in range(a.size):
        if not moving[k]:
            left = k + 1
            for q, _, _ in queues:
                q.clear()
            continue
        for q, vals, is_max in queues:
            while q and (vals[q[-1]] <= vals[k] if is_max else vals[q[-1]] >= vals[k]):
                q.pop()
            q.append(k)
        while a[hi_a[0]] > a[lo_a[0]] * (1 + stroke_tolerance) or r[hi_r[0]] > r[lo_r[0]] * (
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
    return [
        PlateauRun(
            start=i,
            stop=j,
            amplitude=float(np.median(a[i:j])),
            stroke_spread=_spread(a[i:j]),
            range_spread=_spread(r[i:j]),
            alignment=alignment,
        )
        for i, j in found
    ]


def choose_plateau(runs: Sequence[PlateauRun], *, stroke_tolerance: float = 0.01) -> PlateauRun:
    """The plateau among candidate runs: longest, then largest stroke amplitude, then the
    smallest stroke spread, then the lowest ``alignment``, then the latest.

    Two amplitudes within ``stroke_tolerance`` are the same level, and two stroke spreads
    within :data:`SPREAD_RESOLUTION` of it the same spread (noise tells them apart, not
    the data).

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
    flattest = min(r.stroke_spread for r in cands)
    cands = [r for r in cands if r.stroke_spread <= flattest + SPREAD_RESOLUTION * stroke_tolerance]
    return min(cands, key=lambda r: (r.alignment, -r.start))


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
