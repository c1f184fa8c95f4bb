"""Real-time scheduling of the loop: modes, fallbacks, restoration, statistics."""

from __future__ import annotations

import gc
import os
import threading

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.control import HiLo
from mrsuspension.engine.simulate import Simulation
from mrsuspension.errors import MRSuspensionError
from mrsuspension.excitation import Harmonic
from mrsuspension.hil import SimulatedRig, StartUp, run_hil
from mrsuspension.hil.loop import TickStats
from mrsuspension.hil.network import UdpRig
from mrsuspension.hil.realtime import normalise_mode, pick_cpu, realtime_session

LINUX_SCHED = hasattr(os, "sched_setscheduler") and hasattr(os, "sched_getaffinity")


def _sim() -> Simulation:
    return Simulation(Harmonic(1.5, 0.02), controller=HiLo(1, mode="ACM"), max_current=0.3)


def test_modes() -> None:
    assert normalise_mode(True) == "auto"
    assert normalise_mode(False) == "unpaced"
    assert normalise_mode(" Off ") == "off"
    raises_validation(lambda: normalise_mode("fifoo"), "realtime must be one of", "'fifoo'")
    raises_validation(lambda: normalise_mode(3), "int 3")  # type: ignore[arg-type]


def test_off_touches_buffers_and_leaves_scheduling() -> None:
    buf = np.full(10000, np.nan)
    policy = os.sched_getscheduler(0) if LINUX_SCHED else None
    with realtime_session("off", buf) as rt:
        assert rt.paced
        assert rt.policy == "unchanged"
        assert rt.cpu is None
        if LINUX_SCHED:
            assert os.sched_getscheduler(0) == policy
    assert np.all(buf == 0.0)
    assert rt.label().startswith("off")


@pytest.mark.skipif(not LINUX_SCHED, reason="Linux scheduling calls")
def test_auto_applies_and_restores_everything() -> None:
    policy = os.sched_getscheduler(0)
    affinity = os.sched_getaffinity(0)
    helper_started = threading.Event()
    stop = threading.Event()

    def helper() -> None:
        helper_started.set()
        stop.wait(10)

    th = threading.Thread(target=helper, daemon=True)
    th.start()
    helper_started.wait(5)
    try:
        with realtime_session("auto") as rt:
            assert rt.gc_frozen
            assert gc.get_freeze_count() > 0
            if rt.policy.startswith("SCHED_FIFO"):
                assert os.sched_getscheduler(0) == os.SCHED_FIFO
                assert th.native_id is not None
                assert os.sched_getscheduler(th.native_id) == os.SCHED_FIFO
                assert "thread" in rt.policy
            else:
                assert any("SCHED_FIFO" in n for n in rt.notes)  # not permitted: noted
            if pick_cpu("loop") is not None and rt.cpu is not None:
                assert os.sched_getaffinity(0) == {rt.cpu}
        assert os.sched_getscheduler(0) == policy
        assert os.sched_getaffinity(0) == affinity
        assert th.native_id is not None
        assert os.sched_getscheduler(th.native_id) == policy
        assert gc.get_freeze_count() == 0
    finally:
        stop.set()
        th.join(5)


@pytest.mark.skipif(not LINUX_SCHED, reason="Linux scheduling calls")
def test_fifo_refused_falls_back_or_raises(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object) -> None:
        raise PermissionError(1, "Operation not permitted")

    affinity = os.sched_getaffinity(0)
    monkeypatch.setattr(os, "sched_setscheduler", refuse)
    with realtime_session("auto") as rt:
        assert rt.policy == "unchanged"
    assert any("SCHED_FIFO refused" in n for n in rt.notes)
    assert "SCHED_FIFO refused" in rt.label()
    with pytest.raises(MRSuspensionError, match="realtime='fifo'"), realtime_session("fifo"):
        pass  # pragma: no cover
    assert os.sched_getaffinity(0) == affinity  # the pinning undone after the error
    assert gc.get_freeze_count() == 0


def test_unpaced_needs_a_simulated_rig() -> None:
    raises_validation(
        lambda: run_hil(_sim(), UdpRig("127.0.0.1", 9), duration=0.1, realtime="unpaced"),
        "realtime='unpaced'",
        "UdpRig",
    )
    raises_validation(lambda: run_hil(_sim(), duration=0.1, realtime="fast"), "'fast'")


@pytest.mark.parametrize("mode", ["auto", "off", "unpaced"])
def test_run_records_the_scheduling(mode: str) -> None:
    sim = _sim()
    result = run_hil(
        sim, SimulatedRig(sim.damper), duration=0.3, rate=1000.0, startup=StartUp.none(),
        realtime=mode,
    )  # fmt: skip
    stats = result.stats
    assert result.reason == "completed"
    assert result.meta["realtime"] == mode
    assert result.meta["scheduling"]["mode"] == mode
    assert stats.scheduling.startswith(mode)
    assert stats.realtime is (mode != "unpaced")
    if mode == "unpaced":
        assert "UNPACED" in stats.summary()
        assert stats.misses == 0
    else:
        assert stats.jitter_max >= stats.jitter * 0.99
        assert "scheduling " + mode in stats.summary()
    assert result.recording.stop["scheduling"]["mode"] == mode


def test_jitter_max_and_misses_from_arrays() -> None:
    compute = np.full(6, 1e-4)
    lateness = np.array([0.0, 0.0, 1.5e-3, 0.6e-3, 0.0, 0.0])
    s = TickStats.from_arrays(compute, lateness, 1e-3, True, scheduling="x")
    assert s.misses == 1  # tick 2 ends 1.6 ms after its release
    assert s.jitter_max == pytest.approx(1.5e-3)
    assert s.scheduling == "x"
    unpaced = TickStats.from_arrays(compute, np.zeros(6), 1e-3, False)
    assert unpaced.misses == 0
    assert unpaced.jitter_max == 0.0


@pytest.mark.skipif(not LINUX_SCHED, reason="Linux scheduling calls")
def test_spin_pins_without_fifo_and_busy_waits() -> None:
    policy = os.sched_getscheduler(0)
    affinity = os.sched_getaffinity(0)
    with realtime_session("spin") as rt:
        assert rt.spin
        assert rt.policy == "unchanged"
        assert os.sched_getscheduler(0) == policy  # ordinary priority: no RT throttling
        if len(affinity) > 1:
            assert os.sched_getaffinity(0) == {rt.cpu}
        assert "busy-wait" in rt.label()
        assert rt.describe()["spin"] is True
    assert os.sched_getaffinity(0) == affinity
    with realtime_session("auto") as rt:
        assert not rt.spin


def test_spin_run_and_network_rig_poll() -> None:
    """A spin run records its scheduling and puts a network rig's reads in poll mode."""
    result = run_hil(_sim(), SimulatedRig(), duration=0.3, rate=1000.0, realtime="spin")
    assert "busy-wait" in result.stats.scheduling
    assert result.meta["scheduling"]["spin"] is True
    assert not UdpRig().spin  # sleeping in select stays the default
