"""Trade-off grid and Pareto fronts."""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.optimize import Road
from mrsuspension.tradeoff import (
    TradeoffPoint,
    TradeoffResult,
    default_grid,
    pareto_front,
    tradeoff,
)

ROAD = Road.from_dict({"iso_class": "C", "length": 30.0, "seed": 3})


def test_pareto_front_by_hand() -> None:
    points = [
        [1.0, 5.0, 1.0],  # best first measure
        [2.0, 2.0, 2.0],
        [3.0, 1.0, 3.0],  # best second measure
        [2.5, 2.5, 2.5],  # dominated by [2, 2, 2]
        [2.0, 2.0, 2.0],  # a tie is not dominated
        [9.0, 9.0, 0.5],  # best third measure
        [np.nan, 0.0, 0.0],  # never on the front
    ]
    assert pareto_front(points).tolist() == [True, True, True, False, True, True, False]
    # in two measures only, the last finite point is dominated by none but [2, 2] beats it
    assert pareto_front(np.array(points)[:6, :2]).tolist() == [True, True, True, False, True, False]


def test_pareto_front_needs_a_matrix() -> None:
    raises_validation(lambda: pareto_front([1.0, 2.0]), "2-D array", "(2,)")


def _point(family: str, law: str, values: tuple[float, float, float]) -> TradeoffPoint:
    measures = dict(zip(("wk_rms_body_acceleration", "DLC", "rms_stroke"), values, strict=True))
    return TradeoffPoint(family, "x", {"controller": {"law": law}}, measures)


def test_ideal_controllers_are_left_out_of_the_front() -> None:
    result = TradeoffResult(
        (
            _point("passive", "passive", (1.0, 0.2, 0.01)),
            _point("sky", "skyhook-hilo", (1.2, 0.1, 0.02)),
            _point("ideal", "ideal-skyhook", (0.5, 0.05, 0.005)),  # dominates both
        ),
        (ROAD,),
    )
    assert result.pareto().tolist() == [True, True, False]
    rows = result.rows()
    assert [r["Pareto (3 measures)"] for r in rows] == ["yes", "yes", ""]
    assert rows[0]["RMS stroke [mm]"] == pytest.approx(10.0)


def test_default_grid_covers_the_families() -> None:
    grid = default_grid()
    assert set(grid) == {
        "passive",
        "skyhook hi-lo SCM",
        "skyhook hi-lo ACM",
        "inverse hi-lo ACM",
        "sliding mode ACM",
        "ideal skyhook",
    }
    currents = [t["controller"]["current"] for _, t in grid["passive"]]
    assert currents[0] == 0.0
    assert currents[-1] == 0.5
    assert len(default_grid(quick=True)["passive"]) < len(currents)


def test_tradeoff_runs_and_averages_roads() -> None:
    grid = {
        "passive": [
            ("0 A", {"controller": {"law": "passive", "current": 0.0}}),
            ("0.3 A", {"controller": {"law": "passive", "current": 0.3}}),
        ]
    }
    one = tradeoff([ROAD], grid=grid, dt=5e-4, workers=1)
    other = Road.from_dict({"iso_class": "C", "length": 30.0, "seed": 4, "weight": 3.0})
    two = tradeoff([ROAD, other], grid=grid, dt=5e-4, workers=1)
    only_other = tradeoff([other], grid=grid, dt=5e-4, workers=1)
    for k in range(2):
        for m in ("wk_rms_body_acceleration", "DLC", "rms_stroke"):
            expected = 0.25 * one.points[k].measures[m] + 0.75 * only_other.points[k].measures[m]
            assert two.points[k].measures[m] == pytest.approx(expected)
    # a harder passive damper: less stroke, more body acceleration; both on the front
    soft, hard = one.points
    assert hard.measures["rms_stroke"] < soft.measures["rms_stroke"]
    assert hard.values[0] > soft.values[0]
    assert one.pareto(("wk_rms_body_acceleration", "rms_stroke")).tolist() == [True, True]
    fig = one.plot(extra={"best": soft.measures})
    assert len(fig.axes) == 2


def test_tradeoff_errors() -> None:
    raises_validation(lambda: tradeoff([], grid={}), "at least one road")
    raises_validation(lambda: tradeoff([ROAD], grid={}), "grid is empty")
    bad = {"passive": [("9 A", {"controller": {"law": "passive", "current": 9.0}})]}
    raises_validation(lambda: tradeoff([ROAD], grid=bad, dt=5e-4), "passive 9 A", "current")
