"""Vehicle measures (measures/vehicle.py) against closed-form values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.measures import weighted_rms
from mrsuspension.measures.vehicle import (
    AXIS_FACTORS,
    COIL_RESISTANCE,
    SuspensionTravel,
    coil_energy,
    lift_off_time,
    seat_acceleration,
    seat_vibration,
    suspension_travel,
    wheel_coil_energy,
    wheel_dlc,
    wheel_lift_off_time,
    wheel_suspension_travel,
)

FS = 1000.0
T = np.arange(0.0, 40.0, 1 / FS)
RNG = np.random.default_rng(19)
HEAVE = np.sin(2 * np.pi * 1.3 * T) + 0.2 * RNG.standard_normal(T.size)
PITCH = 0.3 * np.sin(2 * np.pi * 1.7 * T + 0.4)
ROLL = 0.2 * np.sin(2 * np.pi * 2.1 * T + 1.0)


def test_seat_at_the_cg_sees_heave_only() -> None:
    acc = seat_acceleration(HEAVE, PITCH, ROLL)
    assert np.array_equal(acc["z"], HEAVE)
    assert not np.any(acc["x"])
    assert not np.any(acc["y"])
    sv = seat_vibration(HEAVE, PITCH, ROLL, FS, purpose="health")
    assert sv.weighted_rms["z"] == weighted_rms(HEAVE, FS)
    assert sv.total == pytest.approx(sv.weighted_rms["z"], rel=1e-15)  # health: translations


def test_seat_lever_terms_and_signs() -> None:
    acc = seat_acceleration([0.0], [1.0], [1.0], x=0.8, y=-0.4, height=0.5)
    # nose-down pitch drops a front seat; left-up roll drops a right seat
    assert acc["z"].tolist() == pytest.approx([-0.8 - 0.4])
    assert acc["x"].tolist() == [0.5]  # top of the body moves forward when pitching nose down
    assert acc["y"].tolist() == [-0.5]  # and to the right when rolling left side up
    assert acc["rx"].tolist() == [1.0]
    assert acc["ry"].tolist() == [1.0]


def test_comfort_total_value_combines_axes() -> None:
    sv = seat_vibration(HEAVE, PITCH, ROLL, FS, x=0.3, y=0.35, height=0.6)
    w = sv.weighted_rms
    k = AXIS_FACTORS["comfort"]
    expected = math.sqrt(sum((k[a] * w[a]) ** 2 for a in ("x", "y", "z", "rx", "ry")))
    assert sv.total == pytest.approx(expected, rel=1e-14)
    assert w["ry"] == pytest.approx(weighted_rms(PITCH, FS, weighting="We"))
    assert w["x"] == pytest.approx(0.6 * weighted_rms(PITCH, FS, weighting="Wd"))
    assert (k["rx"], k["ry"]) == (0.63, 0.4)
    assert AXIS_FACTORS["health"] == {"x": 1.4, "y": 1.4, "z": 1.0}


def test_sine_heave_through_wk() -> None:
    sv = seat_vibration(np.sin(2 * np.pi * 4.0 * T), np.zeros_like(T), None, FS)
    assert sv.weighted_rms["z"] * math.sqrt(2) == pytest.approx(0.967, abs=0.003)  # |Wk(4 Hz)|


def test_wheel_dlc_reuses_the_quarter_car_definition() -> None:
    f = 3000.0 + 300.0 * np.sin(2 * np.pi * T)
    out = wheel_dlc({"front_left": f, "rear_right": f + 1000.0})
    assert out["front_left"] == pytest.approx(300.0 / math.sqrt(2) / 3000.0, rel=1e-9)
    assert out["rear_right"] == pytest.approx(300.0 / math.sqrt(2) / 4000.0, rel=1e-9)
    static = wheel_dlc({"front": f}, static_loads={"front": 6000.0})
    assert static["front"] == pytest.approx(300.0 / math.sqrt(2) / 6000.0, rel=1e-9)


def test_lift_off_time_of_a_constructed_force() -> None:
    # 1 kN mean, 1.5 kN swing, clipped at 0 like the tire: off while sin < -2/3
    force = np.maximum(0.0, 1000.0 + 1500.0 * np.sin(2 * np.pi * 1.0 * T))
    expected = 40.0 * (math.pi - 2 * math.asin(2 / 3)) / (2 * math.pi)
    assert lift_off_time(force, FS) == pytest.approx(expected, abs=40 * 2 / FS)
    exact = np.ones(1000)
    exact[100:137] = 0.0
    assert lift_off_time(exact, 100.0) == pytest.approx(0.37)
    assert wheel_lift_off_time({"front_left": exact, "rear": np.ones(5)}, 100.0) == {
        "front_left": pytest.approx(0.37),
        "rear": 0.0,
    }


def test_suspension_travel() -> None:
    stroke = 0.02 * np.sin(2 * np.pi * 2.0 * T) + 0.005
    travel = suspension_travel(stroke)
    assert travel.rms == pytest.approx(math.sqrt(0.02**2 / 2 + 0.005**2), rel=1e-9)
    assert travel.peak_to_peak == pytest.approx(0.04, rel=1e-6)
    both = wheel_suspension_travel({"front": stroke, "rear": np.zeros(3)})
    assert both["rear"] == SuspensionTravel(0.0, 0.0)


def test_energy_of_constant_current() -> None:
    current = np.full(int(10 * FS) + 1, 0.3)  # 10 s at 0.3 A
    assert coil_energy(current, FS, resistance=5.0) == pytest.approx(5.0 * 0.09 * 10.0, rel=1e-12)
    assert coil_energy(current, FS) == pytest.approx(COIL_RESISTANCE * 0.09 * 10.0, rel=1e-12)
    ramp = np.linspace(0.0, 0.5, 100001)  # integral of (0.5 t/T)^2 over T = 1 s: 0.25/3
    assert coil_energy(ramp, 1e5, resistance=1.0) == pytest.approx(0.25 / 3, rel=1e-8)
    assert wheel_coil_energy({"fl": current}, FS, 2.0)["fl"] == pytest.approx(1.8)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: seat_vibration(HEAVE, PITCH, ROLL, FS, purpose="fun"), "purpose must be one of"),
        (lambda: seat_acceleration([1.0, 2.0], [1.0]), "same length"),
        (lambda: seat_acceleration([1.0], [1.0], x=math.nan), "x must be finite"),
        (lambda: coil_energy([0.1], FS, resistance=-1.0), "resistance must be in \\[0, inf\\)"),
        (lambda: lift_off_time([1.0], 0.0), "fs must be finite and > 0"),
        (lambda: wheel_dlc([1.0, 2.0]), "mapping from corner name"),  # type: ignore[arg-type]
        (lambda: wheel_dlc({"front": [1.0, 2.0]}, {"rear": 1.0}), "no entry for front"),
    ],
)
def test_bad_input(call: object, message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        call()  # type: ignore[operator]
