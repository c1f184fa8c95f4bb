"""Issue 7: the attached run (``hil run --monitor``) hands its result over when it ends."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest

from _helpers import raises_validation
from mrsuspension.control import HiLo
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import Harmonic
from mrsuspension.hil.loop import TickStats

pytest.importorskip("starlette")

from mrsuspension.monitor.app import AttachedRun, MonitorState


def _wait_for(state: MonitorState, got: list[Any], timeout: float = 90.0) -> None:
    deadline = time.monotonic() + timeout
    while not got and time.monotonic() < deadline:
        state.poll()
        time.sleep(0.05)


def test_attached_run_reports_its_result_once(tmp_path: Path) -> None:
    state = MonitorState(tmp_path, rig="ideal")
    got: list[dict[str, Any]] = []
    sim = Simulation(Harmonic(1.5, 0.01), controller=HiLo(1, mode="ACM"), max_current=0.3)
    state.attach(AttachedRun(sim, rate=1000.0, duration=0.3, on_end=got.append))
    _wait_for(state, got)
    assert len(got) == 1
    info = got[0]
    # the object `hil run --json` prints without --monitor
    assert set(info) == {
        "reason", "ending", "signal", "tripped", "rows", "out", "stats", "rms_body_acceleration"
    }  # fmt: skip
    assert info["reason"] == "completed"
    assert info["tripped"] is False
    assert info["stats"]["ticks"] == info["rows"] >= 300
    assert info["out"] == str(tmp_path / "run-001")
    assert set(info["stats"]) == set(TickStats.__dataclass_fields__)
    state.poll()  # once only
    state.report_end()
    assert len(got) == 1


def test_a_stopped_attached_run_reports_too(tmp_path: Path) -> None:
    state = MonitorState(tmp_path, rig="ideal")
    got: list[dict[str, Any]] = []
    sim = Simulation(Harmonic(1.5, 0.01), controller=HiLo(1, mode="ACM"), max_current=0.3)
    state.attach(AttachedRun(sim, rate=1000.0, duration=30.0, on_end=got.append))
    time.sleep(0.5)
    state.stop()
    assert state.handle is not None
    state.handle.join(30.0)
    state.poll()
    assert len(got) == 1
    assert got[0]["reason"] == "STOP pressed"
    assert got[0]["tripped"] is True
    assert got[0]["stats"]["ticks"] < 30000


@pytest.mark.parametrize("mode", ["off", "spin"])
def test_the_monitor_runs_its_loop_with_the_chosen_scheduling(tmp_path: Path, mode: str) -> None:
    state = MonitorState(tmp_path, rig="ideal", realtime=mode.upper())
    assert state.realtime == mode
    assert _short_run(state)["stats"]["scheduling"].startswith(mode)


def _short_run(state: MonitorState) -> dict[str, Any]:
    """A 0.2 s skyhook run attached to ``state``; its result (checked completed)."""
    got: list[dict[str, Any]] = []
    sim = Simulation(Harmonic(1.5, 0.01), controller=HiLo(1, mode="ACM"), max_current=0.3)
    state.attach(AttachedRun(sim, rate=1000.0, duration=0.2, on_end=got.append))
    _wait_for(state, got)
    assert got
    assert got[0]["reason"] == "completed"
    return got[0]


@pytest.mark.parametrize(
    ("mode", "fragments"),
    [("unpaced", ("unpaced", "real time", "spin")), ("spinn", ("spinn", "spin"))],
)
def test_the_monitor_refuses_a_scheduling_it_cannot_run(
    tmp_path: Path, mode: str, fragments: tuple[str, ...]
) -> None:
    raises_validation(lambda: MonitorState(tmp_path, realtime=mode), *fragments)


def test_the_monitor_isolates_its_loops_core_when_asked(tmp_path: Path) -> None:
    raises_validation(
        lambda: MonitorState(tmp_path, realtime="off", isolate=True), "isolate needs a pinned loop"
    )
    state = MonitorState(tmp_path, rig="ideal", realtime="spin", isolate=True)
    scheduling = _short_run(state)["stats"]["scheduling"]
    assert "isolated cpu" in scheduling or "not isolated" in scheduling  # one core: noted


def test_a_server_off_the_loop_core_still_gives_its_loop_that_core(tmp_path: Path) -> None:
    from mrsuspension.hil.realtime import pick_cpu, yield_loop_cpu

    loop_cpu = pick_cpu("loop")
    got: list[dict[str, Any]] = []
    sim = Simulation(Harmonic(1.5, 0.01), controller=HiLo(1, mode="ACM"), max_current=0.3)
    with yield_loop_cpu() as cpus:  # as `mrsus monitor` serves
        state = MonitorState(tmp_path, rig="ideal", realtime="spin")
        state.loop_cpus = cpus
        state.attach(AttachedRun(sim, rate=1000.0, duration=0.2, on_end=got.append))
        _wait_for(state, got)
    assert got
    assert got[0]["reason"] == "completed"
    if cpus is not None:  # two cores or more: the loop pinned itself to the freed one
        assert f"cpu {loop_cpu}" in got[0]["stats"]["scheduling"]
