"""The shared-memory tap ring: order, loss accounting, status block, across processes."""

from __future__ import annotations

import multiprocessing
import queue
import time

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.hil.tap import STATUS_FIELDS, ChangeQueue, StopFlag, TapRing


def test_rows_in_order_and_lost_counted() -> None:
    ring = TapRing(3, capacity=8)
    for k in range(5):
        ring.put((k, k + 0.5, -k))
    rows, lost = ring.read()
    assert rows[:, 0].tolist() == [0, 1, 2, 3, 4]
    assert lost == 0
    rows, lost = ring.read()
    assert rows.shape == (0, 3)
    for k in range(5, 25):  # 20 rows into 8 slots: the reader lost 12
        ring.put((k, 0.0, 0.0))
    rows, lost = ring.read()
    assert rows[:, 0].tolist() == list(range(17, 25))
    assert lost == 12


def test_status_block() -> None:
    ring = TapRing(2)
    assert ring.status()["seq"] == 0.0
    ring.put_status({"ticks": 200, "misses": 3, "state_code": 1, "current": 0.25})
    st = ring.status()
    assert st["seq"] == 1.0
    assert st["ticks"] == 200
    assert st["misses"] == 3
    assert st["current"] == 0.25
    assert set(st) == set(STATUS_FIELDS)


def _writer(ring: TapRing, n: int) -> None:
    for k in range(n):
        ring.put((float(k), 2.0 * k))
    ring.put_status({"ticks": n})


def test_across_processes() -> None:
    ctx = multiprocessing.get_context("spawn")
    ring = TapRing(2, capacity=4096, context=ctx)
    proc = ctx.Process(target=_writer, args=(ring, 1000))
    proc.start()
    proc.join(60)
    assert proc.exitcode == 0
    rows, lost = ring.read()
    assert lost == 0
    np.testing.assert_array_equal(rows[:, 0], np.arange(1000.0))
    np.testing.assert_array_equal(rows[:, 1], 2.0 * np.arange(1000.0))
    assert ring.status()["ticks"] == 1000


def test_bad_shape() -> None:
    raises_validation(lambda: TapRing(0), "width >= 1")
    raises_validation(lambda: TapRing(2, capacity=1), "capacity >= 2")


def _raise(flag: StopFlag) -> None:
    flag.set()


def test_stop_flag_across_processes() -> None:
    ctx = multiprocessing.get_context("spawn")
    flag = StopFlag(ctx)
    assert not flag.is_set()
    proc = ctx.Process(target=_raise, args=(flag,))
    proc.start()
    proc.join(60)
    assert flag.is_set()
    flag.clear()
    assert not flag.is_set()


class _Untouchable:
    def get_nowait(self) -> None:
        raise AssertionError("the queue was polled although nothing was put")


def test_change_queue_poll_of_an_empty_queue_never_touches_the_queue() -> None:
    q = ChangeQueue(2)
    q._queue = _Untouchable()  # type: ignore[assignment]
    for _ in range(3):
        with pytest.raises(queue.Empty):
            q.get_nowait()


def _wait_get(q: ChangeQueue, timeout: float = 10.0) -> object:
    deadline = time.monotonic() + timeout
    while True:
        try:
            return q.get_nowait()
        except queue.Empty:
            assert time.monotonic() < deadline, "the change never arrived"
            time.sleep(0.001)


def test_change_queue_keeps_polling_while_a_change_is_in_transit() -> None:
    q = ChangeQueue(2)
    q._sent.value += 1  # counted, but not in the pipe yet (the feeder is slow)
    with pytest.raises(queue.Empty):
        q.get_nowait()
    q._queue.put("late")
    assert _wait_get(q) == "late"
    with pytest.raises(queue.Empty):  # taken: nothing more pending
        q.get_nowait()


def test_change_queue_full_is_not_counted() -> None:
    q = ChangeQueue(1)
    q.put_nowait("a")
    with pytest.raises(queue.Full):
        q.put_nowait("b")
    assert q._sent.value == 1
    assert _wait_get(q) == "a"


def _take(q: ChangeQueue, out: multiprocessing.queues.Queue, n: int) -> None:  # type: ignore[type-arg]
    out.put([_wait_get(q) for _ in range(n)])


def test_change_queue_across_processes() -> None:
    ctx = multiprocessing.get_context("spawn")
    q = ChangeQueue(4, ctx)
    q.put_nowait("before start")  # put before the taking process has its copy
    out = ctx.Queue()
    proc = ctx.Process(target=_take, args=(q, out, 3))
    proc.start()
    q.put_nowait("second")
    q.put_nowait({"third": 3})
    assert out.get(timeout=60) == ["before start", "second", {"third": 3}]
    proc.join(60)
    assert proc.exitcode == 0
