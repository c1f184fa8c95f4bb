"""The named measured signals (control/signals.py): each one against an independent value.

A Python law (``numba=False``) keeps every signal vector it is called with; the run's
record (one row per step, ``output_rate = 1/dt``) gives the independent values: row ``k``
is the state at the start of step ``k`` and the rates evaluated there (the end of step
``k - 1``), which is what the controller of step ``k`` sees.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from mrsuspension.control import law
from mrsuspension.control.sensing import BandPassObserver, Sensing, StrokeSensor, band_pass_corner
from mrsuspension.control.signals import NS, SIGNAL_NAMES, SIGNALS
from mrsuspension.engine import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import Harmonic
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.vehicle import FullCar

DT = 1e-4
SEEN: list[Any] = []


@law(numba=False)
def keep(s, current=0.1):  # type: ignore[no-untyped-def]
    """Every signal vector, kept; a constant current (the damper is then a passive one)."""
    SEEN.append(s)
    return current


def _seen(corners: int = 1) -> dict[str, np.ndarray]:
    """The kept signals by name: arrays of (steps, corners)."""
    rows = np.array(SEEN, dtype=float).reshape(-1, corners, NS)
    SEEN.clear()
    return {name: rows[:, :, SIGNALS[name].slot] for name in SIGNAL_NAMES}


def test_the_table_has_every_slot_once() -> None:
    assert sorted(s.slot for s in SIGNALS.values()) == list(range(NS))
    assert all(s.unit or s.name == "corner" for s in SIGNALS.values())


def test_quarter_car_signals_are_the_state_and_the_previous_steps_rates() -> None:
    SEEN.clear()
    res = Simulation(Harmonic(2.0, 0.02), controller=keep()).run(0.2, dt=DT, output_rate=1 / DT)
    s = {k: v[:, 0] for k, v in _seen().items()}
    n = s["time"].size
    assert n == res.time.size - 1  # one control sample per step
    np.testing.assert_array_equal(s["time"], np.arange(n) * DT)
    for name in ("z_s", "z_s_dot", "z_u", "z_u_dot", "z_s_ddot", "z_u_ddot", "F_d", "i_d"):
        np.testing.assert_array_equal(s[name], res[name][:n], err_msg=name)
    np.testing.assert_allclose(s["x_d"], res["x_d"][:n], atol=1e-15)
    np.testing.assert_allclose(s["v_d"], res["v_d"][:n], atol=1e-15)
    np.testing.assert_array_equal(s["v_m"], res["v_m"][1 : n + 1])  # latched in step k
    # the acceleration signal is the body's own rate: the central difference of the
    # recorded velocity (independent of the engine's rates) agrees to O(dt^2)
    fd = (res["z_s_dot"][2:n] - res["z_s_dot"][: n - 2]) / (2 * DT)
    scale = np.max(np.abs(s["z_s_ddot"]))
    assert np.max(np.abs(s["z_s_ddot"][1 : n - 1] - fd)) < 1e-3 * scale
    # the quarter car's body: heave is z_s, no pitch or roll
    np.testing.assert_array_equal(s["heave"], s["z_s"])
    np.testing.assert_array_equal(s["heave_dot"], s["z_s_dot"])
    np.testing.assert_array_equal(s["heave_ddot"], s["z_s_ddot"])
    for name in ("pitch", "roll", "pitch_dot", "roll_dot", "pitch_ddot", "roll_ddot", "corner"):
        assert not s[name].any(), name
    assert not s["z_s0"].any()  # the reference model runs for sliding mode only


@pytest.fixture(scope="module")
def car() -> FullCar:
    return FullCar()


def _road(car: FullCar) -> WheelRoads:
    return WheelRoads.two_track(
        "C", (car.wheelbase, car.front_track), speed_kmh=54.0, length=30.0, seed=3
    )


def test_full_car_signals_ideal(car: FullCar) -> None:
    SEEN.clear()
    sim = VehicleSimulation(car, _road(car), controllers=keep())
    res = sim.run(0.15, dt=DT, output_rate=1 / DT)
    s = _seen(4)
    n = s["time"].shape[0]
    for i, c in enumerate(car.corners):
        assert np.all(s["corner"][:, i] == i)
        for name in ("z_s", "z_s_dot", "z_u", "z_u_dot", "z_s_ddot", "z_u_ddot", "F_d", "i_d"):
            np.testing.assert_array_equal(s[name][:, i], res[f"{name}.{c}"][:n], err_msg=name)
    for name in ("heave", "pitch", "roll", "heave_dot", "pitch_dot", "roll_dot"):
        for i in range(4):
            np.testing.assert_array_equal(s[name][:, i], res[name][:n], err_msg=name)
    for name in ("heave_ddot", "pitch_ddot", "roll_ddot"):
        np.testing.assert_array_equal(s[name][:, 0], res[name][:n], err_msg=name)
    # the body's velocity at a corner from heave, pitch and roll rates (small angles)
    x, y = car.corner_positions()
    v = s["heave_dot"][:, 0, None] - x * s["pitch_dot"][:, 0, None] + y * s["roll_dot"][:, 0, None]
    np.testing.assert_allclose(v, s["z_s_dot"], atol=1e-12)


def test_full_car_signals_with_band_pass_sensing_and_a_stroke_sensor(car: FullCar) -> None:
    """z_s_dot is the estimate the sensing tests check (the sensed velocity the record
    keeps), z_s_ddot the accelerometer's held sample, x_d the stroke sensor's reading."""
    fs, every = 1000.0, 10
    est = BandPassObserver(band_pass_corner(1.0, 10.0, fs=fs), fs)
    sensing = Sensing(est, StrokeSensor(fs=2000.0, resolution=1e-5, noise_std=0.0))
    SEEN.clear()
    res = VehicleSimulation(car, _road(car), controllers=keep(), sensing=sensing).run(
        0.2, dt=DT, output_rate=1 / DT
    )
    s = _seen(4)
    n = s["time"].shape[0]
    for i, c in enumerate(car.corners):
        sensed = res[f"z_s_dot_sensed.{c}"][1 : n + 1]  # row k + 1: what step k used
        np.testing.assert_array_equal(s["z_s_dot"][:, i], sensed)
        acc = res[f"z_s_ddot.{c}"][:n]
        held = np.repeat(acc[::every], every)[:n]
        np.testing.assert_array_equal(s["z_s_ddot"][:, i], held)
        np.testing.assert_array_equal(s["z_s_ddot"][:, i], held)
        # the stroke as seen: the true one quantised to 10 um, sampled every 5 steps
        stroke = res[f"x_d.{c}"][:n]
        sampled = np.repeat(stroke[::5], 5)[:n]
        assert np.max(np.abs(s["x_d"][:, i] - sampled)) <= 0.5e-5 + 1e-12
    # the body rates from the corners' estimates: D^T v reproduces each corner's estimate
    x, y = car.corner_positions()
    v = s["heave_dot"][:, 0, None] - x * s["pitch_dot"][:, 0, None] + y * s["roll_dot"][:, 0, None]
    warp = v - s["z_s_dot"]  # what the rigid body cannot hold (the corners' disagreement)
    assert np.max(np.abs(warp)) <= np.max(np.abs(s["z_s_dot"]))
