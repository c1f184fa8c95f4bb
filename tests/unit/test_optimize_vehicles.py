"""Optimisation problems over a half or full car: per-corner fields and vehicle measures."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.optimize import OptimizationProblem, optimize

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "optimize" / "half-car-rear-gain.toml"


def test_the_example_tunes_corner_fields() -> None:
    problem = OptimizationProblem.load(EXAMPLE)
    assert [p.field for p in problem.parameters] == [
        "controller.rear.gain",
        "damper.front.force_gain",
    ]
    s = problem.scenario({"controller.rear.gain": 50.0, "damper.front.force_gain": 1.1},
                         problem.roads[0])  # fmt: skip
    sim = s.vehicle_simulations()[0]
    assert sim.corner_simulation("front").damper.force_gain == 1.1
    assert sim.corner_simulation("rear").damper.force_gain == 1.0
    assert sim.corner_simulation("rear").controller.describe()["gain"] == 50.0
    assert sim.corner_simulation("front").controller.describe()["gain"] != 50.0
    result = optimize(problem, max_evaluations=5, workers=1, progress=False)
    assert 0.0 < result.objective < 1.5  # the reference scores 1
    assert set(result.measures["ISO 8608 C"]) >= {"heave_ddot_rms", "DLC.rear"}


def _problem(**changes: object) -> dict[str, object]:
    data: dict[str, object] = {
        "vehicle": {"model": "full-car"},
        "controller": {"law": "skyhook-hilo", "mode": "ACM"},
        "simulation": {"duration": 1.0},
        "parameters": [{"field": "controller.front_left.gain", "lower": 1.0, "upper": 10.0}],
        "roads": [{"iso_class": "C", "length": 30.0}],
        "objective": {"weights": {"roll_ddot_rms": 1.0}},
    }
    data.update(changes)
    return data


def test_errors() -> None:
    OptimizationProblem.from_dict(_problem())  # valid
    with pytest.raises(ValidationError, match=re.escape("Did you mean 'DLC.front_left'")):
        OptimizationProblem.from_dict(_problem(objective={"weights": {"DLC.front_lef": 1.0}}))
    with pytest.raises(ValidationError, match=re.escape("'controller.front_lft.gain' is not")):
        OptimizationProblem.from_dict(
            _problem(parameters=[{"field": "controller.front_lft.gain", "lower": 1, "upper": 2}])
        )
    # a quarter car has no per-corner measures
    with pytest.raises(ValidationError, match=re.escape("unknown measure 'DLC.front_left'")):
        OptimizationProblem.from_dict(
            _problem(vehicle={}, controller={"law": "skyhook-hilo"},
                     parameters=[{"field": "controller.gain", "lower": 1, "upper": 2}],
                     objective={"weights": {"DLC.front_left": 1.0}})
        )  # fmt: skip


def test_two_track_roads_roll_the_body_and_tune_roll() -> None:
    """Issue 31: a full car tuned for roll needs a road per side; one track rolls nothing."""
    one_track = OptimizationProblem.from_dict(_problem())
    with pytest.raises(ValidationError, match="give kind = 'two-track' roads"):
        optimize(one_track, max_evaluations=6, workers=1, progress=False)
    data = _problem(roads=[{"kind": "two-track", "iso_class": "C", "length": 30.0}])
    problem = OptimizationProblem.from_dict(data)
    road = problem.roads[0]
    assert road.kind == "two-track"
    assert road.name == "two-track ISO 8608 C, seed 0, 30 m, 50 km/h"
    assert OptimizationProblem.from_dict(problem.to_dict()).roads == problem.roads  # round trip
    result = optimize(problem, max_evaluations=6, workers=1, progress=False)
    assert result.measures[road.name]["roll_ddot_rms"] > 0.0
    assert 0.0 < result.objective < 1.5
    with pytest.raises(ValidationError, match="scale does not apply to kind 'two-track'"):
        OptimizationProblem.from_dict(
            _problem(roads=[{"kind": "two-track", "iso_class": "C", "scale": 2.0}])
        )
    with pytest.raises(ValidationError, match="not a road kind of an objective"):
        OptimizationProblem.from_dict(_problem(roads=[{"kind": "bump", "iso_class": "C"}]))
    quarter = _problem(
        vehicle={}, controller={"law": "skyhook-hilo"},
        parameters=[{"field": "controller.gain", "lower": 1, "upper": 2}],
        roads=[{"kind": "two-track", "iso_class": "C"}],
        objective={"weights": {"DLC": 1.0}},
    )  # fmt: skip
    with pytest.raises(ValidationError, match="gives a road per wheel"):
        OptimizationProblem.from_dict(quarter)
