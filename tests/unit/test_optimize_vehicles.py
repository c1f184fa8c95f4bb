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
