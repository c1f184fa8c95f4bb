"""One test per safety trip: current 0 in the trip tick, return to mid-stroke, complete record."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mrsuspension.control import HiLo, Passive
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import Harmonic
from mrsuspension.hil import (
    HilResult,
    RigSample,
    SafetyLimits,
    SimulatedRig,
    StartUp,
    load_recording,
    run_hil,
)
from mrsuspension.hil.loop import STATE_TRIPPED

RATE = 1000.0


class FreezingRig(SimulatedRig):
    """A rig whose readings stop updating after ``freeze_after`` reads (a dead link)."""

    freeze_after: int = 300

    def reset(self, period: float) -> None:
        super().reset(period)
        self._reads = 0
        self._frozen: RigSample | None = None

    def read(self) -> RigSample:
        self._reads += 1
        if self._frozen is not None:
            return self._frozen
        sample = super().read()
        if self._reads >= self.freeze_after:
            self._frozen = sample
        return sample


class ShortedRig(SimulatedRig):
    """An amplifier fault: the coil current runs away whatever the command."""

    def read(self) -> RigSample:
        sample = super().read()
        t = sample.timestamp
        return sample._replace(current=sample.current + (0.4 if t > 0.5 else 0.0))


def _run(tmp_path: Path, sim: Simulation, limits: SafetyLimits, **kw: object) -> HilResult:
    rig = kw.pop("rig", None) or SimulatedRig(sim.damper)
    return run_hil(
        sim, rig, duration=3.0, rate=RATE, out=tmp_path / "rec", limits=limits,
        startup=StartUp.none(), realtime=False, **kw,  # type: ignore[arg-type]
    )  # fmt: skip


def _check_safe_stop(result: HilResult, reason: str, tmp_path: Path) -> int:
    rec = result.recording
    assert result.tripped
    assert reason in result.reason
    state = rec["state"]
    trip = int(np.argmax(state == STATE_TRIPPED))
    assert state[trip] == STATE_TRIPPED
    assert np.all(state[trip:] == STATE_TRIPPED)
    assert np.all(state[:trip] < STATE_TRIPPED)
    # current 0 within one tick: the trip tick's command is already 0
    assert np.all(rec["i_cmd"][trip:] == 0.0)
    # the actuator is ramped back and ends at mid-stroke
    assert rec["x_cmd"][-1] == 0.0
    assert abs(rec["x_m"][-1]) < 3e-3
    step = SafetyLimits().return_rate / RATE
    assert np.all(np.abs(np.diff(rec["x_cmd"][trip:])) <= step + 1e-12)
    # the recording on disk is complete and states the reason
    back = load_recording(tmp_path / "rec")
    assert back.complete
    assert reason in back.reason
    assert len(back) == len(rec) == int(back.stop["rows"])
    np.testing.assert_allclose(back["time"], np.arange(len(back)) / RATE, rtol=0, atol=1e-9)
    return trip


def test_over_current_command_trips(tmp_path: Path) -> None:
    sim = Simulation(Harmonic(1.5, 0.02), controller=Passive(current=0.4), max_current=0.5)
    result = _run(tmp_path, sim, SafetyLimits(), cap_current=False)
    trip = _check_safe_stop(result, "drive current command", tmp_path)
    assert trip == 0
    assert result.recording["i_cmd"].max() == 0.0


def test_measured_over_current_trips(tmp_path: Path) -> None:
    sim = Simulation(Harmonic(1.5, 0.02), controller=Passive(current=0.1), max_current=0.3)
    result = _run(tmp_path, sim, SafetyLimits(), rig=ShortedRig(sim.damper))
    trip = _check_safe_stop(result, "measured drive current", tmp_path)
    assert trip == pytest.approx(500, abs=2)


def test_stroke_trips(tmp_path: Path) -> None:
    sim = Simulation(Harmonic(1.5, 0.05), controller=HiLo(1, mode="ACM"), max_current=0.3)
    result = _run(tmp_path, sim, SafetyLimits(stroke=0.01, velocity=10.0))
    trip = _check_safe_stop(result, "stroke", tmp_path)
    assert np.abs(result.recording["x_m"][:trip]).max() <= 0.0105


def test_velocity_trips(tmp_path: Path) -> None:
    sim = Simulation(Harmonic(1.5, 0.02), controller=HiLo(1, mode="ACM"), max_current=0.3)
    result = _run(tmp_path, sim, SafetyLimits(velocity=0.05))
    trip = _check_safe_stop(result, "velocity", tmp_path)
    assert trip > 0


def test_force_trips(tmp_path: Path) -> None:
    sim = Simulation(Harmonic(1.5, 0.02), controller=Passive(current=0.2), max_current=0.3)
    result = _run(tmp_path, sim, SafetyLimits(force=300.0))
    trip = _check_safe_stop(result, "load-cell force", tmp_path)
    assert abs(result.recording["F_dm"][trip]) > 300.0


def test_rig_timeout_trips(tmp_path: Path) -> None:
    sim = Simulation(Harmonic(1.5, 0.02), controller=Passive(current=0.0), max_current=0.3)
    rig = FreezingRig(sim.damper)
    result = _run(tmp_path, sim, SafetyLimits(watchdog=0.02), rig=rig)
    rec = result.recording
    trip = int(np.argmax(rec["state"] == STATE_TRIPPED))
    assert "watchdog" in result.reason
    # frozen from read 300 (tick 299): the watchdog trips after its 20 ms timeout
    assert trip == pytest.approx(299 + 21, abs=2)
    assert np.all(rec["i_cmd"][trip:] == 0.0)
    assert rec["x_cmd"][-1] == 0.0
    # the readings are stale, but the actuator really went home
    assert abs(rig.true_state["displacement"]) < 1e-3
    back = load_recording(tmp_path / "rec")
    assert back.complete
    assert "watchdog" in back.reason


def test_startup_ramp(tmp_path: Path) -> None:
    sim = Simulation(Harmonic(1.5, 0.02), controller=HiLo(1, mode="ACM"), max_current=0.3)
    startup = StartUp(duration=0.5, damping=800.0)
    result = run_hil(
        sim, SimulatedRig(sim.damper), duration=1.0, rate=RATE, startup=startup, realtime=False
    )
    rec = result.recording
    n = int(0.5 * RATE)
    assert not result.tripped
    assert result.reason == "completed"
    assert np.all(rec["state"][: n - 1] == 0)
    assert np.all(rec["state"][n:1000] == 1)
    assert np.all(rec["i_cmd"][: n - 1] == 0.0)  # current held at 0
    extra = rec["F_d"] - rec["F_dm"]
    assert np.abs(extra[:50]).max() > 0.0  # extra damping at first
    assert np.all(extra[n:1000] == 0.0)  # removed after the ramp
    assert rec["i_cmd"][n:1000].max() > 0.0
