"""A signal that lands where a raised exception would be lost is delivered again after.

Python runs a signal handler at the next bytecode of the main thread; inside a finalizer
(``Popen.__del__`` during garbage collection) the handler's exception is printed as
"Exception ignored ... Traceback" and dropped, and inside numba's LLVM callbacks (ctypes)
it can crash the process. Both the CLI's handler (``_pool.handle_signals``) and the HiL
loop's (``hil._process._raise_interrupted``) then send the signal again a moment later.
"""

from __future__ import annotations

import os
import signal
import sys
import time
from types import FrameType

import pytest

from mrsuspension._pool import Interrupted, handle_signals, raise_is_lost


class _Finalized:
    def __init__(self, box: list[FrameType]) -> None:
        self.box = box

    def __del__(self) -> None:
        self.box.append(sys._getframe())


def test_a_finalizer_frame_is_where_a_raise_is_lost() -> None:
    box: list[FrameType] = []
    _Finalized(box)  # collected at once: its __del__ records its frame
    assert box
    assert raise_is_lost(box[0])
    assert not raise_is_lost(sys._getframe())


def test_a_signal_during_a_finalizer_still_interrupts() -> None:
    seen: list[bool] = []

    class Signals:
        def __del__(self) -> None:
            os.kill(os.getpid(), signal.SIGTERM)
            for _ in range(10_000):  # the handler runs here, inside the finalizer
                pass
            seen.append(True)

    def collect_then_wait() -> None:
        with handle_signals():
            Signals()
            deadline = time.monotonic() + 5.0
            while time.monotonic() < deadline:  # the redelivered signal raises here
                time.sleep(0.001)

    with pytest.raises(Interrupted) as err:
        collect_then_wait()
    assert seen == [True]  # the finalizer ran to its end
    assert err.value.exit_code == 143
