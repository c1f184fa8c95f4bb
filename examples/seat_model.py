"""Add your own vehicle model: a quarter car with a seat and driver, in one file.

The engine runs any model that keeps its run contract (``mrsuspension.engine.contract
.RunModel``). This file defines one, a quarter car with a seat-and-driver mass on the
body (three masses, a linear suspension damper), and registers it with one call to
``register_plant``. From then on scenarios name it in ``[vehicle] model``, and
``Scenario.run``, ``mrsus simulate``, ``mrsus sweep`` and studies run it without
knowing what it is (``docs/develop.md``, "Adding a vehicle model").

The model is linear, so it is solved exactly on the output grid (``scipy.signal.lsim``)
rather than stepped by RK4; the seat's values (80 kg, 4 Hz, 25 % damping) are typical of
a passenger car seat with its driver.

Run it: ``python examples/seat_model.py``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import signal

from mrsuspension.engine.plants import Plant, RunParts, register_plant
from mrsuspension.engine.settings import MAX_DT, RunPlan, RunSettings, check_step, run_settings
from mrsuspension.errors import ValidationError
from mrsuspension.vehicle import QuarterCar

MODEL = "seat-quarter-car"
#: the measures of every run, with their units
UNITS = {
    "rms_body_acceleration": "m/s^2",
    "rms_seat_acceleration": "m/s^2",
    "seat_to_body": "-",
}


@dataclass(frozen=True)
class SeatQuarterCar(QuarterCar):
    """The quarter car with a seat-and-driver mass on its sprung mass."""

    seat_mass: float = 80.0  # kg, seat and driver
    seat_stiffness: float = 50_000.0  # N/m: 4.0 Hz with 80 kg
    seat_damping: float = 1000.0  # N s/m: 25 % of critical

    def __post_init__(self) -> None:
        super().__post_init__()
        for name in ("seat_mass", "seat_stiffness", "seat_damping"):
            if not getattr(self, name) > 0.0:
                raise ValidationError(f"{name} must be positive; got {getattr(self, name)!r}")


@dataclass(frozen=True)
class SeatResult:
    """Time histories of a run [s, m/s^2]; ``measures()`` as every model's result."""

    time: np.ndarray
    body_acceleration: np.ndarray
    seat_acceleration: np.ndarray
    scenario: dict[str, Any]
    velocity_clamp_fraction: float | None = None  # a linear damper has no clamp

    def measures(self, **_kwargs: Any) -> dict[str, float]:
        body = float(np.sqrt(np.mean(self.body_acceleration**2)))
        seat = float(np.sqrt(np.mean(self.seat_acceleration**2)))
        return {
            "rms_body_acceleration": body,
            "rms_seat_acceleration": seat,
            "seat_to_body": seat / body if body > 0.0 else float("nan"),
        }


@dataclass(frozen=True)
class SeatSimulation:
    """One run of the seat model: the run contract (``RunModel``)."""

    vehicle: SeatQuarterCar
    excitation: Any  # a one-track road input (z_r(t), its velocity)
    damping: float  # N s/m, the suspension damper

    model_name = MODEL

    def describe(self) -> dict[str, Any]:
        return {
            "model": MODEL,
            "vehicle": dataclasses.asdict(self.vehicle),
            "damper": {"model": "linear", "c": self.damping},
            "excitation": self.excitation.describe(),
        }

    def max_stable_dt(self) -> float:
        return MAX_DT  # solved exactly: any step the engine allows

    def check_dt(self, dt: float) -> float:
        return check_step(dt)

    def record_values(self, plan: RunPlan) -> float:
        return float(plan.rows * 3)

    def state_space(self) -> signal.StateSpace:
        """x = (z_s, z_u, z_q, z_s', z_u', z_q'); u = (z_r, z_r'); y = (z_s'', z_q'')."""
        v = self.vehicle
        ms, mu, mq = v.sprung_mass, v.unsprung_mass, v.seat_mass
        ks, kt, kq = v.suspension_stiffness, v.tire_stiffness, v.seat_stiffness
        c, ct, cq = self.damping, v.tire_damping, v.seat_damping
        k = np.array([[-ks - kq, ks, kq], [ks, -ks - kt, 0.0], [kq, 0.0, -kq]])
        d = np.array([[-c - cq, c, cq], [c, -c - ct, 0.0], [cq, 0.0, -cq]])
        m = np.array([ms, mu, mq])[:, None]
        road = np.zeros((3, 2))
        road[1] = [kt, ct]
        a = np.block([[np.zeros((3, 3)), np.eye(3)], [k / m, d / m]])
        b = np.vstack([np.zeros((3, 2)), road / m])
        return signal.StateSpace(a, b, a[[3, 5]], b[[3, 5]])

    def run(
        self,
        duration: float | None = None,
        *,
        dt: float | None = None,
        output_rate: float | None = None,
        settings: RunSettings | None = None,
    ) -> SeatResult:
        plan = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate).plan(self)
        t = plan.time()
        u = np.column_stack([self.excitation.displacement(t), self.excitation.velocity(t)])
        _, y, _ = signal.lsim(self.state_space(), u, t)
        return SeatResult(t, y[:, 0], y[:, 1], self.describe())

    def stepper(self, dt: float = 1e-4) -> Any:
        raise ValidationError(f"the {MODEL} model has no step-by-step driver (no HiL)")


def build(car: SeatQuarterCar, parts: RunParts) -> SeatSimulation:
    """A run from a scenario's choices: the suspension damper must be linear."""
    values = getattr(parts.damper, "values", {})
    if getattr(parts.damper, "name", None) != "linear":
        raise ValidationError(
            f"the {MODEL} model takes [damper] model = 'linear'; got {parts.damper.name!r}"
        )
    return SeatSimulation(car, parts.road, float(values["c"]))


def run_many(
    runs: Sequence[SeatSimulation],
    *,
    settings: RunSettings,
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    reduce: Callable[[SeatResult], Any] | None = None,
) -> list[Any]:
    """Each run in this process (it is fast), reduced when asked, in order."""
    out = []
    for n, run in enumerate(runs, start=1):
        result = run.run(settings=settings)
        out.append(result if reduce is None else reduce(result))
        if progress is not None:
            progress(n, len(runs))
    return out


def measure_many(
    runs: Sequence[SeatSimulation], settings: Sequence[RunSettings], **_kwargs: Any
) -> list[dict[str, float]]:
    return [run.run(settings=s).measures() for run, s in zip(runs, settings, strict=True)]


register_plant(
    Plant(
        name=MODEL,
        params=SeatQuarterCar,
        build=build,
        run_many=run_many,
        measure_many=measure_many,
        measure_names=lambda _per_run: tuple(UNITS),
        make_params=lambda values, _set: SeatQuarterCar(**values),
        units=UNITS,
    )
)


if __name__ == "__main__":
    from mrsuspension.scenario import Scenario

    scenario = Scenario.from_dict(
        {
            "vehicle": {"model": MODEL, "seat_mass": 90.0},
            "damper": {"model": "linear", "damping": 1500.0},
            "excitation": {"kind": "road", "profile": "rough", "speed": 50.0},
            "simulation": {"duration": 10.0},
        }
    )
    (result,) = scenario.run()
    for name, value in result.measures().items():
        print(f"{name:>22} = {value:.4g} [{UNITS[name]}]")
