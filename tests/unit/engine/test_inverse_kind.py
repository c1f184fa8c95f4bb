"""The inverse-model controllers with the mean or the hysteretic inverse (Figs 5.1-5.2, 6.1-6.2)."""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.control import InverseHiLo, SlidingMode
from mrsuspension.dampers import WangSymmetric
from mrsuspension.engine import Simulation
from mrsuspension.excitation import Harmonic
from mrsuspension.measures import force_tracking_error
from mrsuspension.scenario import Scenario

LAWS = [InverseHiLo, SlidingMode]


def _run(controller: object, hysteresis: bool) -> object:
    sim = Simulation(
        Harmonic(1.5, 0.025),
        controller=controller,  # type: ignore[arg-type]
        damper=WangSymmetric(force_gain=2.5, hysteresis=hysteresis),
    )
    return sim.run(6.0, dt=2e-4, output_rate=5000.0)


def _tracking(result: object) -> float:
    r = result  # SimulationResult
    keep = r["time"] >= 3.0  # type: ignore[index]
    return float(
        force_tracking_error(
            r["F_d"][keep],  # type: ignore[index]
            r["F_target"][keep],  # type: ignore[index]
            r["z_c"][keep],  # type: ignore[index]
        )
    )


@pytest.mark.parametrize("law", LAWS)
def test_mean_inverse_on_the_mean_damper_is_the_same_controller(law: type) -> None:
    """With a mean damper (k4 = 0) both inverse kinds are the same function."""
    a = _run(law(mode="ACM", inverse="mean"), hysteresis=False)
    b = _run(law(mode="ACM"), hysteresis=False)
    np.testing.assert_array_equal(a["i_d"], b["i_d"])  # type: ignore[index]


@pytest.mark.parametrize("law", LAWS)
def test_hysteretic_inverse_tracks_a_hysteretic_damper_better(law: type) -> None:
    """Section 5.2/6.2: the mean inverse on the hysteretic damper mistracks the target."""
    mean = _tracking(_run(law(mode="SCM", inverse="mean"), hysteresis=True))
    hyst = _tracking(_run(law(mode="SCM"), hysteresis=True))
    assert hyst < mean, (hyst, mean)


def test_scenario_key_and_bad_value() -> None:
    harmonic = {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.025}
    sc = Scenario.from_dict(
        {"controller": {"law": "sliding-mode", "inverse": "mean"}, "excitation": harmonic}
    )
    assert sc.controller.inverse == "mean"
    raises_validation(lambda: InverseHiLo(inverse="meen"), "meen", "hysteretic", "mean")
    raises_validation(
        lambda: Scenario.from_dict(
            {"controller": {"law": "skyhook-hilo", "inverse": "mean"}, "excitation": harmonic}
        ),
        "inverse",
    )
