"""Starting the HiL loop's process (:mod:`mrsuspension.hil._process`): signals meanwhile."""

from __future__ import annotations

import signal
import threading
from pathlib import Path

import pytest

from mrsuspension._pool import Interrupted
from mrsuspension.hil import _process

MAIN = threading.current_thread() is threading.main_thread()


@pytest.mark.skipif(not MAIN, reason="signals: main thread")
def test_a_ctrl_c_while_the_loop_process_starts_reaches_the_caller() -> None:
    """A Ctrl-C to this thread while the child starts is pending while SIGINT is blocked
    and ignored: it must land in the caller's handler once the start is over (it was
    discarded: the child ended with 130 and the parent reported a failed start)."""

    class Starting:
        def start(self) -> None:  # a Ctrl-C for this thread, during the start
            signal.pthread_kill(threading.get_ident(), signal.SIGINT)

    # the caller's Ctrl-C handler (a pytest-xdist worker ignores SIGINT), SIGINT unblocked
    outer = signal.signal(signal.SIGINT, signal.default_int_handler)
    mask = signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    try:
        before = {s: signal.getsignal(s) for s in _process.LOOP_SIGNALS}
        with pytest.raises(KeyboardInterrupt):
            _process._start(Starting())  # type: ignore[arg-type]
        assert {s: signal.getsignal(s) for s in _process.LOOP_SIGNALS} == before
        assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, set())
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        signal.signal(signal.SIGINT, outer)


@pytest.mark.parametrize(("signum", "code"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_loop_process_stopped_by_a_signal_before_its_run_is_an_interruption(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, signum: int, code: int
) -> None:
    """The group's signal can miss this process (another thread took it while SIGINT was
    ignored for the start); the child's 128 + signal before any recording then says the
    run was interrupted (exit 130 / 143 from the CLI), not that it failed to start."""

    class Stopped:
        exitcode = code

        def start(self) -> None:
            pass

        def join(self, timeout: float | None = None) -> None:
            pass

    monkeypatch.setattr(_process, "_new_process", lambda *args, **kwargs: Stopped())
    with pytest.raises(Interrupted) as info:
        _process._run_in_process(print, None, None, 1.0, 1000.0, tmp_path)
    assert info.value.exit_code == code
    assert int(info.value.signum) == signum
