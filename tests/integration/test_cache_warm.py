"""``mrsus cache warm`` compiles every entry point ahead of time; the notice says so."""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from typer.testing import CliRunner

from mrsuspension.cli import app
from mrsuspension.cli.compiling import (
    COMPILE_NOTICE,
    WARM_STEPS,
    engine_cache_cold,
    notify_if_compiling,
)


def test_cache_warm_compiles_every_entry_point_with_progress() -> None:
    result = CliRunner().invoke(app, ["cache", "warm"])
    assert result.exit_code == 0, result.stderr
    n = len(WARM_STEPS)
    assert f"compiled kernels ready: {n} entry points in" in result.stdout
    for i, (what, _) in enumerate(WARM_STEPS, 1):
        assert f"[{i}/{n}] {what}: " in result.stderr  # each step said with its time
    assert not engine_cache_cold("run", "step")


def test_the_notice_names_each_cold_entry_point_and_an_estimate(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))  # an empty cache: all cold
    log = io.StringIO()
    assert notify_if_compiling(log, "run", "step")
    assert log.getvalue() == COMPILE_NOTICE + "\n"
    assert "5-20 s" in COMPILE_NOTICE
    assert "mrsus cache warm" in COMPILE_NOTICE
    (tmp_path / "kernel.run-1.py311.nbi").write_text("")
    assert engine_cache_cold("run", "step")  # step still cold
    assert not engine_cache_cold("run")


@pytest.fixture
def fresh_notice(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """A process that has said nothing yet, with a cache that looks cold."""
    from mrsuspension import _numba_cache

    monkeypatch.setattr(_numba_cache, "_SEEN", set())
    monkeypatch.setattr(_numba_cache, "_SAID", [False])
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))  # numba read its own at import


def test_a_first_run_from_python_says_why_it_waits_once(
    fresh_notice: None, capsys: pytest.CaptureFixture[str]
) -> None:
    """Issue 31: the Python API and the vehicles announce compiling, once per process."""
    from mrsuspension.engine import Simulation
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import Harmonic, WheelRoads
    from mrsuspension.vehicle import HalfCar

    Simulation(Harmonic(2.0, 0.01)).run(0.01)
    assert capsys.readouterr().err == COMPILE_NOTICE + "\n"
    Simulation(Harmonic(2.0, 0.01)).run(0.01)
    car = HalfCar()
    VehicleSimulation(car, WheelRoads.from_excitation(Harmonic(2.0, 0.01), car, 50.0)).run(0.01)
    assert capsys.readouterr().err == ""  # said once per process


def test_a_first_vehicle_run_says_it_too(
    fresh_notice: None, capsys: pytest.CaptureFixture[str]
) -> None:
    from mrsuspension.engine.vehicle import VehicleSimulation, run_vehicles
    from mrsuspension.excitation import Harmonic, WheelRoads
    from mrsuspension.vehicle import FullCar

    car = FullCar()
    sim = VehicleSimulation(car, WheelRoads.from_excitation(Harmonic(2.0, 0.01), car, 50.0))
    run_vehicles([sim], duration=0.01, workers=1)
    assert capsys.readouterr().err == COMPILE_NOTICE + "\n"


def test_the_command_and_the_engine_say_it_once_between_them(
    fresh_notice: None, capsys: pytest.CaptureFixture[str]
) -> None:
    from mrsuspension.engine import Simulation
    from mrsuspension.excitation import Harmonic

    assert notify_if_compiling()  # the command, before its first run
    Simulation(Harmonic(2.0, 0.01)).run(0.01)  # the engine stays quiet
    assert capsys.readouterr().err == COMPILE_NOTICE + "\n"
