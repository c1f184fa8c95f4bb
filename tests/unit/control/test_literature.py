"""The literature's benchmark laws (control/literature.py, issue 29 part 1).

Each law: its switching rule against hand-computed cases (the function itself, in this
toolkit's signs: up-positive, ``v_d = z_u' - z_s'``, the damper force ``c v_d`` up on the
body), and a closed-loop run on the quarter car showing the effect the rule is for. The
LQ law through an ideal actuator against the closed-form response of the linear quarter
car (1 %), and the literature's ranking of skyhook and ADD on the quarter car with an ideal
two-state damper (docs/control-laws.md, "The literature's benchmark laws").
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
import pytest

from mrsuspension.control import Passive, make_controller
from mrsuspension.control import literature as L
from mrsuspension.dampers.peers import Bingham, LinearViscous
from mrsuspension.engine import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import Harmonic
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.vehicle import FullCar, QuarterCar

HI, LO = 0.5, 0.0
#: the ideal two-state damper's damping at 0 A and 0.5 A [N s/m] (the viscous range of the
#: dissertation's damper, the Bingham fit bingham-wang-low)
C_MIN, C_MAX = 2043.0, 10613.0


def ideal_damper() -> Bingham:
    """A damper linear in its current: ``F = (c_min + (c_max - c_min) i / 0.5 A) v_d``."""
    return Bingham(
        parameters={
            "fc_a": 0.0,
            "fc_b": 0.0,
            "c0_a": C_MIN,
            "c0_b": (C_MAX - C_MIN) / HI,
            "f0": 0.0,
        }
    )


# -- the switching rules against hand-computed cases -------------------------------------
def test_skyhook_onoff_is_high_when_the_damper_opposes_the_body_velocity() -> None:
    f = L.skyhook_onoff.function
    # body up (0.1 m/s), wheel up faster: v_d = +0.2 (compression), c v_d pushes the body
    # up, with it: low; body up, wheel down: v_d < 0, force down against it: high
    assert f(z_s_dot=0.1, v_d=0.2, i_min=LO, i_max=HI) == LO
    assert f(z_s_dot=0.1, v_d=-0.2, i_min=LO, i_max=HI) == HI
    assert f(z_s_dot=-0.1, v_d=0.2, i_min=LO, i_max=HI) == HI


def test_groundhook_is_high_when_the_damper_opposes_the_wheel_velocity() -> None:
    f = L.groundhook.function
    # wheel up at 0.3 m/s, body still: v_d = 0.3; the damper pushes the wheel down with
    # -c v_d: against its velocity: high. Wheel up, body up faster (v_d < 0): low
    assert f(z_u_dot=0.3, v_d=0.3, i_min=LO, i_max=HI) == HI
    assert f(z_u_dot=0.3, v_d=-0.1, i_min=LO, i_max=HI) == LO
    assert f(z_u_dot=-0.3, v_d=-0.3, i_min=LO, i_max=HI) == HI


def test_continuous_groundhook_asks_c_g_z_u_dot_where_dissipative() -> None:
    f = L.groundhook_continuous.function
    assert f(z_u_dot=0.2, v_d=0.1, groundhook_damping=1000.0) == pytest.approx(200.0)
    assert f(z_u_dot=0.2, v_d=-0.1, groundhook_damping=1000.0) == 0.0


def test_hybrid_gates_each_part_by_its_own_rule() -> None:
    f = L.hybrid_skyhook_groundhook.function
    kw: dict[str, Any] = {"alpha": 0.25, "gain": 10.0, "i_min": 0.0, "i_max": 5.0}
    # z_s' = 0.1, z_u' = -0.3, v_d = -0.4: skyhook can (0.1 * -0.4 < 0), groundhook can
    # (-0.3 * -0.4 > 0): i = 10 (0.25 * 0.1 + 0.75 * 0.3) = 2.5 A
    assert f(z_s_dot=0.1, z_u_dot=-0.3, v_d=-0.4, **kw) == pytest.approx(2.5)
    # v_d = +0.4: neither can: i_min
    assert f(z_s_dot=0.1, z_u_dot=-0.3, v_d=0.4, **kw) == 0.0
    # z_u' = +0.3, v_d = -0.2: skyhook only: 10 * 0.25 * 0.1 = 0.25 A
    assert f(z_s_dot=0.1, z_u_dot=0.3, v_d=-0.2, **kw) == pytest.approx(0.25)
    # clipped to i_max
    assert f(z_s_dot=1.0, z_u_dot=-1.0, v_d=-2.0, **kw) == 5.0


def test_add_is_high_when_the_damper_opposes_the_body_acceleration() -> None:
    f = L.add.function
    # body accelerating up (2 m/s^2); the damper force c v_d is down when v_d < 0: high
    assert f(z_s_ddot=2.0, v_d=-0.1, i_min=LO, i_max=HI) == HI
    assert f(z_s_ddot=2.0, v_d=0.1, i_min=LO, i_max=HI) == LO
    assert f(z_s_ddot=-2.0, v_d=0.1, i_min=LO, i_max=HI) == HI


def test_sh_add_picks_skyhook_below_alpha_and_add_above() -> None:
    f = L.sh_add.function
    kw: dict[str, Any] = {"alpha": 10.0, "i_min": LO, "i_max": HI}
    # |z_s''| = 0.5 < 10 |z_s'| = 1: skyhook: z_s' v_d = 0.1 * -0.2 < 0: high, although
    # ADD (z_s'' v_d = -0.5 * -0.2 > 0) would say low
    assert f(z_s_dot=0.1, z_s_ddot=-0.5, v_d=-0.2, **kw) == HI
    # |z_s''| = 5 > 1: ADD: z_s'' v_d = -5 * -0.2 > 0: low, although skyhook says high
    assert f(z_s_dot=0.1, z_s_ddot=-5.0, v_d=-0.2, **kw) == LO
    # on the boundary (z_s''^2 = alpha^2 z_s'^2): skyhook
    assert f(z_s_dot=0.1, z_s_ddot=1.0, v_d=-0.2, **kw) == HI


def test_pdd_cancels_the_spring_within_the_damping_range() -> None:
    f = L.pdd.function
    # k = 50 kN/m, x_d = 0.01, v_d = -0.1: c = -k x_d / v_d = 5000 N s/m: F* = -500 N,
    # the spring's k x_d = +500 N cancelled
    assert f(x_d=0.01, v_d=-0.1, stiffness=5e4, c_min=1000.0, c_max=8000.0) == pytest.approx(-500.0)
    # c would be negative (-5000): c_min
    assert f(x_d=0.01, v_d=0.1, stiffness=5e4, c_min=1000.0, c_max=8000.0) == pytest.approx(100.0)
    # c would be 50 000: c_max
    assert f(x_d=0.1, v_d=-0.1, stiffness=5e4, c_min=1000.0, c_max=8000.0) == pytest.approx(-800.0)
    assert f(x_d=0.1, v_d=0.0, stiffness=5e4, c_min=1000.0, c_max=8000.0) == 0.0
    g = L.pdd_current.function  # c = 5000 of 1000-8000 N s/m: 4/7 of the current range
    got = g(x_d=0.01, v_d=-0.1, stiffness=5e4, c_min=1000.0, c_max=8000.0, i_min=0.0, i_max=0.7)
    assert got == pytest.approx(0.4)


def test_clipped_lq_follows_dykes_rule() -> None:
    f = L.clipped_lq.function
    k = np.array([[1000.0, 2000.0, 0.0, 100.0]])
    kw: dict[str, Any] = {"K": k, "w_rattle": 0.0, "w_tire": 0.0, "w_force": 1.0}
    # x = (z_s - z_u, z_s', ., z_u') = (0.01, 0.1, ., -0.2): f_c = -(10 + 200 - 20) = -190 N
    s = {"z_s_dot": 0.1, "z_u_dot": -0.2, "x_d": -0.01}
    assert f(F_d=-100.0, **s, **kw, i_min=LO, i_max=HI) == HI  # |F_d| below, same sign: more
    assert f(F_d=-300.0, **s, **kw, i_min=LO, i_max=HI) == LO  # above: less
    assert f(F_d=50.0, **s, **kw, i_min=LO, i_max=HI) == LO  # opposite sign: less
    assert L.lq_force.function(**s, **kw) == pytest.approx(-190.0)


# -- closed loop on the quarter car ------------------------------------------------------
def _run(controller: Any, f: float, damper: Any = None, seconds: float = 3.0) -> Any:
    kw = {} if damper is None else {"damper": damper}
    return Simulation(Harmonic(f, 0.005), controller=controller, **kw).run(seconds)


def _steady(result: Any, name: str, last: float = 1.0) -> np.ndarray:
    t = np.asarray(result.time)
    return np.asarray(result[name])[t >= t[-1] - last]


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean((x - x.mean()) ** 2)))


@pytest.mark.parametrize(
    ("law", "f", "ideal", "signal", "gain"),
    [
        # law, road frequency [Hz], ideal two-state damper?, measure, at most x passive 0 A
        ("skyhook-onoff", 1.3, True, "z_s_ddot", 0.5),  # 0.338 vs 0.812 m/s^2
        ("groundhook", 10.0, True, "F_T", 0.6),  # 1192 vs 2359 N
        ("pdd-current", 4.0, True, "z_s_ddot", 0.98),  # 0.530 vs 0.550 (c_max: 1.816)
        ("groundhook-continuous", 10.0, False, "F_T", 0.7),  # 1213 vs 1930 N (0.5 A: 1168)
        ("hybrid-skyhook-groundhook", 1.3, False, "z_s_ddot", 0.85),  # 0.299 vs 0.392
        ("hybrid-skyhook-groundhook", 10.0, False, "F_T", 0.7),  # 1159 vs 1930 N
        ("pdd", 4.0, False, "z_s_ddot", 0.99),  # 0.612 vs 0.632 (0.5 A: 1.879)
    ],
)
def test_the_law_does_what_it_is_for_on_the_quarter_car(
    law: str, f: float, ideal: bool, signal: str, gain: float
) -> None:
    damper = ideal_damper() if ideal else None
    got = _rms(_steady(_run(make_controller(law), f, ideal_damper() if ideal else None), signal))
    low = _rms(_steady(_run(Passive(0.0), f, damper), signal))
    high = _rms(_steady(_run(Passive(HI), f, damper), signal))
    assert got < gain * low, (got, low)
    assert got < 1.05 * high, (got, high)  # and near 0.5 A's, or below it


def _lq_cost(controller: Any) -> float:
    """The LQ's own cost (``z_s''^2 + w_rattle x_1^2 + w_tire x_3^2``, default weights,
    the force's share left out) summed over five sine roads, 1-8 Hz, 5 mm."""
    total = 0.0
    for f in (1.0, 1.6, 2.0, 4.0, 8.0):
        r = _run(controller, f, seconds=2.5)
        x1, x3 = -_steady(r, "x_d"), _steady(r, "z_u") - _steady(r, "z_r")
        total += float(np.mean(_steady(r, "z_s_ddot") ** 2))
        total += L.LQ_WEIGHTS["w_rattle"] * float(np.mean(x1**2))
        total += L.LQ_WEIGHTS["w_tire"] * float(np.mean((x3 - x3.mean()) ** 2))
    return total


@functools.cache
def _passive_lq_costs() -> tuple[float, float]:
    return _lq_cost(Passive(0.0)), _lq_cost(Passive(HI))


@pytest.mark.parametrize("law", ["clipped-lq", "lq-force"])
def test_clipped_lq_lowers_its_cost_below_either_passive_current(law: str) -> None:
    """With the dissertation's damper (measured: clipped-lq 3.70, lq-force 3.58,
    clipped-lqg 3.67; passive 0 A 4.12, 0.5 A 8.03). Not at every frequency (3 s runs: at
    1.6 Hz 0.5 A is lower, 0.24 against 0.41; at 8 Hz 0 A, 2.16 against 2.36): clipping
    the optimal force is not optimal."""
    got = _lq_cost(make_controller(law))
    low, high = _passive_lq_costs()
    assert got < 0.95 * min(low, high), (got, low, high)


def test_lq_through_an_ideal_actuator_matches_the_closed_form_lqr_response() -> None:
    """``lq-active``: the engine's steady-state body transmissibility at seven frequencies
    equals ``|[0 1 0 0] (jw - (A - B K))^-1 E|`` of the linear quarter car within 1 %
    (small amplitude: the tire never lifts off)."""
    car = QuarterCar()
    ctl = make_controller("lq-active").for_plant(car)
    a, b, e = L.quarter_car_model(car)
    k = np.array(ctl.K)
    k[0, 2] = 0.0  # the unmeasured tire deflection's gain is not applied
    acl = a - b @ k
    assert np.all(np.linalg.eigvals(acl).real < 0.0)
    amp = 0.0005
    for f in (0.5, 1.0, 1.6, 3.0, 6.0, 10.0, 15.0):
        w = 2.0 * np.pi * f
        closed = abs(np.linalg.solve(1j * w * np.eye(4) - acl, e[:, 0])[1])
        cycles, settle = max(6, int(3 * f)), max(6.0, 8.0 / f)
        seconds = settle + cycles / f
        r = Simulation(Harmonic(f, amp), controller=ctl, damper=LinearViscous(damping=0.0)).run(
            seconds
        )
        t, zs = np.asarray(r.time), np.asarray(r["z_s"])
        keep = t >= seconds - cycles / f
        m = np.column_stack([np.sin(w * t[keep]), np.cos(w * t[keep]), np.ones(keep.sum())])
        c, *_ = np.linalg.lstsq(m, zs[keep], rcond=None)
        engine = float(np.hypot(c[0], c[1])) / amp
        assert engine == pytest.approx(closed, rel=0.01), (f, engine, closed)
        assert np.all(np.isnan(_steady(r, "i_d")) | (_steady(r, "i_d") == 0.0))


# -- the literature's ranking (Savaresi & Spelta 2007) -----------------------------------
#: the body-motion band of the ranking's measures [Hz]: an ideal two-state damper switched by
#: ADD or SH-ADD chatters at the step rate (5 kHz at 0.1 ms), an artefact of its infinite
#: bandwidth that a record of one step in ten would alias into the band
BODY_BAND = 30.0


def _body_rms(result: Any, since: float, rate: float) -> tuple[np.ndarray, np.ndarray, float]:
    """One-sided power of z_s'' after ``since`` [s] by frequency, its frequencies [Hz] and
    its mean, from a record of every step."""
    t = np.asarray(result.time)
    a = np.asarray(result["z_s_ddot"])[t >= since]
    power = np.abs(np.fft.rfft(a - a.mean())) ** 2 * 2.0 / a.size**2
    f = np.fft.rfftfreq(a.size, 1.0 / rate)
    return power, f, float(a.mean())


@functools.cache
def _transmissibility(law: str, f: float, alpha: float | None = None, amp: float = 0.005) -> float:
    """rms z_s'' (below 30 Hz) / rms z_r'' in the steady state of a sine road (the switched
    linear damper is homogeneous: the ratio does not depend on the amplitude while the tire
    holds the road), recorded at every step."""
    cycles = max(8, int(np.ceil(3.0 * f)))
    seconds = (cycles + max(4, int(2 * f))) / f
    options = {} if alpha is None else {"alpha": alpha}
    r = Simulation(
        Harmonic(f, amp), controller=make_controller(law, **options), damper=ideal_damper()
    ).run(seconds, output_rate=1e4)
    power, freq, mean = _body_rms(r, seconds - cycles / f, 1e4)
    rms = float(np.sqrt(power[freq < BODY_BAND].sum() + mean**2))
    return rms / ((2 * np.pi * f) ** 2 * amp / np.sqrt(2.0))


def test_skyhook_wins_below_the_body_resonance_and_add_above() -> None:
    """Body resonance 1.6 Hz: skyhook below ADD at 0.8 and 1.3 Hz (1.25 vs 1.47, 1.40 vs
    2.10), ADD below skyhook at 3 and 5 Hz (0.40 vs 0.52, 0.20 vs 0.33)."""
    for f in (0.8, 1.3):
        sh, add = _transmissibility("skyhook-onoff", f), _transmissibility("add", f)
        assert sh < 0.9 * add, (f, sh, add)
    for f in (3.0, 5.0):
        sh, add = _transmissibility("skyhook-onoff", f), _transmissibility("add", f)
        assert add < 0.9 * sh, (f, sh, add)


def test_sh_add_is_within_a_few_per_cent_of_the_better_of_skyhook_and_add() -> None:
    """Savaresi & Spelta 2007 on sines: SH-ADD (alpha 8 rad/s) against the better of skyhook
    and ADD at each frequency; measured over 14 frequencies of 0.5-15 Hz +1 to +11 % (mean
    +5.4 %); here five of them, 1.3 Hz and 5 Hz the worst (+11 %, +9 %)."""
    ratios = []
    for f in (0.8, 1.3, 2.5, 5.0, 8.0):
        best = min(_transmissibility("skyhook-onoff", f), _transmissibility("add", f))
        ratios.append(_transmissibility("sh-add", f, 8.0) / best)
    assert max(ratios) < 1.13, ratios
    assert float(np.mean(ratios)) < 1.08, ratios
    assert min(ratios) > 0.95, ratios  # a mix, not a better law than both


# -- every corner of the full car ----------------------------------------------------------
def test_the_laws_run_at_every_corner_of_the_full_car() -> None:
    car = FullCar()
    road = WheelRoads.two_track(
        "C", (car.wheelbase, car.front_track), speed_kmh=72.0, length=20.0, seed=1
    )
    for law in ("sh-add", "clipped-lq"):
        res = VehicleSimulation(car, road, controllers=make_controller(law)).run(0.3)
        currents = {c: np.asarray(res[f"i_d.{c}"]) for c in car.corners}
        for c, i in currents.items():
            assert np.all(np.isfinite(i)), (law, c)
            assert i.max() == HI, (law, c)
            assert i.min() == LO, (law, c)
    # each corner's LQ gain from its own quarter car (front and rear differ)
    ks = [
        np.asarray(make_controller("clipped-lq").for_plant(car.corner_quarter_car(c)).K)
        for c in car.corners
    ]
    assert not np.allclose(ks[0], ks[-1])


def test_a_scenario_names_a_literature_law_with_its_gain_matrix() -> None:
    from mrsuspension.scenario import Scenario

    def controller(table: dict[str, Any]) -> Any:
        data = {"excitation": {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.02}}
        return Scenario.from_dict({**data, "controller": table}).simulations()[0].controller

    ctl = controller({"law": "clipped-lq", "K": [[1000.0, 2000.0, 0.0, 10.0]], "i_max": 0.4})
    assert ctl.law == "clipped-lq"
    assert ctl.K == ((1000.0, 2000.0, 0.0, 10.0),)  # given gains are kept
    assert ctl.i_max == 0.4
    with pytest.raises(ValidationError, match=r"K must be an array of shape \(1, 4\)"):
        controller({"law": "clipped-lq", "K": [1.0, 2.0]})


def test_sh_add_is_near_the_better_of_skyhook_and_add_on_a_road() -> None:
    """ISO 8608 class C road at 72 km/h (30 s), an ideal two-state damper of 300 and
    3000 N s/m (2.6 and 26 % of critical), recorded at every step: SH-ADD (alpha 15 rad/s)
    within 12 % of the better of skyhook and ADD in every band from 1.2 to 15 Hz (measured:
    +5, -1, +5, +9, +2 %), +22 % at 0.5-1.2 Hz, and lowest overall (1.166 m/s^2 against
    skyhook's 1.204 and ADD's 1.633). (With the dissertation's range, 2043-10613
    N s/m, it is +24 to +51 % below 2 Hz: docs/control-laws.md.)"""
    from mrsuspension.excitation.road import iso8608

    road = iso8608("C", length=620.0, seed=3, speed_kmh=72.0)
    damper = Bingham(
        parameters={"fc_a": 0.0, "fc_b": 0.0, "c0_a": 300.0, "c0_b": 2700.0 / HI, "f0": 0.0}
    )
    bands = [(0.5, 1.2), (1.2, 2.0), (2.0, 3.0), (3.0, 5.0), (5.0, 8.0), (8.0, 15.0), (0.5, 15.0)]

    def band_rms(law: str, **options: float) -> np.ndarray:
        r = Simulation(road, controller=make_controller(law, **options), damper=damper).run(
            30.0, output_rate=1e4
        )
        power, f, _ = _body_rms(r, 2.0, 1e4)
        return np.array([np.sqrt(power[(f >= lo) & (f < hi)].sum()) for lo, hi in bands])

    sh, add_, mix = band_rms("skyhook-onoff"), band_rms("add"), band_rms("sh-add", alpha=15.0)
    best = np.minimum(sh, add_)
    assert sh[0] < add_[0]  # skyhook below the resonance, ADD above it
    assert sh[1] < add_[1]
    assert np.all(add_[2:5] < sh[2:5])
    assert np.all(mix[1:6] < 1.12 * best[1:6]), mix / best
    assert mix[0] < 1.3 * best[0], mix / best
    assert mix[6] < best[6], mix / best


# -- LQG: the law's memory holds a Kalman estimate -------------------------------------
def _count(time: float, memory: Any, step: float = 1e-4) -> float:
    memory[0] += 1.0
    return memory[0] * step


@pytest.mark.parametrize("numba", [None, False])
def test_a_laws_memory_is_kept_between_calls_and_zero_at_each_run_start(numba: Any) -> None:
    from mrsuspension.control import law

    counter = law(numba=numba, memory=1)(_count)
    sim = Simulation(Harmonic(1.0, 0.01), controller=counter())
    for _ in range(2):  # the second run starts from zero again
        i_d = np.asarray(sim.run(0.05, output_rate=10000.0).i_d)
        np.testing.assert_allclose(i_d[1:4], [1e-4, 2e-4, 3e-4])
        assert i_d[-1] == pytest.approx(0.05)  # 500 steps
    car = FullCar()  # one memory per corner: every corner counts its own steps
    road = WheelRoads.two_track(
        "C", (car.wheelbase, car.front_track), speed_kmh=72.0, length=20.0, seed=1
    )
    res = VehicleSimulation(car, road, controllers=counter()).run(0.02)
    for c in car.corners:
        assert np.asarray(res[f"i_d.{c}"])[-1] == pytest.approx(0.02)


def test_lqg_estimates_the_lq_force_and_responds_as_the_full_state_lqr() -> None:
    """``lqg-active``: the force from the Kalman estimate within 5 % (rms) of ``-K x`` of
    the true states, tire deflection included (measured 0.9-4.4 % at 0.5-15 Hz), and the
    body transmissibility within 5 % of the full-state LQR's ``A - B K`` (measured +4.1,
    +3.8, +1.8, -0.7 % at 0.5, 1.6, 6 and 10 Hz)."""
    car = QuarterCar()
    ctl = make_controller("lqg-active").for_plant(car)
    k = np.asarray(ctl.K)
    a, b, e = L.quarter_car_model(car)
    acl = a - b @ k
    amp = 0.0005
    for f in (0.5, 1.6, 6.0, 10.0):
        cycles = max(6, int(3 * f))
        seconds = max(6.0, 8.0 / f) + cycles / f
        r = Simulation(Harmonic(f, amp), controller=ctl, damper=LinearViscous(damping=0.0)).run(
            seconds
        )
        last = cycles / f
        x = np.vstack(
            [
                _steady(r, "z_s", last) - _steady(r, "z_u", last),
                _steady(r, "z_s_dot", last),
                _steady(r, "z_u", last) - _steady(r, "z_r", last),
                _steady(r, "z_u_dot", last),
            ]
        )
        true = -(k @ x)[0]
        error = _steady(r, "F_target", last) - true
        assert np.sqrt(np.mean(error**2)) < 0.05 * np.sqrt(np.mean(true**2)), f
        w = 2.0 * np.pi * f
        closed = abs(np.linalg.solve(1j * w * np.eye(4) - acl, e[:, 0])[1])
        t = np.asarray(r.time)[-x.shape[1] :]  # the samples _steady kept
        m = np.column_stack([np.sin(w * t), np.cos(w * t), np.ones(t.size)])
        c, *_ = np.linalg.lstsq(m, _steady(r, "z_s", last), rcond=None)
        assert float(np.hypot(c[0], c[1])) / amp == pytest.approx(closed, rel=0.05), f


def test_clipped_lqg_lowers_the_lq_cost_below_either_passive_current() -> None:
    got = _lq_cost(make_controller("clipped-lqg"))
    low, high = _passive_lq_costs()
    assert got < 0.95 * min(low, high), (got, low, high)
