"""Every rig kind of the registry (:data:`mrsuspension.hil.rigs.RIGS`) passes one contract.

Each constructs from its ``--rig`` spec, resets, runs a few ticks of ``command`` /
``read`` and returns a finite force, and closes. The UDP rig talks to ``serve_rig`` in a
thread of this process on an ephemeral loopback port.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Iterator
from contextlib import contextmanager

import pytest

from _helpers import raises_validation
from mrsuspension.dampers import WangSymmetric
from mrsuspension.hil.rig import Rig
from mrsuspension.hil.rigs import RIGS, make_rig, normalise_rig_spec, rig_kind, rig_syntax


@contextmanager
def _served() -> Iterator[str]:
    """A simulated rig served over UDP from a thread; yields its ``udp://`` spec."""
    from mrsuspension.hil.network import serve_rig
    from mrsuspension.hil.rig import SimulatedRig

    stop = threading.Event()
    port: list[int] = []
    ready = threading.Event()

    def ready_at(p: int) -> None:
        port.append(p)
        ready.set()

    thread = threading.Thread(
        target=serve_rig,
        args=(SimulatedRig(WangSymmetric()),),
        kwargs={"port": 0, "ready": ready_at, "should_stop": stop.is_set, "watchdog": 0.0},
        daemon=True,
    )
    thread.start()
    try:
        assert ready.wait(30), "serve_rig did not start"
        yield f"udp://127.0.0.1:{port[0]}"
    finally:
        stop.set()
        thread.join(10)


@contextmanager
def _spec(name: str) -> Iterator[str]:
    if name == "udp":
        with _served() as spec:
            yield spec
    else:
        yield RIGS[name].syntax


@pytest.mark.parametrize("name", list(RIGS))
def test_rig_contract(name: str) -> None:
    with _spec(name) as spec:
        kind = rig_kind(spec)
        assert kind.name == name
        rig = make_rig(spec, WangSymmetric())
        assert isinstance(rig, Rig)
        try:
            period = 1e-3
            rig.reset(period)
            forces = []
            for k in range(20):
                sample = rig.read()
                forces.append(sample.force)
                rig.command(0.002 * math.sin(2 * math.pi * 1.5 * k * period), 0.1, 0.0)
            assert all(math.isfinite(f) for f in forces)
            assert isinstance(rig.describe(), dict)
        finally:
            rig.close()


def test_registry_drives_help_and_errors() -> None:
    assert rig_syntax() == " | ".join(k.syntax for k in RIGS.values())
    assert "udp://HOST:PORT" not in rig_syntax(local_only=True)
    syntaxes = [k.syntax for k in RIGS.values()]
    raises_validation(
        lambda: make_rig("bench", WangSymmetric()), "unknown --rig 'bench'", *syntaxes
    )
    assert normalise_rig_spec(" SIMULATED ") == "simulated"
    raises_validation(lambda: make_rig("udp://nohost", WangSymmetric()), "udp://nohost")
