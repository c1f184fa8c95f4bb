"""Adding a vehicle model: a toy model in its own file plus one registry call.

``examples/seat_model.py`` defines a quarter car with a seat-and-driver mass (its own
parameters, run, result and batch runners) and registers it with one
:func:`~mrsuspension.engine.plants.register_plant` call; nothing under ``src/`` names it.
It must then run wherever a built-in model runs: ``Scenario.run``, ``mrsus simulate``,
``mrsus sweep`` and a study whose grid varies one of its own parameters. Its physics is
checked against the engine's own quarter car (a second solver): with a rigid seat the
seat mass rides on the body, so the body's RMS acceleration must equal that of the quarter
car carrying both masses.
"""

from __future__ import annotations

import importlib.util
import json
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from typer.testing import CliRunner

from mrsuspension.cli import app
from mrsuspension.engine.plants import PLANTS
from mrsuspension.scenario import Scenario
from mrsuspension.studies import Study, run_study

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "seat_model.py"
SRC = ROOT / "src" / "mrsuspension"

SCENARIO = """\
[vehicle]
model = "seat-quarter-car"
seat_mass = 90.0

[damper]
model = "linear"
damping = 1500.0

[excitation]
kind = "{kind}"
{options}

[simulation]
dt = 1e-3
duration = 4.0
"""


@pytest.fixture(scope="module")
def seat() -> Iterator[ModuleType]:
    """The example module, loaded (it registers its model), unregistered afterwards."""
    spec = importlib.util.spec_from_file_location("seat_model_example", EXAMPLE)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up
    spec.loader.exec_module(module)
    try:
        yield module
    finally:
        PLANTS.pop(module.MODEL, None)
        sys.modules.pop(spec.name, None)


def _write(tmp_path: Path, kind: str, options: str) -> Path:
    path = tmp_path / f"seat_{kind}.toml"
    path.write_text(SCENARIO.format(kind=kind, options=options))
    return path


def test_nothing_under_src_names_the_toy_model(seat: ModuleType) -> None:
    for path in SRC.rglob("*.py"):
        assert seat.MODEL not in path.read_text(), path


def test_rigid_seat_rides_on_the_body_as_in_the_engines_quarter_car(seat: ModuleType) -> None:
    road = {"kind": "road", "profile": "rough", "speed": 50.0}
    sim = {"duration": 8.0, "dt": 2e-4}
    rigid = Scenario.from_dict({
        "vehicle": {"model": seat.MODEL, "sprung_mass": 240.0, "seat_mass": 80.0,
                    "seat_stiffness": 1e9, "seat_damping": 1e5},
        "damper": {"model": "linear", "damping": 1500.0},
        "excitation": road, "simulation": sim,
    })  # fmt: skip
    quarter = Scenario.from_dict({
        "vehicle": {"sprung_mass": 320.0},
        "damper": {"model": "linear", "damping": 1500.0},
        "excitation": road, "simulation": sim,
    })  # fmt: skip
    (toy,) = rigid.run()
    (engine,) = quarter.run()
    a_toy = toy.measures()["rms_body_acceleration"]
    a_engine = engine.measures()["rms_body_acceleration"]
    print(f"rigid seat: toy {a_toy:.5f}, engine quarter car {a_engine:.5f} m/s^2")
    assert a_toy == pytest.approx(a_engine, rel=0.01)
    assert toy.measures()["seat_to_body"] == pytest.approx(1.0, abs=1e-3)


def test_simulate_from_the_command_line(seat: ModuleType, tmp_path: Path) -> None:
    path = _write(tmp_path, "road", 'profile = "rough"\nspeed = 50.0')
    res = CliRunner().invoke(app, ["simulate", str(path)])
    assert res.exit_code == 0, res.stderr
    assert "rms_seat_acceleration" in res.stdout
    assert "[m/s^2]" in res.stdout
    as_json = CliRunner().invoke(app, ["simulate", str(path), "--json"])
    m = json.loads(as_json.stdout)
    assert 0.0 < m["seat_to_body"] < 1.5


def test_sweep_from_the_command_line(seat: ModuleType, tmp_path: Path) -> None:
    path = _write(tmp_path, "harmonic", "frequency = 1.0\namplitude = 0.01")
    res = CliRunner().invoke(
        app, ["sweep", str(path), "--frequencies", "1,4,12", "--amplitude", "0.005", "--json"]
    )
    assert res.exit_code == 0, res.stderr
    rows = json.loads(res.stdout)
    assert [r["frequency"] for r in rows] == [1.0, 4.0, 12.0]
    ratio = [r["seat_to_body"] for r in rows]
    assert ratio[1] > 1.0 > ratio[2]  # amplified near the seat's 4 Hz, isolated above


def test_a_study_varies_the_models_own_parameter(seat: ModuleType, tmp_path: Path) -> None:
    study = Study.from_dict({
        "vehicle": {"model": seat.MODEL},
        "damper": {"model": "linear", "damping": 1500.0},
        "excitation": {"kind": "road", "profile": "rough", "speed": 50.0},
        "simulation": {"dt": 1e-3, "duration": 4.0},
        "grid": {"vehicle.seat_stiffness": [20_000.0, 80_000.0]},
    })  # fmt: skip
    assert study.measures == tuple(seat.UNITS)
    res = run_study(study, workers=1, progress=False, cache_dir=False)
    seat_rms = np.asarray(res["rms_seat_acceleration"])
    assert seat_rms.shape == (2,)
    assert np.all(np.isfinite(seat_rms))
    assert seat_rms[0] != seat_rms[1]


def test_a_model_name_is_registered_once(seat: ModuleType) -> None:
    from mrsuspension.engine.plants import register_plant
    from mrsuspension.errors import ValidationError

    other = PLANTS["quarter-car"]
    with pytest.raises(ValidationError, match="already registered"):
        register_plant(type(other)(**{**other.__dict__, "name": seat.MODEL}))
