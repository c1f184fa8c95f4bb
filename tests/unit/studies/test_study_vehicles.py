"""Studies over half- and full-car scenarios: vehicle and per-corner fields, measures."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.studies import Study, run_study

ROOT = Path(__file__).resolve().parents[3]
BUMP = {"kind": "bump", "side": "left", "height": 0.02, "length": 0.5, "position": 1.0}


def test_per_corner_fields_and_vehicle_measures() -> None:
    st = Study.from_dict(
        {
            "study": {"measures": ["roll_ddot_rms", "DLC.front_left"]},
            "vehicle": {"model": "full-car"},
            "excitation": BUMP,
            "simulation": {"duration": 0.8},
            "grid": {
                "damper": {"front_left": {"force_gain": [1.0, 1.5]}},
                "vehicle.roll_inertia": [300.0, 400.0],
            },
        }
    )
    assert st.dims == ("damper.front_left.force_gain", "vehicle.roll_inertia")
    gains = [
        s.vehicle_simulations()[0].corner_simulation("front_left").damper.force_gain
        for s in st.scenarios
    ]
    assert gains == [1.0, 1.0, 1.5, 1.5]
    other = st.scenarios[-1].vehicle_simulations()[0].corner_simulation("front_right")
    assert other.damper.force_gain == 1.0
    result = run_study(st, workers=1, progress=False, cache_dir=False)
    ds = result.to_xarray()
    assert ds["roll_ddot_rms"].attrs["units"] == "rad/s^2"
    assert ds["DLC"].dims == ("damper_front_left_force_gain", "vehicle_roll_inertia", "corner")
    assert ds["DLC"].attrs["units"] == "-"
    assert float(result["DLC.front_left"].min()) > 0.0
    assert ds["vehicle_roll_inertia"].attrs["units"] == "kg m^2"
    assert float(ds["roll_ddot_rms"].min()) > 0.0


def test_errors() -> None:
    base = {"vehicle": {"model": "full-car"}, "excitation": BUMP}
    with pytest.raises(
        ValidationError, match=re.escape("unknown field 'damper.front_lef.force_gain'")
    ):
        Study.from_dict({**base, "grid": {"damper.front_lef.force_gain": [1.0]}})
    with pytest.raises(ValidationError, match=re.escape("Did you mean 'DLC.front_left'")):
        Study.from_dict({**base, "study": {"measures": ["DLC.front_lef"]}, "grid": {}})
    with pytest.raises(ValidationError, match=re.escape("unknown corner table [damper.front]")):
        Study.from_dict({**base, "grid": {"damper.front.force_gain": [1.0]}})


def test_the_example_loads() -> None:
    st = Study.load(ROOT / "examples" / "studies" / "full-car-bump-corners.toml")
    assert len(st) == 4
    assert "controller.front_left.current" in st.dims
