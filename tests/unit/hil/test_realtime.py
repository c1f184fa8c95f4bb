"""Real-time scheduling of the loop: modes, fallbacks, restoration, statistics."""

from __future__ import annotations

import contextlib
import gc
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from collections.abc import Iterator

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.control import HiLo
from mrsuspension.engine.simulate import Simulation
from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.excitation import Harmonic
from mrsuspension.hil import SimulatedRig, StartUp, run_hil
from mrsuspension.hil._isolation import _all_tids, _stat
from mrsuspension.hil.latency import measure_latency
from mrsuspension.hil.loop import TickStats
from mrsuspension.hil.network import UdpRig
from mrsuspension.hil.realtime import (
    IsolationReport,
    isolate_cpu,
    normalise_mode,
    pick_cpu,
    realtime_session,
)

LINUX_SCHED = hasattr(os, "sched_setscheduler") and hasattr(os, "sched_getaffinity")
#: two CPUs or more allowed: a core can be isolated
MULTI_CPU = LINUX_SCHED and len(os.sched_getaffinity(0)) >= 2


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
        stop.wait(300)  # alive until the test ends (set in its finally), however slow the machine

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


# -- isolating the loop's core --------------------------------------------------------------
@pytest.fixture
def sleeper() -> Iterator[subprocess.Popen[bytes]]:
    """A child process (inheriting this process's CPUs) that sleeps until killed."""
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        yield child
    finally:
        child.kill()
        child.wait(10)


def _tids(pid: int) -> list[int]:
    return [int(t) for t in os.listdir(f"/proc/{pid}/task")]


@pytest.mark.skipif(not MULTI_CPU, reason="needs Linux and two CPUs")
def test_isolate_moves_a_process_off_the_core_and_back(sleeper: subprocess.Popen[bytes]) -> None:
    cpus = os.sched_getaffinity(0)
    cpu = max(cpus)
    tids = _tids(sleeper.pid)
    assert all(os.sched_getaffinity(t) == cpus for t in tids)
    with isolate_cpu(cpu, tasks=tids) as report:
        for t in tids:
            assert os.sched_getaffinity(t) == cpus - {cpu}
        assert os.sched_getaffinity(0) == cpus  # the calling thread is kept by default
    for t in tids:
        assert os.sched_getaffinity(t) == cpus
    assert report == IsolationReport(cpu, moved=len(tids))
    assert report.label() == f"isolated cpu {cpu} (moved {len(tids)} task" + (
        "s)" if len(tids) > 1 else ")"
    )


@pytest.mark.skipif(not MULTI_CPU, reason="needs Linux and two CPUs")
def test_a_killed_isolating_process_is_restored_by_its_guard(
    sleeper: subprocess.Popen[bytes],
) -> None:
    cpus = os.sched_getaffinity(0)
    cpu = max(cpus)
    tids = _tids(sleeper.pid)
    script = textwrap.dedent(
        f"""
        import os, signal
        from mrsuspension.hil.realtime import isolate_cpu
        with isolate_cpu({cpu}, tasks={tids!r}) as report:
            assert report.moved == {len(tids)}
            assert all(os.sched_getaffinity(t) == {cpus - {cpu}!r} for t in {tids!r})
            os.kill(os.getpid(), signal.SIGKILL)  # no chance to restore anything
        """
    )
    proc = subprocess.run([sys.executable, "-c", script], timeout=120)
    assert proc.returncode == -signal.SIGKILL
    deadline = time.monotonic() + 60  # the guard restores them
    while time.monotonic() < deadline and any(os.sched_getaffinity(t) != cpus for t in tids):
        time.sleep(0.1)
    assert all(os.sched_getaffinity(t) == cpus for t in tids)


@pytest.mark.skipif(not MULTI_CPU, reason="needs Linux and two CPUs")
def test_isolate_counts_bound_tasks_and_skips_kept_and_gone_ones(
    sleeper: subprocess.Popen[bytes],
) -> None:
    cpus = os.sched_getaffinity(0)
    cpu = max(cpus)
    os.sched_setaffinity(sleeper.pid, {cpu})  # may run on that core only
    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    gone.wait(30)
    with isolate_cpu(cpu, tasks=[sleeper.pid, gone.pid, 0], keep=[0]) as report:
        assert os.sched_getaffinity(sleeper.pid) == {cpu}
        assert os.sched_getaffinity(0) == cpus
    assert (report.moved, report.fixed, report.denied) == (0, 1, 0)
    assert report.label() == f"isolated cpu {cpu} (moved 0 tasks; 1 bound to the core)"
    assert os.sched_getaffinity(sleeper.pid) == {cpu}


@pytest.mark.skipif(not MULTI_CPU, reason="needs Linux and two CPUs")
def test_isolate_does_not_restore_over_someone_elses_change(
    sleeper: subprocess.Popen[bytes],
) -> None:
    other = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        cpus = os.sched_getaffinity(0)
        cpu = max(cpus)
        with isolate_cpu(cpu, tasks=[sleeper.pid, other.pid]) as report:
            assert os.sched_getaffinity(other.pid) == cpus - {cpu}
            os.sched_setaffinity(other.pid, {cpu})  # someone else pins it meanwhile
        assert report.moved == 2
        assert os.sched_getaffinity(other.pid) == {cpu}  # theirs: left as they set it
        assert os.sched_getaffinity(sleeper.pid) == cpus  # the untouched one: restored
    finally:
        other.kill()
        other.wait(10)


_SPAWNER = """
import subprocess, sys, time
sys.stdin.readline()
child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
print(child.pid, flush=True)
time.sleep(30)
"""


@pytest.mark.skipif(not MULTI_CPU, reason="needs Linux and two CPUs")
def test_isolate_restores_tasks_started_by_moved_ones() -> None:
    """A process started inside the block by a moved one inherits its narrowed affinity;
    it gets the old one back at the end, as its parent does."""
    cpus = os.sched_getaffinity(0)
    cpu = max(cpus)
    parent = subprocess.Popen(
        [sys.executable, "-c", _SPAWNER], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    grandchild = 0
    try:
        assert parent.stdin is not None
        assert parent.stdout is not None
        with isolate_cpu(cpu, tasks=_tids(parent.pid)) as report:
            parent.stdin.write("go\n")
            parent.stdin.flush()
            grandchild = int(parent.stdout.readline())
            assert os.sched_getaffinity(grandchild) == cpus - {cpu}  # inherited
        assert report.moved == len(_tids(parent.pid))
        assert os.sched_getaffinity(parent.pid) == cpus
        assert os.sched_getaffinity(grandchild) == cpus
    finally:
        if grandchild:
            with contextlib.suppress(ProcessLookupError):
                os.kill(grandchild, signal.SIGKILL)
        parent.kill()
        parent.wait(10)


def test_isolation_report_label_and_kernel_threads() -> None:
    r = IsolationReport(1, moved=143, kernel_threads=12, fixed=9, denied=3)
    assert r.label() == (
        "isolated cpu 1 (moved 143 tasks, 12 of them kernel threads; 9 bound to the core; "
        "3 not permitted)"
    )
    assert r.describe()["kernel_threads"] == 12
    assert IsolationReport(0, note="one CPU").label() == "cpu 0 not isolated (one CPU)"
    if sys.platform.startswith("linux"):
        own = _stat(os.getpid())
        assert own is not None
        assert own.kernel is False
        assert own.ppid == os.getppid()
        kthreadd = _stat(2)  # pid 2 is the kernel's thread creator
        if kthreadd is not None:
            assert kthreadd.kernel is True


def test_isolate_does_nothing_with_one_cpu(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(os, "cpu_count", lambda: 1)
    with isolate_cpu(0) as report:
        pass
    assert report.moved == 0
    assert report.note is not None
    assert report.label().startswith("cpu 0 not isolated")


@pytest.mark.skipif(
    not MULTI_CPU or os.geteuid() != 0, reason="needs root (every task) and two CPUs"
)
def test_isolate_whole_machine_round_trip(sleeper: subprocess.Popen[bytes]) -> None:
    """Every task is moved back; checked by (thread id, start time) against a snapshot.

    Other sessions on the machine may change their own tasks' affinity meanwhile, so
    the check is for what isolation would leave behind: a task that had the core and
    now has exactly its old CPUs minus the core.
    """
    cpu = max(os.sched_getaffinity(0))
    before: dict[int, tuple[frozenset[int], str]] = {}
    for tid in _all_tids():
        info = _stat(tid)
        try:
            if info is not None:
                before[tid] = (frozenset(os.sched_getaffinity(tid)), info.start)
        except OSError:
            continue
    child = _tids(sleeper.pid)
    with isolate_cpu(cpu) as report:
        for t in child:
            assert cpu not in os.sched_getaffinity(t)
        assert cpu in os.sched_getaffinity(0)  # the calling thread is kept
    assert report.moved >= len(child)
    assert report.note is None
    left = []
    for tid, (old, start) in before.items():
        info = _stat(tid)
        if info is None or info.start != start or cpu not in old:
            continue  # ended, or the id reused
        try:
            now = frozenset(os.sched_getaffinity(tid))
        except OSError:
            continue
        if now != old and now == old - {cpu}:
            left.append(tid)
    assert left == []
    for t in child:
        assert cpu in os.sched_getaffinity(t)


@pytest.mark.skipif(not MULTI_CPU, reason="needs Linux and two CPUs")
def test_spin_session_isolates_the_pinned_core(sleeper: subprocess.Popen[bytes]) -> None:
    """The session moves other processes off its core, keeps its own threads, undoes it."""
    cpus = os.sched_getaffinity(0)
    stop = threading.Event()
    helper = threading.Thread(target=stop.wait, args=(10,), daemon=True)
    helper.start()
    try:
        with realtime_session("spin", isolate=True) as rt:
            assert rt.cpu is not None
            assert rt.isolated is not None
            assert rt.isolated.startswith(f"isolated cpu {rt.cpu} (moved ")
            assert rt.isolated in rt.label()
            assert rt.describe()["isolated"] == rt.isolated
            assert os.sched_getaffinity(sleeper.pid) == cpus - {rt.cpu}
            assert helper.native_id is not None
            assert os.sched_getaffinity(helper.native_id) == cpus  # own process: kept
        assert os.sched_getaffinity(sleeper.pid) == cpus
        assert os.sched_getaffinity(0) == cpus
    finally:
        stop.set()
        helper.join(5)
    with realtime_session("spin") as plain:
        assert plain.isolated is None
        assert "isolated" not in plain.label()


def test_isolated_run_records_it() -> None:
    result = run_hil(
        _sim(), SimulatedRig(), duration=0.2, rate=1000.0, realtime="spin", isolate=True
    )
    assert result.reason == "completed"
    assert result.meta["isolate"] is True
    if MULTI_CPU:
        assert "; isolated cpu " in result.stats.scheduling
        assert result.meta["scheduling"]["isolated"].startswith("isolated cpu")
    else:  # one core: nothing pinned, nothing to isolate (noted)
        assert "not isolated" in result.stats.scheduling


def test_isolate_needs_a_pinned_loop() -> None:
    message = "isolate needs a pinned loop: use realtime auto, fifo or spin"
    for mode in ("off", "unpaced", False):
        with pytest.raises(ValidationError, match=message), realtime_session(mode, isolate=True):
            pass  # pragma: no cover
    raises_validation(lambda: run_hil(_sim(), duration=0.1, realtime="off", isolate=True), message)
    raises_validation(
        lambda: run_hil(_sim(), duration=0.1, realtime="off", isolate=True, process=True),
        message,
    )
    raises_validation(lambda: measure_latency(duration=0.1, realtime="off", isolate=True), message)
    raises_validation(
        lambda: measure_latency(duration=0.1, realtime="off", isolate=True, process=True), message
    )
