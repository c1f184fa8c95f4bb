"""One test per safety trip: current 0 in the trip tick, return to mid-stroke, complete record."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from _rig_faults import check_interlock_stop, faulty_rig
from mrsuspension.control import HiLo, Passive
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import Harmonic
from mrsuspension.hil import (
    HilResult,
    PICurrentDriver,
    RigSample,
    SafetyLimits,
    SafetySupervisor,
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


# -- interlocks: non-finite and impossible readings (issue 26) ------------------------------
NAN, INF = float("nan"), float("inf")
GOOD = {"force": 1200.0, "displacement": 0.02, "current": 0.15}


def _sample(sup: SafetySupervisor, t: float, stamp: float | None = None, **bad: float) -> bool:
    values = {**GOOD, **bad}
    return sup.check_sample(
        t, values["force"], values["displacement"], values["current"], t if stamp is None else stamp
    )


@pytest.mark.audit("rig interlocks")
@pytest.mark.parametrize(
    ("bad", "reason"),
    [
        ({"current": NAN}, "measured current is nan A: the rig's reading is not a number"),
        ({"force": NAN}, "load-cell force is nan N: the rig's reading is not a number"),
        ({"displacement": NAN}, "measured stroke is nan m: the rig's reading is not a number"),
        ({"current": INF}, "measured current is inf A: the rig's reading is not finite"),
        ({"force": -INF}, "load-cell force is -inf N: the rig's reading is not finite"),
        ({"displacement": INF}, "measured stroke is inf m: the rig's reading is not finite"),
        (
            {"current": -5.0},
            "measured current -5 A is below -0.02 A: impossible from a unipolar driver "
            "(a sensor or wiring fault)",
        ),
        ({"current": -0.0201}, "measured current -0.0201 A is below -0.02 A: impossible"),
        ({"current": 5.0}, "measured drive current 5.0000 A exceeds 0.3 A (+0.02 A tolerance)"),
        (
            {"displacement": -0.25},
            "measured stroke -0.25 m is beyond the actuator's travel +/-0.1 m: impossible "
            "reading (a sensor or wiring fault)",
        ),
        ({"force": 9000.0}, "load-cell force 9000.0 N exceeds 8800 N"),
    ],
    ids=[
        "nan-current", "nan-force", "nan-displacement", "inf-current", "minus-inf-force",
        "inf-displacement", "minus-5A", "just-below-0A", "5A", "beyond-travel", "over-force",
    ],
)  # fmt: skip
def test_interlock_trips_on_a_bad_reading(bad: dict[str, float], reason: str) -> None:
    sup = SafetySupervisor()
    assert not _sample(sup, 0.0)  # a healthy reading first
    assert _sample(sup, 1e-3, **bad)
    assert sup.tripped
    assert sup.reason.startswith(reason), sup.reason
    assert "\n" not in sup.reason
    assert sup.trip_time == 1e-3


@pytest.mark.audit("rig interlocks")
def test_interlock_passes_healthy_edges() -> None:
    sup = SafetySupervisor()
    # noise about 0 A (sense offset, A/D steps) and readings at the limits are healthy
    for k, bad in enumerate(
        [
            {"current": -0.02},
            {"current": 0.0},
            {"current": 0.32},
            {"displacement": -0.1},
            {"displacement": 0.1},
            {"force": -8800.0},
        ]
    ):
        assert not _sample(sup, k * 1e-3, **bad), (bad, sup.reason)
    # a bipolar driver may drive the current either way; |current| is checked
    bipolar = SafetySupervisor(SafetyLimits(unipolar=False))
    assert not _sample(bipolar, 0.0, current=-0.3)
    assert _sample(bipolar, 1e-3, current=-0.33)
    assert bipolar.reason.startswith("measured drive current -0.3300 A exceeds 0.3 A")
    # a stroke limit tighter than the travel trips as a limit, not as a fault
    tight = SafetySupervisor(SafetyLimits(stroke=0.05))
    assert _sample(tight, 0.0, displacement=0.06)
    assert tight.reason == "measured stroke 0.0600 m exceeds +/-0.05 m"


@pytest.mark.audit("rig interlocks")
def test_interlock_rig_timestamp() -> None:
    # non-finite at once
    for stamp, word in ((NAN, "nan"), (INF, "inf")):
        sup = SafetySupervisor()
        assert not _sample(sup, 0.0, stamp=0.0)
        assert _sample(sup, 1e-3, stamp=stamp)
        assert sup.reason.startswith(f"rig timestamp is {word} s: the rig's reading is not")
    # backwards at once
    sup = SafetySupervisor()
    assert not _sample(sup, 0.0, stamp=0.5)
    assert not _sample(sup, 1e-3, stamp=0.501)
    assert _sample(sup, 2e-3, stamp=0.2)
    assert sup.reason.startswith("rig timestamp went backwards: 0.2 s after 0.501 s")
    # stalled: held until the watchdog's 50 ms, then a trip
    sup = SafetySupervisor()
    assert not _sample(sup, 0.0, stamp=1.0)
    assert not _sample(sup, 0.05, stamp=1.0)
    assert _sample(sup, 0.0501, stamp=1.0)
    assert sup.reason.startswith("rig watchdog: no fresh sample for 0.0501 s (limit 0.05 s)")


@pytest.mark.audit("rig interlocks")
@pytest.mark.parametrize(
    ("stroke", "velocity", "current", "reason"),
    [
        (0.01, 0.2, NAN, "drive current command is nan A: the controller gave a value that is"),
        (0.01, 0.2, -INF, "drive current command is -inf A: the controller gave a value that"),
        (NAN, 0.2, 0.1, "stroke command is nan m: the vehicle model gave a value that is not"),
        (0.01, INF, 0.1, "stroke velocity command is inf m/s: the vehicle model gave a value"),
        (0.01, 0.2, 0.31, "drive current command 0.3100 A exceeds 0.3 A"),
        (-0.11, 0.2, 0.1, "stroke command -0.1100 m exceeds +/-0.1 m"),
        (0.01, -1.6, 0.1, "stroke velocity -1.600 m/s exceeds 1.5 m/s"),
    ],
    ids=["nan-current", "minus-inf-current", "nan-stroke", "inf-velocity", "over-current",
         "over-stroke", "over-velocity"],
)  # fmt: skip
def test_interlock_trips_on_a_bad_command(
    stroke: float, velocity: float, current: float, reason: str
) -> None:
    sup = SafetySupervisor()
    assert not sup.check_command(0.0, 0.01, 0.2, 0.1)
    assert not sup.check_command(0.0, 0.0, 0.0, -0.1)  # a negative demand: the driver gives 0
    assert sup.check_command(1e-3, stroke, velocity, current)
    assert sup.reason.startswith(reason), sup.reason


@pytest.mark.audit("rig interlocks")
def test_driver_never_raises_on_non_finite_values() -> None:
    drv = PICurrentDriver()
    drv.reset(1e-3)
    assert drv.update(0.2, 0.1) > 0.0
    for ref, sense in ((0.2, NAN), (0.2, INF), (0.2, -INF), (NAN, 0.1), (INF, 0.0)):
        drv.update(0.2, 0.1)  # wind the integrator up a little
        assert drv.update(ref, sense) == 0.0
        assert drv.output == 0.0
        assert drv.integral == 0.0  # not poisoned: the next good tick regulates again
    assert 0.0 < drv.update(0.2, 0.1) <= drv.current_limit
    for ref in (NAN, INF, -INF):
        assert drv.direct(ref) == 0.0
    assert PICurrentDriver(bits=0).direct(NAN) == 0.0


@pytest.mark.audit("rig interlocks")
@pytest.mark.parametrize(
    ("channel", "value", "reason"),
    [
        ("current", NAN, "measured current is nan A: the rig's reading is not a number"),
        ("displacement", NAN, "measured stroke is nan m: the rig's reading is not a number"),
        ("force", NAN, "load-cell force is nan N: the rig's reading is not a number"),
        ("force", INF, "load-cell force is inf N: the rig's reading is not finite"),
        ("current", -5.0, "measured current -5 A is below -0.02 A: impossible from a unipolar"),
        ("timestamp", 0.0, "rig timestamp went backwards: 0 s after 0.198 s"),
    ],
    ids=["nan-current", "nan-displacement", "nan-force", "inf-force", "minus-5A", "clock-back"],
)
def test_simulated_rig_fault_trips_and_homes(
    tmp_path: Path, channel: str, value: float, reason: str
) -> None:
    sim = Simulation(Harmonic(1.5, 0.01), controller=HiLo(1, mode="ACM"), max_current=0.3)
    rig = faulty_rig(sim.damper, channel, value, at=200)
    out = tmp_path / "rec"
    result = run_hil(
        sim, rig, duration=0.5, rate=RATE, out=out, startup=StartUp.none(), realtime="unpaced"
    )
    trip = check_interlock_stop(result, rig, reason, out)
    assert trip == 199  # the tick of the first bad reading (read 200 after the reset)
    assert (
        rig.true_state["current"]
        < 0.3 * np.exp(-(len(result.recording) - trip) / RATE / 0.008) + 1e-3
    )
