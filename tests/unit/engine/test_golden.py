"""The engine's results stay bit-identical across refactors, for every controller.

``tests/data/golden_engine.npz`` holds every output signal of a short harmonic run and
a short rounded-pulse run for each registered controller law, made on ``main`` before
the controllers moved into ``control/``. A change that alters any sample by any amount
fails here (but for :data:`NUMPY_ONLY`); regenerate only for an intended change of the physics, with
``python tests/unit/engine/test_golden.py --write`` and a CHANGELOG entry.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from mrsuspension.control import CONTROLLERS, UserLaw, controller_class, make_controller
from mrsuspension.engine import Simulation
from mrsuspension.excitation import Harmonic, RoundedPulse

GOLDEN = Path(__file__).resolve().parents[2] / "data" / "golden_engine.npz"

#: the compiled kernel's laws (the literature's laws of control/literature.py run through
#: the user-law entry, made after this record: their own tests check them,
#: tests/unit/control/test_literature.py)
LAWS = sorted(law for law in CONTROLLERS if not issubclass(controller_class(law), UserLaw))
#: signals computed by numpy alone, outside the engine's step (the road acceleration,
#: from the excitation's closed form, reported beside the run and fed back into nothing):
#: numpy's ``exp`` and ``sin`` take CPU-specific SIMD paths (AVX-512 or AVX2), which
#: differ by an ulp, so these are held to 4 ulp; every signal of the step stays bit-exact
NUMPY_ONLY = {"z_r_ddot"}
#: options pinned to the defaults the record was made with (a default changed since by
#: evidence: docs/errata.md, "Control unknowns identified"), so the record still checks
#: the engine bit for bit
PINNED: dict[str, dict[str, float]] = {"sliding-mode": {"beta": 1.25}}
CASES = {
    "harmonic": (lambda: Harmonic(2.0, 0.02), 1.5),
    "pulse": (lambda: RoundedPulse(0.05, 2.0, delay=0.2), 1.0),
}


def _signals(law: str, case: str) -> dict[str, np.ndarray]:
    excitation, duration = CASES[case]
    sim = Simulation(excitation(), controller=make_controller(law, **PINNED.get(law, {})))
    result = sim.run(duration=duration, dt=2e-4, output_rate=250.0)
    out = {f"{law}/{case}/time": result.time}
    out.update({f"{law}/{case}/{k}": np.asarray(v) for k, v in result.signals.items()})
    return out


def _all() -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    for law in LAWS:
        for case in CASES:
            out.update(_signals(law, case))
    return out


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("law", LAWS)
def test_engine_results_are_bit_identical_to_the_golden_record(law: str, case: str) -> None:
    golden = np.load(GOLDEN)
    got = _signals(law, case)
    prefix = f"{law}/{case}/"
    expected = {k for k in golden.files if k.startswith(prefix)}
    assert expected, f"no golden record for {law}/{case}: a new law needs one (--write)"
    assert set(got) == expected
    for key in sorted(expected):
        if key.rsplit("/", 1)[1] in NUMPY_ONLY:
            np.testing.assert_array_max_ulp(got[key], golden[key], maxulp=4)
        else:
            np.testing.assert_array_equal(got[key], golden[key], err_msg=key)


if __name__ == "__main__" and "--write" in sys.argv:
    np.savez_compressed(GOLDEN, **_all())
    print(f"wrote {GOLDEN}")
