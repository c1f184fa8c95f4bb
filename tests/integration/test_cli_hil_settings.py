"""``mrsus hil run`` takes its duration and rate from the scenario's ``[simulation]``."""

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
    scenario = tmp_path / "fast.toml"
    scenario.write_text(SCENARIO)
    out = tmp_path / "rec"
    res = CliRunner().invoke(
        _app(), ["run", str(scenario), "--rig", "ideal", "--out", str(out), "--json"]
    )
    assert res.exit_code == 0, res.output
    assert "duration 3 s from [simulation] duration" in res.stderr
    assert "rate 20000 Hz from [simulation] dt = 5e-05 s" in res.stderr
    info = json.loads(res.stdout)
    assert info["reason"] == "completed"
    rec = load_recording(out)
    assert rec.meta["rate"] == 20000.0
    assert rec.meta["duration"] == 3.0
    assert np.isclose(np.median(np.diff(rec["time"])), 5e-5)
    assert info["stats"]["ticks"] >= 60000  # 3 s at 20 kHz (plus the start-up and return)


def test_hil_run_options_win_and_a_too_fast_scenario_is_refused(tmp_path: Path) -> None:
    scenario = tmp_path / "fast.toml"
    scenario.write_text(SCENARIO)
    res = CliRunner().invoke(
        _app(),
        ["run", str(scenario), "--rig", "ideal", "--duration", "0.2", "--rate", "500", "--json"],
    )
    assert res.exit_code == 0, res.output
    assert "from [simulation]" not in res.stderr
    assert json.loads(res.stdout)["stats"]["ticks"] >= 100
    # the monitor runs at most 5 kHz: a 20 kHz scenario needs an explicit --rate
    res = CliRunner().invoke(_app(), ["run", str(scenario), "--monitor"])
    assert res.exit_code == 2
    assert "asks for a 20000 Hz loop" in res.stderr
    assert "give --rate" in res.stderr
