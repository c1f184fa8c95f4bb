"""The optimum's linear model and bands against the toolkit's own models."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.benchmark import ActiveBand, LinearBand, MRBand, MREnvelopeBand, wk_state_space
from mrsuspension.benchmark.model import linear_quarter_car, trapezoidal
from mrsuspension.dampers import WangSymmetric
from mrsuspension.errors import ValidationError
from mrsuspension.measures import wk_weighting
from mrsuspension.vehicle import QuarterCar, linear_frequency_response


def _response(a: np.ndarray, b: np.ndarray, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    n = a.shape[0]
    return np.array([(c @ np.linalg.solve(sk * np.eye(n) - a, b)).item() for sk in s])


def test_wk_state_space_matches_the_toolkits_weighting() -> None:
    a, b, c, d = wk_state_space()
    assert d.item() == 0.0  # strictly proper
    f = np.logspace(-1, math.log10(250.0), 300)
    h = _response(a, b, c, 2j * np.pi * f)
    assert np.max(np.abs(np.abs(h) / wk_weighting(f) - 1.0)) < 0.01
    # balanced: equal diagonal Gramians (its states are of one size)
    from scipy.linalg import solve_continuous_lyapunov

    wc = solve_continuous_lyapunov(a, -b @ b.T)
    wo = solve_continuous_lyapunov(a.T, -c.T @ c)
    assert np.allclose(wc, wo, rtol=1e-6, atol=1e-9 * np.max(wc))


def test_trapezoidal_wk_is_the_bilinear_filter_within_one_percent_to_40_hz() -> None:
    """The transcription's Wk (trapezoidal at 1 ms) against |Wk| over the body band."""
    a, b, c, _ = wk_state_space()
    h = 1e-3
    m = np.eye(8) - 0.5 * h * a
    ad = np.linalg.solve(m, np.eye(8) + 0.5 * h * a)
    bd = np.linalg.solve(m, h * b)  # input held over the interval (its mean)
    f = np.linspace(0.5, 40.0, 80)
    z = np.exp(2j * np.pi * f * h)
    # a sine's interval means are its middle values times sinc(f h); the response from the
    # sine to a_w at the nodes is then the bilinear Wk times 2 / (z + 1) times sinc(f h)
    hd = np.array([(c @ np.linalg.solve(zk * np.eye(8) - ad, bd)).item() for zk in z])
    hd = hd * np.sinc(f * h)
    assert np.max(np.abs(np.abs(hd) / wk_weighting(f) - 1.0)) < 0.01


@pytest.mark.parametrize("damping", [500.0, 2500.0])
def test_linear_car_matches_the_vehicles_frequency_response(damping: float) -> None:
    car = QuarterCar(sprung_mass=500.0, tire_damping=150.0)
    lin = linear_quarter_car(car)
    a = lin.a + np.outer(lin.b, damping * (np.eye(12)[3] - np.eye(12)[1]))  # F = c v_d
    f = np.array([0.5, 1.4, 4.0, 10.0, 20.0])
    s = 2j * np.pi * f
    # road input z_r = e^{st}: r = [1, s]
    zs = np.array([np.linalg.solve(sk * np.eye(12) - a, lin.e @ [1.0, sk])[0] for sk in s])
    zu = np.array([np.linalg.solve(sk * np.eye(12) - a, lin.e @ [1.0, sk])[2] for sk in s])
    ref = linear_frequency_response(car, damping, f)
    assert np.allclose(np.abs(zs), ref["T_as"], rtol=1e-9)
    assert np.allclose(np.abs(zu - zs), ref["T_dr"], rtol=1e-9)
    # and the Wk output is Wk of the body acceleration
    aw = np.array(
        [(lin.c[0] @ np.linalg.solve(sk * np.eye(12) - a, lin.e @ [1.0, sk])) for sk in s]
    )
    assert np.allclose(np.abs(aw), wk_weighting(f) * np.abs(s**2 * zs), rtol=1e-8)


def test_trapezoidal_step_is_stable_and_consistent() -> None:
    d = trapezoidal(linear_quarter_car(QuarterCar()), 2e-3)
    assert np.max(np.abs(np.linalg.eigvals(d.p))) < 1.0
    # a constant road offset is an equilibrium with everything lifted by it
    x = np.zeros(12)
    x[0] = x[2] = 0.01
    nxt = d.p @ x + d.r @ [0.01, 0.0] + d.s @ [0.01, 0.0]
    assert np.allclose(nxt, x, atol=1e-15)


def test_mr_band_is_the_damper_models_mean_curve() -> None:
    vm = 0.25
    band = MRBand(peak_velocity=vm, min_current=0.05, max_current=0.4)
    damper = WangSymmetric(hysteresis=False)
    v = np.linspace(-0.6, 0.6, 61)
    lo = damper.force(0.0, v, 0.0, 0.05, peak_velocity=vm)
    hi = damper.force(0.0, v, 0.0, 0.4, peak_velocity=vm)
    assert np.allclose(band.force(v, 0.0), lo, rtol=1e-12, atol=1e-9)
    assert np.allclose(band.force(v, 1.0), hi, rtol=1e-12, atol=1e-9)
    # every coordinate is dissipative and maps to the current that gives its force
    for u in (0.0, 0.3, 1.0):
        f = band.force(v, u)
        assert np.all(f * v >= 0.0)
        i = band.current(f[v != 0], v[v != 0])
        back = damper.force(0.0, v[v != 0], 0.0, i, peak_velocity=vm)
        assert np.allclose(back, f[v != 0], rtol=1e-9)
    assert np.isnan(band.current([0.0], [0.0])[0])


def test_envelope_band_holds_every_force_of_the_hysteretic_damper() -> None:
    """Any current, either branch, any v_m of the range: inside the band; the table is
    outward of the exact envelope, which it meets at the grid's velocities."""
    vm_range = (0.01, 0.4)
    band = MREnvelopeBand(vm_range)
    damper = WangSymmetric()  # with hysteresis: the engine's
    rng = np.random.default_rng(3)
    n = 4000
    v = rng.choice([-1.0, 1.0], n) * 10.0 ** rng.uniform(-5.0, 0.0, n)
    sgn_a = rng.choice([-1.0, 1.0], n)
    vm = rng.uniform(*vm_range, n)
    i = rng.uniform(0.0, 0.5, n)
    f = damper.force(0.0, v, sgn_a, i, peak_velocity=vm)
    assert np.all(band.contains(f, v, tol=0.0))
    # the hysteresis makes forces against the velocity near v_d = 0 (the band holds them)
    assert np.any(f * v < 0.0)
    lo, hi = band.edges(v)
    ex_lo, ex_hi = band.exact_edges(v)
    assert np.all(lo <= ex_lo + 1e-9)
    assert np.all(hi >= ex_hi - 1e-9)
    assert np.all(hi - lo <= (ex_hi - ex_lo) * 1.02 + 1.0)  # outward by little
    # the top edge: 0.5 A at the range's top v_m, the larger of the two branches
    vv = np.array([0.3])
    top = [damper.force(0.0, vv, s, 0.5, peak_velocity=vm_range[1])[0] for s in (-1, 1)]
    assert band.exact_edges(vv)[1][0] == pytest.approx(max(top), rel=1e-9)
    # the mean model's band at v_m in the range lies inside; the band is not dissipative
    mean = MRBand(peak_velocity=0.3)
    w = np.linspace(-0.8, 0.8, 81)
    for u in (0.0, 1.0):
        assert np.all(band.contains(mean.force(w, u), w))
    assert band.edges([0.0])[0][0] < 0.0 < band.edges([0.0])[1][0]
    assert np.array_equal(band.passive_band.force(w, 0.0), MRBand().force(w, 0.0))
    u = band.coordinate(band.force(w, 0.25), w)
    assert np.allclose(u[w != 0.0], 0.25)


def test_envelope_band_holds_the_engines_damper_force_in_closed_loop() -> None:
    """Recorded runs (0 A, 0.5 A, a hi-lo law) over a bump: the engine's force against the
    band of the record's v_m range, at every sample; the fixed-v_m mean band misses most."""
    from mrsuspension.benchmark.study import (
        BenchmarkRoad,
        _scenario,
        engine_peak_velocity_floor,
    )
    from mrsuspension.engine.simulate import run_quietly
    from mrsuspension.scenario import Scenario

    exc = BenchmarkRoad("bump", "bump", height=0.03, length=0.5).excitation("quarter", 100.0, 2.0)
    runs = []
    for law, opt in (("passive", {"current": 0.0}), ("passive", {"current": 0.5}),
                     ("skyhook-hilo", {"gain": 8.0})):  # fmt: skip
        scenario = Scenario.from_dict(_scenario(law, opt, "quarter", exc, 2.0))
        runs.append(run_quietly(scenario.runs()[0], scenario.settings))
    top = max(float(np.max(r.v_m)) for r in runs)
    band = MREnvelopeBand((engine_peak_velocity_floor(), top))
    mean = MRBand()
    for r in runs:
        v, f = np.asarray(r.v_d), np.asarray(r.F_d)
        inside = np.mean(band.contains(f, v, tol=0.0))
        assert inside >= 0.999, inside
        lo, hi = mean.edges(v)
        assert np.mean((f >= lo) & (f <= hi)) < 0.5  # the band of issue 29 missed them


def test_bands_refuse_bad_inputs() -> None:
    with pytest.raises(ValidationError, match="max_current must be > min_current"):
        MRBand(min_current=0.3, max_current=0.2)
    with pytest.raises(ValidationError, match="peak_velocity"):
        MRBand(peak_velocity=2.0)
    with pytest.raises(ValidationError, match="max_damping must be >= min_damping"):
        LinearBand(3000.0, 1000.0)
    with pytest.raises(ValidationError, match="max_force must be > 0 N"):
        ActiveBand(0.0)
    with pytest.raises(ValidationError, match="peak_velocity_range high"):
        MREnvelopeBand((0.3, 0.1))
    with pytest.raises(ValidationError, match="two numbers"):
        MREnvelopeBand((0.3,))  # type: ignore[arg-type]
    with pytest.raises(ValidationError, match="WangSymmetric"):
        MREnvelopeBand(damper=object())  # type: ignore[arg-type]
