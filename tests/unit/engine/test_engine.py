"""Engine behaviour: physics checks, controller properties, the dissertation's findings."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension import ValidationError
from mrsuspension.control import (
    CONTROLLERS,
    HiLo,
    IdealSkyhook,
    InverseHiLo,
    OnOffADFG,
    Passive,
    SlidingMode,
    UserLaw,
    controller_class,
    make_controller,
)
from mrsuspension.control import kernel as CK
from mrsuspension.dampers import InstantaneousPeak, LinearViscous, WangSymmetric
from mrsuspension.dampers import kernels as DK
from mrsuspension.engine import Simulation, SimulationDiverged, run_many
from mrsuspension.excitation import Harmonic, RoadProfile, RoundedPulse, preset_road
from mrsuspension.vehicle import GRAVITY, QuarterCar

HARMONIC = Harmonic(1.5, 0.025)


# -- vehicle and reference models (model reference, sections 4-5) ----------------------------------
@pytest.mark.parametrize(("mass", "freq"), [(703.0, 1.3), (563.0, 1.5), (422.0, 1.7)])
def test_body_frequencies_of_spec_section_4(mass: float, freq: float) -> None:
    assert QuarterCar(sprung_mass=mass).body_frequency() == pytest.approx(freq, abs=0.05)


def test_static_deflections_and_reference_model() -> None:
    car = QuarterCar.reference()
    assert car.static_suspension_deflection == pytest.approx(0.0969, abs=5e-5)
    assert car.static_tire_deflection == pytest.approx(0.0225, abs=5e-5)
    assert car.skyhook_damping == 6750.0
    f1, f2 = car.undamped_frequencies()
    assert f1 == pytest.approx(1.5, abs=0.05)  # f_n-s0 ~ 1.5 Hz (section 3.4.1)
    assert f2 == pytest.approx(10.0, abs=0.2)  # f_n-u0 ~ 10 Hz


def test_equilibrium_at_rest() -> None:
    """Erratum 1: with no road input nothing moves and the tire carries the weight."""
    flat = RoadProfile(np.linspace(0.0, 100.0, 200), np.zeros(200), speed_kmh=50.0)
    res = Simulation(flat, controller=Passive(0.2)).run(1.0)
    assert np.max(np.abs(res.z_s)) < 1e-12
    assert np.max(np.abs(res.z_u)) < 1e-12
    assert pytest.approx(QuarterCar().static_load, rel=1e-12) == res.F_T


def test_tire_lift_off_gives_zero_force() -> None:
    res = Simulation(RoundedPulse(0.05, 3.0, speed_kmh=100.0), controller=Passive(0.5)).run()
    assert res.F_T.min() == 0.0
    assert np.all(res.F_T >= 0.0)


def _energy(res, car: QuarterCar) -> np.ndarray:  # type: ignore[no-untyped-def]
    """Mechanical energy about equilibrium (no lift-off, road at rest)."""
    return (
        0.5 * car.sprung_mass * res.z_s_dot**2
        + 0.5 * car.unsprung_mass * res.z_u_dot**2
        + 0.5 * car.suspension_stiffness * res.x_d**2
        + 0.5 * car.tire_stiffness * (res.z_u - res.z_r) ** 2
    )


def test_energy_conserved_without_damping_and_dissipated_with() -> None:
    pulse = RoundedPulse(0.01, 3.0, delay=0.05)
    after = pulse.delay + 4 * pulse.pulse_duration
    lossless = QuarterCar(tire_damping=0.0)
    res = Simulation(pulse, vehicle=lossless, damper=LinearViscous(damping=0.0)).run(3.0)
    e = _energy(res, lossless)[res.time > after]
    assert np.ptp(e) / e.mean() < 1e-8  # conserved to RK4 accuracy
    car = QuarterCar()
    res = Simulation(pulse, vehicle=car, damper=LinearViscous(damping=1500.0)).run(3.0)
    keep = res.time > after
    e = _energy(res, car)[keep]
    assert np.all(np.diff(e) <= 1e-9 * e[0])  # never gains energy
    # and the loss equals the dissipated work  integral(c v_d^2 + c_t z_u'^2) dt
    t = res.time[keep]
    power = 1500.0 * res.v_d[keep] ** 2 + car.tire_damping * res.z_u_dot[keep] ** 2
    dissipated = np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(t))
    assert e[0] - e[-1] == pytest.approx(dissipated, rel=1e-3)


# -- controllers ------------------------------------------------------------------------
#: the compiled kernel's laws (the literature's user laws, control/literature.py: the same
#: current limit in tests/unit/control/test_contract.py)
ALL_LAWS = sorted(law for law in CONTROLLERS if not issubclass(controller_class(law), UserLaw))


def _simulation(law: str, excitation, **kw) -> Simulation:  # type: ignore[no-untyped-def]
    ctl = make_controller(law)
    damper = WangSymmetric(force_gain=2.5 if ctl.needs_inverse else 1.0)
    return Simulation(excitation, controller=ctl, damper=damper, **kw)


@pytest.mark.parametrize("law", ALL_LAWS)
@pytest.mark.parametrize(
    "excitation", [HARMONIC, RoundedPulse(0.05, 3.0)], ids=["harmonic", "pulse"]
)
def test_every_controller_keeps_current_within_limits(law: str, excitation) -> None:  # type: ignore[no-untyped-def]
    res = _simulation(law, excitation, max_current=0.3).run(3.0)
    assert np.all(res.i_d >= 0.0)
    assert np.all(res.i_d <= 0.3 + 1e-15)
    assert np.all(np.isfinite(res.F_d))


def test_ideal_references_are_dissipative() -> None:
    for ctl in (IdealSkyhook(), make_controller("ideal-onoff")):
        res = Simulation(HARMONIC, controller=ctl).run(4.0)
        assert np.all(res.F_d * res.v_d >= -1e-9)
        assert np.any(res.F_d != 0.0)


def _gamma(mode: str, **kw: float) -> float:
    res = Simulation(HARMONIC, controller=HiLo(1, mode=mode, **kw)).run()
    m = res.measures()
    return float(m["gamma"])


def test_policy_one_asymmetry_ratio_acm_and_scm() -> None:
    """gamma ~ 2.8 in ACM with (2.3) as written, the default (dissertation ~2.4), ~1 in SCM
    at 1.5 Hz, 2.5 cm; the identified ADFG centre 0.1 gives less compression current, so a
    larger gamma (docs/errata.md, "Control unknowns identified").

    Model reference, section 2.4.
    """
    printed = _gamma("ACM")
    assert 2.0 <= printed <= 3.5
    assert printed < _gamma("ACM", adfg_centre=0.1) <= 4.5
    assert _gamma("SCM") == pytest.approx(1.0, abs=0.05)


def test_policy_one_force_levels_of_spec_section_2_4() -> None:
    res = Simulation(HARMONIC, controller=HiLo(1, mode="SCM")).run()
    steady = res.time > 7.0
    peak = np.max(np.abs(res.F_d[steady]))
    assert peak == pytest.approx(2100.0, rel=0.1)  # "about +-2.1 kN in SCM"


def test_acm_draws_less_current_than_scm() -> None:
    """Section 4.3.2."""
    acm = Simulation(HARMONIC, controller=HiLo(1, mode="ACM")).run().measures()
    scm = Simulation(HARMONIC, controller=HiLo(1, mode="SCM")).run().measures()
    assert acm["mean_current"] < scm["mean_current"]


def _transients(hysteresis: bool) -> tuple[float, float]:
    damper = WangSymmetric(hysteresis=hysteresis)
    res = Simulation(HARMONIC, damper=damper, controller=OnOffADFG(0.3, p=0.0)).run(
        6.0, output_rate=10_000.0
    )
    keep = res.time > 3.0
    dfdt = np.diff(res.F_d[keep]) / np.diff(res.time[keep])
    return float(np.max(np.abs(dfdt))), float(np.max(np.abs(res.z_u_ddot[keep])))


def test_hysteresis_with_onoff_switching_gives_larger_transients() -> None:
    """Fig. 4.3: the hysteretic model shows larger force-rate and wheel-acceleration peaks."""
    rate_h, acc_h = _transients(True)
    rate_m, acc_m = _transients(False)
    assert rate_h > rate_m
    assert acc_h > acc_m


def _peak_didt(order: float) -> float:
    res = Simulation(HARMONIC, controller=HiLo(1, order=order, mode="SCM")).run(
        6.0, output_rate=10_000.0
    )
    keep = res.time > 3.0
    return float(np.max(np.abs(np.diff(res.i_d[keep]) / np.diff(res.time[keep]))))


def test_controller_order_smooths_current() -> None:
    """Fig. 4.26: n = 1 gives a larger peak |di/dt| than n = 2, and n = 3 a smaller one."""
    d1, d2, d3 = (_peak_didt(n) for n in (1.0, 2.0, 3.0))
    assert d1 > d2 > d3


def test_sliding_condition_holds_for_the_load_range() -> None:
    """(3.31): s s' <= -phi |s| outside the boundary layer, m_s in [m_s0/beta, beta m_s0].

    The control law (CK.control) gives F_c; an ideal actuator applies it; s' follows from
    the plant with the *true* sprung mass and the reference model.
    """
    ctl = SlidingMode()
    cp = ctl.params(0.5)
    car = QuarterCar()
    vp = car.params()
    dp = WangSymmetric(vh_variant="2.13").kernel(1e-4).params
    rng = np.random.default_rng(3)
    checked = 0
    for _ in range(2000):
        y = np.concatenate([rng.normal(0, 0.05, 1), rng.normal(0, 0.5, 1),
                            rng.normal(0, 0.02, 1), rng.normal(0, 0.5, 1),
                            rng.normal(0, 0.05, 1), rng.normal(0, 0.5, 1)])  # fmt: skip
        zs, vs, zu, vu, z0, v0 = y
        e, ed = zs - z0, vs - v0
        s = ed + ctl.slope * e
        if abs(s) <= ctl.boundary_layer:
            continue
        f_c = CK.control(CK.C_SLIDING, cp, vp, dp, y, 0.0, 0.3, np.zeros(DK.PH_SIZE))[3]
        a0 = (-ctl.passive_damping * (v0 - vu) - ctl.skyhook_damping * v0
              - car.suspension_stiffness * (z0 - zu)) / ctl.nominal_mass  # fmt: skip
        for m_s in (ctl.nominal_mass / ctl.beta, ctl.nominal_mass, ctl.beta * ctl.nominal_mass):
            acc = (car.suspension_stiffness * (zu - zs) + f_c) / m_s
            sdot = acc - a0 + ctl.slope * ed
            assert s * sdot <= -ctl.phi * abs(s) + 1e-9 * abs(s) * (1 + abs(f_c))
        checked += 1
    assert checked > 500


# -- numerics and errors ---------------------------------------------------------------
def test_dt_too_large_is_rejected_with_the_stable_limit() -> None:
    sim = Simulation(HARMONIC, controller=HiLo(1))
    with pytest.raises(ValidationError, match=r"dt = 0.002 s is too large for stability.*dt <= "):
        sim.run(1.0, dt=2e-3)
    assert 1e-4 < sim.max_stable_dt() < 2e-3


def test_runaway_estimator_is_reported_not_returned() -> None:
    """(2.14) unclamped runs away on a bump; the run stops with a clear error.

    Model reference, section 2.4.
    """
    damper = WangSymmetric(estimator=InstantaneousPeak(v_max=5.0))
    sim = Simulation(RoundedPulse(0.035, 3.0), damper=damper, controller=Passive(0.5))
    # the step-size check sees the runaway slope before anything runs ...
    with pytest.raises(ValidationError, match=r"too large for stability.*slope up to 4.\d+e\+13"):
        sim.run(1.0, dt=2e-5)
    # ... and without it the run stops at the runaway, saying when and which signal
    with pytest.raises(SimulationDiverged, match=r"diverged at t = .* s: F_d = .* N") as err:
        sim.run(1.0, dt=2e-5, check_stability=False)
    assert err.value.signal == "F_d"
    assert 0.5 < err.value.time < 0.7


def test_default_estimator_cannot_run_away_on_the_same_bump() -> None:
    res = Simulation(RoundedPulse(0.035, 3.0), controller=Passive(0.5)).run()
    assert np.max(np.abs(res.F_d)) < 2e4


def test_inverse_controllers_need_the_symmetric_model() -> None:
    with pytest.raises(ValidationError, match="needs the 'wang-symmetric' damper model"):
        Simulation(HARMONIC, damper=LinearViscous(), controller=InverseHiLo())


def test_max_current_above_the_damper_limit() -> None:
    with pytest.raises(ValidationError, match=r"max_current must be in \[0, 0.5\] A"):
        Simulation(HARMONIC, max_current=0.8)


# -- one physics for offline runs and tick-by-tick use -----------------------------------
def test_stepper_reproduces_run_exactly() -> None:
    sim = Simulation(HARMONIC, controller=HiLo(1, mode="ACM"))
    dt = 1e-4
    res = sim.run(0.5, dt=dt, output_rate=1.0 / dt)
    stepper = sim.stepper(dt)
    stepper.reset(0.0, float(HARMONIC.velocity(0.0)))
    t = np.arange(res.time.size) * dt
    for k in range(1, res.time.size):
        t0, t1 = t[k - 1], t[k - 1] + 0.5 * dt
        out = stepper.step(
            float(HARMONIC.displacement(t0)),
            float(HARMONIC.velocity(t0)),
            road_mid=(float(HARMONIC.displacement(t1)), float(HARMONIC.velocity(t1))),
            road_end=(float(HARMONIC.displacement(t[k])), float(HARMONIC.velocity(t[k]))),
        )
    assert out["z_s"] == pytest.approx(res.z_s[-1], rel=1e-12, abs=1e-15)
    assert out["F_d"] == pytest.approx(res.F_d[-1], rel=1e-12)
    assert out["i_d"] == pytest.approx(res.i_d[-1], rel=1e-12, abs=1e-15)


def test_stepper_with_external_force_matches_the_model_it_replaces() -> None:
    """HiL mode: feeding the model's own force back as a measured force changes nothing."""
    sim = Simulation(HARMONIC, damper=LinearViscous(damping=2000.0))
    model, hil = sim.stepper(1e-4), sim.stepper(1e-4, external_force=True)
    for k in range(2000):
        t = k * 1e-4
        zr, vr = float(HARMONIC.displacement(t)), float(HARMONIC.velocity(t))
        a = model.step(zr, vr)
        force = 2000.0 * (hil.y[3] - hil.y[1])
        b = hil.step(zr, vr, damper_force=force)
    assert b["z_s"] == pytest.approx(a["z_s"], rel=1e-3)
    with pytest.raises(ValidationError, match="needs a finite damper_force"):
        hil.step(0.0, 0.0)


def test_run_many_matches_sequential_runs() -> None:
    sims = [Simulation(Harmonic(f, 0.02), controller=HiLo(1)) for f in (1.0, 2.0, 4.0)]
    parallel = run_many(sims, duration=2.0, workers=2, lanes=False)  # bit for bit
    lanes = run_many(sims, duration=2.0, workers=2)  # lanes: to round-off (their exp)
    for sim, par, lane in zip(sims, parallel, lanes, strict=True):
        seq = sim.run(2.0)
        np.testing.assert_array_equal(seq.z_s, par.z_s)
        np.testing.assert_allclose(lane.z_s, seq.z_s, rtol=0, atol=1e-9 * np.abs(seq.z_s).max())


def test_result_exports(tmp_path) -> None:  # type: ignore[no-untyped-def]
    res = Simulation(HARMONIC).run(0.2)
    assert res["z_s"] is res.z_s
    assert set(res) >= {"time", "z_s", "F_d", "F_T", "i_d", "F_target", "z_c", "x_d"}
    assert res.units["F_d"] == "N"
    with pytest.raises(ValidationError, match="Did you mean 'F_d'"):
        res["F_dd"]
    csv = res.save(tmp_path / "run.csv")
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert table.shape == (res.time.size, len(res))
    np.testing.assert_allclose(table[:, 0], res.time)
    df = res.to_pandas()
    assert "F_d" in df.columns
    assert df.attrs["units"]["F_d"] == "N"
    with pytest.raises(ValidationError, match=r"use \.csv, \.nc"):
        res.save(tmp_path / "run.xlsx")


def test_pulse_measures_state_their_road_peak() -> None:
    res = Simulation(RoundedPulse(0.035, 3.0), controller=HiLo(1, mode="ACM")).run(2.0)
    after, onset = res.measures(), res.measures(road_peak="onset")
    assert after["road_peak"] == "after-onset"  # the default (model reference, section 9)
    assert onset["road_peak"] == "onset"
    for k in ("SDR_s", "SDR_u", "RDR", "peak_tire_force"):
        assert after[k] == onset[k]
    for k in ("SAR_s", "SAR_u"):  # the 1 kHz record holds the onset instant (0.5 s)
        assert after[k] / onset[k] == pytest.approx(4.854, rel=2e-3)
    with pytest.raises(ValidationError, match="road_peak must be one of 'after-onset', 'onset'"):
        res.measures(road_peak="peak")  # type: ignore[arg-type]
    harmonic = Simulation(HARMONIC).run(0.5)
    with pytest.raises(ValidationError, match="road_peak"):
        harmonic.measures(road_peak="peak")  # type: ignore[arg-type]


def test_road_static_load_and_mean_tire_force() -> None:
    res = Simulation(preset_road("medium-rough", 50.0), controller=HiLo(1)).run(10.0)
    assert res.F_T.mean() == pytest.approx(QuarterCar().total_mass * GRAVITY, rel=0.01)
    m = res.measures()
    assert 0.0 < m["DLC"] < 1.0
    assert m["wk_rms_body_acceleration"] > 0.0
    assert math.isfinite(m["vdv"])


@pytest.mark.parametrize("suffix", [".nc", ".parquet"])
def test_result_round_trips_through_standard_formats(tmp_path, suffix: str) -> None:  # type: ignore[no-untyped-def]
    res = Simulation(HARMONIC, controller=HiLo(1)).run(0.3)
    path = res.save(tmp_path / f"run{suffix}")
    if suffix == ".nc":
        import xarray as xr

        with xr.open_dataset(path) as ds:
            np.testing.assert_allclose(ds["F_d"].values, res.F_d)
            assert ds["F_d"].attrs["units"] == "N"
    else:
        import pandas as pd

        df = pd.read_parquet(path)
        np.testing.assert_allclose(df["i_d"].to_numpy(), res.i_d)


class _PlainHarmonic:
    """A road input with only the RoadInput protocol (no sample_grid)."""

    def __init__(self, inner: Harmonic) -> None:
        self.inner = inner
        self.duration = 1.0

    def displacement(self, t):
        return self.inner.displacement(t)

    def velocity(self, t):
        return self.inner.velocity(t)

    def acceleration(self, t):
        return self.inner.acceleration(t)

    def describe(self):
        return {"kind": "plain harmonic"}


def test_any_road_input_works_and_the_fast_harmonic_grid_changes_nothing_but_round_off() -> None:
    fast = Simulation(Harmonic(3.0, 0.02), controller=HiLo(1, mode="ACM"))
    plain = Simulation(_PlainHarmonic(Harmonic(3.0, 0.02)), controller=HiLo(1, mode="ACM"))
    a, b = fast.run(1.0), plain.run(1.0)
    scale = np.max(np.abs(b.z_s))
    assert np.max(np.abs(a.z_s - b.z_s)) <= 1e-11 * scale
    assert np.max(np.abs(a.F_d - b.F_d)) <= 1e-8 * np.max(np.abs(b.F_d))
