"""The engine's one batch front door: many runs of any plant, results in order.

:func:`run_batch` runs a list of runs (any :class:`~mrsuspension.engine.plants.RunModel`:
quarter cars, half and full cars, a registered model, mixed) with one
:class:`~mrsuspension.engine.settings.RunSettings` for all or one per run, across
processes, with one progress count; :func:`measure_batch` gives each run's measures on an
open process pool, a diverged run in its place. Each plant family's own batch runner does
the work (:attr:`Plant.run_many <mrsuspension.engine.plants.Plant.run_many>`: the quarter
car's lanes, in-kernel measures where the model has them, process pools), so callers
never ask which vehicle a run drives.

Examples
--------
>>> from mrsuspension.excitation import Harmonic
>>> from mrsuspension.engine.simulate import Simulation
>>> from mrsuspension.engine.vehicle import VehicleSimulation
>>> from mrsuspension.excitation import WheelRoads
>>> from mrsuspension.vehicle import HalfCar
>>> car = HalfCar()
>>> runs = [Simulation(Harmonic(2.0, 0.01)),
...         VehicleSimulation(car, WheelRoads.from_excitation(Harmonic(2.0, 0.01), car, 36.0))]
>>> [type(r).__name__ for r in run_batch(runs, settings=RunSettings(duration=0.2), workers=1)]
['SimulationResult', 'VehicleResult']
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from mrsuspension.engine.plants import RunModel, plant_of
from mrsuspension.engine.settings import RunSettings, run_settings
from mrsuspension.errors import ValidationError

__all__ = ["measure_batch", "run_batch"]

Progress = Callable[[int, int], None]


def _settings_per_run(
    runs: Sequence[RunModel], settings: RunSettings | Sequence[RunSettings]
) -> list[RunSettings]:
    if isinstance(settings, RunSettings):
        return [settings] * len(runs)
    out = list(settings)
    if len(out) != len(runs):
        raise ValidationError(
            f"one RunSettings for all runs or one per run: {len(runs)} runs, {len(out)} settings"
        )
    return out


def run_batch(
    runs: Sequence[RunModel],
    *,
    settings: RunSettings | Sequence[RunSettings] | None = None,
    duration: float | None = None,
    dt: float | None = None,
    output_rate: float | None = None,
    workers: int | None = None,
    progress: Progress | None = None,
    reduce: Callable[[Any], Any] | None = None,
) -> list[Any]:
    """Run every run (any plant) and return the results in order.

    Parameters
    ----------
    runs : sequence of RunModel
        Quarter cars, half and full cars or registered models, in any mix.
    settings : RunSettings or sequence of RunSettings, optional
        One for every run, or one per run (runs with equal settings and plant go to their
        family's batch runner together); or the ``duration``, ``dt`` and ``output_rate``
        keywords (not both).
    workers : int or None
        Processes (None: one per core; 1: this process).
    progress : callable, optional
        ``progress(done, total)`` over all runs, as they finish.
    reduce : callable, optional
        A module-level function applied to each result in its worker; given
        :func:`~mrsuspension.engine.simulate.measures_of` or a
        :class:`~mrsuspension.engine.simulate.MeasuresOf`, runs reduce to their measures
        inside the kernels where the model can.

    Raises
    ------
    SimulationDiverged
        When a run leaves the physical range.
    """
    items = list(runs)
    if not items:
        return []
    if settings is None or isinstance(settings, RunSettings):
        one = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate)
        per_run = [one] * len(items)
    else:
        if duration is not None or dt is not None or output_rate is not None:
            raise ValidationError(
                "give settings per run or the duration, dt and output_rate keywords, not both"
            )
        per_run = _settings_per_run(items, settings)
    groups: dict[tuple[Any, RunSettings], list[int]] = {}
    for k, (run, plan) in enumerate(zip(items, per_run, strict=True)):
        groups.setdefault((plant_of(run).run_many, plan), []).append(k)
    out: list[Any] = [None] * len(items)
    done = 0
    for (runner, plan), idx in groups.items():

        def tick(n: int, _total: int, offset: int = done) -> None:
            if progress is not None:
                progress(offset + n, len(items))

        values = runner(
            [items[k] for k in idx], settings=plan, workers=workers, progress=tick, reduce=reduce
        )
        for k, value in zip(idx, values, strict=True):
            out[k] = value
        done += len(idx)
    return out


def measure_batch(
    runs: Sequence[RunModel],
    settings: RunSettings | Sequence[RunSettings],
    *,
    pool: Any = None,
    road_peak: str = "after-onset",
) -> list[Any]:
    """Each run's measures (its own settings), in order; a diverged run gives its
    :class:`~mrsuspension.engine.result.SimulationDiverged` in its place.

    ``pool``: an open process pool (:func:`mrsuspension._pool.process_pool`) to run on;
    None: this process. Each plant family measures its runs its own way
    (:attr:`Plant.measure_many <mrsuspension.engine.plants.Plant.measure_many>`; the quarter
    car in lanes, reduced in the kernels).

    Examples
    --------
    >>> from mrsuspension.excitation import RoundedPulse
    >>> from mrsuspension.engine.simulate import Simulation
    >>> runs = [Simulation(RoundedPulse(0.02, mu)) for mu in (1.0, 2.0)]
    >>> [round(m["SDR_s"], 3) for m in measure_batch(runs, RunSettings(dt=5e-4))]
    [1.443, 1.123]
    """
    items = list(runs)
    per_run = _settings_per_run(items, settings)
    groups: dict[Any, list[int]] = {}
    for k, run in enumerate(items):
        groups.setdefault(plant_of(run).measure_many, []).append(k)
    out: list[Any] = [None] * len(items)
    for measure, idx in groups.items():
        values = measure(
            [items[k] for k in idx], [per_run[k] for k in idx], pool=pool, road_peak=road_peak
        )
        for k, value in zip(idx, values, strict=True):
            out[k] = value
    return out
