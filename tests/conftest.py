"""Shared fixtures: an independent plain-``math`` reference of the damper equations.

The reference below is written from the model reference (docs/model.md), sections 2-3,
only (never from the package's kernels), so tests can compare the package against it. The
published parameter values are typed in again from the model reference's Tables 2.2 and
2.3 for the same reason.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import pytest

# model reference, section 2.1, Table 2.2 (0.5-5 Hz and 5-15 Hz columns)
TABLE_2_2_LOW = {
    "a0": 992.985, "a1": 5.197, "a2": 7.258, "a3": 6.635, "a4": 7.504, "I0": 0.079,
    "I1": 0.267, "k0": 125.987, "k1": 11.2, "k2": 9.244, "k3": 9.186, "k4": -0.119,
    "F0": 68.506,
}  # fmt: skip
TABLE_2_2_HIGH = {
    "a0": 988.967, "a1": 4.477, "a2": 12.757, "a3": 10.137, "a4": 5.501, "I0": -0.082,
    "I1": 0.165, "k0": 177.249, "k1": 9.486, "k2": 4.355, "k3": 17.781, "k4": -0.156,
    "F0": 70.921,
}  # fmt: skip
# model reference, section 2.2, Table 2.3
TABLE_2_3 = {
    "a0": 995.499, "a1": 1.417, "a2": 5.225, "a3": 2.441, "a4": 2.383, "I0": 0.268,
    "I1": 1.131, "k0": 177.51, "k1c": 16.877, "k1e": 4.673, "k2": 10.61, "k3": 10.666,
    "k4": -0.125, "k5": 0.269, "k6": 0.453, "F0": 79.92,
}  # fmt: skip

SPEC_SETS = {
    "wang-symmetric-low": TABLE_2_2_LOW,
    "wang-symmetric-high": TABLE_2_2_HIGH,
    "wang-asymmetric": TABLE_2_3,
}


def _sgn(u: float) -> float:
    return 1.0 if u > 0 else (-1.0 if u < 0 else 0.0)


@dataclass(frozen=True)
class WangReference:
    """The dissertation's damper model, eqs. (2.7)-(2.21), in plain ``math``."""

    p: Mapping[str, float]

    def current_gain(self, i: float) -> float:  # C_i, (2.9)
        p = self.p
        return (
            1.0
            + p["k2"] / (1.0 + math.exp(-p["a2"] * (i + p["I0"])))
            - p["k2"] / (1.0 + math.exp(-p["a2"] * p["I0"]))
        )

    def h(self, i: float) -> float:  # H(i) of (2.12)
        p = self.p
        return (
            1.0
            + p["k3"] / (1.0 + math.exp(-p["a3"] * (i + p["I1"])))
            - p["k3"] / (1.0 + math.exp(-p["a3"] * p["I1"]))
        )

    def transition_force(self, vm: float) -> float:  # F_t, (2.7)
        return self.p["F0"] * (1.0 + math.exp(self.p["a1"] * vm))

    def alpha(self, vm: float) -> float:  # (2.11)
        return self.p["a0"] / (1.0 + self.p["k0"] * vm)

    def k_v(self, vm: float, v: float = 1.0) -> float:  # (2.10) / (2.21)
        p = self.p
        k1 = p["k1"] if "k1" in p else (p["k1c"] if v >= 0 else p["k1e"])
        return k1 * math.exp(-p["a4"] * vm)

    def v_h(self, a: float, vm: float, i: float, variant: str = "2.12", k4=None) -> float:
        k4 = self.p["k4"] if k4 is None else k4
        factor = self.h(i) if variant == "2.12" else 1.0  # (2.12) / (2.13)
        return _sgn(a) * k4 * vm * factor

    def force(
        self,
        v: float,
        a: float,
        i: float,
        vm: float,
        *,
        variant: str = "2.12",
        kd: float = 1.0,
        hysteresis: bool = True,
    ) -> float:
        """F_d of (2.15) (symmetric sets) or (2.19) (sets with k5, k6, k1c, k1e)."""
        p = self.p
        ci = self.current_gain(i)
        ft = self.transition_force(vm)
        vh = self.v_h(a, vm, i, variant, k4=None if hysteresis else 0.0)
        vb = p.get("k6", 0.0) * vm  # (2.20)
        fb = p.get("k5", 0.0) * ci * ft  # (2.20)
        hyst = ft * math.tanh(self.alpha(vm) * (v + vh + vb) / 2.0) - fb
        return kd * ci * hyst * (1.0 + self.k_v(vm, v) * abs(v))

    def passive_hysteron(self, v: float, a: float, vm: float) -> float:
        """F_h of (2.8) at zero current, v_h of (2.13) (the inverse model's reference)."""
        vh = _sgn(a) * self.p["k4"] * vm
        ft = self.transition_force(vm)
        return ft * math.tanh(self.alpha(vm) * (v + vh) / 2.0) * (1.0 + self.k_v(vm, v) * abs(v))


@pytest.fixture(scope="session")
def wang_reference():
    """Factory: ``wang_reference(name_or_values)`` gives a :class:`WangReference`."""

    def make(spec: str | Mapping[str, float]) -> WangReference:
        return WangReference(dict(SPEC_SETS[spec] if isinstance(spec, str) else spec))

    return make


@pytest.fixture(scope="session")
def spec_sets():
    """Tables 2.2 and 2.3 as typed in from the model reference, by registry name."""
    return {k: dict(v) for k, v in SPEC_SETS.items()}


#: the files that hold the tests marked ``realtime``: ``make test`` runs exactly these
#: after the parallel run (collecting only them saves the rest's import and collection)
REALTIME_FILES = (
    "tests/integration/test_hil.py",
    "tests/integration/test_hil_udp.py",
    "tests/integration/test_monitor.py",
)


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """A ``realtime`` test outside :data:`REALTIME_FILES` would never run in ``make test``."""
    for item in items:
        path = item.nodeid.split("::")[0]
        if item.get_closest_marker("realtime") and path not in REALTIME_FILES:
            raise pytest.UsageError(
                f"{item.nodeid} is marked realtime: add {path} to REALTIME_FILES "
                "(tests/conftest.py) and to the realtime run of `make test` (Makefile)"
            )


@pytest.fixture(autouse=True)
def _signal_handlers_come_back():  # type: ignore[no-untyped-def]
    """A test that leaves SIGINT, SIGTERM or SIGHUP handled otherwise than it found them,
    or the signal mask changed, fails, and they are put back: a later test in the same
    worker (a HiL loop stopped by Ctrl-C) would otherwise see the signal ignored. Found:
    ``mrsus hil rig-emulator`` refusing bad input in-process left its SIGTERM handler."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    watched = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
    before = {s: signal.getsignal(s) for s in watched}
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, ())
    yield
    after = {s: signal.getsignal(s) for s in watched}
    changed = [signal.Signals(s).name for s in watched if after[s] != before[s]]
    for s in watched:
        if after[s] != before[s]:
            signal.signal(s, before[s] if before[s] is not None else signal.SIG_DFL)
    now = signal.pthread_sigmask(signal.SIG_SETMASK, mask)
    if now != mask:
        changed.append(f"mask {sorted(int(s) for s in now)}")
    if changed:
        pytest.fail(f"the test left {', '.join(changed)} changed (put back)", pytrace=False)
