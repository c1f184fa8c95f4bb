"""The half and full car reduced to their measures in the kernel, against the record.

The post-processing (:meth:`VehicleResult.measures`) is the reference: the in-kernel
measures (:meth:`VehicleSimulation.run_measures`, :func:`measure_vehicles`,
:func:`run_vehicles` given :class:`MeasuresOf`) step exactly as :meth:`VehicleSimulation.run`
(the same drive loop) and sum in another order, so every key must agree to 1e-9
relative (1e-12 absolute near zero) under every excitation kind a vehicle takes, with
the corners' controllers, sensing and the vehicle-level laws.
"""

from __future__ import annotations

import math
import tracemalloc
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

from mrsuspension.control import HiLo, make_controller
from mrsuspension.control.modal import CornerSkyhook, ModalSkyhook
from mrsuspension.control.sensing import BandPassObserver, LeakyIntegrator, Sensing, StrokeSensor
from mrsuspension.engine import measures_of
from mrsuspension.engine import vehicle as V
from mrsuspension.engine import vehicle_kernel as VX
from mrsuspension.engine.result import SimulationDiverged
from mrsuspension.engine.settings import RunSettings
from mrsuspension.engine.simulate import MeasuresOf
from mrsuspension.engine.vehicle import VehicleSimulation, measure_vehicles, run_vehicles
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import Harmonic, RoadProfile, RoundedPulse, WheelRoads, preset_road
from mrsuspension.vehicle import FullCar, HalfCar

RTOL = 1e-9
ATOL = 1e-12
DT = 2e-4


def differences(got: dict[str, Any], ref: dict[str, Any]) -> tuple[float, str, list[str]]:
    """The largest relative difference over the keys (equal keys, in order), its key, and
    the keys off by more than RTOL relative and ATOL absolute."""
    assert list(got) == list(ref)
    out, where, off = 0.0, "", []
    for key, b in ref.items():
        a = got[key]
        if b is None or isinstance(b, str):
            assert a == b, key
            continue
        diff = abs(a - b)
        rel = diff / abs(b) if b else (math.inf if diff else 0.0)
        if rel > RTOL and diff > ATOL:
            off.append(key)
        if rel > out:
            out, where = rel, key
    return out, where, off


def _geometry(car: HalfCar | FullCar) -> tuple[float, float]:
    return car.wheelbase, getattr(car, "front_track", 1.5)


def _iso(car: HalfCar | FullCar) -> WheelRoads:
    road = RoadProfile.from_options({"iso_class": "C", "length": 60.0})
    return WheelRoads.from_excitation(road, car, speed_kmh=72.0)


#: name -> (vehicle, wheel input, keywords of VehicleSimulation, duration [s], road_peak)
CASES: dict[str, Callable[[], tuple[Any, Any, dict[str, Any], float | None, str]]] = {
    "harmonic-half": lambda: (
        HalfCar(), WheelRoads.from_excitation(Harmonic(5.0, 0.01), HalfCar(), speed_kmh=50.0),
        {"controllers": HiLo(1, mode="ACM")}, None, "after-onset",
    ),
    "harmonic-full-sliding": lambda: (
        FullCar(), WheelRoads.from_excitation(Harmonic(8.0, 0.005), FullCar(), speed_kmh=30.0),
        {"controllers": {"front_left": make_controller("sliding-mode")}}, None, "after-onset",
    ),
    "preset-road-full": lambda: (
        FullCar(), WheelRoads.from_excitation(preset_road("rough"), FullCar(), speed_kmh=50.0),
        {"controllers": HiLo(1, mode="ACM")}, 2.0, "after-onset",
    ),
    "iso-road-half": lambda: (HalfCar(), _iso(HalfCar()), {}, 2.0, "after-onset"),
    "two-track-full-modal-sensing": lambda: (
        FullCar(), WheelRoads.two_track("C", _geometry(FullCar()), 54.0, length=60.0, seed=2),
        {
            "body_control": ModalSkyhook.corner_equivalent(*FullCar().corner_positions()),
            "sensing": Sensing(BandPassObserver(0.1, 1.0 / DT), StrokeSensor(500.0, 1e-5, 2e-5)),
        },
        2.0, "after-onset",
    ),
    "bump-full": lambda: (
        FullCar(), WheelRoads.bump("left", 0.04, 0.5, _geometry(FullCar()), position=1.0),
        {"controllers": HiLo(1, mode="ACM")}, 1.5, "after-onset",
    ),
    "pothole-half": lambda: (
        HalfCar(), WheelRoads.pothole("left", 0.03, 0.6, HalfCar(), position=1.0),
        {"body_control": CornerSkyhook(), "sensing": Sensing(LeakyIntegrator(0.92, 1.0 / DT))},
        1.5, "after-onset",
    ),
    "pulse-at-speed-full": lambda: (
        FullCar(), WheelRoads.from_excitation(RoundedPulse(0.035, 3.0), FullCar(), speed_kmh=36.0),
        {"controllers": HiLo(1, mode="ACM")}, None, "onset",
    ),
    "pulse-at-speed-half": lambda: (
        HalfCar(), WheelRoads.from_excitation(RoundedPulse(0.02, 1.0), HalfCar(), speed_kmh=36.0),
        {}, None, "after-onset",
    ),
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(CASES))
def test_in_kernel_measures_equal_the_recorded_path(name: str) -> None:
    car, road, options, duration, how = CASES[name]()
    sim = VehicleSimulation(car, road, **options)
    ref = sim.run(duration, dt=DT).measures(road_peak=how)
    got = sim.run_measures(duration, dt=DT, road_peak=how)
    diff, key, off = differences(got, ref)
    print(f"\n{name}: {len(ref)} measures, worst relative difference {diff:.1e} ({key})")
    assert not off
    assert any(k.startswith("roll_ddot") for k in got) == isinstance(car, FullCar)


def test_a_sweep_measures_each_run_with_its_own_settings() -> None:
    car = FullCar()
    sims = [
        VehicleSimulation(
            car, WheelRoads.from_excitation(Harmonic(f, 0.005), car, speed_kmh=40.0),
            controllers=HiLo(1, mode="ACM"),
        )
        for f in (4.0, 9.0)
    ]  # fmt: skip
    plans = [RunSettings(dt=DT), RunSettings(dt=1e-4, output_rate=500.0)]
    rows = measure_vehicles(sims, plans)
    for sim, plan, row in zip(sims, plans, rows, strict=True):
        assert isinstance(row, dict)
        assert not differences(row, sim.run(settings=plan).measures())[2]
    assert rows[0] != rows[1]


def test_runs_of_a_batch_reduce_in_the_kernel(monkeypatch: pytest.MonkeyPatch) -> None:
    car = HalfCar()
    sims = [
        VehicleSimulation(car, WheelRoads.from_excitation(Harmonic(f, 0.01), car, speed_kmh=50.0))
        for f in (5.0, 7.0)
    ]
    reference = [s.run(dt=DT).measures(road_peak="onset") for s in sims]

    def no_record(*args: Any, **kwargs: Any) -> None:
        raise AssertionError("a measures batch recorded a time history")

    monkeypatch.setattr(VehicleSimulation, "run", no_record)
    for reduce in (MeasuresOf("onset"), measures_of):
        rows = run_vehicles(sims, dt=DT, workers=1, reduce=reduce)
        for row, ref in zip(rows, reference, strict=True):
            assert not differences(row, ref)[2]
    with pytest.raises(AssertionError, match="recorded"):  # any other reducer: the record
        run_vehicles(sims, dt=DT, workers=1, reduce=MeasuresOf().__call__)


def test_a_diverged_run_gives_its_divergence_in_its_place(monkeypatch: pytest.MonkeyPatch) -> None:
    car = HalfCar()
    sims = [
        VehicleSimulation(car, WheelRoads.bump("left", h, 0.5, car, position=0.5))
        for h in (0.001, 0.08)
    ]
    monkeypatch.setattr(VX, "LIMITS", np.array([0.02, 100.0, 1e6, 1e7]))
    ok, bad = measure_vehicles(sims, [RunSettings(dt=DT, duration=1.5)] * 2)
    assert isinstance(ok, dict)
    assert isinstance(bad, SimulationDiverged)
    with pytest.raises(SimulationDiverged) as recorded:
        sims[1].run(1.5, dt=DT)
    assert str(bad) == str(recorded.value)
    assert (bad.signal, bad.time) == (recorded.value.signal, recorded.value.time)


def test_a_harmonic_run_too_short_is_refused_before_running() -> None:
    car = HalfCar()
    sim = VehicleSimulation(car, WheelRoads.from_excitation(Harmonic(1.0, 0.01), car, 50.0))
    with pytest.raises(ValidationError, match="too short for the steady-state rule"):
        sim.run_measures(5.0)


@dataclass(frozen=True)
class _Sine:
    """A wheel input without a fast grid: the road at exactly the times the engine asks."""

    corners: tuple[str, ...]
    duration: float | None = None

    def displacement(self, t: npt.ArrayLike) -> np.ndarray:
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.stack(
            [0.01 * np.sin(2 * np.pi * (2.0 + i) * t) for i in range(len(self.corners))]
        )

    def velocity(self, t: npt.ArrayLike) -> np.ndarray:
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.stack(
            [0.02 * np.pi * (2.0 + i) * np.cos(2 * np.pi * (2.0 + i) * t)
             for i in range(len(self.corners))]
        )  # fmt: skip


def test_a_run_driven_in_pieces_of_road_is_the_run_in_one_piece(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # dt a power of two: the half-step times k dt/2 are exact whatever piece asks for them,
    # so the pieces see the very road of one piece and the runs agree bit for bit; 997
    # steps a piece is no multiple of the decimation (8)
    car = FullCar()
    sim = VehicleSimulation(
        car, _Sine(car.corners), controllers=HiLo(1, mode="ACM"),
        sensing=Sensing(LeakyIntegrator(0.92, 1024.0), StrokeSensor(1024.0, 1e-5, 2e-5)),
    )  # fmt: skip
    dt = 2.0**-13
    plan = RunSettings(dt=dt, duration=4000 * dt, output_rate=1024.0)
    whole = sim.run(settings=plan)
    monkeypatch.setattr(V, "ROAD_CHUNK", 997)
    pieces = sim.run(settings=plan)
    assert whole.time.size == pieces.time.size == 501
    for key in whole.signals:
        np.testing.assert_array_equal(pieces[key], whole[key], err_msg=key)


def _peak(call: Callable[[], object]) -> int:
    tracemalloc.start()
    try:
        call()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_memory_of_a_reduced_run_does_not_grow_with_its_duration() -> None:
    car = HalfCar()
    sim = VehicleSimulation(
        car, WheelRoads.from_excitation(Harmonic(2.0, 0.01), car, speed_kmh=50.0),
        controllers=HiLo(1, mode="ACM"),
    )  # fmt: skip
    sim.run_measures(10.0, dt=DT)  # compiled and imported before measuring
    peaks = {
        (how, d): _peak(
            (lambda d=d: sim.run_measures(d, dt=DT))
            if how == "reduced"
            else (lambda d=d: sim.run(d, dt=DT).measures())
        )
        for how in ("reduced", "recorded")
        for d in (10.0, 40.0)
    }
    for (how, d), peak in peaks.items():
        print(f"\n{how} {d:g} s: peak {peak / 1e6:.2f} MB")
    assert peaks["reduced", 40.0] <= 1.05 * peaks["reduced", 10.0]
    assert peaks["recorded", 40.0] >= 3.0 * peaks["recorded", 10.0]
