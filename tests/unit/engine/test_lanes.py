"""The lane kernel (many runs stepped together) against single runs of the scalar step.

The lanes share the scalar kernels for everything but the RK4 stages, where the damper's
tanh takes its exp from plain arithmetic (``exp_neg``, within 1.5 ulp of libm's). So
every signal must agree with :meth:`Simulation.run` to round-off, for every controller
acting through the damper, with runs of different lengths refilling the lanes.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.control import CONTROLLERS, UserLaw, controller_class, make_controller
from mrsuspension.dampers import CycleRms, LinearViscous, WangAsymmetric, WangSymmetric
from mrsuspension.dampers import kernels as DK
from mrsuspension.engine import Simulation, SimulationDiverged, measures_of, run_many
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import lanes as LN
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import Harmonic, RoundedPulse, log_frequencies

SIGNALS = ("z_s", "z_u", "z_s_ddot", "z_u_ddot", "F_d", "F_T", "i_d", "v_m", "z_s0")
#: the compiled laws acting through the damper (user laws, e.g. the literature's laws of
#: control/literature.py, run outside the lanes: each on its own)
THROUGH_DAMPER = [
    law
    for law in CONTROLLERS
    if not law.startswith("ideal-") and not issubclass(controller_class(law), UserLaw)
]


def agree(lane, single, rtol=1e-9) -> None:  # type: ignore[no-untyped-def]
    assert lane.time.shape == single.time.shape
    np.testing.assert_array_equal(lane.time, single.time)
    for name in SIGNALS:
        a, b = lane.signals[name], single.signals[name]
        scale = max(float(np.max(np.abs(b))), 1e-30)
        assert float(np.max(np.abs(a - b))) <= rtol * scale, name


# -- the vectorisable exp and tanh -----------------------------------------------------
def test_exp_neg_within_round_off_of_libm() -> None:
    xs = -np.concatenate([np.linspace(0.0, 40.0, 200_001), np.geomspace(1e-12, 1.0, 1000)])
    got = np.array([DK.exp_neg(float(x)) for x in xs])
    rel = np.abs(got - np.exp(xs)) / np.exp(xs)
    assert rel.max() < 4e-16  # about 1.5 ulp
    assert DK.exp_neg(0.0) == 1.0


def test_exp_neg_clamps_far_below() -> None:
    assert DK.exp_neg(-1e6) == DK.exp_neg(DK.EXP_NEG_FLOOR)
    assert 0.0 < DK.exp_neg(-1e6) < 1e-17


def test_lane_tanh_matches_fast_tanh_and_both_forms() -> None:
    edge = DK.TANH_RATIONAL_BELOW
    us = np.concatenate(
        [np.linspace(-25.0, 25.0, 20_001), [0.0, -0.0, edge, -edge, np.nextafter(edge, 0.0)]]
    )
    for u in us:
        ref = DK.fast_tanh(float(u))
        assert abs(DK.lane_tanh(float(u)) - ref) <= 8e-16 * abs(ref), u  # a few ulp
    assert DK.lane_tanh(30.0) == 1.0
    assert DK.lane_tanh(-30.0) == -1.0
    assert DK.lane_tanh(0.0) == 0.0


def test_wang_combine_is_the_models_force() -> None:
    # the scalar model assembles its force with wang_combine: same value bit for bit
    dp = WangSymmetric(force_gain=1.7).kernel(1e-4).params
    s = np.zeros(DK.STATE_SIZE)
    DK.wang_latch_motion(dp, s, 0.2, -1.0)
    for v in (-0.3, -0.01, 0.0, 0.05, 0.4):
        f = DK.wang_eval(dp, s, v, 0.3)
        k1 = dp[DK.W_K1C] if v >= 0 else dp[DK.W_K1E]
        tanh = DK.fast_tanh(s[DK.WS_HALF_ALPHA] * (v + s[DK.WS_SHIFT]))
        kdci = dp[DK.W_KD] * s[DK.WS_CI]
        assert DK.wang_combine(kdci, s[DK.WS_FT], s[DK.WS_FB], tanh, k1, s[DK.WS_DECAY], v) == f


def _scalar_latch(dp: np.ndarray, vm: float, sgn: float, i: float) -> list[float]:
    s = np.zeros(DK.STATE_SIZE)
    DK.wang_latch_motion(dp, s, vm, sgn)
    DK.wang_latch_current(dp, s, i)
    return [
        s[DK.WS_HALF_ALPHA], s[DK.WS_SHIFT], s[DK.WS_FT], s[DK.WS_FB], dp[DK.W_KD] * s[DK.WS_CI],
        s[DK.WS_DECAY],
    ]  # fmt: skip


def _lane_latch(dp: np.ndarray, vm: np.ndarray, sgn: np.ndarray, i: np.ndarray) -> np.ndarray:
    n = LN.LANES
    lat = np.zeros(LN.N_LAT * n)
    lat[LN.L_VM * n : (LN.L_VM + 1) * n] = vm
    lat[LN.L_SGN * n : (LN.L_SGN + 1) * n] = sgn
    lat[LN.L_I * n : (LN.L_I + 1) * n] = i
    lin = np.zeros(LN.N_IN * n)
    LN.lane_latch(lat, lin, dp, np.zeros((n, DK.STATE_SIZE)))
    fields = (LN.I_HA, LN.I_SH, LN.I_FT, LN.I_FB, LN.I_KDCI, LN.I_DEC)
    return np.array([[lin[f * n + q] for f in fields] for q in range(n)])


@pytest.mark.parametrize("vh_variant", ["2.12", "2.13"])
def test_the_lane_latch_is_the_scalar_latch_to_round_off(vh_variant: str) -> None:
    dp = WangAsymmetric(force_gain=1.7, vh_variant=vh_variant).kernel(1e-4).params
    rng = np.random.default_rng(3)
    vm = rng.uniform(1e-3, 0.75, LN.LANES)
    sgn = rng.choice([-1.0, 0.0, 1.0], LN.LANES)
    i = rng.uniform(0.0, 0.5, LN.LANES)
    got = _lane_latch(dp, vm, sgn, i)
    for q in range(LN.LANES):
        want = _scalar_latch(dp, vm[q], sgn[q], i[q])
        np.testing.assert_allclose(got[q], want, rtol=2e-15, atol=0.0)


def test_the_lane_latch_falls_back_to_libm_beyond_its_exp_range() -> None:
    # a1 v_m and a4 v_m beyond LANE_EXP_LIMIT in one lane: every lane latches exactly
    dp = WangSymmetric().kernel(1e-4).params
    vm = np.full(LN.LANES, 0.3)
    vm[5] = 1.5 * DK.LANE_EXP_LIMIT / dp[DK.W_A4]
    sgn, i = np.ones(LN.LANES), np.full(LN.LANES, 0.2)
    got = _lane_latch(dp, vm, sgn, i)
    for q in range(LN.LANES):
        assert list(got[q]) == _scalar_latch(dp, vm[q], sgn[q], i[q])


def test_the_lane_latch_falls_back_in_the_damper_state_of_each_slots_lane() -> None:
    # three busy lanes (9, 2, 14) packed into slots 0..2, one beyond the exp range: the
    # scalar latch uses (and writes) each slot's own lane's damper state, no other
    dp = WangSymmetric().kernel(1e-4).params
    n = LN.LANES
    lanes = np.array([9, 2, 14] + [0] * (n - 3), dtype=np.int64)
    vm = np.array([0.3, 1.5 * DK.LANE_EXP_LIMIT / dp[DK.W_A4], 0.1])
    sgn, i = np.array([1.0, -1.0, 0.0]), np.array([0.2, 0.0, 0.4])
    lat = np.zeros(LN.N_LAT * n)
    for field, values in ((LN.L_VM, vm), (LN.L_SGN, sgn), (LN.L_I, i)):
        lat[field * n : field * n + 3] = values
    lin = np.zeros(LN.N_IN * n)
    dss = np.zeros((n, DK.STATE_SIZE))
    LN.lane_latch(lat, lin, dp, dss, lanes, 3)
    fields = (LN.I_HA, LN.I_SH, LN.I_FT, LN.I_FB, LN.I_KDCI, LN.I_DEC)
    for p, q in enumerate(lanes[:3]):
        assert [lin[f * n + p] for f in fields] == _scalar_latch(dp, vm[p], sgn[p], i[p])
        assert dss[q, DK.WS_VM] == vm[p]
        assert dss[q, DK.WS_I] == i[p]
    idle = [q for q in range(n) if q not in lanes[:3]]
    assert not dss[idle].any()


# -- lanes against single runs --------------------------------------------------------
@pytest.mark.parametrize("law", THROUGH_DAMPER)
def test_every_controller_matches_single_runs(law: str) -> None:
    needs = make_controller(law).needs_inverse
    damper = WangSymmetric(force_gain=2.5 if needs else 1.0)
    sims = [
        Simulation(Harmonic(f, 0.02), controller=make_controller(law), damper=damper)
        for f in (0.8, 1.5, 2.5, 4.0, 7.0, 11.0)
    ]
    lanes = LN.run_lanes(sims, duration=1.5)
    for sim, lane in zip(sims, lanes, strict=True):
        assert not isinstance(lane, Exception)
        agree(lane, sim.run(1.5))


@pytest.mark.parametrize(
    "controllers",
    [
        [make_controller("passive", current=i) for i in (0.0, 0.1, 0.25, 0.5)],
        [
            make_controller("skyhook-hilo", gain=k, mode=m)
            for k in (3.0, 300.0)
            for m in ("SCM", "ACM")
        ],
        [
            make_controller("sliding-mode", slope=s, boundary_layer=b)
            for s in (0.3, 0.8)
            for b in (0.02, 0.1)
        ],
    ],
    ids=["passive currents", "hi-lo gains and modes", "sliding-mode gains"],
)
def test_runs_differing_in_controller_parameters_share_lanes(controllers: list) -> None:  # type: ignore[type-arg]
    # a gain or current sweep (the trade-off, the optimiser's candidates): each run keeps
    # its own controller parameters in the lanes
    damper = WangSymmetric(force_gain=2.5)
    sims = [
        Simulation(Harmonic(f, 0.02), controller=c, damper=damper)
        for c in controllers
        for f in (1.2, 4.0)
    ]
    assert len({LN.lane_key(s, 1e-4) for s in sims}) == 1
    lanes = LN.run_lanes(sims, duration=1.0)
    for sim, lane in zip(sims, lanes, strict=True):
        assert not isinstance(lane, Exception)
        agree(lane, sim.run(1.0))
    currents = [float(np.abs(lane.signals["i_d"]).max()) for lane in lanes]
    assert len(set(currents)) > 1  # the parameters did reach the runs


def test_lane_key_keeps_the_constants_the_stages_share() -> None:
    # the sliding-mode reference model's constants enter the lanes' stages: not shared
    a = Simulation(Harmonic(1.0, 0.01), controller=make_controller("sliding-mode"))
    b = Simulation(
        Harmonic(1.0, 0.01), controller=make_controller("sliding-mode", skyhook_damping=5000.0)
    )
    assert LN.lane_key(a, 1e-4) != LN.lane_key(b, 1e-4)


@pytest.mark.parametrize("law", ["inverse-hilo", "sliding-mode"])
@pytest.mark.parametrize("estimator", [None, CycleRms(window=0.5)], ids=["shared", "own"])
def test_inverse_laws_take_the_lanes_v_m_terms_only_for_their_own_v_m(
    law: str, estimator: CycleRms | None
) -> None:
    # the lanes fill the laws' memo with the damper's v_m terms (lane_motion); a
    # controller with its own estimator (another v_m) must compute its own
    sims = [
        Simulation(
            Harmonic(f, 0.02),
            controller=make_controller(law, mode="ACM"),
            damper=WangSymmetric(force_gain=2.5),
            estimator=estimator,
        )
        for f in (0.8, 2.5, 7.0)
    ]
    for sim, lane in zip(sims, LN.run_lanes(sims, duration=1.5), strict=True):
        assert not isinstance(lane, Exception)
        agree(lane, sim.run(1.5))


def test_more_runs_than_lanes_of_different_lengths_refill_the_lanes() -> None:
    # pulses at different speeds and delays: lengths from 2.1 to 3.6 s, all run to the
    # end of their own excitation, more runs than lanes (lanes are refilled)
    hilo = make_controller("skyhook-hilo")
    sims = [
        Simulation(
            RoundedPulse(
                0.02 + 0.001 * k, 2.0 + k % 3, speed_kmh=30.0 + 7.0 * k, delay=0.1 * (k % 5)
            ),
            controller=hilo,
        )
        for k in range(LN.LANES + 5)
    ]
    lengths = {round(s.excitation.duration, 3) for s in sims}
    assert len(lengths) > 10
    lanes = LN.run_lanes(sims, output_rate=500.0)
    for sim, lane in zip(sims, lanes, strict=True):
        agree(lane, sim.run(output_rate=500.0))


# relative to each signal's range, as the lanes module docstring states them
DOCUMENTED = {"z_s": 2.2e-13, "F_d": 1.8e-11, "i_d": 3.3e-11}


@pytest.mark.parametrize("law", ["skyhook-hilo", "sliding-mode"])
def test_runs_of_very_different_lengths_agree_while_lanes_fall_idle(law: str) -> None:
    # a frequency-response group: 10 harmonic runs from 0.5 to 15 Hz, each its own
    # length (40 s down to 7 s), so that most lanes idle for most of the group's time and
    # the busy lanes are packed into fewer and fewer slots; and a group of 3 runs
    controller = make_controller(law)
    damper = WangSymmetric(force_gain=2.5 if controller.needs_inverse else 1.0)
    group = [
        Simulation(Harmonic(f, 0.01), controller=controller, damper=damper)
        for f in log_frequencies(10, 0.5, 15.0)
    ]
    lengths = [s.excitation.duration for s in group]
    assert max(lengths) > 5.0 * min(lengths)
    for sims in (group, [group[0], group[4], group[9]]):
        lanes = LN.run_lanes(sims, output_rate=200.0)
        for sim, lane in zip(sims, lanes, strict=True):
            single = sim.run(output_rate=200.0)
            assert not isinstance(lane, Exception)
            np.testing.assert_array_equal(lane.time, single.time)
            for name, rtol in DOCUMENTED.items():
                a, b = lane.signals[name], single.signals[name]
                assert float(np.max(np.abs(a - b))) <= rtol * float(np.ptp(b)), name


def test_the_asymmetric_model_runs_in_lanes() -> None:
    sims = [
        Simulation(
            Harmonic(f, 0.02), controller=make_controller("skyhook-hilo"), damper=WangAsymmetric()
        )
        for f in (1.0, 3.0, 6.0)
    ]
    for sim, lane in zip(sims, LN.run_lanes(sims, duration=1.0), strict=True):
        agree(lane, sim.run(1.0))  # type: ignore[arg-type]


def test_a_diverging_run_is_reported_and_the_others_kept(monkeypatch: pytest.MonkeyPatch) -> None:
    # a small |z| limit: the 4 cm runs leave it, the 1 mm runs do not
    monkeypatch.setattr(EK, "LIMITS", np.array([0.01, 100.0, 1e6, 1e7]))
    sims = [Simulation(Harmonic(2.0, a)) for a in (0.001, 0.04, 0.001, 0.04)]
    out = LN.run_lanes(sims, duration=1.0)
    for sim, lane in zip(sims, out, strict=True):
        if sim.excitation.amplitude < 0.01:  # type: ignore[attr-defined]
            agree(lane, sim.run(1.0))  # type: ignore[arg-type]
            continue
        assert isinstance(lane, SimulationDiverged)
        with pytest.raises(SimulationDiverged) as single:
            sim.run(1.0)
        assert lane.signal == single.value.signal
        assert math.isclose(lane.time, single.value.time)
        assert str(lane) == str(single.value)


def test_runs_that_cannot_share_lanes_are_refused() -> None:
    base = Simulation(Harmonic(1.0, 0.01))
    with pytest.raises(ValidationError, match="differ only in their excitation"):
        LN.run_lanes(
            [base, Simulation(Harmonic(2.0, 0.01), controller=make_controller("skyhook-hilo"))]
        )
    with pytest.raises(ValidationError, match="dissertation's damper model"):
        LN.run_lanes([Simulation(Harmonic(1.0, 0.01), damper=LinearViscous(damping=1500.0))] * 2)
    with pytest.raises(ValidationError):
        LN.run_lanes([base, base], dt=-1.0)
    assert LN.run_lanes([]) == []


def test_lane_key_separates_what_matters() -> None:
    a = Simulation(Harmonic(1.0, 0.01))
    assert LN.lane_key(a, 1e-4) == LN.lane_key(Simulation(Harmonic(5.0, 0.03)), 1e-4)
    assert LN.lane_key(a, 1e-4) != LN.lane_key(a, 5e-5)
    assert LN.lane_key(a, 1e-4) != LN.lane_key(
        Simulation(Harmonic(1.0, 0.01), damper=WangSymmetric(force_gain=2.0)), 1e-4
    )
    assert (
        LN.lane_key(
            Simulation(Harmonic(1.0, 0.01), controller=make_controller("ideal-skyhook")), 1e-4
        )
        is None
    )
    assert (
        LN.lane_key(Simulation(Harmonic(1.0, 0.01), damper=LinearViscous(damping=1500.0)), 1e-4)
        is None
    )


def test_plan_batches_groups_splits_and_leaves_the_rest_single() -> None:
    hilo = make_controller("skyhook-hilo")
    group_a = [Simulation(Harmonic(1.0 + k, 0.01)) for k in range(2 * LN.MIN_GROUP)]
    group_b = [
        Simulation(Harmonic(1.0 + k, 0.01), controller=hilo) for k in range(LN.MIN_GROUP - 1)
    ]
    linear = [Simulation(Harmonic(1.0, 0.01), damper=LinearViscous(damping=1500.0))]
    sims = group_a + group_b + linear
    one = LN.plan_batches(sims, 1e-4, None, parts=1)
    two = LN.plan_batches(sims, 1e-4, None, parts=2)
    for plan in (one, two):
        assert sorted(j for b in plan for j in b) == list(range(len(sims)))
    assert [len(b) for b in one] == [len(group_a)] + [1] * (len(group_b) + 1)
    # two workers and one lane group: the group is split in two of similar length
    halves = [b for b in two if len(b) > 1]
    assert len(halves) == 2
    assert sorted(halves[0] + halves[1]) == list(range(len(group_a)))
    load = [sum(sims[j].excitation.duration for j in b) for b in halves]
    assert abs(load[0] - load[1]) <= max(sims[j].excitation.duration for j in halves[0] + halves[1])
    assert sum(len(b) == 1 for b in two) == len(group_b) + 1


def test_plan_batches_hands_out_the_costliest_first() -> None:
    # equal runs: a sliding-mode step costs LAW_COST more than a passive one, so its group
    # of 8 goes before a passive group of 8 and after one of 16; single runs (the linear damper's and
    # a group too small for lanes) last, the longest of them first
    sliding = make_controller("sliding-mode")
    damper = WangSymmetric(force_gain=2.5)
    passive = [Simulation(Harmonic(2.0, 0.01)) for _ in range(LN.MIN_GROUP)]
    more = [Simulation(Harmonic(2.0, 0.01)) for _ in range(2 * LN.MIN_GROUP)]
    sm = [Simulation(Harmonic(2.0, 0.01), controller=sliding, damper=damper)] * LN.MIN_GROUP
    linear = [
        Simulation(Harmonic(f, 0.01), damper=LinearViscous(damping=1500.0)) for f in (4.0, 0.5)
    ]
    sims = linear + passive + sm
    plan = LN.plan_batches(sims, 1e-4, 1.0, parts=1)
    n = LN.MIN_GROUP
    assert plan == [list(range(2 + n, 2 + 2 * n)), list(range(2, 2 + n)), [0], [1]]
    cost = [LN.batch_cost(sims, b, 1e-4, 1.0) for b in plan]
    assert cost == sorted(cost, reverse=True)
    singles = [b for b in LN.plan_batches(sims, 1e-4, None, parts=1) if len(b) == 1]
    assert singles == [[1], [0]]  # 0.5 Hz: longer
    sims = sm + more
    assert LN.plan_batches(sims, 1e-4, 1.0, parts=1) == [list(range(n, 3 * n)), list(range(n))]


def test_run_many_keeps_the_input_order_whatever_the_submission_order() -> None:
    sliding = make_controller("sliding-mode")
    damper = WangSymmetric(force_gain=2.5)
    sims = [Simulation(Harmonic(1.0 + k, 0.01)) for k in range(LN.MIN_GROUP)]
    sims += [
        Simulation(Harmonic(1.0 + k, 0.01), controller=sliding, damper=damper)
        for k in range(LN.MIN_GROUP)
    ]
    sims.insert(3, Simulation(Harmonic(3.0, 0.01), damper=LinearViscous(damping=1500.0)))
    out = run_many(sims, duration=0.3, output_rate=200.0, workers=1)
    for sim, got in zip(sims, out, strict=True):
        np.testing.assert_allclose(got.z_s, sim.run(0.3, output_rate=200.0).z_s, rtol=0, atol=1e-15)


# -- through run_many -----------------------------------------------------------------
def test_run_many_with_lanes_matches_without(monkeypatch: pytest.MonkeyPatch) -> None:
    batches: list[int] = []
    real = LN.run_lanes

    def spy(sims, **kw):  # type: ignore[no-untyped-def]
        batches.append(len(sims))
        return real(sims, **kw)

    monkeypatch.setattr(LN, "run_lanes", spy)
    acm = make_controller("skyhook-hilo", mode="ACM")
    sims = [
        Simulation(RoundedPulse(0.035, 2.0, speed_kmh=v), controller=acm)
        for v in np.linspace(20.0, 120.0, LN.MIN_GROUP + 3)
    ]
    sims.append(Simulation(RoundedPulse(0.035, 2.0), damper=LinearViscous(damping=1500.0)))
    seen: list[tuple[int, int]] = []
    with_lanes = run_many(
        sims, workers=1, reduce=measures_of, lanes=True, progress=lambda d, t: seen.append((d, t))
    )
    assert batches == [len(sims) - 1]  # the linear damper's run went on its own
    without = run_many(sims, workers=1, reduce=measures_of, lanes=False)
    assert batches == [len(sims) - 1]
    assert seen[-1] == (len(sims), len(sims))
    for a, b in zip(with_lanes, without, strict=True):
        assert a.keys() == b.keys()
        for key in ("SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR", "peak_tire_force"):
            assert math.isclose(a[key], b[key], rel_tol=1e-9), key
    parallel = run_many(sims, workers=2, reduce=measures_of, lanes=True)
    assert parallel == with_lanes


def test_run_many_raises_a_lane_runs_divergence(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(EK, "LIMITS", np.array([0.01, 100.0, 1e6, 1e7]))
    sims = [Simulation(Harmonic(2.0, 0.001)) for _ in range(LN.MIN_GROUP)]
    sims[-1] = Simulation(Harmonic(2.0, 0.04))
    with pytest.raises(SimulationDiverged, match=r"z_s|z_u"):
        run_many(sims, duration=1.0, workers=1, lanes=True)


def test_plan_batches_keeps_batches_under_the_step_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    sims = [Simulation(Harmonic(5.0, 0.01)) for _ in range(4 * LN.MIN_GROUP)]  # 7 s each
    assert [len(b) for b in LN.plan_batches(sims, 1e-4, None, parts=1)] == [len(sims)]
    # each run is 70 000 steps: a limit of 3 runs' worth asks for many batches, but a
    # batch keeps at least MIN_GROUP runs
    monkeypatch.setattr(LN, "MAX_BATCH_STEPS", 210_000)
    assert [len(b) for b in LN.plan_batches(sims, 1e-4, None, parts=1)] == [LN.MIN_GROUP] * 4
    monkeypatch.setattr(LN, "MAX_BATCH_STEPS", (4 * LN.MIN_GROUP + 1) * 35_000)  # two batches
    assert [len(b) for b in LN.plan_batches(sims, 1e-4, 7.0, parts=1)] == [2 * LN.MIN_GROUP] * 2


def test_lanes_take_their_roads_in_chunks(monkeypatch: pytest.MonkeyPatch) -> None:
    # a few steps a chunk: many refills, some landing on output samples and run ends
    monkeypatch.setattr(LN, "ROAD_CHUNK", 7)
    acm = make_controller("skyhook-hilo", mode="ACM")
    sims = [Simulation(Harmonic(f, 0.02), controller=acm) for f in (1.0, 2.5, 4.0)]
    lanes = LN.run_lanes(sims, duration=0.05, output_rate=2000.0)
    for sim, lane in zip(sims, lanes, strict=True):
        agree(lane, sim.run(0.05, output_rate=2000.0))
