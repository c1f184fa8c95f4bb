"""The machine latency check (``measure_latency``, ``mrsus hil latency``).

Short runs only, and no assertion on the share of ticks in deadline: the machine is
shared, so misses are whatever the other processes and the hypervisor make them.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from _helpers import raises_validation
from mrsuspension.cli import app
from mrsuspension.hil.latency import LatencyResult, count_stalls, cpu_times, measure_latency


@pytest.mark.parametrize("mode", ["off", "spin"])
def test_short_run_statistics(mode: str) -> None:
    r = measure_latency(rate=1000.0, duration=0.3, realtime=mode)
    s = r.stats
    assert isinstance(r, LatencyResult)
    assert s.ticks == 300
    assert s.period == pytest.approx(1e-3)
    assert s.realtime
    assert s.scheduling.startswith(mode)
    assert r.scheduling["mode"] == mode
    assert r.scheduling["spin"] is (mode == "spin")
    for v in (s.compute_p50, s.compute_p99, s.compute_max, s.lateness_p50, s.lateness_p99):
        assert math.isfinite(v)
        assert v >= 0.0
    assert s.compute_p50 <= s.compute_p99 <= s.compute_max
    assert s.lateness_p50 <= s.lateness_p99 <= s.lateness_max
    assert r.longest_stall == s.lateness_max
    assert 0 <= r.stalls <= s.misses <= s.ticks  # a stall > 1 period makes a miss
    if r.stalls:
        assert r.longest_stall > s.period
    assert r.wall >= 0.3 - 2e-3  # the ticks are paced, not run back to back
    assert r.steal >= 0.0
    assert r.others >= 0.0
    info = r.describe()
    assert info["stats"]["ticks"] == 300
    json.dumps(info)  # plain data
    assert "300 ticks" in r.summary()
    assert "steal" in r.summary()


def test_work_shows_in_compute() -> None:
    """The busy work is the tick's compute time; empty ticks take microseconds."""
    empty = measure_latency(rate=1000.0, duration=0.2, realtime="off")
    busy = measure_latency(rate=1000.0, duration=0.2, realtime="off", work=4e-4)
    assert busy.work == 4e-4
    assert 4e-4 <= busy.stats.compute_p50 < 6e-4
    assert empty.stats.compute_p50 < 1e-4
    assert "400 us of busy work" in busy.summary()
    assert "empty ticks" in empty.summary()


def test_progress_is_reported_between_ticks() -> None:
    calls: list[tuple[int, int]] = []
    measure_latency(
        rate=1000.0, duration=0.25, realtime="off", progress=lambda d, n: calls.append((d, n))
    )
    assert calls[0] == (100, 250)  # every 0.1 s of ticks
    assert calls[-1] == (250, 250)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)


def test_a_stall_counts_once() -> None:
    """A stall of n periods delays n ticks (catching up); it is one stall."""
    T = 1e-3
    late = np.zeros(100)
    late[10:16] = np.array([6, 5, 4, 3, 2, 1]) * T  # one 6-period stall, caught up
    late[40] = 0.5 * T  # shorter than a period: not a stall
    late[60:63] = np.array([2.5, 1.5, 0.5]) * T  # a second one
    assert count_stalls(late, T) == 2
    assert count_stalls(np.r_[3 * T, np.zeros(5)], T) == 1  # the first tick late
    assert count_stalls(np.zeros(0), T) == 0
    assert count_stalls(np.full(50, 0.9 * T), T) == 0  # late but steady: no stall


def test_cpu_times_are_counters() -> None:
    busy0, steal0 = cpu_times()
    if math.isnan(busy0):
        pytest.skip("no /proc/stat")
    sum(i * i for i in range(300_000))  # some CPU time
    busy1, steal1 = cpu_times()
    assert busy0 >= 0.0
    assert steal0 >= 0.0
    assert busy1 >= busy0
    assert steal1 >= steal0


def test_invalid_inputs() -> None:
    raises_validation(lambda: measure_latency(rate=0.0), "rate", "(0, 100000] Hz", "got 0")
    raises_validation(lambda: measure_latency(rate=-5.0), "rate", "got -5")
    raises_validation(lambda: measure_latency(rate=math.nan), "rate", "finite")
    raises_validation(lambda: measure_latency(rate=math.inf), "rate", "finite")
    raises_validation(lambda: measure_latency(duration=0.0), "duration", "(0, ", "got 0")
    raises_validation(lambda: measure_latency(work=-1e-6), "work", "[0, 0.001) s")
    raises_validation(lambda: measure_latency(work=1e-3), "work", "[0, 0.001) s", "got 0.001")
    raises_validation(
        lambda: measure_latency(realtime="unpaced"), "'unpaced'", "valid: auto, fifo, spin, off"
    )
    raises_validation(lambda: measure_latency(realtime=False), "valid: auto, fifo, spin, off")
    raises_validation(lambda: measure_latency(realtime="fifoo"), "realtime must be one of")
    raises_validation(
        lambda: measure_latency(rate=100000.0, duration=1e4), "ticks", "at most 20000000"
    )


def test_cli_json() -> None:
    res = CliRunner().invoke(
        app,
        ["hil", "latency", "--duration", "0.2", "--realtime", "off", "--work-us", "50", "--json"],
    )
    assert res.exit_code == 0, res.output
    info = json.loads(res.stdout)
    expected = {"rate", "duration", "work", "wall", "steal", "others", "longest_stall", "stalls"}
    assert expected | {"stats", "scheduling"} <= set(info)
    assert info["stats"]["ticks"] == 200
    assert info["work"] == pytest.approx(5e-5)
    assert info["stats"]["compute_p50"] >= 5e-5
    assert info["scheduling"]["mode"] == "off"


def test_cli_isolate_json() -> None:
    """``hil latency --isolate``: the floor measured with the loop's core isolated."""
    res = CliRunner().invoke(app, ["hil", "latency", "--duration", "0.2", "--isolate", "--json"])
    assert res.exit_code == 0, res.output
    info = json.loads(res.stdout)
    assert info["stats"]["ticks"] == 200
    sched = info["scheduling"]
    if sched["cpu"] is not None:  # pinned (two cores or more): isolated
        assert sched["isolated"].startswith(f"isolated cpu {sched['cpu']} (moved ")
        assert sched["isolated"] in info["stats"]["scheduling"]
    else:
        assert sched["isolated"] is None
        assert any("not isolated" in n for n in sched["notes"])


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["--realtime", "off", "--isolate"], "--isolate needs a pinned loop"),
        (["--work-us", "1000"], "--work-us must be in [0, 1000) us"),
        (["--rate", "0"], "--rate"),
        (["--duration", "0"], "--duration"),
        (["--realtime", "unpaced"], "valid: auto, fifo, spin, off"),
        (["--realtime", "sometimes"], "realtime must be one of"),
    ],
)
def test_cli_bad_values_exit_2(args: list[str], fragment: str) -> None:
    res = CliRunner().invoke(app, ["hil", "latency", *args])
    assert res.exit_code == 2, res.output
    assert fragment in res.output
    assert len(res.output.strip().splitlines()) == 1
