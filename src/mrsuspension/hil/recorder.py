"""Recorder of the HiL loop: every channel at loop rate, written while the loop runs.

The loop fills preallocated row blocks in memory and hands each full block (a tenth of a
second by default) to a writer thread through a bounded queue; the loop never waits for
the disk (a full queue drops the block and counts it). The writer appends the rows as
little-endian float64 to ``channels.f64`` and flushes after each block, so a crash or a
kill loses at most the block being filled. The layout is described in ``meta.json``
(channel names and units, loop rate); ``stop.json`` states ``"running"`` until the run
ends, then the reason it stopped. :func:`load_recording` reads a directory back (also one
left by a killed run) and :meth:`Recording.to_csv` exports it.
"""

from __future__ import annotations

import json
import os
import queue
import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension.errors import ValidationError

__all__ = ["DATA_FILE", "META_FILE", "STOP_FILE", "Recorder", "Recording", "load_recording"]

DATA_FILE = "channels.f64"
META_FILE = "meta.json"
STOP_FILE = "stop.json"


def _write_json(path: Path, data: Mapping[str, Any]) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=2, default=str))
    os.replace(tmp, path)


class Recorder:
    """Incremental writer of fixed-width float64 rows.

    Parameters
    ----------
    out : path
        Output directory (created).
    channels : sequence of str
        Column names, in row order.
    units : mapping, optional
        Unit of each channel (for ``meta.json``).
    block_rows : int
        Rows per block handed to the writer (the most a kill can lose).
    queue_blocks : int
        Capacity of the queue between the loop and the writer, in blocks.
    meta : mapping, optional
        Extra metadata for ``meta.json`` (scenario, rig, rate...).
    """

    def __init__(
        self,
        out: str | Path,
        channels: Sequence[str],
        *,
        units: Mapping[str, str] | None = None,
        block_rows: int = 100,
        queue_blocks: int = 64,
        meta: Mapping[str, Any] | None = None,
    ) -> None:
        if block_rows < 1 or queue_blocks < 1:
            raise ValidationError("block_rows and queue_blocks must be at least 1")
        self.out = Path(out)
        self.out.mkdir(parents=True, exist_ok=True)
        self.channels = tuple(channels)
        self.width = len(self.channels)
        self.block_rows = int(block_rows)
        self._queue: queue.Queue[tuple[np.ndarray, int] | None] = queue.Queue(queue_blocks)
        self._free: queue.Queue[np.ndarray] = queue.Queue()
        for _ in range(queue_blocks + 2):
            self._free.put(np.zeros((self.block_rows, self.width)))
        self._blk = self._free.get()
        self._pos = 0
        self.rows = 0
        self.dropped_blocks = 0
        self.written_rows = 0
        self._error: BaseException | None = None
        meta_data = {
            "format": "float64 little-endian rows, one column per channel",
            "data_file": DATA_FILE,
            "channels": list(self.channels),
            "units": dict(units or {}),
            "block_rows": self.block_rows,
            **dict(meta or {}),
        }
        _write_json(self.out / META_FILE, meta_data)
        _write_json(self.out / STOP_FILE, {"status": "running"})
        self._file = open(self.out / DATA_FILE, "wb")  # noqa: SIM115 (closed by the writer)
        self._thread = threading.Thread(target=self._writer, name="hil-recorder", daemon=True)
        self._thread.start()

    # -- loop side (no waiting) ---------------------------------------------------------
    def append(self, values: Sequence[float]) -> None:
        """Add one row (the loop's hot path: a copy into a preallocated block)."""
        self._blk[self._pos] = values
        self._pos += 1
        if self._pos == self.block_rows:
            self._hand_over()

    def _hand_over(self) -> None:
        try:
            self._queue.put_nowait((self._blk, self._pos))
        except queue.Full:
            self.dropped_blocks += 1
            self._pos = 0
            return
        self.rows += self._pos
        try:
            self._blk = self._free.get_nowait()
        except queue.Empty:  # the writer is behind; allocate rather than wait
            self._blk = np.zeros((self.block_rows, self.width))
        self._pos = 0

    # -- writer thread ------------------------------------------------------------------
    def _writer(self) -> None:
        f = self._file
        try:
            while True:
                item = self._queue.get()
                if item is None:
                    break
                blk, n = item
                f.write(blk[:n].data)
                f.flush()
                self.written_rows += n
                self._free.put(blk)
        except BaseException as exc:
            self._error = exc
        finally:
            f.close()

    def close(self, stop: Mapping[str, Any]) -> None:
        """Write the partial block, stop the writer and record why the run stopped."""
        if self._pos:
            self._queue.put((self._blk, self._pos))
            self.rows += self._pos
            self._pos = 0
        self._queue.put(None)
        self._thread.join()
        data = {
            "status": "stopped",
            "rows": self.written_rows,
            "dropped_blocks": self.dropped_blocks,
            **dict(stop),
        }
        _write_json(self.out / STOP_FILE, data)
        if self._error is not None:
            raise self._error


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
