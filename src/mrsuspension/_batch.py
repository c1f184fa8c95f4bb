"""Batches of scenario runs reduced to their measures, on one reusable process pool.

Shared by :mod:`mrsuspension.optimize` (one batch per generation) and
:mod:`mrsuspension.tradeoff`: a pool per batch would cost about 0.3 s each time, so the
caller keeps one :func:`process_pool` open across its batches. The pool itself is
:mod:`mrsuspension._pool`'s, the same one :func:`~mrsuspension.engine.simulate.run_many`
uses.
"""

from __future__ import annotations

from collections.abc import Sequence
from concurrent.futures import Executor
from dataclasses import dataclass
from typing import Any

from mrsuspension._pool import pool_map, process_pool
from mrsuspension.engine.batch import measure_batch
from mrsuspension.engine.plants import RunModel
from mrsuspension.engine.settings import RunSettings
from mrsuspension.engine.simulate import SimulationDiverged, measures_of, run_quietly
from mrsuspension.engine.vehicle_result import WithSeatMeasures
from mrsuspension.scenario import Scenario

__all__ = ["Job", "job_of", "measure_job", "measure_job_with_seat", "process_pool", "run_jobs"]


@dataclass(frozen=True)
class Job:
    """One run of a batch: the simulation and its run settings (picklable).

    Examples
    --------
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import RoundedPulse
    >>> job = Job(Simulation(RoundedPulse(0.02, 1.0)), RunSettings(dt=5e-4, duration=1.0))
    >>> sorted(measure_job(job))[:2]
    ['RDR', 'SAR_s']
    """

    simulation: RunModel
    settings: RunSettings


def measure_job(job: Job) -> dict[str, Any] | None:
    """One run reduced to its measures; None when it diverges (module level: picklable)."""
    try:
        return measures_of(run_quietly(job.simulation, job.settings))
    except SimulationDiverged:
        return None


def job_of(scenario: Scenario) -> Job:
    """The run of a (single-run) scenario of any model, with its ``[simulation]`` settings."""
    return Job(scenario.runs()[0], scenario.settings)


def measure_job_with_seat(job: Job) -> dict[str, Any] | None:
    """One run's measures and its seat's ISO 2631-1 measures
    (:class:`~mrsuspension.engine.vehicle_result.WithSeatMeasures`); None when it diverges."""
    try:
        return WithSeatMeasures()(run_quietly(job.simulation, job.settings))
    except SimulationDiverged:
        return None


def run_jobs(
    jobs: Sequence[Job], pool: Executor | None, *, seat: bool = False
) -> list[dict[str, Any] | None]:
    """Measures of each job, in order (None for a diverged run); ``pool`` None: here.

    Any model (:func:`~mrsuspension.engine.batch.measure_batch`): quarter cars that differ
    only in their excitation step together in lanes, reduced to their measures inside the
    kernel; half and full cars give the body and per-corner measures. ``seat``: a half or
    full car's seat measures too (:func:`measure_job_with_seat`: each run keeps its time
    history, the ISO 2631-1 weighting filters need it).
    """
    if seat:
        return pool_map(measure_job_with_seat, list(jobs), pool=pool, workers=1)
    values = measure_batch([j.simulation for j in jobs], [j.settings for j in jobs], pool=pool)
    return [None if isinstance(v, SimulationDiverged) else v for v in values]
