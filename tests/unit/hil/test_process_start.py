"""Starting the HiL loop's process (:func:`mrsuspension.hil._process._start`): signals."""

from __future__ import annotations

import os
import signal
import threading

import pytest

from mrsuspension.hil import _process


@pytest.mark.skipif(
    threading.current_thread() is not threading.main_thread(), reason="signals: main thread"
)
def test_a_ctrl_c_while_the_loop_process_starts_reaches_the_caller() -> None:
    """A Ctrl-C to the process group while the child starts is pending here while SIGINT
    is blocked and ignored: it must land in the caller's handler once the start is over
    (it was discarded: the child ended with 130 and the parent reported a failed start)."""

    class Starting:
        def start(self) -> None:  # the group's Ctrl-C, during the start
            os.kill(os.getpid(), signal.SIGINT)

    # the caller's Ctrl-C handler (a pytest-xdist worker ignores SIGINT)
    outer = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        before = {s: signal.getsignal(s) for s in _process.LOOP_SIGNALS}
        with pytest.raises(KeyboardInterrupt):
            _process._start(Starting())  # type: ignore[arg-type]
        assert {s: signal.getsignal(s) for s in _process.LOOP_SIGNALS} == before
        assert not signal.pthread_sigmask(signal.SIG_BLOCK, set()) & set(_process.LOOP_SIGNALS)
    finally:
        signal.signal(signal.SIGINT, outer)
