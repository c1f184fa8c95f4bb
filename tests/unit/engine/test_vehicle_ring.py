"""The MR corners' 30-90 Hz ring after a bump (issue 29, part 5): the model's, not the step's.

After the bump of ``examples/vehicles/full_car_bump.toml`` the front-left MR corner rings
at about 34 Hz. It is a limit cycle of the damper model's hysteresis term: ``v_h =
sgn(a_d) k4 v_m`` with ``k4 < 0`` shifts the force by ``2 F_t tanh(alpha |k4| v_m / 2)``
against the sign of the relative acceleration ``a_d``, and that jump drives ``a_d``
further the same way (a latching relay). Between two flips the wheel (the body is nearly
still at these frequencies) obeys the linear ``m_u z'' + c z' + (k_s + k_t) z = +-c h``
with the pre-yield slope ``c = k_d C_i(i) F_t(v_m) alpha(v_m) / 2`` and ``h = |k4| v_m``;
the symmetric periodic solution whose acceleration returns to zero at the next flip gives
the half period (:func:`relay_frequency`), independent of ``h``. docs/damper-models.md,
"The hysteresis ring", has the numbers.

Checked here: the example's ring frequency within 10 % of that estimate; the same ring at
``dt / 4``; none with the mean model (``k4 = 0``) nor at the linear corner; and a steady
ring at a known ``v_m`` for 0, 0.2 and 0.5 A, each within 10 % of its estimate.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from mrsuspension.control import Passive
from mrsuspension.dampers import WangSymmetric
from mrsuspension.engine.simulate import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.scenario import Scenario
from mrsuspension.vehicle import FullCar

EXAMPLE = Path(__file__).parents[3] / "examples" / "vehicles" / "full_car_bump.toml"
WINDOW = (0.8, 1.6)  # s: after the bump has passed both axles
CORNER = "front_left"


def pre_yield_damping(damper: WangSymmetric, current: float, vm: float) -> float:
    """``k_d C_i(i) F_t(v_m) alpha(v_m) / 2`` [N s/m]: the slope of (2.15) at zero force."""
    p = damper.describe()["parameters"]
    ft = p["F0"] * (1.0 + math.exp(p["a1"] * vm))
    alpha = p["a0"] / (1.0 + p["k0"] * vm)
    ci = float(damper.current_gain(current))
    return damper.describe()["force_gain"] * ci * ft * alpha / 2.0


def relay_frequency(mass: float, stiffness: float, damping: float) -> float:
    """Frequency [Hz] of the symmetric relay cycle of ``m z'' + c z' + k z = -c h s``,
    ``s = sgn(z'')`` flipped whenever ``z''`` crosses zero.

    With ``c h = 1`` (the period does not depend on ``h``): a half period ``T`` starts
    just after a flip at ``x0 = (z0, v0)`` with ``k z0 + c v0 = -1`` (``z'' = 0`` before
    the flip) and ends at ``-x0``; with ``Phi = exp(A T)`` and the new equilibrium ``e =
    (1/k, 0)``, ``x0 = -(I + Phi)^-1 (I - Phi) e``. The first ``T`` that meets the flip
    condition is the half period.
    """
    a = np.array([[0.0, 1.0], [-stiffness / mass, -damping / mass]])
    e = np.array([1.0 / stiffness, 0.0])
    eye = np.eye(2)
    half_trace = -damping / (2.0 * mass)
    root = complex(half_trace**2 - stiffness / mass) ** 0.5  # imaginary when underdamped

    def mismatch(t: float) -> float:
        # exp(A t) of a 2 x 2 matrix: e^(tr t/2) (cosh(r t) I + sinh(r t)/r (A - tr/2 I))
        sinhc = t if abs(root) * t < 1e-8 else complex(np.sinh(root * t) / root).real
        phi = math.exp(half_trace * t) * (
            complex(np.cosh(root * t)).real * eye + sinhc * (a - half_trace * eye)
        )
        x0 = -np.linalg.solve(eye + phi, (eye - phi) @ e)
        return float(stiffness * x0[0] + damping * x0[1] + 1.0)

    grid = np.geomspace(1e-4, 0.1, 400)
    values = [mismatch(t) for t in grid]
    for k in range(grid.size - 1):
        if values[k] * values[k + 1] < 0.0:
            return 1.0 / (2.0 * brentq(mismatch, grid[k], grid[k + 1], xtol=1e-12))
    raise AssertionError("no relay cycle")  # pragma: no cover


def ring(time: np.ndarray, force: np.ndarray, window: tuple[float, float]) -> tuple[float, float]:
    """``(std [N], frequency of the largest peak above 15 Hz [Hz])`` of ``force`` in ``window``."""
    keep = (time >= window[0]) & (time <= window[1])
    x = force[keep] - force[keep].mean()
    n = 16 * x.size
    spectrum = np.abs(np.fft.rfft(x * np.hanning(x.size), n))
    freq = np.fft.rfftfreq(n, float(time[1] - time[0]))
    spectrum[freq < 15.0] = 0.0
    return float(x.std()), float(freq[np.argmax(spectrum)])


def corner_estimate(car: FullCar, damper: WangSymmetric, current: float, vm: float) -> float:
    i = car.corner_index(CORNER)
    stiffness = car.tire_stiffnesses[i] + car.suspension_stiffnesses[i]
    return relay_frequency(
        car.unsprung_masses[i], stiffness, pre_yield_damping(damper, current, vm)
    )


@pytest.fixture(scope="module")
def example() -> VehicleSimulation:
    sim = Scenario.load(EXAMPLE).vehicle_simulations()[0]
    assert isinstance(sim, VehicleSimulation)
    return sim


def _run(sim: VehicleSimulation, dt: float) -> dict[str, np.ndarray]:
    res = sim.run(WINDOW[1], dt=dt, output_rate=1e4)
    return {
        k: np.asarray(res[k])
        for k in ("time", *(f"{s}.{c}" for s in ("F_d", "v_m", "i_d") for c in sim.corners))
    }


@pytest.fixture(scope="module")
def example_run(example: VehicleSimulation) -> dict[str, np.ndarray]:
    return _run(example, 1e-4)


def test_the_example_rings_at_the_relay_frequency(
    example: VehicleSimulation, example_run: dict[str, np.ndarray]
) -> None:
    res = example_run
    t = res["time"]
    keep = (t >= WINDOW[0]) & (t <= WINDOW[1])
    std, freq = ring(t, res[f"F_d.{CORNER}"], WINDOW)
    assert std > 80.0  # about 125 N
    assert 30.0 < freq < 38.0  # about 33.8 Hz
    damper = example.dampers[CORNER]  # type: ignore[index]
    vm = float(res[f"v_m.{CORNER}"][keep].mean())
    current = float(res[f"i_d.{CORNER}"][keep].mean())
    estimate = corner_estimate(example.vehicle, damper, current, vm)  # type: ignore[arg-type]
    assert freq == pytest.approx(estimate, rel=0.10)
    # the linear corner (rear left) shows none of it
    linear_std, _ = ring(t, res["F_d.rear_left"], WINDOW)
    assert linear_std < 0.1 * std


def test_the_ring_does_not_depend_on_the_step(
    example: VehicleSimulation, example_run: dict[str, np.ndarray]
) -> None:
    std, freq = ring(example_run["time"], example_run[f"F_d.{CORNER}"], WINDOW)
    fine = _run(example, 2.5e-5)
    std_fine, freq_fine = ring(fine["time"], fine[f"F_d.{CORNER}"], WINDOW)
    assert freq_fine == pytest.approx(freq, rel=0.02)
    assert std_fine == pytest.approx(std, rel=0.05)


def test_no_ring_with_the_mean_model(
    example: VehicleSimulation, example_run: dict[str, np.ndarray]
) -> None:
    std, _ = ring(example_run["time"], example_run[f"F_d.{CORNER}"], WINDOW)
    dampers = {**example.dampers, CORNER: WangSymmetric(hysteresis=False)}  # type: ignore[dict-item]
    mean = _run(dataclasses.replace(example, dampers=dampers), 1e-4)
    t, fd = mean["time"], mean[f"F_d.{CORNER}"]
    keep = (t >= WINDOW[0]) & (t <= WINDOW[1])
    spectrum = np.abs(np.fft.rfft((fd[keep] - fd[keep].mean()) * np.hanning(keep.sum())))
    freq = np.fft.rfftfreq(int(keep.sum()), 1e-4)
    band = (freq > 25.0) & (freq < 100.0)
    total = float(np.sqrt(np.sum(spectrum**2)))
    assert float(np.sqrt(np.sum(spectrum[band] ** 2))) < 0.2 * total  # only the wheel hop
    assert float(fd[keep].std()) < 0.3 * std


@pytest.mark.parametrize(("current", "vm"), [(0.0, 0.3), (0.2, 0.2), (0.5, 0.1)])
def test_steady_ring_at_a_known_peak_velocity(current: float, vm: float) -> None:
    # the front-left corner as a quarter car over the bump, v_m held: the cycle persists
    car = FullCar()
    road = WheelRoads.bump("left", 0.03, 0.5, (car.wheelbase, car.front_track), 36.0, position=2.0)
    damper = WangSymmetric(estimator="known", value=vm)
    assert road.left is not None
    sim = Simulation(
        road.left, car.corner_quarter_car(CORNER), damper, Passive(current=current), 0.5
    )
    res = sim.run(2.5, dt=1e-4, output_rate=1e4)
    std, freq = ring(np.asarray(res["time"]), np.asarray(res["F_d"]), (1.5, 2.5))
    assert std > 50.0
    assert freq == pytest.approx(corner_estimate(car, damper, current, vm), rel=0.10)
