"""Who takes the loop's core: trace the scheduler on one CPU while a command runs.

Run as root (the kernel's tracefs)::

    python tools/trace_core.py --cpu 1 -- python benchmarks/bench_monitor.py --duration 30

It records every ``sched_switch`` on ``--cpu`` while the command runs, takes the task that
spent the most time on that CPU as the loop (or ``--loop TID``), and lists, for every
other task, how often and for how long it was running while the loop was off its core
(the loop's stalls; ``--threshold-ms``, default 0.8 ms). Task names are sampled from
``/proc`` during the run, so tasks that ended are still named. docs/monitor.md shows
what it found on the test VM.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import os
import re
import subprocess
import sys
import threading
import time
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

TRACEFS = Path("/sys/kernel/tracing")
_SWITCH = re.compile(
    r"\s(\d+\.\d+): sched_switch: prev_comm=(.*?) prev_pid=(\d+) .*? ==> "
    r"next_comm=(.*?) next_pid=(\d+)"
)


@dataclass(frozen=True)
class Switch:
    """One ``sched_switch``: at ``time`` [s], ``prev`` left the CPU and ``next`` took it."""

    time: float
    prev: int
    next: int
    prev_comm: str
    next_comm: str


def parse(lines: Iterable[str]) -> list[Switch]:
    """The ``sched_switch`` events of a tracefs ``trace`` text (other lines ignored)."""
    out = []
    for line in lines:
        m = _SWITCH.search(line)
        if m:
            out.append(Switch(float(m[1]), int(m[3]), int(m[5]), m[2], m[4]))
    return out


@dataclass
class Report:
    """What :func:`attribute` found."""

    loop: int
    on_cpu: dict[int, float]  # task -> seconds on the CPU
    stalls: int = 0  # loop stalls longer than the threshold
    count: collections.Counter[int] = field(default_factory=collections.Counter)
    seconds: collections.Counter[int] = field(default_factory=collections.Counter)


def attribute(events: list[Switch], threshold: float, loop: int | None = None) -> Report:
    """Per task: how often it ran while ``loop`` was off the CPU for over ``threshold`` s.

    Examples
    --------
    >>> ev = [Switch(0.0, 0, 7, "", "loop"), Switch(1.0, 7, 9, "loop", "kd"),
    ...       Switch(1.005, 9, 7, "kd", "loop"), Switch(2.0, 7, 0, "loop", "idle")]
    >>> r = attribute(ev, 1e-3)
    >>> r.loop, r.stalls, r.count[9], round(r.seconds[9], 4)
    (7, 1, 1, 0.005)
    """
    on: dict[int, float] = collections.defaultdict(float)
    since: dict[int, float] = {}
    for e in events:
        if e.prev in since:
            on[e.prev] += e.time - since.pop(e.prev)
        since[e.next] = e.time
    on.pop(0, None)  # the idle task
    if loop is None:
        loop = max(on, key=lambda t: on[t]) if on else -1
    report = Report(loop, dict(on))
    off: float | None = None
    ran: set[int] = set()
    for e in events:
        if e.prev == loop:
            off, ran = e.time, set()
        if off is not None and e.next not in (loop, 0):
            ran.add(e.next)
        if e.next == loop and off is not None:
            gap = e.time - off
            if gap > threshold:
                report.stalls += 1
                for task in ran:
                    report.count[task] += 1
                    report.seconds[task] += gap
            off = None
    return report


def _names(into: dict[int, str], stop: threading.Event) -> None:
    """Sample every task's name (and its process's command line) until ``stop``."""
    while not stop.is_set():
        for proc in Path("/proc").glob("[0-9]*"):
            with contextlib.suppress(OSError):
                cmd = (proc / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
                for task in (proc / "task").iterdir():
                    comm = (task / "comm").read_text().strip()
                    into[int(task.name)] = f"{comm} {cmd.strip()}"[:80]
        stop.wait(1.0)


@contextlib.contextmanager
def tracing(cpu: int, buffer_kb: int = 65536) -> Iterator[Path]:
    """``sched_switch`` tracing on ``cpu`` for the block; yields the trace file.

    The CPU mask and buffer size are set back to what they were afterwards.
    """
    if not (TRACEFS / "trace").exists():
        subprocess.run(["mount", "-t", "tracefs", "nodev", str(TRACEFS)], check=False)
    if not (TRACEFS / "trace").exists():
        raise SystemExit(f"no tracefs at {TRACEFS} (run as root on Linux)")
    w = lambda name, value: (TRACEFS / name).write_text(value)  # noqa: E731
    names = ("tracing_cpumask", "buffer_size_kb")  # ("7 (expanded: 1408)": the first word)
    before = {n: (TRACEFS / n).read_text().split()[0] for n in names}
    try:
        w("tracing_on", "0")
        w("trace", "")
        w("tracing_cpumask", f"{1 << cpu:x}")
        w("buffer_size_kb", str(buffer_kb))
        w("events/sched/sched_switch/enable", "1")
        w("tracing_on", "1")
    except PermissionError as exc:
        raise SystemExit(f"tracefs refused ({exc}): run as root") from exc
    try:
        yield TRACEFS / "trace"
    finally:
        w("tracing_on", "0")
        w("events/sched/sched_switch/enable", "0")
        for name, value in before.items():  # as they were
            w(name, value)


def main(argv: list[str] | None = None) -> int:
    """Command line (see the module docstring)."""
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--cpu", type=int, default=(os.cpu_count() or 1) - 1, help="CPU to trace")
    ap.add_argument(
        "--loop", type=int, default=None, help="the loop's thread id (default: busiest)"
    )
    ap.add_argument("--threshold-ms", type=float, default=0.8, help="stall threshold [ms]")
    ap.add_argument("command", nargs=argparse.REMAINDER, help="-- COMMAND ...")
    args = ap.parse_args(argv)
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        ap.error("give the command to run after --")
    if not 0 <= args.cpu < (os.cpu_count() or 1):
        ap.error(f"--cpu {args.cpu}: this machine has CPUs 0-{(os.cpu_count() or 1) - 1}")
    names: dict[int, str] = {}
    stop = threading.Event()
    sampler = threading.Thread(target=_names, args=(names, stop), daemon=True)
    sampler.start()
    t0 = time.monotonic()
    with tracing(args.cpu) as trace:
        code = subprocess.run(command, check=False).returncode
        text = trace.read_text(errors="replace").splitlines()
    stop.set()
    r = attribute(parse(text), args.threshold_ms * 1e-3, args.loop)
    print(
        f"\ncpu {args.cpu}, {time.monotonic() - t0:.0f} s; loop: {r.loop} {names.get(r.loop, '?')}"
    )
    print(f"loop stalls > {args.threshold_ms:g} ms: {r.stalls}")
    print(f"{'task':>8} {'stalls':>6} {'in them [ms]':>12} {'on cpu [ms]':>11}  name")
    for task, n in r.count.most_common(15):
        print(
            f"{task:8d} {n:6d} {1e3 * r.seconds[task]:12.1f} "
            f"{1e3 * r.on_cpu.get(task, 0.0):11.1f}  {names.get(task, '?')}"
        )
    return code


if __name__ == "__main__":
    sys.exit(main())
