"""Study files: validation before any computation, expansion, caching, saving."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.studies import Study, run_study

SWEEP: dict[str, Any] = {
    "kind": "swept",
    "amplitude": 0.025,
    "frequencies": "log:3:1:6",
}


def _study(**tables: Any) -> dict[str, Any]:
    return {"excitation": dict(SWEEP), "simulation": {"dt": 5e-4}, **tables}


def test_grid_and_cases_expand_in_order() -> None:
    study = Study.from_dict(
        _study(
            grid={"vehicle.sprung_mass": [422.0, 563.0]},
            cases={
                "policy": {
                    "I": {"controller": {"law": "skyhook-hilo", "gain": 3.0}},
                    "IV": {"controller.law": "policy-iv", "controller.gain": 300.0},
                }
            },
        )
    )
    assert study.dims == ("vehicle.sprung_mass", "policy", "frequency")
    assert study.shape == (2, 2, 3)
    assert len(study) == 12 == len(study.simulations())
    s = study.scenarios[1]  # 422 kg, policy IV
    assert s.vehicle.sprung_mass == 422.0
    assert s.controller.law == "policy-iv"
    assert study.frequencies == pytest.approx((1.0, 6**0.5, 6.0))


def test_nested_grid_tables_are_fields() -> None:
    study = Study.from_dict(_study(grid={"vehicle": {"sprung_mass": [500.0, 600.0]}}))
    assert study.dims[0] == "vehicle.sprung_mass"


TOML = """
[study]
name = "masses"
measures = ["T_as", "DLC"]

[controller]
law = "skyhook-hilo"
mode = "ACM"

[excitation]
kind = "swept"
amplitude = 0.025
frequencies = [1.5, 4.0]

[simulation]
dt = 5e-4

[grid]
"vehicle.sprung_mass" = [422.0, 703.0]
"""


def test_load_toml(tmp_path: Path) -> None:
    path = tmp_path / "s.toml"
    path.write_text(TOML)
    study = Study.load(path)
    assert study.name == "masses"
    assert study.measures == ("T_as", "DLC")
    assert study.shape == (2, 2)


@pytest.mark.parametrize(
    ("tables", "message"),
    [
        ({"grid": {"vehicle.sprung_mas": [1.0]}}, "Did you mean 'vehicle.sprung_mass'"),
        ({"grid": {"vehicle.sprung_mass": []}}, "empty list"),
        ({"grid": {"vehicle.sprung_mass": 500.0}}, "must be a list"),
        ({"grid": {"vehicle.sprung_mass": [500.0, 500.0]}}, "given twice"),
        ({"grid": {"vehicle.sprung_mass": [500.0, -5.0]}}, "vehicle.sprung_mass=-5"),
        ({"grid": {"controller.law": ["skyhook-hilo", "skyhok"]}}, "Did you mean 'skyhook"),
        ({"grid": {"excitation.frequencies": [[1.0]]}}, "set in [excitation] frequencies"),
        ({"cases": {"policy": {}}}, "is empty"),
        ({"cases": {"policy": {"I": {"controller.gian": 3.0}}}}, "Did you mean 'controller.gain'"),
        ({"grdi": {}}, "Did you mean 'grid'"),
        ({"study": {"measures": ["T_ass"]}}, "Did you mean 'T_as'"),
        ({"study": {"measure": ["T_as"]}}, "Did you mean 'measures'"),
        ({"simulation": {"dt": 5e-4, "duration": 1.0}}, "too short for the harmonic measures"),
        ({"controller": {"law": "passive", "current": 0.8}}, "current"),
    ],
)
def test_bad_studies_fail_before_running(tables: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError) as err:
        Study.from_dict(_study(**tables))
    assert message in str(err.value)


def test_bad_frequency_spec() -> None:
    with pytest.raises(ValidationError, match="not a frequency spec"):
        Study.from_dict({"excitation": {**SWEEP, "frequencies": "log:3:1"}})


def test_hash_changes_with_content() -> None:
    a = Study.from_dict(_study(grid={"vehicle.sprung_mass": [422.0, 563.0]}))
    b = Study.from_dict(_study(grid={"vehicle.sprung_mass": [422.0, 563.0]}))
    c = Study.from_dict(_study(grid={"vehicle.sprung_mass": [422.0, 564.0]}))
    assert a.content_hash() == b.content_hash() != c.content_hash()


def test_run_cache_and_save(tmp_path: Path) -> None:
    study = Study.from_dict(
        _study(
            grid={"controller.current": [0.0, 0.2]},
            controller={"law": "passive"},
            study={"measures": ["T_as", "mean_current"]},
        )
    )
    calls: list[tuple[int, int]] = []
    first = run_study(
        study, workers=1, progress=lambda d, t: calls.append((d, t)), cache_dir=tmp_path
    )
    assert not first.from_cache
    assert calls[-1] == (6, 6)
    ds = first.to_xarray()
    assert ds["T_as"].dims == ("controller_current", "frequency")
    assert ds["controller_current"].attrs["field"] == "controller.current"
    assert ds["mean_current"].sel(controller_current=0.2).values == pytest.approx(0.2)
    assert "amplitude" in ds.coords
    again = run_study(study, workers=1, progress=False, cache_dir=tmp_path)
    assert again.from_cache
    assert (again["T_as"].values == first["T_as"].values).all()
    nc = first.save(tmp_path / "out" / "r.nc")
    csv = first.save(tmp_path / "out" / "r.csv")
    import xarray as xr

    with xr.open_dataset(nc) as back:
        assert float(back["T_as"].sum()) == pytest.approx(float(ds["T_as"].sum()))
        units = {k: back[k].attrs.get("units") for k in [*back.data_vars, *back.coords]}
    assert units == {
        "T_as": "-",
        "mean_current": "A",
        "controller_current": "A",
        "frequency": "Hz",
        "amplitude": "m",
    }
    assert again.to_xarray()["mean_current"].attrs["units"] == "A"
    df = first.to_pandas()
    assert list(df.columns[:2]) == ["controller_current", "frequency"]
    assert len(df) == 6
    assert csv.with_suffix(".json").is_file()
    with pytest.raises(ValidationError, match=r"use \.nc"):
        first.save(tmp_path / "r.xlsx")


def test_pulse_study_without_frequency_dim() -> None:
    study = Study.from_dict(
        {
            "excitation": {"kind": "pulse", "amplitude": 0.05, "severity": 3},
            "simulation": {"dt": 5e-4, "duration": 3.0},
            "grid": {"excitation.speed": [50.0, 100.0]},
            "study": {"measures": ["SAR_s", "RDR"]},
        }
    )
    res = run_study(study, workers=1, progress=False, cache_dir=False)
    assert res["SAR_s"].dims == ("excitation_speed",)
    assert res["SAR_s"].notnull().all()


def test_pulse_study_road_peak() -> None:
    tables = {
        "excitation": {"kind": "pulse", "amplitude": 0.035, "severity": 3},
        "simulation": {"dt": 5e-4, "duration": 2.0},
        "grid": {"vehicle.sprung_mass": [563.0]},
        "study": {"measures": ["SDR_s", "SAR_s", "SAR_u"]},
    }
    after = Study.from_dict(tables)
    assert after.road_peak == "after-onset"  # the dissertation-matching default
    onset = Study.from_dict({**tables, "study": {**tables["study"], "road_peak": "onset"}})
    assert onset.content_hash() != after.content_hash()  # cached results stay apart
    assert after.describe()["road_peak"] == "after-onset"
    a = run_study(after, workers=1, progress=False, cache_dir=False)
    o = run_study(onset, workers=1, progress=False, cache_dir=False)
    assert a.dataset.attrs["road_peak"] == "after-onset"
    assert o.dataset.attrs["road_peak"] == "onset"
    assert float(a["SDR_s"][0]) == float(o["SDR_s"][0])
    for k in ("SAR_s", "SAR_u"):
        assert float(a[k][0]) / float(o[k][0]) == pytest.approx(4.854, rel=2e-3)
    with pytest.raises(ValidationError, match=r"\[study\] road_peak must be one of"):
        Study.from_dict({**tables, "study": {"road_peak": "first"}})
    # not a pulse study: no road_peak in its identity or description
    harmonic = Study.from_dict(
        {"excitation": {"kind": "harmonic", "frequency": 5.0, "amplitude": 0.01}}
    )
    assert "road_peak" not in harmonic.canonical()
    assert "road_peak" not in harmonic.describe()
