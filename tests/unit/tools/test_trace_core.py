"""tools/trace_core.py: parsing tracefs sched_switch lines and attributing loop stalls."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

_PATH = Path(__file__).resolve().parents[3] / "tools" / "trace_core.py"
_spec = importlib.util.spec_from_file_location("trace_core", _PATH)
assert _spec is not None
assert _spec.loader is not None
tc = importlib.util.module_from_spec(_spec)
sys.modules["trace_core"] = tc
_spec.loader.exec_module(tc)

# a loop (tid 500) on CPU 1, displaced by kdamond (71) for 5 ms, by a worker (12) for
# 0.3 ms and by python (700) then rcu (15) in one 2 ms stall; a task name with spaces
TRACE = """\
# tracer: nop
          <idle>-0       [001] d..2.   100.000000: sched_switch: prev_comm=swapper/1 prev_pid=0 prev_prio=120 prev_state=R ==> next_comm=python next_pid=500 next_prio=120
          python-500     [001] d..2.   100.100000: sched_switch: prev_comm=python prev_pid=500 prev_prio=120 prev_state=R+ ==> next_comm=kdamond.0 next_pid=71 next_prio=120
       kdamond.0-71      [001] d..2.   100.105000: sched_switch: prev_comm=kdamond.0 prev_pid=71 prev_prio=120 prev_state=I ==> next_comm=python next_pid=500 next_prio=120
          python-500     [001] d..2.   100.200000: sched_switch: prev_comm=python prev_pid=500 prev_prio=120 prev_state=R+ ==> next_comm=kworker/u8:0 next_pid=12 next_prio=120
    kworker/u8:0-12      [001] d..2.   100.200300: sched_switch: prev_comm=kworker/u8:0 prev_pid=12 prev_prio=120 prev_state=I ==> next_comm=python next_pid=500 next_prio=120
          python-500     [001] d..2.   100.300000: sched_switch: prev_comm=python prev_pid=500 prev_prio=120 prev_state=R+ ==> next_comm=Web Content next_pid=700 next_prio=120
     Web Content-700     [001] d..2.   100.301000: sched_switch: prev_comm=Web Content prev_pid=700 prev_prio=120 prev_state=S ==> next_comm=rcu_preempt next_pid=15 next_prio=120
     rcu_preempt-15      [001] d..2.   100.302000: sched_switch: prev_comm=rcu_preempt prev_pid=15 prev_prio=120 prev_state=I ==> next_comm=python next_pid=500 next_prio=120
          python-500     [001] d..2.   101.000000: sched_switch: prev_comm=python prev_pid=500 prev_prio=120 prev_state=S ==> next_comm=swapper/1 next_pid=0 next_prio=120
"""


def test_parse_reads_every_switch_and_names_with_spaces() -> None:
    events = tc.parse(TRACE.splitlines())
    assert len(events) == 9
    assert events[5].next_comm == "Web Content"
    assert (events[1].time, events[1].prev, events[1].next) == (100.1, 500, 71)


def test_stalls_are_attributed_to_the_tasks_that_ran() -> None:
    report = tc.attribute(tc.parse(TRACE.splitlines()), threshold=0.8e-3)
    assert report.loop == 500  # the busiest task
    assert report.stalls == 2  # the 5 ms and the 2 ms ones; 0.3 ms is below the threshold
    assert dict(report.count) == {71: 1, 700: 1, 15: 1}
    assert report.seconds[71] == pytest.approx(5e-3)
    assert report.seconds[15] == pytest.approx(2e-3)
    assert report.on_cpu[71] == pytest.approx(5e-3)
    low = tc.attribute(tc.parse(TRACE.splitlines()), threshold=0.1e-3)
    assert low.count[12] == 1
    assert low.stalls == 3


def test_an_explicit_loop_task() -> None:
    report = tc.attribute(tc.parse(TRACE.splitlines()), threshold=0.5e-3, loop=71)
    assert report.loop == 71  # not the busiest task, as asked
    assert report.stalls == 0  # it left the CPU at 100.105 and never came back
    assert not report.count


def test_command_line_refusals(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        tc.main(["--cpu", "0"])
    assert "give the command" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        tc.main(["--cpu", "999", "--", "true"])
    assert "--cpu 999" in capsys.readouterr().err
