"""Units wherever numbers leave the program: the measures table and Parquet metadata."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from mrsuspension.engine.result import (
    MEASURE_NOTES,
    MEASURE_UNITS,
    MEASURES_BY_KIND,
    PARQUET_METADATA_KEY,
    SimulationResult,
)
from mrsuspension.errors import ValidationError


def test_every_measure_has_a_unit() -> None:
    names = {m for kind in MEASURES_BY_KIND.values() for m in kind}
    assert names - set(MEASURE_UNITS) == set()
    notes = {n for kind in MEASURE_NOTES.values() for n in kind}
    assert notes.isdisjoint(MEASURE_UNITS)  # notes are not numbers


def test_measure_units_are_the_spec_units() -> None:
    ratios = ["T_as", "T_au", "T_dr", "DLC", "gamma", "SDR_s", "SAR_s", "RDR"]
    assert {MEASURE_UNITS[k] for k in ratios} == {"-"}
    assert MEASURE_UNITS["mean_current"] == "A"
    assert MEASURE_UNITS["mean_square_current"] == "A^2"
    assert MEASURE_UNITS["peak_tire_force"] == "N"
    assert MEASURE_UNITS["rms_body_acceleration"] == "m/s^2"
    assert MEASURE_UNITS["vdv"] == "m/s^1.75"
    assert MEASURE_UNITS["rms_stroke"] == "m"


def _result() -> SimulationResult:
    t = np.linspace(0.0, 1.0, 11)
    scenario = {"excitation": {"kind": "harmonic", "frequency": 1.5}, "controller": {"law": "x"}}
    return SimulationResult(t, {"F_d": np.sin(t), "i_d": np.cos(t)}, scenario, dt=1e-3)


def test_parquet_keeps_scenario_and_units(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    res = _result()
    path = res.save(tmp_path / "run.parquet")
    meta = json.loads(pq.read_schema(path).metadata[PARQUET_METADATA_KEY.encode()])
    assert meta["scenario"] == res.scenario
    assert meta["units"] == {"time": "s", "F_d": "N", "i_d": "A"}
    back = SimulationResult.load(path)
    assert back.scenario == res.scenario
    assert back.dt == res.dt
    assert dict(back.units) == {"time": "s", "F_d": "N", "i_d": "A"}
    np.testing.assert_array_equal(back.time, res.time)
    np.testing.assert_array_equal(back.F_d, res.F_d)


def test_netcdf_loads_back(tmp_path: Path) -> None:
    res = _result()
    back = SimulationResult.load(res.save(tmp_path / "run.nc"))
    assert back.scenario == res.scenario
    assert back.units["i_d"] == "A"
    np.testing.assert_array_equal(back.i_d, res.i_d)


def test_parquet_without_pyarrow_names_the_extra(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "pyarrow" else real(name, *a)
    )
    with pytest.raises(ValidationError, match=r"mrsuspension\[data\]"):
        _result().save(tmp_path / "run.parquet")
    assert not (tmp_path / "run.parquet").exists()


def test_load_rejects_foreign_files(tmp_path: Path) -> None:
    with pytest.raises(ValidationError, match=r"use \.parquet or \.nc"):
        SimulationResult.load(tmp_path / "run.csv")
    with pytest.raises(ValidationError, match="no result file"):
        SimulationResult.load(tmp_path / "missing.parquet")
