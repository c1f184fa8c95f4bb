"""The inverse-model laws keep the damper's v_m terms in a memo: same results, fresh per run.

Sliding mode and inverse hi-lo evaluate the passive hysteron every step; its v_m terms
(F_t, alpha/2, exp(-a4 v_m)) are kept in ``mem`` at ``EK.M_PH`` while v_m is unchanged
(:func:`~mrsuspension.dampers.kernels.passive_hysteron_memo`). The memo must give the
outputs bit for bit and must not carry over from one run, or one damper, to the next.
"""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.control import InverseHiLo, SlidingMode
from mrsuspension.control import kernel as CK
from mrsuspension.dampers import WangAsymmetric, WangSymmetric
from mrsuspension.dampers import kernels as DK
from mrsuspension.engine import Simulation
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import lanes as LN
from mrsuspension.excitation import Harmonic
from mrsuspension.vehicle import QuarterCar

LAWS = [SlidingMode(), InverseHiLo(mode="ACM")]
IDS = ["sliding-mode", "inverse-hilo"]


@pytest.mark.parametrize("ctl", LAWS, ids=IDS)
def test_law_with_the_memo_is_the_law_without(ctl) -> None:  # type: ignore[no-untyped-def]
    cp = ctl.params(0.5)
    vp = QuarterCar().params()
    dp = WangAsymmetric().kernel(1e-4).params
    rng = np.random.default_rng(11)
    memo = np.zeros(DK.PH_SIZE)
    vms = np.repeat(rng.uniform(0.05, 1.0, 30), 20)  # v_m held over 20 steps at a time
    for vm in vms:
        y = rng.normal(0.0, [0.03, 0.4, 0.01, 0.6, 0.03, 0.4])
        ad = rng.normal(0.0, 20.0)
        kept = CK.control(ctl.code, cp, vp, dp, y, ad, float(vm), memo)
        fresh = CK.control(ctl.code, cp, vp, dp, y, ad, float(vm), np.zeros(DK.PH_SIZE))
        assert kept == fresh
    assert memo[DK.PH_VM] == vms[-1]


def _kernel_run(a, zr, zrd, n, dt):  # type: ignore[no-untyped-def]
    y = np.array([zr[0], 0.0, zr[0], 0.0, zr[0], 0.0])
    rec = np.zeros((n + 1, EK.N_REC))
    status = EK.run(
        y, n, dt, zr, zrd, *a.args(), 1, EK.LIMITS, np.zeros(EK.SCRATCH_SIZE), *EK.recording(rec)
    )
    assert status[0] == EK.D_OK
    return rec


def test_start_empties_the_memo_of_the_previous_run() -> None:
    # a short run leaves a memo at the estimator's first v_m, which the next run starts
    # at too; that run's damper has another seal friction (another F_t): a memo kept
    # across the start would give it the old F_t
    sim = Simulation(Harmonic(2.0, 0.02), controller=SlidingMode())
    dt, n = 2e-4, 1500
    zr, zrd = sim.road_samples(n, dt)
    first = sim.kernel_arrays(dt)
    _kernel_run(first, zr, zrd, 3, dt)
    assert first.memory[EK.M_PH + DK.PH_FT] != 0.0
    runs = []
    for memory in (first.memory, np.zeros(EK.MEM_SIZE)):
        memory[: EK.M_PH] = 0.0  # all but the memo, as a new run's memory
        a = sim.kernel_arrays(dt)
        dp = a.damper_params.copy()
        dp[DK.W_F0] *= 1.5
        runs.append(_kernel_run(a.replace(damper_params=dp, memory=memory), zr, zrd, n, dt))
    np.testing.assert_array_equal(runs[0], runs[1])


def test_lanes_run_after_run_as_separate_runs() -> None:
    # more runs than lanes: each lane runs several in sequence, at different v_m
    sims = [
        Simulation(Harmonic(f, a), controller=SlidingMode())
        for f in (1.0, 2.0, 3.0)
        for a in (0.002, 0.004, 0.006, 0.008, 0.01, 0.012)
    ]
    assert len(sims) > LN.LANES
    lanes = LN.run_lanes(sims, duration=0.6)
    peaks = set()
    for sim, lane in zip(sims, lanes, strict=True):
        single = sim.run(0.6)
        assert not isinstance(lane, Exception)
        for name in ("z_s", "F_d", "i_d", "v_m", "z_s0"):
            a, b = np.asarray(lane.signals[name]), np.asarray(single.signals[name])
            assert np.max(np.abs(a - b)) <= 1e-9 * max(np.max(np.abs(b)), 1e-30), name
        peaks.add(round(float(single.signals["v_m"][-1]), 6))
    assert len(peaks) > 10  # the runs did latch different peak velocities


def test_stepper_update_to_another_damper_empties_the_memo() -> None:
    # a live change of damper keeps the step memory but not the memo: the first step
    # after it inverts the new damper
    sim = Simulation(Harmonic(2.0, 0.02), controller=SlidingMode(), damper=WangSymmetric())
    stepper = sim.stepper(1e-4)
    for k in range(3):
        stepper.step(float(sim.excitation.displacement(k * 1e-4)), 0.0)
    assert stepper.arrays.memory[EK.M_PH + DK.PH_FT] != 0.0
    other = Simulation(
        sim.excitation, controller=SlidingMode(), damper=WangSymmetric("wang-symmetric-high")
    )
    stepper.update(other)
    a = stepper.arrays
    y, ad = stepper.y.copy(), float(a.memory[EK.M_AD])
    out = stepper.step(0.0, 0.0)
    expected = CK.control(
        a.controller_kind, a.controller_params, a.vehicle, a.damper_params, y, ad,
        out["v_m"], np.zeros(DK.PH_SIZE),
    )  # fmt: skip
    assert (out["i_z"], out["z_c"]) == expected[1:3]
