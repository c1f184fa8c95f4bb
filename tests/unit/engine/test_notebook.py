"""The notebook conventions of the results (issue 31, item 3), one test per convention.

``_repr_html_`` and a short ``__repr__``; ``plot(ax=)`` without pyplot; ``to_pandas()`` by
plain name with units in ``df.attrs``; xarray with a ``corner`` dimension, CF-style
``units``/``long_name`` and valid dimension names; ``measures()`` carrying units.
"""

from __future__ import annotations

import json
import pickle
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mrsuspension._notebook import new_figure, with_unit_headers
from mrsuspension.engine import Measures, Simulation, SimulationResult
from mrsuspension.engine.result import MEASURE_UNITS
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import Harmonic

HARMONIC = Harmonic(5.0, 0.005)
BUMP = {"kind": "bump", "side": "left", "height": 0.02, "length": 0.5, "position": 0.5}


@pytest.fixture(scope="module")
def quarter() -> SimulationResult:
    """A quarter-car run long enough for its harmonic measures (steady-state rule)."""
    return Simulation(HARMONIC).run(dt=5e-4)


@pytest.fixture(scope="module")
def half() -> Any:
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import WheelRoads
    from mrsuspension.vehicle import HalfCar

    road = WheelRoads.in_phase(HARMONIC, "half-car")
    return VehicleSimulation(HalfCar(), road).run(dt=2e-4)


@pytest.fixture(scope="module")
def studies(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """A quarter-car study over a dotted field and a half-car study with corner measures."""
    from mrsuspension.studies import Study, run_study

    quarter = Study.from_dict(
        {
            "study": {"name": "currents", "measures": ["T_as", "mean_current"]},
            "excitation": {"kind": "harmonic", "frequency": 5.0, "amplitude": 0.005},
            "simulation": {"dt": 5e-4},
            "grid": {"controller.current": [0.0, 0.2]},
        }
    )
    vehicle = Study.from_dict(
        {
            "study": {"measures": ["heave_ddot_rms", "DLC.front", "DLC.rear", "rms_stroke.rear"]},
            "vehicle": {"model": "half-car"},
            "excitation": BUMP,
            "simulation": {"duration": 0.5, "dt": 2e-4},
            "grid": {"vehicle.pitch_inertia": [700.0, 900.0]},
        }
    )
    folder = tmp_path_factory.mktemp("notebook")
    return {
        "quarter": run_study(quarter, workers=1, progress=False, cache_dir=False),
        "vehicle": run_study(vehicle, workers=1, progress=False, cache_dir=folder),
        "vehicle_study": vehicle,
        "cache": folder,
    }


# -- _repr_html_ and a short __repr__ ------------------------------------------------------
def test_repr_is_one_short_line_and_html_a_summary_table(
    quarter: SimulationResult, half: Any, studies: dict[str, Any]
) -> None:
    text = repr(quarter)
    assert "\n" not in text
    assert len(text) < 200
    assert text.startswith("SimulationResult(quarter car, wang-symmetric damper, passive")
    assert "harmonic 5 Hz, 5 mm" in text
    assert "dt 0.5 ms" in text
    page = quarter._repr_html_()
    m = quarter.measures()
    for cell in ("model", "excitation", "duration", "dt", "0.5 ms", "mean_current", "A^2"):
        assert cell in page, cell
    assert f"{m['T_as']:.4g}" in page  # the measure's value, beside its unit
    short = Simulation(HARMONIC).run(0.2, dt=5e-4)
    assert "measures</th><td" in short._repr_html_()  # too short: said, not raised
    assert "not available: record too short" in short._repr_html_()

    vtext = repr(half)
    assert vtext.startswith("VehicleResult(half-car (2 corners)")
    assert "array(" not in vtext
    assert len(vtext) < 250
    vpage = half._repr_html_()
    assert '<th style="text-align:left">front</th>' in vpage  # a column per corner
    assert "rad/s^2" in vpage

    study = studies["quarter"]
    stext = repr(study)
    assert stext == ("StudyResult('currents': 2 runs over controller_current (2); 2 measures)")
    spage = study._repr_html_()
    assert "dimension controller_current" in spage
    assert "(controller.current)" in spage
    assert "<details>" in spage  # the data set itself, folded


# -- plot(ax=) without pyplot ---------------------------------------------------------------
def test_plot_makes_no_pyplot_figure_and_draws_into_given_axes(
    quarter: SimulationResult, half: Any
) -> None:
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    from mrsuspension.dampers import LinearViscous

    before = plt.get_fignums()
    fig = quarter.plot()
    assert isinstance(fig, Figure)
    assert len(fig.axes) == 5
    assert plt.get_fignums() == before  # not managed by pyplot: shown once in Jupyter
    small = Simulation(HARMONIC).run(0.05, dt=5e-4).plot(("F_d",))
    assert small._repr_png_().startswith(b"\x89PNG")  # Jupyter shows it without pyplot
    axes = new_figure(6.0, 4.0).subplots(2, 1)
    out = quarter.plot(("F_d", "F_T"), ax=axes)
    assert out is axes
    assert [a.get_ylabel() for a in axes] == ["F_d [N]", "F_T [N]"]
    assert len(axes[0].get_lines()) == 1
    one = new_figure(6.0, 4.0).subplots()
    assert quarter.plot(("F_d", "F_target"), ax=one, title="forces") is one
    assert len(one.get_lines()) == 2
    assert one.get_legend() is not None
    assert one.get_title() == "forces"
    with pytest.raises(ValidationError, match="2 Axes for 3 signals"):
        quarter.plot(("F_d", "F_T", "i_d"), ax=list(axes))
    vaxes = new_figure(6.0, 4.0).subplots(2, 1)
    assert half.plot(("heave_ddot", "F_T.rear"), ax=vaxes) is vaxes
    t = np.linspace(0.0, 1.0, 201)
    response = LinearViscous(damping=1000.0).response(t, 0.01 * np.sin(2 * np.pi * t))
    ax = response.plot()
    assert ax.get_xlabel() == "damper velocity $v_d$ [m/s]"
    assert plt.get_fignums() == before
    rdf = response.to_pandas()
    assert rdf.attrs["units"]["force"] == "N"
    np.testing.assert_array_equal(rdf["force"].to_numpy(), response.force)


# -- to_pandas: plain names, units in attrs ----------------------------------------------
def test_to_pandas_plain_names_units_in_attrs(
    quarter: SimulationResult, half: Any, tmp_path: Path
) -> None:
    df = quarter.to_pandas()
    np.testing.assert_array_equal(df["z_s"].to_numpy(), quarter.z_s)
    assert df.index.name == "time"
    assert df.attrs["units"]["z_s"] == "m"
    assert df.attrs["units"]["time"] == "s"
    assert set(df.attrs["units"]) == {"time", *quarter.signals}
    assert not any("[" in c for c in df.columns)
    labelled = with_unit_headers(df)
    assert list(labelled.columns[:2]) == ["z_s [m]", "z_u [m]"]
    assert labelled.index.name == "time [s]"
    header = quarter.save(tmp_path / "run.csv").read_text().splitlines()[0]
    assert header.split(",")[:3] == ["time [s]", "z_s [m]", "z_u [m]"]  # CSV keeps units

    vdf = half.to_pandas()
    np.testing.assert_array_equal(vdf["F_T.rear"].to_numpy(), half["F_T.rear"])
    assert vdf.attrs["units"]["F_T.rear"] == "N"
    assert vdf.attrs["units"]["pitch"] == "rad"


def test_parquet_of_either_naming_loads(quarter: SimulationResult, tmp_path: Path) -> None:
    pa = pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    from mrsuspension.engine.result import PARQUET_METADATA_KEY

    new = SimulationResult.load(quarter.save(tmp_path / "new.parquet"))
    assert pq.read_table(tmp_path / "new.parquet").column_names[0] == "z_s"
    np.testing.assert_array_equal(new.F_d, quarter.F_d)
    # a file written before: columns "name [unit]", mapped in the metadata
    labels = {"time": "time [s]", **{k: f"{k} [{quarter.units[k]}]" for k in quarter.signals}}
    table = pa.table({labels[k]: quarter[k] for k in labels})
    meta = {"scenario": quarter.scenario, "dt": quarter.dt, "columns": labels,
            "units": {k: quarter.units[k] for k in labels}}  # fmt: skip
    entry = {PARQUET_METADATA_KEY.encode(): json.dumps(meta, default=str).encode()}
    pq.write_table(table.replace_schema_metadata(entry), tmp_path / "old.parquet")
    old = SimulationResult.load(tmp_path / "old.parquet")
    np.testing.assert_array_equal(old.F_d, quarter.F_d)
    assert old.units["F_d"] == "N"


def test_study_to_pandas_units_and_fields(studies: dict[str, Any], tmp_path: Path) -> None:
    df = studies["quarter"].to_pandas()
    assert list(df.columns) == ["controller_current", "T_as", "mean_current"]
    assert df.attrs["units"] == {"controller_current": "A", "T_as": "-", "mean_current": "A"}
    assert df.attrs["fields"] == {"controller_current": "controller.current"}
    vdf = studies["vehicle"].to_pandas()
    assert list(vdf.columns) == [
        "vehicle_pitch_inertia", "heave_ddot_rms", "DLC.front", "DLC.rear", "rms_stroke.rear"
    ]  # fmt: skip
    assert vdf.attrs["units"]["rms_stroke.rear"] == "m"
    header = studies["vehicle"].save(tmp_path / "s.csv").read_text().splitlines()[0]
    assert header.startswith("vehicle_pitch_inertia [kg m^2],heave_ddot_rms [m/s^2],DLC.front [-]")


# -- xarray: corner dimension, CF attributes, valid names ----------------------------------
def test_vehicle_xarray_has_a_corner_dimension_and_round_trips(half: Any, tmp_path: Path) -> None:
    import xarray as xr

    from mrsuspension.engine.vehicle_result import VehicleResult

    ds = half.to_xarray()
    assert ds["F_T"].dims == ("time", "corner")
    assert ds["corner"].values.tolist() == ["front", "rear"]
    np.testing.assert_array_equal(ds["F_T"].sel(corner="rear").values, half["F_T.rear"])
    assert not [n for n in ds.variables if "." in str(n)]
    for name in ds.data_vars:
        assert ds[name].attrs["units"], name
        assert ds[name].attrs["long_name"], name
    assert ds["F_T"].attrs == {"units": "N", "long_name": "tire force (total, 0 when lifted off)"}
    back = VehicleResult.load(half.save(tmp_path / "v.nc"))
    assert back.corners == half.corners
    assert back.corner_scenarios == half.corner_scenarios
    for key in half.signals:
        np.testing.assert_array_equal(back[key], half[key])
    assert back.corner("rear").measures()["DLC"] == half.corner("rear").measures()["DLC"]
    # a file written before: one flat variable per corner signal
    flat = xr.Dataset(
        {k: ("time", v, {"units": half.units[k]}) for k, v in half.signals.items()},
        coords={"time": half.time},
        attrs={"scenario": json.dumps(half.scenario, default=str), "dt": half.dt},
    )
    flat.to_netcdf(tmp_path / "old.nc")
    old = VehicleResult.load(tmp_path / "old.nc")
    assert old.corners == ("front", "rear")
    np.testing.assert_array_equal(old["F_T.rear"], half["F_T.rear"])


def test_study_dataset_follows_cf_and_reads_old_cache_files(studies: dict[str, Any]) -> None:
    from mrsuspension.studies import run_study
    from mrsuspension.studies.run import cache_key

    ds = studies["quarter"].to_xarray()
    assert ds["T_as"].dims == ("controller_current",)
    assert ds["controller_current"].attrs == {
        "units": "A", "field": "controller.current", "long_name": "controller.current"
    }  # fmt: skip
    assert ds["T_as"].attrs["long_name"] == "sprung-mass acceleration transmissibility"
    vds = studies["vehicle"].to_xarray()
    assert vds["DLC"].dims == ("vehicle_pitch_inertia", "corner")
    assert vds["corner"].values.tolist() == ["front", "rear"]
    assert vds["heave_ddot_rms"].dims == ("vehicle_pitch_inertia",)
    assert vds["rms_stroke"].sel(corner="front").isnull().all()  # not kept for the front
    assert float(studies["vehicle"]["DLC.rear"][0]) == float(vds["DLC"].sel(corner="rear")[0])
    for name in [*vds.data_vars, "vehicle_pitch_inertia"]:
        assert {"units", "long_name"} <= set(vds[name].attrs), name
    with pytest.raises(ValidationError, match=re.escape("Did you mean 'DLC.rear'")):
        studies["vehicle"]["DLC.raer"]
    # a cache file of the earlier layout (dotted dimension, "DLC.front" variables)
    old = vds.copy()
    for name in ("DLC", "rms_stroke"):
        for c in ("front", "rear"):
            old[f"{name}.{c}"] = vds[name].sel(corner=c, drop=True)
    old = old.drop_vars(["DLC", "rms_stroke", "corner"]).drop_vars("rms_stroke.front")
    old = old.rename({"vehicle_pitch_inertia": "vehicle.pitch_inertia"})
    path = studies["cache"] / f"{cache_key(studies['vehicle_study'])}.nc"
    path.unlink()
    old.to_netcdf(path)
    again = run_study(
        studies["vehicle_study"], workers=1, progress=False, cache_dir=studies["cache"]
    )
    assert again.from_cache
    assert again.to_xarray()["DLC"].dims == ("vehicle_pitch_inertia", "corner")
    np.testing.assert_array_equal(again["DLC.front"].values, studies["vehicle"]["DLC.front"].values)
    assert again.to_pandas().columns.tolist() == studies["vehicle"].to_pandas().columns.tolist()


def test_a_case_table_may_not_take_a_dimension_name() -> None:
    from mrsuspension.studies import Study

    base = {"excitation": {"kind": "harmonic", "frequency": 5.0, "amplitude": 0.005}}
    taken = "the name 'controller_current' is taken (the dimension of controller.current)"
    with pytest.raises(ValidationError, match=re.escape(taken)):
        Study.from_dict(
            {
                **base,
                "grid": {"controller.current": [0.0, 0.1]},
                "cases": {"controller_current": {"a": {"damper.force_gain": 1.0}}},
            }
        )
    with pytest.raises(ValidationError, match="the name 'corner' is taken"):
        Study.from_dict({**base, "cases": {"corner": {"a": {"controller.current": 0.1}}}})
    alone = Study.from_dict(
        {**base, "cases": {"controller_current": {"a": {"controller.current": 0.1}}}}
    )
    assert alone.dims == ("controller_current",)  # no field of that name: a valid case name


# -- measures() carrying units ---------------------------------------------------------------
def test_measures_carry_units_and_stay_a_dict(quarter: SimulationResult, half: Any) -> None:
    m = quarter.measures()
    assert isinstance(m, dict)
    assert isinstance(m, Measures)
    assert dict(m) == m
    assert m.units == {k: MEASURE_UNITS[k] for k in m}
    assert m["mean_current"] + 1.0 == pytest.approx(1.0)  # passive 0 A: float arithmetic
    assert json.loads(json.dumps(m)) == pytest.approx(dict(m))
    back = pickle.loads(pickle.dumps(m))  # a process pool's reducer sends it back
    assert back == m
    assert back.units == m.units
    series = m.to_series()
    assert series["T_as"] == m["T_as"]
    assert series.attrs["units"]["mean_square_current"] == "A^2"
    assert m.label("mean_current") == "mean_current [A]"
    assert "<table>" in m._repr_html_()
    vm = half.measures()
    assert vm.units["pitch_ddot_rms"] == "rad/s^2"
    assert vm.units["DLC.rear"] == "-"
    assert vm.units["mean_current.front"] == "A"
    assert set(vm.units) == set(vm)
    seat = half.vehicle_measures()
    assert seat.units["lift_off_time.front"] == "s"
    assert seat.units["coil_energy"] == "J"
    assert set(seat.units) == set(seat)
