"""Recorder of the HiL loop: every channel at loop rate, written while the loop runs.

The loop copies each row into a shared-memory ring and publishes it (a counter in the
same memory): no lock, no system call and no second thread in the loop's process, so
nothing there competes with the loop for the interpreter lock or the loop's core. A
writer **process** (``hil/_recwriter.py``, standard library only, started from the
recorder and kept off the loop's core by :func:`~mrsuspension.hil.loop.run_hil`)
appends the published rows to ``channels.f64`` as little-endian float64 every 20 ms. A
crash or a kill of the loop process loses only the row being written: the ring outlives
the loop in the writer, which writes everything published before it exits. When the
writer falls a whole ring behind, a real-time loop overwrites the oldest unwritten rows
(counted as ``dropped_rows``) rather than wait; an unpaced run waits for it instead. The
layout is described in ``meta.json`` (channel names and units, loop rate);
``stop.json`` states ``"running"`` until the run ends, then the reason it stopped.
:func:`load_recording` reads a directory back (also one left by a killed run) and
:meth:`Recording.to_csv` exports it.
"""

from __future__ import annotations

import contextlib
import json
import mmap
import os
import subprocess
import sys
import tempfile
import time
import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

import numpy as np

from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.hil import _recwriter as rw

__all__ = ["DATA_FILE", "META_FILE", "STOP_FILE", "Recorder", "Recording", "load_recording"]

DATA_FILE = "channels.f64"
META_FILE = "meta.json"
STOP_FILE = "stop.json"
#: the writer process's script (run by path: it imports the standard library only)
_WRITER = Path(rw.__file__)
#: how long :meth:`Recorder.close` lets the writer drain the ring [s]
_CLOSE_TIMEOUT = 60.0
#: how long the writer may take to start [s]
_START_TIMEOUT = 30.0


#: bytes reserved for ``stop.json`` when the run starts, so that the stop record can be
#: written in place on a disk that filled up meanwhile
_STOP_RESERVE = 16384


def _write_json(path: Path, data: Mapping[str, Any], reserved: bool = False) -> None:
    """Write ``data`` as JSON to ``path`` (atomically: a new file moved into place).

    With ``reserved`` (a file written earlier with :data:`_STOP_RESERVE` bytes), a disk
    too full for the new file gets the record written over the old one in place.
    """
    text = json.dumps(data, indent=2, default=str)
    tmp = path.with_suffix(".tmp")
    try:
        tmp.write_text(text)
        os.replace(tmp, path)
    except OSError:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raw = text.encode()
        if not reserved or len(raw) > _STOP_RESERVE:
            raise
        with open(path, "r+b") as f:  # blocks already allocated: no new space needed
            f.write(raw + b" " * (_STOP_RESERVE - len(raw)))
            f.flush()
            os.fsync(f.fileno())


def _shared_buffer(size: int) -> tuple[int, mmap.mmap, IO[bytes] | None]:
    """An anonymous shared buffer that a child process can map through its descriptor."""
    if hasattr(os, "memfd_create"):  # Linux
        fd, keep = os.memfd_create("mrsus-recorder"), None
    else:  # other POSIX systems: an unlinked temporary file
        keep = tempfile.TemporaryFile()  # noqa: SIM115 (closed with the recorder)
        fd = keep.fileno()
    os.ftruncate(fd, size)
    return fd, mmap.mmap(fd, size), keep


def _abandon(proc: subprocess.Popen[bytes], buf: mmap.mmap) -> None:
    """Finalizer of a recorder never closed: let its writer drain and end."""
    with contextlib.suppress(ValueError, OSError):  # buffer already closed
        rw._put(buf, rw.CLOSE, 1)
    try:
        proc.wait(_CLOSE_TIMEOUT)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


class Recorder:
    """Incremental writer of fixed-width float64 rows (the HiL loop's recording).

    Parameters
    ----------
    out : path
        Output directory (created).
    channels : sequence of str
        Column names, in row order.
    units : mapping, optional
        Unit of each channel (for ``meta.json``).
    buffer_rows : int
        Rows the shared ring holds: how far the writer may fall behind before rows are
        lost (``wait=False``) or the loop waits (``wait=True``).
    flush_interval : float
        How often the writer appends the new rows to the file [s] (0.02: at most the
        last 20 ms are missing from a file read while the run goes on).
    wait : bool
        When the ring is full, wait for the writer (True: for unpaced runs, which must
        lose nothing) instead of overwriting the oldest unwritten rows (False, the
        default: a real-time loop never waits; the lost rows are counted).
    meta : mapping, optional
        Extra metadata for ``meta.json`` (scenario, rig, rate...).

    Examples
    --------
    >>> import tempfile
    >>> out = Path(tempfile.mkdtemp()) / "rec"
    >>> rec = Recorder(out, ["time", "x"], units={"time": "s", "x": "m"})
    >>> for k in range(5):
    ...     rec.append((0.001 * k, 2.0 * k))
    >>> rec.close({"reason": "completed"})
    >>> back = load_recording(out)
    >>> back["x"].tolist(), back.complete, back.stop["rows"]
    ([0.0, 2.0, 4.0, 6.0, 8.0], True, 5)
    """

    def __init__(
        self,
        out: str | Path,
        channels: Sequence[str],
        *,
        units: Mapping[str, str] | None = None,
        buffer_rows: int = 16384,
        flush_interval: float = 0.02,
        wait: bool = False,
        meta: Mapping[str, Any] | None = None,
    ) -> None:
        if not isinstance(buffer_rows, int) or buffer_rows < 2:
            raise ValidationError(f"buffer_rows must be an integer >= 2; got {buffer_rows!r}")
        if not 1e-4 <= flush_interval <= 10.0:
            raise ValidationError(
                f"flush_interval must be within [0.0001, 10] s; got {flush_interval!r}"
            )
        self.out = Path(out)
        self.out.mkdir(parents=True, exist_ok=True)
        self.channels = tuple(channels)
        self.width = len(self.channels)
        if self.width < 1:
            raise ValidationError("a recording needs at least one channel")
        self.capacity = int(buffer_rows)
        self._wait = bool(wait)
        self._error: str | None = None
        self._n = 0
        self.dropped_rows = 0
        self.written_rows = 0
        meta_data = {
            "format": "float64 little-endian rows, one column per channel",
            "data_file": DATA_FILE,
            "channels": list(self.channels),
            "units": dict(units or {}),
            "flush_interval": flush_interval,
            **dict(meta or {}),
        }
        _write_json(self.out / META_FILE, meta_data)
        # the stop record's space is taken now (JSON allows the trailing blanks)
        running = json.dumps({"status": "running"}).encode()
        (self.out / STOP_FILE).write_bytes(running + b" " * (_STOP_RESERVE - len(running)))
        (self.out / DATA_FILE).write_bytes(b"")
        size = 8 * (rw.HEADER + self.capacity * self.width)
        fd, self._buf, self._keep = _shared_buffer(size)
        self._head = np.frombuffer(self._buf, dtype=np.int64, count=rw.HEADER)
        self._data = np.frombuffer(self._buf, dtype=np.float64, offset=8 * rw.HEADER).reshape(
            self.capacity, self.width
        )
        self._data.fill(0.0)  # every page of the ring in memory before the loop runs
        args = [str(fd), str(self.out / DATA_FILE), str(self.capacity), str(self.width)]
        args += [str(os.getpid()), repr(float(flush_interval))]
        try:
            self._proc = subprocess.Popen(
                [sys.executable, "-I", "-S", str(_WRITER), *args],
                pass_fds=(fd,),
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.PIPE,
            )
        finally:
            if self._keep is None:
                os.close(fd)  # the mapping and the child keep the memory
        self._finalizer = weakref.finalize(self, _abandon, self._proc, self._buf)
        t_end = time.monotonic() + _START_TIMEOUT
        while self._head[rw.STATE] == rw.STARTING:
            if self._proc.poll() is not None or time.monotonic() > t_end:
                self._finalizer()
                raise MRSuspensionError(
                    f"the recorder's writer process did not start: {self._writer_error()}"
                )
            time.sleep(1e-3)

    @property
    def rows(self) -> int:
        """Rows appended so far."""
        return self._n

    # -- loop side ----------------------------------------------------------------------
    def append(self, values: Sequence[float]) -> None:
        """Add one row (the loop's hot path: a copy into shared memory, then publish)."""
        n = self._n
        if self._wait and n - int(self._head[rw.CONSUMED]) >= self.capacity:
            self._wait_for_writer(n)
        self._data[n % self.capacity] = values
        self._n = n + 1
        self._head[rw.PUBLISHED] = n + 1  # published after the row is in place

    def failure(self) -> str | None:
        """Why the writer stopped recording, or None while it records (a few us).

        The writer ends on its own only when it failed (a full disk, a write error) or
        was killed; the loop checks this every few milliseconds and trips.
        """
        if self._head[rw.STATE] != rw.FAILED and self._proc.poll() is None:
            return None
        self._proc.wait()
        return f"the recorder's writer process ended: {self._writer_error()}"

    def _wait_for_writer(self, n: int) -> None:
        while n - int(self._head[rw.CONSUMED]) >= self.capacity:
            if self._proc.poll() is not None:
                raise MRSuspensionError(
                    f"the recorder's writer process ended while the run went on: "
                    f"{self._writer_error()}"
                )
            time.sleep(1e-4)

    def _writer_error(self) -> str:
        code = self._proc.poll()
        if code is None:
            return "it is still running"
        if self._error is None:
            err = ""
            if self._proc.stderr is not None and not self._proc.stderr.closed:
                err = self._proc.stderr.read().decode(errors="replace").strip()
            self._error = err.splitlines()[-1] if err else "no message"
        return f"exit code {code} ({self._error})"

    def close(self, stop: Mapping[str, Any]) -> None:
        """Let the writer write every row, stop it and record why the run stopped.

        Raises
        ------
        MRSuspensionError
            When the writer failed (``stop.json`` is written first and says so).
        """
        if self._buf.closed:
            raise MRSuspensionError(f"the recording in {self.out} is already closed")
        self._finalizer.detach()
        self._head[rw.CLOSE] = 1
        error = ""
        try:
            code = self._proc.wait(_CLOSE_TIMEOUT)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            self._proc.wait()
            code = None
            error = f"the recorder's writer did not finish within {_CLOSE_TIMEOUT:g} s"
        consumed = int(self._head[rw.CONSUMED])
        self.dropped_rows = int(self._head[rw.LOST])
        self.written_rows = consumed - self.dropped_rows
        if not error and (code != 0 or consumed != self._n):
            error = (
                f"the recorder's writer failed: {self._writer_error()}; "
                f"{consumed} of {self._n} rows handled"
            )
        if self._proc.stderr is not None:
            with contextlib.suppress(OSError):
                self._proc.stderr.close()
        data = {
            "status": "stopped",
            "rows": self.written_rows,
            "dropped_rows": self.dropped_rows,
            **dict(stop),
        }
        if error:
            data["recorder_error"] = error
        _write_json(self.out / STOP_FILE, data, reserved=True)
        del self._head, self._data  # the views go before the mapping
        self._buf.close()
        if self._keep is not None:
            self._keep.close()
        if error:
            raise MRSuspensionError(error)


@dataclass
class Recording:
    """A recording read back: channels by name, metadata and the stop record.

    ``complete`` is False for a run that did not end normally (killed or crashed): its
    data stops at the last block written.
    """

    channels: dict[str, np.ndarray]
    meta: dict[str, Any] = field(default_factory=dict)
    stop: dict[str, Any] = field(default_factory=dict)

    @property
    def complete(self) -> bool:
        """True when the run ended through the loop (normally or by a trip)."""
        return self.stop.get("status") == "stopped"

    @property
    def reason(self) -> str:
        """Why the run stopped (empty for an incomplete recording)."""
        return str(self.stop.get("reason", ""))

    def __getitem__(self, name: str) -> np.ndarray:
        return self.channels[name]

    def __len__(self) -> int:
        return len(next(iter(self.channels.values()))) if self.channels else 0

    def to_csv(self, path: str | Path) -> Path:
        """Write all channels to a CSV file (header: the channel names)."""
        path = Path(path)
        names = list(self.channels)
        data = np.column_stack([self.channels[n] for n in names]) if names else np.zeros((0, 0))
        np.savetxt(path, data, delimiter=",", header=",".join(names), comments="", fmt="%.9g")
        return path


def load_recording(out: str | Path) -> Recording:
    """Read a recording directory (a partial trailing row of a killed run is dropped)."""
    out = Path(out)
    try:
        meta = json.loads((out / META_FILE).read_text())
    except FileNotFoundError as exc:
        raise ValidationError(f"{out} holds no HiL recording ({META_FILE} missing)") from exc
    names = list(meta["channels"])
    raw = np.fromfile(out / meta.get("data_file", DATA_FILE), dtype="<f8")
    n = raw.size // len(names)
    table = raw[: n * len(names)].reshape(n, len(names))
    try:
        stop = json.loads((out / STOP_FILE).read_text())
    except (FileNotFoundError, json.JSONDecodeError):
        stop = {}
    return Recording({k: table[:, j].copy() for j, k in enumerate(names)}, meta, stop)
