"""The compiled half and full car against their closed-form frequency responses.

Linear dampers (``F_d = c v_d``) and a small road (no tire lift-off) make the vehicle
linear; its steady state at 30 frequencies from 0.5 to 20 Hz must match
:meth:`~mrsuspension.vehicle.body.VehicleBody.frequency_response` within 0.5 % in
amplitude and phase (the complex error) for the body's heave, pitch and roll, the body at
every corner and every wheel. The road differs at every wheel (a delay front to rear and a
smaller, phase-shifted right track) so that every output is excited.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pytest

from mrsuspension.dampers import LinearViscous
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.vehicle import FullCar, HalfCar

FREQS = np.geomspace(0.5, 20.0, 30)
AMPLITUDE = 1e-3  # m: the tires stay in contact
DAMPING = {"front": 1400.0, "rear": 1600.0}  # N s/m, the published set's linear dampers
DT = 5e-4  # s: (w dt)^4 / 120 < 1e-6 at 20 Hz, far below 0.5 %
SETTLE = math.log(1e7)  # decay the transient by 1e7 (in units of the slowest time constant)
TOLERANCE = 5e-3


@dataclass(frozen=True)
class HarmonicWheels:
    """``z_r,i = A Im(P_i exp(j w t))``: a harmonic road with a phasor per wheel."""

    corners: tuple[str, ...]
    frequency: float
    phasors: npt.NDArray[np.complex128]
    duration: float | None = None

    def _rotating(self, t: npt.ArrayLike) -> np.ndarray:
        w = 2.0 * math.pi * self.frequency
        return self.phasors[:, None] * np.exp(1j * w * np.atleast_1d(np.asarray(t, float)))[None, :]

    def displacement(self, t: npt.ArrayLike) -> np.ndarray:
        return AMPLITUDE * self._rotating(t).imag

    def velocity(self, t: npt.ArrayLike) -> np.ndarray:
        w = 2.0 * math.pi * self.frequency
        return AMPLITUDE * (1j * w * self._rotating(t)).imag


def phasors(car: HalfCar | FullCar, f: float) -> np.ndarray:
    """Rear wheels 0.1 s late; the right track 0.7 times the left, 40 degrees behind."""
    delay = np.exp(-2j * math.pi * f * 0.1)
    if isinstance(car, HalfCar):
        return np.array([1.0, delay])
    right = 0.7 * np.exp(-1j * math.radians(40.0))
    return np.array([1.0, right, delay, right * delay])


def slowest_time_constant(car: HalfCar | FullCar, damping: dict[str, float]) -> float:
    lin = car.linear_matrices(damping)
    n = lin.M.shape[0]
    minv = np.linalg.inv(lin.M)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ lin.K, -minv @ lin.C]])
    return 1.0 / float(np.min(-np.linalg.eigvals(a).real))


def fitted_phasor(t: np.ndarray, x: np.ndarray, f: float) -> complex:
    """``X`` with ``x = Im(X exp(j w t))`` by least squares on sin and cos."""
    w = 2.0 * math.pi * f
    basis = np.column_stack([np.sin(w * t), np.cos(w * t), np.ones_like(t)])
    (s, c, _), *_ = np.linalg.lstsq(basis, x, rcond=None)
    return complex(s, c)


def frf_errors(car: HalfCar | FullCar) -> dict[str, float]:
    """Largest relative complex error over FREQS of every output (simulated vs exact)."""
    damping = {c: DAMPING[c.split("_")[0]] for c in car.corners}
    dampers = {c: LinearViscous(damping=v) for c, v in damping.items()}
    settle = SETTLE * slowest_time_constant(car, damping)
    worst: dict[str, float] = {}
    for f in FREQS:
        p = phasors(car, f)
        exact = car.frequency_response([f], damping, p)
        periods = max(4, math.ceil(2.0 * f))  # a window of whole periods, >= 2 s
        duration = settle + periods / f
        sim = VehicleSimulation(car, HarmonicWheels(car.corners, f, p), dampers=dampers)
        res = sim.run(duration, dt=DT, output_rate=1.0 / DT)
        assert min(res[f"F_T.{c}"].min() for c in car.corners) > 0.0  # linear: no lift-off
        keep = res.time >= res.time[-1] - periods / f - 1e-9
        outputs = [*car.body_dofs, *(f"z_s.{c}" for c in car.corners),
                   *(f"z_u.{c}" for c in car.corners)]  # fmt: skip
        for name in outputs:
            x = fitted_phasor(res.time[keep], res[name][keep] / AMPLITUDE, f)
            ref = complex(exact[name][0])
            worst[name] = max(worst.get(name, 0.0), abs(x - ref) / abs(ref))
    return worst


@pytest.mark.parametrize("cls", [HalfCar, FullCar])
def test_simulated_response_matches_closed_form(cls: type[HalfCar | FullCar]) -> None:
    errors = frf_errors(cls())
    print(f"\n{cls.__name__} max relative error over 30 frequencies (0.5-20 Hz):")
    for name, err in errors.items():
        print(f"  {name:<16} {err:.2e}")
    bad = {k: v for k, v in errors.items() if v > TOLERANCE}
    assert not bad, bad


def test_any_wheel_input_gets_the_road_measures_per_corner() -> None:
    car = HalfCar()
    wheels = HarmonicWheels(car.corners, 3.0, phasors(car, 3.0))
    res = VehicleSimulation(car, wheels).run(1.0)
    m = res.measures()
    assert m["DLC.front"] > 0.0
    assert "rms_body_acceleration.rear" in m
