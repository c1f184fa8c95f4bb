"""Ctrl-C and SIGTERM stop the long commands fast, with one line and no process left.

Each case starts ``python -m mrsuspension ...`` in its own process group on inputs that
would run far longer than the test, waits until the two pool workers exist and compute,
then signals: SIGINT to the whole group (what a terminal's Ctrl-C does), twice 0.2 s
apart, or SIGTERM to the parent only (what ``kill PID`` does, the case that used to leave
orphans). It asserts the exit within :data:`LIMIT` seconds, exit code 130 or 143, one
``interrupted:`` line on stderr without a traceback, no output folder left behind, and
that every process of the tree recorded before the signal is gone. The pool and signal
handling live in :mod:`mrsuspension._pool`, the message in
:func:`mrsuspension.cli.errors.interrupts`.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

psutil = pytest.importorskip("psutil")  # a dependency of dask.distributed (dev extra)

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]

#: seconds from the signal to the exit: the 2 s promised, plus slack for a loaded CI
#: machine (measured on the 2-vCPU test VM: at most 0.2 s, typically 0.05-0.1 s)
LIMIT = 3.0

#: seconds to wait for a command to start its workers (imports and a numba cache load)
START = 60.0

# a study of 60 steady-state sweep runs (~15 s on 2 workers)
STUDY = """
[study]
name = "interrupt-me"
measures = ["T_as"]

[controller]
law = "passive"

[excitation]
kind = "swept"
amplitude = 0.025
frequencies = "log:20:0.5:15"

[grid]
"controller.current" = [0.0, 0.1, 0.2]
"""


def _commands(tmp: Path) -> dict[str, list[str]]:
    study = tmp / "study.toml"
    study.write_text(STUDY)
    return {
        "sweep": [
            "sweep",
            str(ROOT / "examples" / "scenarios" / "passive-harmonic.toml"),
            "-f",
            "log:200:0.5:15",
            "-j",
            "2",
            "--json",
            "--out",
            str(tmp / "out"),
        ],
        "study": [
            "study",
            str(study),
            "--workers",
            "2",
            "--no-cache",
            "--json",
            "--out",
            str(tmp / "out.nc"),
        ],
        "optimize": [
            "optimize",
            str(ROOT / "examples" / "optimize" / "skyhook-gain.toml"),
            "--workers",
            "2",
            "--json",
            "--out",
            str(tmp / "out"),
        ],
        "reproduce": ["reproduce", "--quick", "--out", str(tmp / "out")],
        "hil run": [
            "hil",
            "run",
            str(ROOT / "examples" / "scenarios" / "passive-harmonic.toml"),
            "--duration",
            "120",
            "--realtime",
            "off",
            "--out",
            str(tmp / "rec"),
        ],
    }


@dataclass
class Stopped:
    """How an interrupted command ended."""

    seconds: float
    code: int
    stderr: str
    left: list[int]


def _tree(proc: psutil.Process) -> list[psutil.Process]:
    try:
        return [proc, *proc.children(recursive=True)]
    except psutil.NoSuchProcess:
        return []


def _alive(p: psutil.Process) -> bool:
    try:
        return p.is_running() and p.status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def interrupt(
    args: list[str],
    how: str,
    cwd: Path,
    ready: Callable[[], bool] | None = None,
    settle: float = 0.5,
) -> Stopped:
    """Run ``mrsus ARGS``, signal it while its two workers compute, and report how it ended.

    ``how``: ``sigint`` (to the group), ``sigint2`` (to the group, again 0.2 s later
    unless it has ended), ``burst`` (six to the group, 5 ms apart: the later ones land
    in the cleanup) or ``sigterm`` (to the parent only). ``seconds`` counts from the
    first signal to the exit. ``ready()``, if given, must be true too, and then the
    signal comes ``settle`` seconds later.
    """
    proc = subprocess.Popen(
        [sys.executable, "-m", "mrsuspension", *args],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        start_new_session=True,  # its own process group, as a terminal's foreground job
        env={**os.environ, "COLUMNS": "120"},
    )
    parent = psutil.Process(proc.pid)
    try:
        deadline = time.monotonic() + START
        while len(_tree(parent)) < 3 or (ready is not None and not ready()):  # two workers
            assert proc.poll() is None, f"mrsus {args[0]} ended early: {proc.stderr.read()}"  # type: ignore[union-attr]
            assert time.monotonic() < deadline, f"mrsus {args[0]} started no workers"
            time.sleep(0.05)
        time.sleep(settle)  # the workers are inside their first runs
        tree = _tree(parent)
        assert proc.poll() is None, f"mrsus {args[0]} finished before the signal"
        start = time.monotonic()
        if how == "sigterm":
            os.kill(proc.pid, signal.SIGTERM)
        else:
            os.killpg(proc.pid, signal.SIGINT)
        for pause in {"sigint2": [0.2], "burst": [0.005] * 5}.get(how, []):
            with contextlib.suppress(subprocess.TimeoutExpired):
                proc.wait(timeout=pause)
            with contextlib.suppress(ProcessLookupError):  # the whole group is gone
                os.killpg(proc.pid, signal.SIGINT)
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.wait(timeout=30)
        seconds = time.monotonic() - start
        code = -1 if proc.returncode is None else proc.returncode
        # reparented workers are reaped; a loop process still importing when its parent
        # ended stops once it can take the parent's death signal: allow it a few seconds
        # on a loaded machine (one that stayed would still be reported)
        gone_by = time.monotonic() + 5.0
        while any(_alive(p) for p in tree) and time.monotonic() < gone_by:
            time.sleep(0.05)
        return Stopped(seconds, code, proc.stderr.read(), [p.pid for p in tree if _alive(p)])  # type: ignore[union-attr]
    finally:
        for p in _tree(parent):
            with contextlib.suppress(psutil.NoSuchProcess):
                p.kill()
        proc.wait()


def _check(stopped: Stopped, tmp_path: Path, command: str, how: str) -> None:
    print(f"{command} {how}: exit {stopped.code} after {stopped.seconds:.3f} s")
    assert stopped.left == [], f"processes left: {stopped.left}"
    assert stopped.code == (143 if how == "sigterm" else 130), stopped.stderr
    assert stopped.seconds < LIMIT
    assert "Traceback" not in stopped.stderr
    lines = [ln for ln in stopped.stderr.splitlines() if ln.strip()]
    assert [ln for ln in lines if ln.startswith("interrupted:")] == lines[-1:], stopped.stderr
    if command != "reproduce":  # reproduce writes in place until it uses the output policy
        assert not (tmp_path / "out").exists()
        assert not (tmp_path / "out.nc").exists()
        assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".out")] == []


#: every command with a Ctrl-C and a SIGTERM; the second Ctrl-C (the signal handling is
#: one, :mod:`mrsuspension._pool`'s) on a pool's command and on the report's (a process
#: each: about 2 s of CPU)
CASES = [
    *((command, how) for command in ("sweep", "study", "optimize", "reproduce")
      for how in ("sigint", "sigterm")),
    ("sweep", "sigint2"),
    ("reproduce", "sigint2"),
]  # fmt: skip


@pytest.mark.parametrize(("command", "how"), CASES)
def test_interrupt_stops_fast_without_orphans(tmp_path: Path, command: str, how: str) -> None:
    _check(interrupt(_commands(tmp_path)[command], how, tmp_path), tmp_path, command, how)


def test_signals_during_the_cleanup_change_nothing(tmp_path: Path) -> None:
    _check(interrupt(_commands(tmp_path)["sweep"], "burst", tmp_path), tmp_path, "sweep", "burst")


# an interrupted `hil run` whose loop runs: tests/integration/test_hil_endings.py (every
# ending, over the simulated and the UDP rig, the rig's last command checked)


@pytest.mark.parametrize("how", ["sigint", "sigterm"])
def test_a_hil_run_interrupted_while_starting_stops_quietly(tmp_path: Path, how: str) -> None:
    """The loop process starts with SIGINT ignored and SIGTERM held back until it can
    handle them: a Ctrl-C while it imports prints no traceback from it."""
    stopped = interrupt(_commands(tmp_path)["hil run"], how, tmp_path, settle=0.0)
    print(f"hil run (starting) {how}: exit {stopped.code} after {stopped.seconds:.3f} s")
    assert stopped.left == [], f"processes left: {stopped.left}"
    assert stopped.code == (143 if how == "sigterm" else 130), stopped.stderr
    assert stopped.seconds < LIMIT
    assert "Traceback" not in stopped.stderr
    assert stopped.stderr.strip().splitlines()[-1].startswith("interrupted: ")
