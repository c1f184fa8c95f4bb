"""A run whose drive current alternates at the step rate warns when its record is decimated.

The kernels count the steps whose change of the current reverses the step before's
(``engine.kernel.note_current``); ``Simulation.run`` and ``VehicleSimulation.run`` warn
(:class:`AliasedRecordWarning`) when that share is above ``ALIAS_WARN_FRACTION`` and the
record keeps one step in several. The count is checked here against a recount in Python
from a record of every step.
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

from mrsuspension.engine import kernel as EK
from mrsuspension.engine.result import ALIAS_WARN_FRACTION, AliasedRecordWarning
from mrsuspension.scenario import Scenario

HARMONIC = {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.02}
DT = 1e-4


def _sim(law: str, vehicle: str = "quarter-car"):  # type: ignore[no-untyped-def]
    d = {
        "damper": {"model": "wang-symmetric", "parameters": "wang-symmetric-low"},
        "controller": {"law": law},
        "excitation": HARMONIC,
    }
    if vehicle != "quarter-car":
        d["vehicle"] = {"model": vehicle}
    return Scenario.from_dict(d).runs()[0]


def _run(sim, output_rate: float) -> tuple[object, list[str]]:  # type: ignore[no-untyped-def]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = sim.run(2.0, dt=DT, output_rate=output_rate)
    # by name, not identity: a second copy of engine/result.py (the doctests' import, before
    # the root conftest.py) gave the engine's warning another class
    said = [w for w in caught if w.category.__name__ == AliasedRecordWarning.__name__]
    return result, [str(w.message) for w in said]


def _recount(i_d: np.ndarray) -> float:
    """The kernel's rule in Python: a change above CHATTER_CURRENT opposite to the step
    before's (which was itself above it)."""
    d = np.diff(i_d)
    big = np.abs(d) > EK.CHATTER_CURRENT
    return float(np.sum(big[1:] & big[:-1] & (d[1:] * d[:-1] < 0.0)))


def test_the_count_of_reversals_in_a_hand_sequence() -> None:
    mem = np.zeros(EK.MEM_SIZE)
    # 0 -> 0.5 -> 0 -> 0.5: two reversals; a 1 mA wiggle is no change (and breaks the run);
    # 0.501 -> 0 -> 0.5 -> 0.5 -> 0: one more (the held step breaks the alternation)
    seq = [0.0, 0.5, 0.0, 0.5, 0.501, 0.0, 0.5, 0.5, 0.0]
    for i in seq:
        mem[EK.M_ID] = i
        EK.note_current(mem)
    assert mem[EK.M_NREV] == 3.0
    assert _recount(np.array(seq)) == 3.0


def test_a_law_that_alternates_at_the_step_rate_warns_at_1khz_not_at_every_step() -> None:
    sim = _sim("add")  # acceleration-driven damper: hi-lo on sgn(z_s'' v_d), flips every step
    _, said = _run(sim, 1000.0)
    assert len(said) == 1, said
    assert "output_rate = 1/dt = 10000 Hz" in said[0]
    assert "one step in 10 (1000 Hz)" in said[0]
    full, quiet = _run(sim, 1.0 / DT)
    assert quiet == []  # every step recorded: nothing aliases
    # the kernel's count is the Python recount of the every-step record
    share = _recount(np.asarray(full.i_d)) / round(2.0 / DT)
    assert share > ALIAS_WARN_FRACTION
    shown = re.search(r"at (\d+) % of the 0.1 ms steps", said[0])
    assert shown is not None
    assert int(shown.group(1)) == round(100 * share)


@pytest.mark.parametrize("law", ["passive", "skyhook-hilo", "sliding-mode", "inverse-hilo"])
def test_the_dissertations_laws_do_not_warn(law: str) -> None:
    _, said = _run(_sim(law), 1000.0)
    assert said == []


def test_a_vehicle_warns_naming_the_corner() -> None:
    _, said = _run(_sim("add", "half-car"), 1000.0)
    assert len(said) == 1, said
    assert "steps at front" in said[0]
    _, quiet = _run(_sim("skyhook-hilo", "half-car"), 1000.0)
    assert quiet == []
