"""Measures reduced inside the kernels against the post-processed measures.

The post-processing (:meth:`SimulationResult.measures`) is the reference. The scalar
reduced run (:func:`~mrsuspension.engine.reduced.run_measures`) steps bit for bit as
:meth:`Simulation.run` and sums in another order; the lanes also differ at round-off in
their exp. Both must give every measure of every controller family under every
excitation kind to 1e-9 relative.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from mrsuspension._batch import Job, run_jobs
from mrsuspension.control import CONTROLLERS, UserLaw, controller_class, make_controller
from mrsuspension.dampers import LinearViscous, WangSymmetric
from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
from mrsuspension.engine import Simulation, SimulationDiverged, measures_of, run_many
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import lanes as LN
from mrsuspension.engine.reduced import run_measures
from mrsuspension.engine.result import MEASURES_BY_KIND
from mrsuspension.engine.settings import RunSettings
from mrsuspension.engine.simulate import MeasuresOf
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import Harmonic, RoadProfile, RoundedPulse

RTOL = 1e-9


def excitations() -> dict[str, tuple[Any, float]]:
    """One excitation of each measures kind and the duration to run it [s]."""
    road = RoadProfile.from_options({"iso_class": "C", "length": 60.0})
    return {
        "harmonic": (Harmonic(4.0, 0.01), 7.5),
        "pulse": (RoundedPulse(0.035, 3.0), 1.5),
        "road": (road, 2.0),
    }


def simulation(law: str, excitation: Any) -> Simulation:
    controller = make_controller(law)
    damper = WangSymmetric(
        force_gain=2.5 if controller.needs_inverse else 1.0, vh_variant=VEHICLE_VH_VARIANT
    )
    return Simulation(excitation, controller=controller, damper=damper)


def worst(a: dict[str, Any], b: dict[str, Any]) -> float:
    """Largest relative difference over the numeric measures (equal keys and notes)."""
    assert a.keys() == b.keys()
    diff = 0.0
    for key, ref in b.items():
        if ref is None or isinstance(ref, str):
            assert a[key] == ref, key
            continue
        diff = max(diff, abs(a[key] - ref) / max(abs(ref), 1e-300) if ref else abs(a[key]))
    return diff


#: the compiled kernel's laws, and of the literature's user laws (control/literature.py)
#: one per output: a current, a force through the inverse model, an ideal actuator's force
_COMPILED = [law for law in CONTROLLERS if not issubclass(controller_class(law), UserLaw)]
REDUCED_LAWS = sorted([*_COMPILED, "clipped-lq", "lq-force", "lq-active"])


@pytest.mark.parametrize("kind", ["harmonic", "pulse", "road"])
@pytest.mark.parametrize("law", REDUCED_LAWS)
def test_in_kernel_measures_equal_the_post_processed(law: str, kind: str) -> None:
    excitation, duration = excitations()[kind]
    sim = simulation(law, excitation)
    reference = sim.run(duration).measures()
    assert set(reference) >= set(MEASURES_BY_KIND[kind])
    assert worst(run_measures(sim, duration=duration), reference) <= RTOL
    if LN.lane_key(sim, 1e-4) is not None:  # the lanes: every family acting through the damper
        (lanes,) = LN.run_lanes([sim], duration=duration, measures=True)
        assert worst(lanes, reference) <= RTOL


def test_lanes_reduce_runs_of_different_lengths_as_single_runs() -> None:
    acm = make_controller("skyhook-hilo", mode="ACM")
    sims = [Simulation(Harmonic(f, 0.01), controller=acm) for f in np.linspace(2.0, 9.0, 21)]
    reduced = LN.run_lanes(sims, measures=True)  # each its own duration: lanes refill
    for sim, m in zip(sims, reduced, strict=True):
        assert worst(m, sim.run().measures()) <= RTOL


def test_road_peak_choice_reaches_the_kernel_path() -> None:
    sim = Simulation(RoundedPulse(0.035, 3.0))
    onset = run_measures(sim, road_peak="onset")
    assert onset["road_peak"] == "onset"
    assert worst(onset, sim.run().measures(road_peak="onset")) <= RTOL
    (lane,) = run_many([sim, sim], workers=1, reduce=MeasuresOf("onset"))[:1]
    assert math.isclose(lane["SAR_s"], onset["SAR_s"], rel_tol=RTOL)


def test_a_record_too_short_is_refused_before_running() -> None:
    with pytest.raises(ValidationError, match="too short for the steady-state rule"):
        run_measures(Simulation(Harmonic(1.0, 0.01)), duration=5.0)


def test_run_many_reduces_in_the_kernels_with_and_without_lanes() -> None:
    acm = make_controller("skyhook-hilo", mode="ACM")
    sims = [Simulation(Harmonic(f, 0.01), controller=acm) for f in np.linspace(3.0, 8.0, 10)]
    sims.append(Simulation(Harmonic(4.0, 0.01), damper=LinearViscous(damping=1500.0)))
    lanes = run_many(sims, workers=1, reduce=measures_of)
    single = run_many(sims, workers=1, reduce=measures_of, lanes=False)
    records = run_many(sims, workers=1, reduce=MeasuresOf().__call__, lanes=False)
    for a, b, c in zip(lanes, single, records, strict=True):
        assert worst(a, c) <= RTOL
        assert worst(b, c) <= RTOL


def test_batches_give_none_for_a_diverged_run(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(EK, "LIMITS", np.array([0.01, 100.0, 1e6, 1e7]))
    plan = RunSettings(duration=1.0)
    jobs = [Job(Simulation(RoundedPulse(0.001, 3.0)), plan) for _ in range(LN.MIN_GROUP)]
    bad = LN.MIN_GROUP - 1  # in the lane group
    jobs[bad] = Job(Simulation(RoundedPulse(0.04, 3.0)), plan)
    jobs.append(Job(Simulation(RoundedPulse(0.002, 2.0)), RunSettings()))
    rows = run_jobs(jobs, None)
    assert rows[bad] is None
    assert all(r is not None for k, r in enumerate(rows) if k != bad)
    assert sorted(rows[-1] or {})[:2] == ["RDR", "SAR_s"]
    (diverged,) = LN.run_lanes([jobs[bad].simulation], duration=1.0, measures=True)
    assert isinstance(diverged, SimulationDiverged)
