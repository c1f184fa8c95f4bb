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
from mrsuspension.excitation import Harmonic, RoadProfile, RoundedPulse, preset_road
from mrsuspension.hil import StartUp, ideal_rig, run_hil
from mrsuspension.hil.driver import PICurrentDriver
from mrsuspension.hil.live import _Road, live_chunk
from mrsuspension.hil.loop import CHANNELS, LiveChange, LoopHooks, tick_step
from mrsuspension.hil.tap import TapRing
from mrsuspension.monitor.settings import ZeroRoad
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
    # 3 cm (a 5 cm bump on top of the 2 cm harmonic drives the stroke past the supervisor's
    # 1.5 m/s limit with the vehicle defaults: cycle-rms, v_h of (2.13))
    pulse = dataclasses.replace(sim, excitation=RoundedPulse(0.03, 1.0, 50.0, delay=0.2))
    hooks = LoopHooks(settings=LateQueue(pulse, after=101), poll_every=10, ramp_time=0.1)
    result = _run(sim, hooks, duration=2.5)
    assert not result.tripped, result.reason
    rec = result.recording
    zr, t = rec["z_r"], rec["time"]
    peak = t[int(np.argmax(zr))]
    assert 1.2 < peak < 1.2 + pulse.excitation.pulse_duration  # change at 1.0 s + delay
    assert zr.max() == pytest.approx(0.03, rel=0.05)


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


# -- the live road: blocks of a few ticks ------------------------------------------------
N_SUB, DT = 10, 1e-4  # 1 kHz, the engine's 1e-4 s step
PERIOD = N_SUB * DT
CHUNK = live_chunk(N_SUB)


class Pointwise:
    """A road input with only displacement/velocity (no fast grid); NaN from ``bad`` on."""

    def __init__(self, inner: Any, bad: float = np.inf) -> None:
        self.inner = inner
        self.bad = bad
        self.duration = 10.0
        self.calls = 0

    def displacement(self, t: Any) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        return np.where(t < self.bad, self.inner.displacement(t), np.nan)

    def velocity(self, t: Any) -> np.ndarray:
        return np.asarray(self.inner.velocity(t), dtype=float)

    def acceleration(self, t: Any) -> np.ndarray:
        return np.asarray(self.inner.acceleration(t), dtype=float)

    def describe(self) -> dict[str, Any]:
        return {"kind": "pointwise", "inner": self.inner.describe(), "bad": self.bad}


class OldGrid(Pointwise):
    """A fast grid of the old signature ``sample_grid(n, step)`` (from 0 only): not used live."""

    def sample_grid(self, n: int, step: float) -> tuple[np.ndarray, np.ndarray]:
        raise AssertionError("the live road must not call a grid without a start")


class FastGrid(Pointwise):
    """A grid from any start (counted), NaN in the velocity from ``bad`` on."""

    def sample_grid(self, n: int, step: float, start: float = 0.0) -> Any:
        self.calls += 1
        t = start + np.arange(n) * step
        return self.inner.displacement(t), np.where(t < self.bad, self.inner.velocity(t), np.nan)


def _road(exc: Any, config: str = "live") -> _Road:
    """The live loop's road (one tick per block with a compiled grid), or fixed blocks."""
    return _Road(exc, N_SUB, DT, CHUNK, fast_chunk=1 if config == "live" else None)


def _live(
    road: _Road, ticks: range, chunks: list[int] | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The road of ``ticks`` as the loop takes it (a block every ``chunk`` ticks from the
    first), one row of 2 n_sub + 1 half steps per tick, and their times."""
    zs, vs, ts = [], [], []
    k_road = ticks[0] - road.chunk
    z: list[float] = []
    v: list[float] = []
    for k in ticks:
        if k - k_road >= road.chunk:
            k_road = k
            z, v = road.block(k)
            assert len(z) == len(v) == 2 * N_SUB * road.chunk + 1
            if chunks is not None:
                chunks.append(road.chunk)
        j = 2 * N_SUB * (k - k_road)
        zs.append(z[j : j + 2 * N_SUB + 1])
        vs.append(v[j : j + 2 * N_SUB + 1])
        ts.append(k * N_SUB * DT + np.arange(2 * N_SUB + 1) * (0.5 * DT))
    return np.array(zs), np.array(vs), np.array(ts)


LIVE_INPUTS = {
    "harmonic": Harmonic(7.0, 0.02),
    "road": preset_road("rough", fade_in=2.0),
    "uneven-road": RoadProfile([0.0, 0.4, 0.5, 1.7, 2.0, 30.1], [0, 0.01, -0.004, 0.02, 0, 0.003]),
    "pulse": RoundedPulse(0.05, 2.0, delay=0.01),
    "pointwise": Pointwise(Harmonic(7.0, 0.02)),
    "old-grid": OldGrid(Harmonic(7.0, 0.02)),
    "fast-grid": FastGrid(Harmonic(7.0, 0.02)),
    "zero": ZeroRoad(),
}


FAST = ("harmonic", "road", "uneven-road", "pulse", "fast-grid", "zero")


@pytest.mark.parametrize("config", ["live", "fixed"])
@pytest.mark.parametrize("name", list(LIVE_INPUTS))
def test_live_road_is_the_pointwise_road_across_blocks(name: str, config: str) -> None:
    exc = LIVE_INPUTS[name]
    assert 1 < CHUNK < 50  # several blocks below
    road = _road(exc, config)
    every = np.linspace(0.0, 13.0, 13001)  # the size of the signal (the tolerances' scale)
    scale_z = max(np.max(np.abs(exc.displacement(every))), 1e-3)
    scale_v = max(np.max(np.abs(exc.velocity(every))), 1e-2)
    for ticks in (range(0, 4 * CHUNK + 2), range(12_345, 12_345 + 3 * CHUNK)):
        chunks: list[int] = []
        z, v, t = _live(road, ticks, chunks)
        z0, v0 = exc.displacement(t.ravel()), exc.velocity(t.ravel())
        np.testing.assert_allclose(z.ravel(), z0, rtol=0, atol=1e-12 * scale_z)
        np.testing.assert_allclose(v.ravel(), v0, rtol=0, atol=1e-12 * scale_v)
        # each tick ends where the next one starts
        np.testing.assert_allclose(z[1:, 0], z[:-1, -1], rtol=0, atol=1e-12 * scale_z)
        # one tick at a time with a compiled grid in the loop, else a few
        assert set(chunks) == {1 if config == "live" and name in FAST else CHUNK}
    if name == "fast-grid":
        assert exc.calls >= 6  # (block 0 is pointwise, the others through the grid)


@pytest.mark.parametrize("name", ["harmonic", "road", "pulse"])
def test_live_road_starts_with_the_whole_run_road(name: str) -> None:
    """The first block is the start of the road of the loop without hooks, bit for bit."""
    exc = LIVE_INPUTS[name]
    whole = _Road(exc, N_SUB, DT, 100).block(0)
    for config in ("live", "fixed"):
        live = _road(exc, config).block(0)
        for a, b in zip(live, whole, strict=True):
            assert a == b[: len(a)]


@pytest.mark.parametrize(
    ("old", "new", "chunk"),
    [
        ("harmonic", "road", 1),
        ("pulse", "zero", 1),
        ("pointwise", "pulse", 1),  # a few ticks at a time while the pointwise one fades out
        ("harmonic", "pointwise", CHUNK),
    ],
)
def test_live_road_cross_fades_by_the_formula(old: str, new: str, chunk: int) -> None:
    a, b = LIVE_INPUTS[old], LIVE_INPUTS[new]
    road = _road(a)
    k_s = 3 * CHUNK + 2  # inside a block: the loop asks for a new one from the change
    fade = 0.025
    _live(road, range(k_s))
    t_s = k_s * PERIOD
    road.switch(b, t_s, fade)
    chunks: list[int] = []
    ticks = range(k_s, k_s + round(fade / PERIOD) + 3 * CHUNK)  # through the fade and past
    z, v, t = _live(road, ticks, chunks)
    t = t.ravel()
    s = np.clip((t - t_s) / fade, 0.0, 1.0)
    w = s * s * (3.0 - 2.0 * s)
    dw = np.where((s > 0.0) & (s < 1.0), 6.0 * s * (1.0 - s) / fade, 0.0)
    za, va = a.displacement(t), a.velocity(t)
    zb, vb = b.displacement(t - t_s), b.velocity(t - t_s)  # the new one on its own clock
    np.testing.assert_allclose(z.ravel(), (1 - w) * za + w * zb, rtol=0, atol=1e-14)
    np.testing.assert_allclose(v.ravel(), (1 - w) * va + w * vb + dw * (zb - za), atol=1e-12)
    assert 0.0 < w[5] < w[-1] == 1.0  # faded
    assert road.old is None  # and over
    assert chunks[-1] == chunk
    assert chunks[0] == (1 if old in FAST and new in FAST else CHUNK)


@pytest.mark.parametrize("cls", [Pointwise, FastGrid])
def test_live_road_refuses_non_finite_values(cls: type) -> None:
    exc = cls(Harmonic(2.0, 0.01), bad=(4 * CHUNK + 0.5) * PERIOD)
    road = _road(exc)
    _live(road, range(4 * CHUNK))  # all finite
    raises_validation(lambda: road.block(4 * CHUNK), "non-finite")
    raises_validation(lambda: road.block(4 * CHUNK), "non-finite")  # and again


def test_live_road_refuses_values_of_the_wrong_shape() -> None:
    class Scalar(Pointwise):
        def sample_grid(self, n: int, step: float, start: float = 0.0) -> Any:
            return np.float64(0.0), np.zeros(n)

    road = _road(Scalar(Harmonic(2.0, 0.01)))
    road.block(0)  # pointwise
    raises_validation(lambda: road.block(1), "shape ()")


@pytest.mark.parametrize("cls", [Pointwise, FastGrid])
def test_a_live_excitation_with_non_finite_values_trips_the_loop(cls: type) -> None:
    sim = _sim(Passive(0.1))
    exc = cls(Harmonic(2.0, 0.01), bad=0.0503)
    hooks = LoopHooks(settings=LateQueue(dataclasses.replace(sim, excitation=exc), after=31))
    result = _run(sim, hooks)
    assert result.tripped
    assert "non-finite" in result.reason
    k = int(np.argmax(result.recording["state"] == 3))
    # in the tick that computes the block holding t - 0.3 s = 0.0503 s (change at 0.3 s)
    assert 350 - CHUNK < k <= 350
    assert np.all(np.isfinite(result.recording["z_r"]))
    assert cls is Pointwise or exc.calls > 0


@pytest.mark.parametrize("cls", [Pointwise, OldGrid])
def test_a_road_input_without_a_fast_grid_runs_live(cls: type) -> None:
    sim = Simulation(cls(Harmonic(1.5, 0.02)), controller=HiLo(1, mode="ACM"), max_current=0.3)
    plain = _run(sim, None)
    hooked = _run(sim, LoopHooks())
    assert hooked.reason == "completed"
    for name in ("z_r", "z_r_dot", "z_s", "x_d", "i_cmd"):
        np.testing.assert_allclose(hooked.recording[name], plain.recording[name], atol=1e-12)


def test_a_live_road_profile_runs_as_the_whole_run_road() -> None:
    road = preset_road("rough").scaled(0.5)
    sim = Simulation(road, controller=HiLo(1, mode="ACM"), max_current=0.3)
    plain = _run(sim, None, duration=2.0)
    hooked = _run(sim, LoopHooks(), duration=2.0)
    for name in ("z_r", "z_r_dot", "z_s", "i_cmd"):
        np.testing.assert_allclose(hooked.recording[name], plain.recording[name], atol=1e-10)


def test_a_live_change_between_compiled_and_pointwise_roads() -> None:
    """Harmonic -> a pulse evaluated pointwise (blocks of a few ticks) -> harmonic (one tick)."""
    sim = _sim(Passive(0.1))
    pulse = Pointwise(RoundedPulse(0.03, 2.0, delay=0.05))
    harmonic = Harmonic(3.0, 0.01)
    # polls every 10 ticks (a change is drained with one more): ticks 300 and 620
    changes = iter([(31, dataclasses.replace(sim, excitation=pulse)),
                    (64, dataclasses.replace(sim, excitation=harmonic))])  # fmt: skip

    class Changes:
        polls = 0
        nxt = next(changes)

        def get_nowait(self) -> Any:
            Changes.polls += 1
            if self.nxt is not None and Changes.polls == self.nxt[0]:
                item, self.nxt = self.nxt[1], next(changes, None)
                return item
            raise queue.Empty

    hooks = LoopHooks(settings=Changes(), poll_every=10, ramp_time=0.05)
    rec = _run(sim, hooks).recording
    t = rec["time"][:1000] + PERIOD  # the road at the end of each tick
    z1 = Harmonic(1.5, 0.02).displacement(t)
    z2 = pulse.displacement(t - 0.3)
    z3 = harmonic.displacement(t - 0.62)
    s1 = np.clip((t - 0.3) / 0.05, 0, 1)
    s2 = np.clip((t - 0.62) / 0.05, 0, 1)
    w1, w2 = s1 * s1 * (3 - 2 * s1), s2 * s2 * (3 - 2 * s2)
    expected = (1 - w2) * ((1 - w1) * z1 + w1 * z2) + w2 * z3
    np.testing.assert_allclose(rec["z_r"][:1000], expected, atol=1e-12)


def test_live_road_kernels_are_loaded_before_the_clock() -> None:
    """Loading a kernel inside a tick takes milliseconds: warm_up loads them all."""
    from mrsuspension.excitation import deterministic, road
    from mrsuspension.hil import live

    _road(ZeroRoad()).warm_up()
    kernels = (
        deterministic._harmonic_grid, deterministic._pulse_grid, road._spline_grid,
        live._cross_fade,
    )  # fmt: skip
    for kernel in kernels:
        assert kernel.signatures, kernel
