"""The closed-loop runaway of issue 14 cannot come back under the default estimator.

Policy I near 2.3 Hz with the old default (the 1 s peak of |v_d|, v_max = 1 m/s, (2.12))
jumped to T_as 6.8, DLC 1.35 and |F_d| 51 kN, the model's ceiling F_t(v_max) C_i(0.5 A).
The defaults now (``cycle-rms``, v_max = the set's identified 0.75 m/s, (2.13) in vehicle
runs; model reference, section 2.4) keep it within the HiL load cell's 8.8 kN.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from mrsuspension.control import HiLo
from mrsuspension.dampers import CycleRms, WangSymmetric
from mrsuspension.engine import Simulation
from mrsuspension.engine.result import VelocityClampWarning
from mrsuspension.excitation import Harmonic
from mrsuspension.excitation.deterministic import two_stage_amplitude

LOAD_CELL = 8.8e3  # N, the dissertation's HiL force sensor
#: At a constant 3.5 cm (road acceleration up to 9.3 m/s^2 at 2.6 Hz, beyond the
#: dissertation's 6.1 m/s^2 sweeps) the damper runs past its identified velocities, v_m sits
#: at the 0.75 m/s clamp and single-step force peaks reach 9.3-9.9 kN in SCM at 2.5-2.6 Hz
#: (dt = 0.1 ms; 7.9 kN at 0.5 ms): above the load cell's rating, far below the old 51 kN.
STRESS_LIMIT = 10.5e3


def run(frequency: float, amplitude: float, mode: str = "SCM", dt: float = 2e-4, **damper: object):
    sim = Simulation(
        Harmonic(frequency, amplitude),
        controller=HiLo(1, mode=mode, gain=3.0),
        **({"damper": WangSymmetric(**damper)} if damper else {}),  # type: ignore[arg-type]
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VelocityClampWarning)
        r = sim.run(dt=dt)
    return r, r.measures(), float(np.max(np.abs(r.F_d)))


def test_the_defaults_are_cycle_rms_with_the_vehicle_v_h_variant():
    damper = Simulation(Harmonic(1.0, 0.01)).damper
    assert isinstance(damper, WangSymmetric)
    assert damper.vh_variant == "2.13"
    assert damper.estimator == CycleRms(window=1.0, v_min=1e-3, v_max=0.75)


def test_the_old_default_runs_away_at_the_fig_4_5_setting():
    # the failure this file guards against, reproduced with the old settings
    a = float(two_stage_amplitude(2.3, 0.025))
    _, m, peak = run(2.3, a, estimator="window", v_max=1.0, vh_variant="2.12")
    assert m["T_as"] > 5.0
    assert peak > 40e3


@pytest.mark.parametrize("frequency", [2.2, 2.3, 2.4])
def test_fig_4_5_setting_stays_bounded(frequency):
    _, m, peak = run(frequency, float(two_stage_amplitude(frequency, 0.025)), dt=1e-4)
    assert m["T_as"] <= 3.0
    assert m["DLC"] < 0.9
    assert peak <= LOAD_CELL
    assert m["vm_clamp_fraction"] == 0.0


@pytest.mark.parametrize("mode", ["SCM", "ACM"])
@pytest.mark.parametrize("frequency", [2.0, 2.3, 2.6])
def test_constant_3_5_cm_stays_bounded_and_reports_the_clamp(mode, frequency):
    r, m, peak = run(frequency, 0.035, mode, dt=1e-4)
    assert m["T_as"] <= 3.0
    assert m["DLC"] < 0.9
    assert peak <= STRESS_LIMIT
    # the damper runs beyond its identified velocities here: the result says so
    assert m["vm_clamp_fraction"] == r.velocity_clamp_fraction
    assert 0.0 <= r.velocity_clamp_time <= float(r.time[-1])


def test_a_run_at_the_clamp_warns_and_counts_its_time():
    sim = Simulation(
        Harmonic(2.3, 0.035), controller=HiLo(1, mode="ACM", gain=3.0, adfg_centre=0.5)
    )
    with pytest.warns(VelocityClampWarning, match=r"upper clamp \(0.75 m/s\) for \d+\.\d %"):
        r = sim.run(dt=2e-4)
    share = float(np.mean(r.v_m >= 0.75))
    assert r.velocity_clamp_fraction == pytest.approx(share)
    assert r.velocity_clamp_fraction > 0.2
    assert r.velocity_clamp_time == pytest.approx(share * float(r.time[-1]))
    assert r.measures()["vm_clamp_fraction"] == pytest.approx(share)


def test_a_run_within_the_identified_range_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", VelocityClampWarning)
        r = Simulation(Harmonic(1.5, 0.025), controller=HiLo(1, mode="ACM")).run(dt=2e-4)
    assert r.velocity_clamp_fraction == 0.0
