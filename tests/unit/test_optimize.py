"""The optimiser: problem validation, the normalised objective, and a known optimum."""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension._batch import job_of, measure_job
from mrsuspension.optimize import (
    OptimizationProblem,
    Parameter,
    Road,
    objective_value,
    optimize,
)

ROOT = Path(__file__).resolve().parents[2]

#: one passive current on one short road: a problem small enough to scan by brute force
PASSIVE: dict[str, Any] = {
    "problem": {"population": 6, "seed": 3},
    "controller": {"law": "passive"},
    "simulation": {"dt": 5e-4},
    "parameters": [{"field": "controller.current", "lower": 0.0, "upper": 0.5}],
    "roads": [{"iso_class": "C", "length": 40.0, "seed": 2}],
    "objective": {"weights": {"wk_rms_body_acceleration": 1.0, "rms_stroke": 1.0}},
}


def _with(**changes: Any) -> dict[str, Any]:
    data = copy.deepcopy(PASSIVE)
    data.update(changes)
    return data


# -- the objective ------------------------------------------------------------------------
def test_objective_by_hand() -> None:
    measures = [{"DLC": 0.1, "rms_stroke": 0.004}, {"DLC": 0.3, "rms_stroke": 0.001}]
    reference = [{"DLC": 0.2, "rms_stroke": 0.002}, {"DLC": 0.2, "rms_stroke": 0.002}]
    # equal road weights: DLC ratios 0.5, 1.5 -> 1.0; stroke 2.0, 0.5 -> 1.25
    value = objective_value(measures, reference, {"DLC": 1.0, "rms_stroke": 3.0})
    assert value == pytest.approx((1.0 * 1.0 + 3.0 * 1.25) / 4.0)
    # road weights 3:1 -> DLC 0.75 * 0.5 + 0.25 * 1.5 = 0.75; stroke 1.5 + 0.125 = 1.625
    value = objective_value(measures, reference, {"DLC": 1.0, "rms_stroke": 1.0}, [3.0, 1.0])
    assert value == pytest.approx((0.75 + 1.625) / 2.0)


def test_objective_of_the_reference_is_one_and_scales_with_units() -> None:
    ref = [{"wk_rms_body_acceleration": 0.7, "DLC": 0.05}]
    assert objective_value(ref, ref, {"wk_rms_body_acceleration": 2.0, "DLC": 5.0}) == 1.0
    # a unit change of a measure (m -> mm) leaves the normalised objective unchanged
    mm = [{"rms_stroke": 3.0}]
    m = [{"rms_stroke": 3e-3}]
    assert objective_value(mm, [{"rms_stroke": 2.0}], {"rms_stroke": 1.0}) == pytest.approx(
        objective_value(m, [{"rms_stroke": 2e-3}], {"rms_stroke": 1.0})
    )


def test_objective_refuses_a_zero_reference() -> None:
    raises_validation(
        lambda: objective_value(
            [{"mean_current": 0.1}], [{"mean_current": 0.0}], {"mean_current": 1.0}
        ),
        "mean_current is 0",
        "reference",
    )


# -- parameters and roads -----------------------------------------------------------------
def test_parameter_search_variables() -> None:
    p = Parameter("controller.gain", 1.0, 1000.0, log=True)
    assert p.search_bounds == (0.0, 3.0)
    assert p.value(1.5) == pytest.approx(10**1.5)
    assert p.value(7.0) == 1000.0  # clipped
    q = Parameter("controller.order", 0.6, 3.2, integer=True)
    assert q.search_bounds == (1.0, 3.0)
    assert q.value(2.4) == 2.0


def test_road_options_over_the_shared_excitation() -> None:
    shared = {"kind": "road", "speed": 80.0, "iso_class": "B", "seed": 4}
    road = Road.from_dict({"profile": "rough"}, shared)
    assert road.options == {"speed": 80.0, "profile": "rough"}  # iso options dropped
    assert road.name == "rough, 80 km/h"
    iso = Road.from_dict({"seed": 5, "weight": 2.0}, shared)
    assert iso.options == {"speed": 80.0, "iso_class": "B", "seed": 5}
    assert iso.weight == 2.0


# -- validation ---------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("changes", "fragments"),
    [
        ({"problme": {}}, ("unknown table [problme]", "Did you mean 'problem'")),
        ({"problem": {"seeed": 1}}, ("unknown key [problem] seeed", "Did you mean 'seed'")),
        (
            {"parameters": [{"field": "controller.current", "lower": 0.4, "upper": 0.1}]},
            ("lower = 0.4 must be below upper = 0.1",),
        ),
        (
            {"parameters": [{"field": "controller.curent", "lower": 0.0, "upper": 0.5}]},
            ("'controller.curent'", "Did you mean 'controller.current'"),
        ),
        (
            {"parameters": [{"field": "excitation.speed", "lower": 10.0, "upper": 90.0}]},
            ("not tuned",),
        ),
        (
            {"parameters": [{"field": "controller.current", "lower": 0.0, "uper": 0.5}]},
            ("unknown key [[parameters]] #1 uper", "Did you mean 'upper'"),
        ),
        (
            {"parameters": [{"field": "controller.current", "lower": 0.0, "upper": 0.9}]},
            ("controller.current = 0.9",),  # above max_current 0.5 A: caught at the bound
        ),
        ({"parameters": []}, ("[[parameters]] must list at least one",)),
        ({"roads": []}, ("[[roads]] must list at least one road",)),
        ({"roads": [{"speed": 50.0}]}, ("needs 'profile'",)),
        ({"roads": [{"profile": "ruogh"}]}, ("ruogh", "Did you mean 'rough'")),
        ({"roads": [{"iso_class": "C", "sede": 1}]}, ("unknown key [[roads]] #1 sede",)),
        ({"objective": {"weights": {"DLX": 1.0}}}, ("unknown measure 'DLX'", "Did you mean 'DLC'")),
        ({"objective": {"weights": {}}}, ("non-empty table",)),
        ({"objective": {"weights": {"DLC": 0.0}}}, ("at least one weight must be > 0",)),
        ({"objective": {"weights": {"DLC": -1.0}}}, ("DLC must be >= 0",)),
        ({"excitation": {"kind": "harmonic"}}, ("kind must be one of road, two-track",)),
        ({"problem": {"population": 3}}, ("population must be an integer >= 5",)),
        ({"problem": {"max_evaluations": 4, "population": 6}}, ("below one population",)),
    ],
)
def test_validation_errors(changes: dict[str, Any], fragments: tuple[str, ...]) -> None:
    raises_validation(lambda: OptimizationProblem.from_dict(_with(**changes)), *fragments)


def test_a_parameter_the_law_does_not_have_is_refused_before_running() -> None:
    data = _with(parameters=[{"field": "controller.gain", "lower": 1.0, "upper": 10.0}])
    raises_validation(
        lambda: OptimizationProblem.from_dict(data), "does not apply to law 'passive'"
    )


def test_load_names_the_file_and_the_stem(tmp_path: Path) -> None:
    raises_validation(lambda: OptimizationProblem.load(tmp_path / "none.toml"), "not found")
    bad = tmp_path / "bad.toml"
    bad.write_text("[problem\n")
    raises_validation(lambda: OptimizationProblem.load(bad), "not valid TOML")
    example = OptimizationProblem.load(ROOT / "examples" / "optimize" / "skyhook-gain.toml")
    assert example.name == "skyhook-gain"
    assert [p.field for p in example.parameters] == ["controller.gain", "controller.order"]
    assert example.parameters[1].integer
    assert example.parameters[0].log


def test_round_trip_through_to_dict() -> None:
    problem = OptimizationProblem.from_dict(PASSIVE)
    again = OptimizationProblem.from_dict(problem.to_dict())
    assert again.parameters == problem.parameters
    assert again.roads == problem.roads
    assert again.weights == problem.weights


# -- the search ---------------------------------------------------------------------------
def test_finds_the_brute_force_optimum() -> None:
    problem = OptimizationProblem.from_dict(PASSIVE)
    road = problem.roads[0]
    reference = measure_job(job_of(problem.scenario(None, road)))
    assert reference is not None
    grid = np.linspace(0.0, 0.5, 51)
    scan = []
    for current in grid:
        row = measure_job(job_of(problem.scenario({"controller.current": float(current)}, road)))
        assert row is not None
        scan.append(objective_value([row], [reference], problem.weights))
    values = np.array(scan)
    best_scan = float(values.min())
    # the scan's optimum is inside the range and clearly better than both ends
    assert best_scan < values[0] - 0.01
    assert best_scan < values[-1] - 0.01

    result = optimize(problem, max_evaluations=60, workers=1, progress=False)
    assert result.evaluations <= 60
    assert result.objective <= best_scan + 2e-3
    # the optimiser's current lies where the scan is within 0.5 % of its best
    near = grid[values <= best_scan + 5e-3]
    found = result.best["controller.current"]
    assert near.min() - 0.01 <= found <= near.max() + 0.01
    # its recorded measures give its objective again
    again = objective_value(
        [result.measures[road.name]], [result.reference[road.name]], problem.weights
    )
    assert again == pytest.approx(result.objective)
    assert result.reference[road.name]["rms_stroke"] == pytest.approx(reference["rms_stroke"])


def test_history_save_and_determinism(tmp_path: Path) -> None:
    problem = OptimizationProblem.from_dict(_with(problem={"population": 5, "seed": 7}))
    calls: list[tuple[int, int, float]] = []
    first = optimize(
        problem, max_evaluations=10, workers=1, progress=lambda g, n, b: calls.append((g, n, b))
    )
    assert [c[:2] for c in calls] == [(1, 2), (2, 2)]
    assert calls[-1][2] == pytest.approx(first.objective)
    assert [h["evaluation"] for h in first.history] == list(range(1, first.evaluations + 1))
    assert {h["generation"] for h in first.history} == {0, 1}
    assert min(h["objective"] for h in first.history) == first.objective
    second = optimize(problem, max_evaluations=10, workers=1, progress=False)
    assert second.best == first.best  # seeded
    files = first.save(tmp_path)
    assert [f.name for f in files] == ["optimization.json", "convergence.png"]
    data = json.loads(files[0].read_text())
    assert data["best"] == first.best
    assert data["reference_objective"] == 1.0
    assert files[1].stat().st_size > 1000
    assert len(first.to_pandas()) == first.evaluations


def test_two_workers_give_the_same_answer() -> None:
    problem = OptimizationProblem.from_dict(_with(problem={"population": 5, "seed": 7}))
    one = optimize(problem, max_evaluations=5, workers=1, progress=False)
    two = optimize(problem, max_evaluations=5, workers=2, progress=False)
    assert two.best == one.best
    assert two.objective == pytest.approx(one.objective, rel=1e-12)


def test_integer_parameters_take_whole_values() -> None:
    data = _with(
        controller={"law": "skyhook-hilo", "mode": "ACM"},
        parameters=[
            {"field": "controller.order", "lower": 1, "upper": 3, "integer": True},
            {"field": "controller.gain", "lower": 1.0, "upper": 1000.0, "log": True},
        ],
        problem={"population": 6, "seed": 1},
    )
    result = optimize(
        OptimizationProblem.from_dict(data), max_evaluations=12, workers=1, progress=False
    )
    orders = {h["controller.order"] for h in result.history}
    assert orders <= {1.0, 2.0, 3.0}
    assert all(1.0 <= h["controller.gain"] <= 1000.0 for h in result.history)
    assert math.isfinite(result.objective)


def test_a_zero_reference_measure_is_refused_before_the_search() -> None:
    data = _with(objective={"weights": {"mean_current": 1.0}})  # passive 0 A draws no current
    problem = OptimizationProblem.from_dict(data)
    raises_validation(
        lambda: optimize(problem, max_evaluations=6, workers=1, progress=False), "mean_current is 0"
    )
