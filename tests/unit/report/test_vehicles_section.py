"""The report section "Beyond the quarter car" (``mrsus reproduce --chapters vehicles``)
and the findings it shows, checked on its own quick-mode numbers."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mrsuspension.control import HiLo
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import WheelRoads, preset_road
from mrsuspension.report import vehicles as V
from mrsuspension.report.chapters import SECTIONS
from mrsuspension.vehicle import FullCar


@pytest.fixture(scope="module")
def data() -> dict[str, Any]:
    return V.compute(quick=True)


def _full(data: dict[str, Any], road: str, controller: str, sensing: str = "ideal") -> dict:
    return next(
        r for r in data["rows"]
        if r["model"] == "full car" and r["road"] == road and r["controller"] == controller
        and r["sensing"] == sensing
    )  # fmt: skip


def test_section_is_registered() -> None:
    assert "vehicles" in SECTIONS


def test_table_has_every_model_controller_and_road(data: dict[str, Any]) -> None:
    rows = data["rows"]
    for road in V.ROADS:
        for controller in V.CONTROLLERS:
            assert _full(data, road, controller)["heave RMS [m/s^2]"] > 0.0
        quarter = [r for r in rows if r["model"] == "quarter car" and r["road"] == road]
        assert len(quarter) == 2  # passive and skyhook hi-lo ACM (no modal on one corner)
        assert all(math.isnan(r["pitch RMS [rad/s^2]"]) for r in quarter)
    assert len(data["costs"]) == 4


def test_per_corner_skyhook_reduces_heave_on_the_rough_road(data: dict[str, Any]) -> None:
    road = V.ROADS[0]
    passive = _full(data, road, V.CONTROLLERS[0])["heave RMS [m/s^2]"]
    assert _full(data, road, V.CONTROLLERS[1])["heave RMS [m/s^2]"] < passive
    # modal skyhook (hi-lo between 0 and 0.5 A) does not: on this road the damper at 0 A
    # is the softest setting; the section reports it (issue note) rather than this test
    # forcing the expected sign
    assert _full(data, road, V.CONTROLLERS[2])["heave RMS [m/s^2]"] > 0.0


def test_roll_is_zero_with_symmetric_input_and_excited_by_the_bump(data: dict[str, Any]) -> None:
    car = FullCar(cg_to_front=1.3, cg_to_rear=1.3, front_track=1.5, rear_track=1.5)
    road = WheelRoads.from_excitation(preset_road("rough"), car, speed_kmh=50.0)
    res = VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM")).run(2.0, dt=2e-4)
    assert np.max(np.abs(res["roll"])) < 1e-15
    assert np.max(np.abs(res["roll_ddot"])) < 1e-12
    for controller in V.CONTROLLERS:
        assert _full(data, V.ROADS[1], controller)["roll RMS [rad/s^2]"] > 0.1


def test_estimator_costs_less_than_a_fifth_of_the_skyhook_gain(data: dict[str, Any]) -> None:
    for row in data["costs"]:
        if row["controller"] != V.CONTROLLERS[1]:
            continue
        gain = row["controller's heave RMS change vs passive [%]"]
        assert gain < 0.0
        assert abs(row["heave RMS change vs ideal [%]"]) < 0.2 * abs(gain)
        assert abs(row["seat Wk RMS change vs ideal [%]"]) < 5.0
        assert abs(row["mean DLC change vs ideal [%]"]) < 5.0


def test_build_writes_figures_tables_and_manifest(
    data: dict[str, Any], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(V, "compute", lambda quick, progress=None: data)
    body, info = V.build(tmp_path / "vehicles", True, lambda _msg: None)
    assert "id='vehicles'" in body
    assert [f["number"] for f in info["figures"]] == ["V.1", "V.2"]
    for f in info["figures"]:
        assert (tmp_path / "vehicles" / f["files"][0]).stat().st_size > 5000
    csv = (tmp_path / "vehicles" / "vehicle_measures.csv").read_text().splitlines()
    assert len(csv) == 1 + len(data["rows"])
    json.dumps(info, default=float)  # the manifest entry is plain data
