"""Live hooks of the HiL loop: tap, external STOP, settings applied between ticks."""

from __future__ import annotations

import dataclasses
import queue
from typing import Any

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.control import HiLo, Passive
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import Harmonic, RoundedPulse
from mrsuspension.hil import StartUp, ideal_rig, run_hil
from mrsuspension.hil.driver import PICurrentDriver
from mrsuspension.hil.loop import CHANNELS, LiveChange, LoopHooks, tick_step
from mrsuspension.hil.tap import TapRing
from mrsuspension.vehicle import QuarterCar

RATE = 1000.0


def _sim(controller: Any = None) -> Simulation:
    return Simulation(
        Harmonic(1.5, 0.02), controller=controller or HiLo(1, mode="ACM"), max_current=0.3
    )


class LateQueue:
    """A settings queue that hands out its item at the ``after``-th poll (deterministic)."""

    def __init__(self, item: Any, after: int) -> None:
        self.item = item
        self.after = after
        self.polls = 0

    def get_nowait(self) -> Any:
        self.polls += 1
        if self.polls == self.after:
            return self.item
        raise queue.Empty


class LateEvent:
    """An event that reads as set from the ``after``-th check on."""

    def __init__(self, after: int) -> None:
        self.after = after
        self.checks = 0

    def is_set(self) -> bool:
        self.checks += 1
        return self.checks >= self.after


def _run(sim: Simulation, hooks: LoopHooks | None, duration: float = 1.0) -> Any:
    return run_hil(
        sim, ideal_rig(sim.damper), duration=duration, rate=RATE, realtime=False,
        startup=StartUp.none(), hooks=hooks,
    )  # fmt: skip


def _drain(q: queue.Queue[Any]) -> list[tuple[str, Any]]:
    out = []
    while not q.empty():
        out.append(q.get_nowait())
    return out


def test_empty_hooks_change_nothing() -> None:
    sim = _sim()
    plain = _run(sim, None)
    hooked = _run(sim, LoopHooks())
    for name in ("z_s", "x_d", "i_cmd", "F_T"):
        np.testing.assert_allclose(hooked.recording[name], plain.recording[name], atol=1e-12)


def test_tap_streams_decimated_rows_and_status() -> None:
    tap: queue.Queue[Any] = queue.Queue(maxsize=1000)
    hooks = LoopHooks(tap=tap, tap_every=5, tap_batch=50, status_every=100)
    result = _run(_sim(), hooks)
    msgs = _drain(tap)
    rows = [r for kind, m in msgs if kind == "data" for r in m]
    assert all(len(r) == len(CHANNELS) for r in rows)
    running = int(np.count_nonzero(result.recording["state"] <= 1))
    assert abs(len(rows) - result.stats.ticks / 5) <= 2
    times = np.array([r[0] for r in rows])
    assert np.allclose(np.diff(times)[: running // 5 - 1], 5 / RATE)
    statuses = [m for kind, m in msgs if kind == "status"]
    assert statuses[-1]["state"] == "ended"
    assert statuses[-1]["safe"]
    assert statuses[0]["ticks"] == 100
    assert statuses[0]["state"] == "running"
    assert hooks.dropped == 0


def test_full_tap_drops_and_never_blocks() -> None:
    tap: queue.Queue[Any] = queue.Queue(maxsize=2)
    hooks = LoopHooks(tap=tap, tap_every=1, tap_batch=10)
    result = _run(_sim(), hooks)
    assert result.reason == "completed"
    assert hooks.dropped > 50
    assert tap.qsize() == 2


def test_external_stop_takes_the_safety_path() -> None:
    sim = _sim(Passive(0.3))
    hooks = LoopHooks(stop=LateEvent(after=400))
    result = _run(sim, hooks, duration=2.0)
    rec = result.recording
    assert result.tripped
    assert result.reason == "STOP pressed"
    k = int(np.argmax(rec["state"] == 3))
    assert k == 399  # the tick that saw it
    assert rec["i_cmd"][k - 1] > 0.25
    assert rec["i_cmd"][k] == 0.0
    assert np.all(rec["i_cmd"][k:] == 0.0)
    assert abs(rec["x_cmd"][-1]) < 1e-12  # back at mid-stroke
    assert rec.stop["reason"] == "STOP pressed"


def test_settings_change_between_ticks() -> None:
    sim = _sim()
    heavier = dataclasses.replace(sim, vehicle=QuarterCar(sprung_mass=800.0))
    tap: queue.Queue[Any] = queue.Queue()
    hooks = LoopHooks(tap=tap, settings=LateQueue(heavier, after=31), poll_every=10)
    changed = _run(sim, hooks)
    plain = _run(sim, None)
    k = 300  # 31st poll, every 10 ticks from tick 0
    a, b = changed.recording["z_s"], plain.recording["z_s"]
    np.testing.assert_allclose(a[:k], b[:k], atol=1e-12)
    assert np.max(np.abs(a[k + 50 : 1000] - b[k + 50 : 1000])) > 1e-4
    applied = [m for kind, m in _drain(tap) if kind == "applied"]
    assert len(applied) == 1
    assert applied[0]["time"] == pytest.approx(k / RATE)
    assert not applied[0]["controller"]
    assert applied[0]["ramp_ticks"] == 0


@pytest.mark.parametrize("ramp_time", [0.1, 0.2])
def test_controller_change_ramps_the_current(ramp_time: float) -> None:
    sim = _sim(Passive(0.0))
    switched = dataclasses.replace(sim, controller=Passive(0.3))
    hooks = LoopHooks(settings=LateQueue(switched, after=21), poll_every=10, ramp_time=ramp_time)
    result = _run(sim, hooks)
    i = result.recording["i_cmd"]
    lsb = PICurrentDriver().da_full_scale / (1 << PICurrentDriver().bits)
    bound = 0.3 / ramp_time / RATE
    k = 200
    assert i[k - 1] == 0.0
    assert np.max(np.diff(i[k - 1 : k + round(ramp_time * RATE) + 5])) <= bound + lsb
    # it gets there: full current once the ramp is over
    assert i[k + round(ramp_time * RATE) + 5] == pytest.approx(0.3, abs=lsb)


def test_change_carries_its_own_ramp_time() -> None:
    sim = _sim(Passive(0.0))
    switched = LiveChange.prepare(
        dataclasses.replace(sim, controller=Passive(0.3)), sim, RATE, ramp_time=0.5
    )
    hooks = LoopHooks(settings=LateQueue(switched, after=21), poll_every=10, ramp_time=0.1)
    i = _run(sim, hooks).recording["i_cmd"]
    lsb = PICurrentDriver().da_full_scale / (1 << PICurrentDriver().bits)
    assert np.max(np.diff(i[199:800])) <= 0.3 / 0.5 / RATE + lsb
    assert i[450] < 0.2  # half-way up a 0.5 s ramp, not yet at 0.3 A
    raises_validation(lambda: LiveChange(sim, ramp_time=0.0), "ramp_time")


def test_without_ramp_the_switch_jumps() -> None:  # the ramp test above can fail
    sim = _sim(Passive(0.0))
    switched = dataclasses.replace(sim, controller=Passive(0.3))
    hooks = LoopHooks(settings=LateQueue(switched, after=21), poll_every=10, ramp_time=1e-6)
    i = _run(sim, hooks).recording["i_cmd"]
    assert np.max(np.diff(i)) > 0.25


def test_excitation_change_cross_fades_the_road() -> None:
    sim = _sim()
    faster = dataclasses.replace(sim, excitation=Harmonic(4.0, 0.01))
    hooks = LoopHooks(settings=LateQueue(faster, after=31), poll_every=10, ramp_time=0.2)
    rec = _run(sim, hooks, duration=1.5).recording
    zr = rec["z_r"]
    # no jump: the largest tick-to-tick change stays that of the faster harmonic
    assert np.max(np.abs(np.diff(zr[:1500]))) < 2 * np.pi * 4.0 * 0.01 / RATE * 1.5
    # after the fade, the new harmonic on its own clock from the change (t = 0.3 s)
    t = rec["time"][700:1500]
    new = Harmonic(4.0, 0.01).displacement(t + 1e-3 - 0.3)
    np.testing.assert_allclose(zr[700:1500], new, atol=1e-9)


def test_a_live_pulse_comes_after_the_change() -> None:
    sim = _sim()
    pulse = dataclasses.replace(sim, excitation=RoundedPulse(0.05, 1.0, 50.0, delay=0.2))
    hooks = LoopHooks(settings=LateQueue(pulse, after=101), poll_every=10, ramp_time=0.1)
    rec = _run(sim, hooks, duration=2.5).recording
    zr, t = rec["z_r"], rec["time"]
    peak = t[int(np.argmax(zr))]
    assert 1.2 < peak < 1.2 + pulse.excitation.pulse_duration  # change at 1.0 s + delay
    assert zr.max() == pytest.approx(0.05, rel=0.05)


def test_bad_change_is_rejected_and_the_run_goes_on() -> None:
    tap: queue.Queue[Any] = queue.Queue()
    hooks = LoopHooks(tap=tap, settings=LateQueue({"sprung_mass": -1}, after=5))
    result = _run(_sim(), hooks)
    assert result.reason == "completed"
    rejected = [m for kind, m in _drain(tap) if kind == "rejected"]
    assert len(rejected) == 1
    assert "Simulation" in rejected[0]["error"]


def test_hooks_validation() -> None:
    raises_validation(lambda: LoopHooks(tap_every=0), "tap_every", ">= 1")
    raises_validation(lambda: LoopHooks(ramp_time=0.0), "ramp_time")


def test_stepper_update_keeps_the_state() -> None:
    sim = _sim()
    stepper = sim.stepper(1e-4)
    for _ in range(100):
        out = stepper.step(0.01, 0.0)
    before = stepper.y.copy()
    stepper.update(dataclasses.replace(sim, vehicle=QuarterCar(sprung_mass=700.0)))
    np.testing.assert_array_equal(stepper.y, before)
    assert stepper.simulation.vehicle.sprung_mass == 700.0
    after = stepper.step(0.01, 0.0)
    assert after["z_s"] != out["z_s"]
    raises_validation(
        lambda: stepper.update(dataclasses.replace(sim, vehicle=QuarterCar(unsprung_mass=0.5))),
        "dt",
    )


def test_prepared_change_matches_a_raw_one() -> None:
    sim = _sim()
    new = dataclasses.replace(
        sim, controller=HiLo(1, mode="SCM"), vehicle=QuarterCar(sprung_mass=650.0)
    )
    change = LiveChange.prepare(new, sim, RATE)
    assert change.controller
    assert not change.excitation
    assert change.arrays is not None
    assert change.dt == tick_step(RATE)
    raw = _run(sim, LoopHooks(settings=LateQueue(new, after=21), poll_every=10))
    prepared = _run(sim, LoopHooks(settings=LateQueue(change, after=21), poll_every=10))
    np.testing.assert_array_equal(prepared.recording["z_s"], raw.recording["z_s"])
    np.testing.assert_array_equal(prepared.recording["i_cmd"], raw.recording["i_cmd"])
    plain = _run(sim, None)
    n = 1000  # the running part (the return to mid-stroke differs in length)
    assert np.max(np.abs(raw.recording["z_s"][:n] - plain.recording["z_s"][:n])) > 1e-5
    raises_validation(
        lambda: LiveChange.prepare(
            dataclasses.replace(sim, vehicle=QuarterCar(unsprung_mass=0.5)), sim, RATE
        ),
        "dt",
    )


def test_ring_tap_takes_rows_and_status() -> None:
    ring = TapRing(len(CHANNELS), capacity=4096)
    tap: queue.Queue[Any] = queue.Queue()
    hooks = LoopHooks(tap=tap, ring=ring, tap_every=5, status_every=100, stop=LateEvent(after=700))
    result = _run(_sim(), hooks)
    rows, lost = ring.read()
    assert lost == 0
    assert abs(len(rows) - result.stats.ticks / 5) <= 2
    np.testing.assert_allclose(np.diff(rows[:50, 0]), 5 / RATE)
    st = ring.status()
    assert st["seq"] >= 6
    assert st["tripped"] == 1.0
    assert st["state_code"] == 3.0
    # the queue only carried the start (before the clock), the trip (once) and the end
    msgs = _drain(tap)
    assert [kind for kind, _ in msgs] == ["started", "status", "status"]
    assert msgs[1][1]["reason"] == "STOP pressed"
    assert msgs[2][1]["state"] == "ended"


def test_live_status_counts_each_miss_once() -> None:
    from mrsuspension.hil.loop import _live_status
    from mrsuspension.hil.safety import SafetySupervisor

    hooks = LoopHooks(status_every=100)
    compute = np.full(1000, 1e-4)
    lateness = np.zeros(1000)
    compute[[50, 150, 160, 990]] = 2e-3  # four misses at 1 kHz
    sup = SafetySupervisor()
    for k in (100, 130, 200, 300, 1000):  # 130: an extra status (e.g. at a trip)
        st = _live_status(hooks, sup, 1, k, compute, lateness, 1e-3, 0.0)
    assert st["misses"] == 4
