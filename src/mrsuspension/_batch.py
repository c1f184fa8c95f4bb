"""Batches of scenario runs reduced to their measures, on one reusable process pool.

Shared by :mod:`mrsuspension.optimize` (one batch per generation) and
:mod:`mrsuspension.tradeoff`: a pool per batch would cost about 0.3 s each time, so the
caller keeps one :func:`process_pool` open across its batches.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager
from typing import Any

from mrsuspension.engine.simulate import (
    Simulation,
    SimulationDiverged,
    measures_of,
    run_quietly,
)
from mrsuspension.scenario import Scenario

__all__ = ["Job", "job_of", "measure_job", "process_pool", "run_jobs"]

#: one run: the simulation, its duration, step and output rate
Job = tuple[Simulation, float | None, float, float]


def measure_job(job: Job) -> dict[str, Any] | None:
    """One run reduced to its measures; None when it diverges (module level: picklable)."""
    sim, duration, dt, rate = job
    try:
        return measures_of(run_quietly(sim, duration, dt, rate))
    except SimulationDiverged:
        return None


def job_of(scenario: Scenario) -> Job:
    """The run of a (single-run) scenario."""
    return (scenario.simulations()[0], scenario.duration, scenario.dt, scenario.output_rate)


@contextmanager
def process_pool(workers: int | None, jobs_per_batch: int) -> Iterator[Executor | None]:
    """A process pool for several batches (None, i.e. this process, for one worker)."""
    n = min(jobs_per_batch, workers or os.cpu_count() or 1)
    if n <= 1:
        yield None
        return
    with ProcessPoolExecutor(max_workers=n) as pool:
        yield pool


def run_jobs(jobs: Sequence[Job], pool: Executor | None) -> list[dict[str, Any] | None]:
    """Measures of each job, in order (None for a diverged run)."""
    if pool is None:
        return [measure_job(j) for j in jobs]
    return list(pool.map(measure_job, jobs))
