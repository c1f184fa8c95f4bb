"""``mrsus hil run`` takes its duration and engine step from the scenario's ``[simulation]``.

The scenario's ``dt`` is the engine step within each tick (``run_hil``'s ``model_dt``), as
it is the step of an offline run; the loop rate stays ``--rate`` (1 kHz by default, the
rig's), so a fine ``dt`` never asks for a loop the rig or the monitor cannot run.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import typer
from typer.testing import CliRunner

from mrsuspension.cli.hil import hil_run_command
from mrsuspension.hil import load_recording

SCENARIO = """
[controller]
law = "passive"
current = 0.1

[excitation]
kind = "harmonic"
frequency = 1.5
amplitude = 0.02

[simulation]
dt = 5e-5
duration = 3.0
"""


def _app() -> typer.Typer:
    app = typer.Typer(pretty_exceptions_enable=False)
    app.command("run")(hil_run_command)
    app.command("other")(lambda: None)
    return app


def test_hil_run_uses_the_scenarios_dt_and_duration(tmp_path: Path) -> None:
    scenario = tmp_path / "fine.toml"
    scenario.write_text(SCENARIO)
    out = tmp_path / "rec"
    res = CliRunner().invoke(
        _app(), ["run", str(scenario), "--rig", "ideal", "--out", str(out), "--json"]
    )
    assert res.exit_code == 0, res.output
    assert "duration 3 s and engine step dt = 5e-05 s from the scenario" in res.stderr
    info = json.loads(res.stdout)
    assert info["reason"] == "completed"
    rec = load_recording(out)
    assert rec.meta["duration"] == 3.0
    assert rec.meta["rate"] == 1000.0
    assert np.isclose(rec.meta["model_dt"], 5e-5)  # 20 engine steps per 1 ms tick
    assert np.isclose(np.median(np.diff(rec["time"])), 1e-3)
    assert info["stats"]["ticks"] >= 3000


def test_hil_run_options_win_and_a_bad_rate_is_refused_before_the_loop(tmp_path: Path) -> None:
    scenario = tmp_path / "fine.toml"
    scenario.write_text(SCENARIO)
    res = CliRunner().invoke(
        _app(),
        ["run", str(scenario), "--rig", "ideal", "--duration", "0.2", "--rate", "500", "--json"],
    )
    assert res.exit_code == 0, res.output
    assert "duration 3 s" not in res.stderr
    assert json.loads(res.stdout)["stats"]["ticks"] >= 100
    # the monitor streams at most 5 kHz: refused with the option named, before any work
    res = CliRunner().invoke(_app(), ["run", str(scenario), "--monitor", "--rate", "20000"])
    assert res.exit_code == 2
    assert "--rate" in res.stderr


def test_run_hil_takes_a_run_plan(tmp_path: Path) -> None:
    from mrsuspension.engine import RunSettings, Simulation
    from mrsuspension.excitation import Harmonic
    from mrsuspension.hil import ideal_rig, run_hil
    from mrsuspension.hil.loop import StartUp

    sim = Simulation(Harmonic(1.5, 0.02))
    plan = RunSettings(dt=2.5e-4, duration=0.5)
    run_hil(
        sim, ideal_rig(), settings=plan, out=tmp_path / "r", realtime="unpaced",
        startup=StartUp.none(),
    )  # fmt: skip
    meta = load_recording(tmp_path / "r").meta
    assert (meta["duration"], meta["rate"], meta["substeps"]) == (0.5, 1000.0, 4)
    assert np.isclose(meta["model_dt"], 2.5e-4)
