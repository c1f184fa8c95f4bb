"""Monitor settings (page -> validated simulation) and acquisition (what is downloaded)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.control import Passive
from mrsuspension.dampers import LinearViscous
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import Harmonic
from mrsuspension.hil.recorder import Recording
from mrsuspension.monitor.acquisition import Acquisition, acquisition_from_settings
from mrsuspension.monitor.settings import ZeroRoad, page_fields, scenario_from_settings


def test_vehicle_fields_and_ramp() -> None:
    s = scenario_from_settings({"sprung_mass": "700", "tire_stiffness": 250000, "ramp_time": "0.5"})
    sim = s.simulation()
    assert sim.vehicle.sprung_mass == 700.0
    assert sim.vehicle.tire_stiffness == 250000.0
    assert s.ramp_time == 0.5
    assert page_fields(sim)["sprung_mass"] == 700.0
    raises_validation(lambda: scenario_from_settings({"ramp_time": 0}), "ramp time", "(0, 5]")
    raises_validation(lambda: scenario_from_settings({"unsprung_mass": -1}), "unsprung_mass")
    raises_validation(lambda: scenario_from_settings({"frequency": 0}), "frequency")


def test_zero_input_is_a_real_zero_road() -> None:
    sim = scenario_from_settings({"excitation": "zero"}).simulation()
    assert isinstance(sim.excitation, ZeroRoad)
    assert sim.excitation.velocity(np.arange(3.0)).tolist() == [0.0, 0.0, 0.0]


def test_base_keeps_the_damper() -> None:
    base = Simulation(Harmonic(1.0, 0.01), damper=LinearViscous(damping=1500.0), max_current=0.3)
    sim = scenario_from_settings(
        {"controller": "passive", "current": 0.0, "sprung_mass": 600}
    ).simulation(base)
    assert sim.damper is base.damper
    assert sim.vehicle.sprung_mass == 600.0
    assert isinstance(sim.controller, Passive)
    # the inverse-model laws need the dissertation's damper: refused on this base
    bad = scenario_from_settings({"controller": "inverse-hilo"})
    raises_validation(lambda: bad.simulation(base), "wang-symmetric")


def test_road_files_only_from_road_dir(tmp_path: Path) -> None:
    raises_validation(
        lambda: scenario_from_settings({"excitation": "road", "profile": "file", "road_file": "x"}),
        "not enabled",
    )
    raises_validation(
        lambda: scenario_from_settings(
            {"excitation": "road", "profile": "file", "road_file": "../etc/passwd"}, tmp_path
        ),
        "not a file in",
    )
    raises_validation(
        lambda: scenario_from_settings({"excitation": "road", "profile": "bumpy"}),
        "unknown road preset 'bumpy'",
    )


def _rec(n: int = 1000, rate: float = 1000.0) -> Recording:
    t = np.arange(n) / rate
    return Recording(
        {"time": t, "z_r": np.sin(2 * np.pi * 2.0 * t - 3.0), "i_cmd": np.full(n, 0.1)}
    )


def test_acquisition_period_and_windows(tmp_path: Path) -> None:
    rec = _rec()
    assert Acquisition().select(rec).size == 1000
    assert Acquisition(period=4).select(rec).tolist()[:3] == [0, 4, 8]
    acq = Acquisition().start(0.2).stop(0.3).start(0.7)
    assert acq.recording
    idx = acq.select(rec)
    t = rec["time"][idx]
    assert t.min() == pytest.approx(0.2)
    assert t.max() == pytest.approx(0.999)
    assert not np.any((t >= 0.3) & (t < 0.7))
    path, rows = acq.stop(0.8).export(rec, tmp_path / "a.csv")
    lines = path.read_text().splitlines()
    assert lines[0] == "time,z_r,i_cmd"
    assert rows == len(lines) - 1 == 200


def test_acquisition_trigger_with_pre_trigger() -> None:
    rec = _rec()
    t = rec["time"]
    first_up = t[np.flatnonzero((rec["z_r"][:-1] < 0) & (rec["z_r"][1:] >= 0))[0] + 1]
    idx = Acquisition(trigger="z_r", level=0.0, pre_trigger=0.05).select(rec)
    assert t[idx[0]] == pytest.approx(first_up - 0.05)
    assert t[idx[-1]] == pytest.approx(t[-1])
    down = Acquisition(trigger="z_r", level=0.5, edge="falling").select(rec)
    assert rec["z_r"][down[0]] <= 0.5 < rec["z_r"][down[0] - 1]
    assert Acquisition(trigger="i_cmd", level=0.5).select(rec).size == 0  # never fires


def test_acquisition_validation() -> None:
    acq = Acquisition()
    raises_validation(lambda: acquisition_from_settings({"acq_period": 0}, acq), "period")
    raises_validation(lambda: acquisition_from_settings({"acq_period": 1.5}, acq), "whole")
    raises_validation(lambda: acquisition_from_settings({"trigger": "nope"}, acq), "trigger")
    raises_validation(lambda: acquisition_from_settings({"trigger_edge": "up"}, acq), "edge")
    raises_validation(lambda: acquisition_from_settings({"pre_trigger": -1}, acq), "pre-trigger")
    raises_validation(lambda: acquisition_from_settings({"display_rate": 33}, acq), "display")
    new = acquisition_from_settings(
        {"acq_period": "10", "trigger": "x_d", "trigger_level": "0.01", "display_rate": "50"}, acq
    )
    assert (new.period, new.trigger, new.level, new.display_rate) == (10, "x_d", 0.01, 50.0)


def test_shaping_factors_override_the_mode() -> None:
    acm = scenario_from_settings({"controller": "skyhook-hilo", "mode": "ACM"}).simulation()
    assert acm.controller.p == 0.0
    half = scenario_from_settings(
        {"controller": "inverse-hilo", "mode": "ACM", "p": "0.5", "xi": "8", "xi_c": ""}
    ).simulation()
    assert (half.controller.p, half.controller.xi) == (0.5, 8.0)
    assert page_fields(half)["p"] == 0.5
    raises_validation(
        lambda: scenario_from_settings({"controller": "sliding-mode", "p": 2}).simulation(), "p"
    )
