"""RunSettings: validation, and the run plan reaching the engine, scenarios and studies."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension import RunSettings
from mrsuspension._batch import Job, job_of, measure_job
from mrsuspension.engine.simulate import Simulation, run_many
from mrsuspension.excitation import Harmonic, RoundedPulse
from mrsuspension.scenario import Scenario
from mrsuspension.studies import Study, run_study

PULSE = {"kind": "pulse", "amplitude": 0.02, "severity": 1.0}


def test_defaults_cite_the_spec() -> None:
    s = RunSettings()
    assert (s.dt, s.duration, s.output_rate) == (1e-4, None, 1000.0)
    assert RunSettings(dt=2e-3).output_rate == 500.0  # 1 kHz, capped at one sample per step
    assert RunSettings(dt=1e-3, output_rate=1000.0).decimation == 1


@pytest.mark.parametrize(
    ("kwargs", "fragments"),
    [
        ({"dt": 0.0}, ("dt", "(0, 0.01] s", "got 0")),
        ({"dt": 0.02}, ("dt", "got 0.02")),
        ({"dt": "1e-4"}, ("dt must be a number", "'1e-4'")),
        ({"duration": -1.0}, ("duration", "(0, 100000] s", "got -1")),
        ({"duration": float("nan")}, ("duration", "finite")),
        ({"output_rate": 0.0}, ("output_rate", "got 0")),
        ({"dt": 1e-3, "output_rate": 1500.0}, ("output_rate", "(0, 1000] Hz", "1500")),
        ({"output_rate": True}, ("output_rate must be a number",)),
    ],
)
def test_validation_names_field_value_range(kwargs: dict, fragments: tuple[str, ...]) -> None:
    raises_validation(lambda: RunSettings(**kwargs), *fragments)


def test_frozen_hashable_and_replace() -> None:
    s = RunSettings(dt=5e-5, duration=3.0)
    assert {s: 1}[RunSettings(5e-5, 3.0)] == 1
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.dt = 1e-4  # type: ignore[misc]
    assert dataclasses.replace(s, duration=None).duration is None
    raises_validation(lambda: dataclasses.replace(s, dt=-1.0), "dt")


def test_nyquist_check() -> None:
    RunSettings(output_rate=100.0).check_for(Harmonic(49.0, 0.001))
    raises_validation(
        lambda: RunSettings(output_rate=100.0).check_for(Harmonic(50.0, 0.001)),
        "output_rate = 100 Hz",
        "50 Hz",
    )
    RunSettings(output_rate=10.0).check_for(RoundedPulse(0.02, 1.0))  # no frequency: passes


def test_run_with_settings_equals_keywords_bit_for_bit() -> None:
    sim = Simulation(RoundedPulse(0.035, 2.0))
    a = sim.run(settings=RunSettings(dt=5e-5, duration=3.0))
    b = sim.run(3.0, dt=5e-5)
    assert np.array_equal(a.time, b.time)
    for name in a.signals:
        assert np.array_equal(a[name], b[name], equal_nan=True), name
    assert a.dt == b.dt == 5e-5


def test_run_refuses_settings_and_keywords() -> None:
    sim = Simulation(RoundedPulse(0.035, 2.0))
    raises_validation(lambda: sim.run(1.0, settings=RunSettings()), "either settings or duration")
    raises_validation(
        lambda: run_many([sim], dt=1e-4, settings=RunSettings()), "either settings or dt"
    )


def test_scenario_toml_settings_arrive(tmp_path: Path) -> None:
    path = tmp_path / "s.toml"
    path.write_text(
        '[excitation]\nkind = "pulse"\namplitude = 0.02\nseverity = 1\n'
        "[simulation]\ndt = 5e-4\nduration = 1.5\noutput_rate = 200\n"
    )
    s = Scenario.load(path)
    assert s.settings == RunSettings(dt=5e-4, duration=1.5, output_rate=200.0)
    assert (s.dt, s.duration, s.output_rate) == (5e-4, 1.5, 200.0)
    assert s.to_dict()["simulation"] == {"dt": 5e-4, "output_rate": 200.0, "duration": 1.5}
    assert job_of(s) == Job(s.simulations()[0], s.settings)
    (res,) = s.run()
    assert res.dt == 5e-4
    assert res.time.size == 301  # 1.5 s at 200 Hz
    assert measure_job(job_of(s)) == res.measures()


def test_scenario_settings_errors_name_the_section() -> None:
    raises_validation(
        lambda: Scenario.from_dict(
            {"excitation": PULSE, "simulation": {"dt": 1e-3, "output_rate": 2000.0}}
        ),
        "[simulation] output_rate",
        "1000",
    )
    raises_validation(
        lambda: Scenario.from_dict(
            {
                "excitation": {"kind": "harmonic", "frequency": 600.0, "amplitude": 1e-4},
                "simulation": {"dt": 1e-4},
            }
        ),
        "[simulation] output_rate = 1000 Hz",
        "600 Hz",
    )


def test_run_many_honours_settings() -> None:
    sims = [Simulation(RoundedPulse(0.02, s)) for s in (1.0, 2.0)]
    plan = RunSettings(dt=2e-4, duration=1.0, output_rate=250.0)
    results = run_many(sims, settings=plan, workers=1)
    for sim, res in zip(sims, results, strict=True):
        alone = sim.run(settings=plan)
        assert res.time.size == 251
        assert res.dt == 2e-4
        assert np.array_equal(res.z_s, alone.z_s)


def test_study_honours_simulation_table() -> None:
    study = Study.from_dict(
        {
            "excitation": PULSE,
            "simulation": {"dt": 5e-4, "duration": 1.2, "output_rate": 500.0},
            "grid": {"simulation.dt": [5e-4, 2.5e-4]},
            "study": {"measures": ["SDR_s"]},
        }
    )
    assert study.run_settings() == [
        RunSettings(dt=5e-4, duration=1.2, output_rate=500.0),
        RunSettings(dt=2.5e-4, duration=1.2, output_rate=500.0),
    ]
    res = run_study(study, workers=1, progress=False, cache_dir=False)
    for k, settings in enumerate(study.run_settings()):
        alone = Simulation(RoundedPulse(0.02, 1.0)).run(settings=settings).measures()
        assert float(res["SDR_s"][k]) == alone["SDR_s"]


# -- RunSettings.plan: the one home of planning (issue 28) ------------------------------------
def test_plan_is_the_same_for_the_quarter_car_and_a_vehicle() -> None:
    from mrsuspension.engine.settings import RunPlan
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import WheelRoads
    from mrsuspension.vehicle import HalfCar

    settings = RunSettings(dt=2e-4, duration=0.0125, output_rate=300.0)
    quarter = Simulation(Harmonic(1.0, 0.01))
    half = VehicleSimulation(
        HalfCar(), WheelRoads.from_excitation(Harmonic(1.0, 0.01), HalfCar(), speed_kmh=50.0)
    )
    # decimation round(1 / (300 * 2e-4)) = 17; ceil(0.0125 / (2e-4 * 17)) = 4 intervals
    expected = RunPlan(dt=2e-4, steps=68, decimate=17)
    assert settings.plan(quarter) == expected
    assert settings.plan(half) == expected
    assert expected.rows == 5
    assert expected.time()[-1] == pytest.approx(68 * 2e-4)
    # the record the run returns is the plan's
    assert quarter.run(settings=settings).time.size == expected.rows
    assert half.run(settings=settings).time.size == expected.rows


def test_plan_checks_stability_duration_and_memory_before_running() -> None:
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import WheelRoads
    from mrsuspension.vehicle import FullCar

    quarter = Simulation(Harmonic(1.0, 0.01))
    raises_validation(lambda: RunSettings(dt=5e-3).plan(quarter), "dt = 0.005 s is too large")
    assert RunSettings(dt=5e-3).plan(quarter, check_stability=False).dt == 5e-3
    raises_validation(
        lambda: RunSettings(dt=1e-5, duration=9e4).plan(quarter), "GiB of memory", "duration"
    )
    full = VehicleSimulation(FullCar(), WheelRoads.bump("left", 0.02, 0.5, FullCar()))
    raises_validation(lambda: RunSettings(dt=1e-2).plan(full), "dt = 0.01 s is too large")

    class Endless:
        excitation = type("NoEnd", (), {"duration": None})()

        def check_dt(self, dt: float) -> float:
            return dt

        def record_values(self, plan: object) -> float:
            return 0.0

    raises_validation(lambda: RunSettings().plan(Endless()), "duration is required")
