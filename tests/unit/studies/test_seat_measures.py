"""The seat's ISO 2631-1 measures in studies and the optimiser (issue 31, item 6).

A half or full car reports ``seat_total``, ``seat_z``, ... when a study lists them in
``[study] measures`` or an objective weights them; they equal the Python values of
``VehicleResult.vehicle_measures()`` and carry their units. They are not in a study's
defaults (they need the time history), and a quarter car has none.
"""

from __future__ import annotations

import re
from typing import Any

import pytest

from mrsuspension.engine.vehicle_result import SEAT_MEASURES
from mrsuspension.errors import ValidationError
from mrsuspension.optimize import OptimizationProblem, optimize
from mrsuspension.scenario import Scenario
from mrsuspension.studies import Study, run_study
from mrsuspension.studies.study import merge_scenario_tables

ROAD = {"kind": "road", "iso_class": "C", "length": 20.0, "seed": 3}
BASE: dict[str, Any] = {
    "vehicle": {"model": "full-car"},
    "controller": {"law": "skyhook-hilo", "mode": "ACM"},
    "excitation": ROAD,
    "simulation": {"duration": 0.5, "dt": 2e-4},
}
GAINS = [1.0, 1000.0]
WANTED = ["seat_total", "seat_z", "seat_x", "seat_y", "heave_ddot_rms", "DLC.front_left"]


@pytest.fixture(scope="module")
def study_result() -> Any:
    study = Study.from_dict(
        {**BASE, "study": {"measures": WANTED}, "grid": {"controller.gain": GAINS}}
    )
    return run_study(study, workers=1, progress=False, cache_dir=False)


def test_a_study_over_a_vehicle_gain_reports_the_seat_as_python_does(study_result: Any) -> None:
    ds = study_result.dataset
    assert ds["seat_z"].attrs["units"] == "m/s^2"
    assert ds["seat_total"].attrs["units"] == "m/s^2"
    assert "ISO 2631-1" in ds["seat_z"].attrs["long_name"]
    for k, gain in enumerate(GAINS):
        data = merge_scenario_tables(BASE, {"controller": {"gain": gain}})
        (res,) = Scenario.from_dict(data).run()
        python = res.vehicle_measures()
        for name in ("seat_total", "seat_z", "seat_x", "seat_y"):
            got = float(study_result[name].values[k])
            assert got == pytest.approx(python[name], rel=1e-9, abs=1e-12), (name, gain)
            assert got > 0.0 or name == "seat_y"  # one track: the body does not roll
        assert float(study_result["heave_ddot_rms"].values[k]) == pytest.approx(
            python["heave_ddot_rms"], rel=1e-9
        )
    # the gain changes the ride: the study does not report one run twice
    assert float(study_result["seat_z"].values[0]) != float(study_result["seat_z"].values[1])
    df = study_result.to_pandas()
    assert {"seat_total", "seat_z", "DLC.front_left"} <= set(df.columns)


def test_seat_measures_are_on_request_only() -> None:
    grid = {"grid": {"controller.gain": GAINS}}
    default = Study.from_dict({**BASE, **grid})
    assert not set(default.measures) & set(SEAT_MEASURES)  # the default stays in-kernel
    quarter = {**BASE, "vehicle": {}, **grid, "study": {"measures": ["seat_z"]}}
    with pytest.raises(ValidationError, match=re.escape("'seat_z' is not a measure")):
        Study.from_dict(quarter)


def test_an_objective_weights_the_seat() -> None:
    data = {
        **{k: v for k, v in BASE.items() if k != "excitation"},
        "parameters": [{"field": "controller.gain", "lower": 1.0, "upper": 1000.0, "log": True}],
        "roads": [{"iso_class": "C", "length": 20.0, "seed": 3}],
        "objective": {"weights": {"seat_total": 1.0}},
        "problem": {"population": 5, "seed": 1},
    }
    problem = OptimizationProblem.from_dict(data)
    result = optimize(problem, max_evaluations=5, workers=1, progress=False)
    (road,) = result.measures
    best, reference = result.measures[road], result.reference[road]
    assert result.objective == pytest.approx(best["seat_total"] / reference["seat_total"])
    # the reference's seat value is the Python one of the reference scenario
    (res,) = problem.scenario(None, problem.roads[0]).run()
    assert reference["seat_total"] == pytest.approx(res.vehicle_measures()["seat_total"], rel=1e-9)
    with pytest.raises(ValidationError, match=re.escape("Did you mean 'seat_z'")):
        OptimizationProblem.from_dict({**data, "objective": {"weights": {"seat_zz": 1.0}}})
