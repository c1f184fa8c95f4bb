"""The HiL recorder's writer process: shared-memory ring -> ``channels.f64``.

Run by path (``python -I -S _recwriter.py FD PATH CAPACITY WIDTH PPID POLL``) by
:class:`~mrsuspension.hil.recorder.Recorder`, so that it imports nothing but the standard
library and starts in a few tens of milliseconds; it shares no interpreter lock with the
loop. ``FD`` is an inherited file descriptor of the shared buffer: a header of
:data:`HEADER` int64 slots, then a ring of ``CAPACITY`` rows of ``WIDTH`` float64 values.

The loop writes a row into the ring and then publishes it (slot ``PUBLISHED``); this
process copies the published rows to the file every ``POLL`` seconds (plain ``write``:
the rows are in the operating system's cache at once), reports its progress
(``CONSUMED``, ``LOST``) and exits once the loop asks it to (``CLOSE``) and everything
published is written, on SIGTERM (after the same drain), or when the loop process is gone
(killed: the ring outlives it here, so every row it published is still written). Rows the
loop overwrote before they were copied are counted as lost, never written torn. Ctrl-C
and a terminal's hang-up (SIGINT, SIGHUP, sent to the whole process group) are ignored:
the loop decides when recording ends. A write error (a full disk) ends it with one line
on stderr and exit status 1; the loop sees it and trips.
"""

from __future__ import annotations

import mmap
import os
import signal
import struct
import sys
import time

#: header slots (int64)
PUBLISHED, CONSUMED, LOST, CLOSE, STATE, PID = range(6)
#: header length in int64 slots (the data ring starts after it)
HEADER = 8
#: writer states (slot ``STATE``)
STARTING, RUNNING, DONE, FAILED = 0, 1, 2, 3
_Q = struct.Struct("<q")


def _get(buf: mmap.mmap, slot: int) -> int:
    return int(_Q.unpack_from(buf, 8 * slot)[0])


def _put(buf: mmap.mmap, slot: int, value: int) -> None:
    _Q.pack_into(buf, 8 * slot, value)


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


def drain(buf: mmap.mmap, out: int, capacity: int, width: int, done: int) -> int:
    """Write the rows published since ``done`` to ``out``; returns the new ``done``.

    Rows overwritten by the loop before they could be copied (the writer was more than
    ``capacity`` rows behind) are skipped and added to slot ``LOST``.
    """
    n = _get(buf, PUBLISHED)
    if n <= done:
        return done
    row = 8 * width
    base = 8 * HEADER
    start = max(done, n - capacity)
    lost = start - done
    a, b = start % capacity, n % capacity
    if b > a:
        data = buf[base + a * row : base + b * row]
    else:  # wraps around the end of the ring (or is the whole ring)
        data = buf[base + a * row : base + capacity * row] + buf[base : base + b * row]
    overwritten = _get(buf, PUBLISHED) - capacity  # rows below this may be torn now
    if overwritten > start:
        cut = min(overwritten - start, n - start)
        data = data[cut * row :]
        lost += cut
    _write_all(out, data)
    if lost:
        _put(buf, LOST, _get(buf, LOST) + lost)
    _put(buf, CONSUMED, n)
    return n


def run(fd: int, path: str, capacity: int, width: int, ppid: int, poll: float) -> int:
    """Copy the ring to ``path`` until told to stop; the exit status (0: all written)."""
    size = 8 * (HEADER + capacity * width)
    buf = mmap.mmap(fd, size)
    stop = []
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGHUP, signal.SIG_IGN)  # a terminal's hang-up: the loop decides too
    signal.signal(signal.SIGTERM, lambda *_: stop.append(True))
    out = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        _put(buf, PID, os.getpid())
        _put(buf, STATE, RUNNING)
        done = _get(buf, CONSUMED)
        while True:
            closing = _get(buf, CLOSE) != 0 or bool(stop) or os.getppid() != ppid
            done = drain(buf, out, capacity, width, done)
            if closing and done == _get(buf, PUBLISHED):
                break
            if not closing:
                time.sleep(poll)
        _put(buf, STATE, DONE)
        return 0
    except OSError as exc:  # a full disk, a write error: one line for the recorder
        _put(buf, STATE, FAILED)
        print(f"OSError: {exc}", file=sys.stderr, flush=True)
        return 1
    except BaseException:
        _put(buf, STATE, FAILED)
        raise
    finally:
        os.close(out)
        buf.close()


def main(argv: list[str]) -> int:
    """Command line: ``FD PATH CAPACITY WIDTH PPID POLL``."""
    fd, path, capacity, width, ppid, poll = argv
    return run(int(fd), path, int(capacity), int(width), int(ppid), float(poll))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
