"""Peak-velocity estimators v_m (model reference, section 2.4)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrsuspension.dampers import (
    CycleRms,
    InstantaneousPeak,
    KnownPeak,
    WangSymmetric,
    WindowPeak,
    make_estimator,
)
from mrsuspension.dampers import kernels as K
from mrsuspension.errors import ValidationError


def brute_force_window(v, n: int, v_min: float, v_max: float) -> np.ndarray:
    """max |v| over the last n samples (fewer at the start), clamped: the definition."""
    out = []
    for k in range(len(v)):
        peak = max(abs(float(u)) for u in v[max(0, k - n + 1) : k + 1])
        out.append(min(max(peak, v_min), v_max))
    return np.array(out)


# ----------------------------------------------------------------------------------
# instantaneous, eq. (2.14)
@pytest.mark.parametrize(("amplitude", "frequency"), [(0.0125, 1.5), (0.025, 1.5), (0.005, 10.0)])
def test_instantaneous_is_exact_for_a_sinusoid(amplitude, frequency):
    w = 2 * math.pi * frequency
    peak = amplitude * w
    est = InstantaneousPeak()
    for phase in np.linspace(0.0, 2 * math.pi, 37):
        x, v, a = (
            amplitude * math.sin(phase),
            peak * math.cos(phase),
            -amplitude * w * w * math.sin(phase),
        )
        assert est.pointwise(x, v, a) == pytest.approx(peak, rel=1e-12)
    # the same through the causal response of a model
    t = np.arange(0.0, 1.0, 1e-3)
    model = WangSymmetric(estimator="instantaneous")
    r = model.response(
        t, amplitude * np.sin(w * t), peak * np.cos(w * t), -amplitude * w * w * np.sin(w * t)
    )
    np.testing.assert_allclose(r.peak_velocity, peak, rtol=1e-12)


def test_instantaneous_is_clamped():
    w = 2 * math.pi * 10.0
    est = InstantaneousPeak(v_min=0.05, v_max=0.8)
    # peak 0.05 * 62.8 = 3.14 m/s > v_max
    assert (
        est.pointwise(0.05 * math.sin(1.0), 0.05 * w * math.cos(1.0), -0.05 * w * w * math.sin(1.0))
        == 0.8
    )
    # peak 1e-4 * 62.8 = 6.3 mm/s < v_min
    assert est.pointwise(0.0, 1e-4 * w, 0.0) == 0.05
    # v^2 - a x < 0 (not a sinusoid) gives the lower clamp, never NaN
    assert est.pointwise(0.1, 0.0, 10.0) == 0.05
    assert InstantaneousPeak().pointwise(0.0, 0.0, 0.0) == 1e-3


# ----------------------------------------------------------------------------------
# window (the old default, kept for comparison)
def test_window_is_selectable_by_name():
    model = WangSymmetric(estimator="window")
    assert model.estimator == WindowPeak(window=1.0, v_min=1e-3, v_max=0.75)


@settings(max_examples=150, deadline=None)
@given(
    values=st.lists(
        st.one_of(
            st.sampled_from([0.0, 0.1, -0.1, 0.3, -0.3, 0.7, 1.5]),  # ties and clamping
            st.floats(-2.0, 2.0),
        ),
        min_size=1,
        max_size=150,
    ),
    n=st.integers(1, 60),
)
def test_window_kernel_is_the_sliding_maximum(values, n):
    dt = 0.01
    kern = WangSymmetric(estimator="window", window=n * dt, v_max=1.0).kernel(dt)
    assert int(kern.estimator_params[2]) == n
    expected = brute_force_window(values, n, 1e-3, 1.0)
    got = [
        K.estimator_update(
            kern.estimator_code, kern.estimator_params, kern.estimator_state, 0.0, v, 0.0
        )
        for v in values
    ]
    np.testing.assert_array_equal(got, expected)


@pytest.mark.parametrize("n", [1, 2, 7, 100, 999, 5000])
@pytest.mark.parametrize("seed", [0, 1])
def test_window_through_response_matches_brute_force(n, seed):
    rng = np.random.default_rng(seed)
    size = 1000
    dt = 1e-3
    v = rng.uniform(-1.3, 1.3, size) * rng.uniform(0, 1, size) ** 3  # many small values
    v[rng.integers(0, size, 50)] = 0.25  # ties
    t = np.arange(size) * dt
    model = WangSymmetric(estimator="window", window=n * dt, v_min=0.02, v_max=0.9)
    r = model.response(t, np.zeros(size), v, np.zeros(size), 0.1)
    np.testing.assert_array_equal(r.peak_velocity, brute_force_window(v, n, 0.02, 0.9))
    # and the force uses that v_m
    np.testing.assert_allclose(
        r.force,
        model.force(0.0, v, 0.0, 0.1, peak_velocity=r.peak_velocity),
        rtol=1e-13,
        atol=1e-12,
    )


def test_window_longer_than_record_is_running_maximum():
    v = np.array([0.1, -0.4, 0.2, 0.3, -0.1, 0.05])
    t = np.arange(v.size) * 0.01
    r = WangSymmetric(estimator="window", window=10.0).response(t, 0.0, v, 0.0, 0.0)
    np.testing.assert_array_equal(r.peak_velocity, [0.1, 0.4, 0.4, 0.4, 0.4, 0.4])


def test_window_forgets_after_the_window():
    dt = 0.01
    v = np.zeros(300)
    v[10] = 0.8
    t = np.arange(v.size) * dt
    r = WangSymmetric(estimator="window", window=1.0, v_max=1.0).response(t, 0.0, v, 0.0, 0.0)
    assert np.all(r.peak_velocity[10:110] == 0.8)
    assert np.all(r.peak_velocity[110:] == 1e-3)  # forgotten, lower clamp
    assert np.all(r.peak_velocity[:10] == 1e-3)


def test_window_pointwise_force_uses_clamped_speed():
    est = WindowPeak(v_min=0.05, v_max=0.6)
    assert est.pointwise(0.0, -0.3, 5.0) == 0.3
    assert est.pointwise(0.0, 2.0, 0.0) == 0.6
    assert est.pointwise(0.0, 0.0, 0.0) == 0.05


@pytest.mark.parametrize("estimator", ["window", "instantaneous", "cycle-rms"])
def test_force_without_peak_velocity_asks_a_fresh_estimator(estimator):
    # force() without peak_velocity = force() with the one-sample estimate, clamped
    rng = np.random.default_rng(2)
    x = rng.uniform(-0.05, 0.05, 300)
    v = rng.uniform(-2.5, 2.5, 300)  # beyond v_max too
    a = rng.uniform(-100, 100, 300)
    model = WangSymmetric(estimator=estimator, v_min=0.02, v_max=0.8)
    if estimator == "window":
        vm = [min(max(abs(u), 0.02), 0.8) for u in v]
    else:
        raw = [math.sqrt(max(u * u - b * y, 0.0)) for y, u, b in zip(x, v, a, strict=True)]
        vm = [min(max(r, 0.02), 0.8) for r in raw]
    assert min(vm) == 0.02
    assert max(vm) == 0.8
    np.testing.assert_allclose(
        model.force(x, v, a, 0.2), model.force(x, v, a, 0.2, peak_velocity=vm), rtol=1e-13
    )


def test_known_peak_velocity():
    t = np.arange(0.0, 0.5, 1e-3)
    v = 0.2 * np.sin(5 * t)
    model = WangSymmetric(estimator="known", value=0.3)
    r = model.response(t, 0.0, v, 0.0, 0.2)
    np.testing.assert_array_equal(r.peak_velocity, 0.3)
    np.testing.assert_allclose(
        r.force, WangSymmetric().force(0.0, v, 0.0, 0.2, peak_velocity=0.3), rtol=1e-14
    )
    assert make_estimator("known", value=0.2).pointwise(0.1, 5.0, 7.0) == 0.2
    assert not model.stateful
    assert WangSymmetric().stateful


# ----------------------------------------------------------------------------------
# validation
@pytest.mark.parametrize(
    ("call", "fragments"),
    [
        (lambda: WindowPeak(window=0.0), ["window", "(0, 600]", "0"]),
        (lambda: WindowPeak(window=-1.0), ["window", "-1"]),
        (lambda: make_estimator("window", window=0.0), ["window"]),
        (lambda: WangSymmetric(window=-0.5), ["window", "-0.5"]),
        (lambda: WindowPeak(v_min=0.5, v_max=0.5), ["v_min < v_max", "v_min=0.5", "v_max=0.5"]),
        (lambda: WindowPeak(v_min=0.6, v_max=0.5), ["v_min < v_max", "0.6"]),
        (lambda: InstantaneousPeak(v_min=0.0), ["0 < v_min"]),
        (lambda: InstantaneousPeak(v_max=6.0), ["v_max <= 5", "v_max=6"]),
        (lambda: WangSymmetric(estimator="instantaneous", v_max=5.5), ["v_max <= 5"]),
        (lambda: KnownPeak(-0.1), ["known peak velocity", "[0, 5", "-0.1"]),
        (lambda: KnownPeak(float("nan")), ["known peak velocity", "nan"]),
        (lambda: make_estimator("windw"), ["windw", "Did you mean 'window'?"]),
        (lambda: WangSymmetric(estimator="instantanous"), ["Did you mean 'instantaneous'?"]),
        (lambda: make_estimator("window", value=0.2), ["window", "value"]),
        (lambda: make_estimator(WindowPeak(), window=2.0), ["options"]),
        (lambda: WindowPeak().samples(0.0), ["dt", "> 0"]),
    ],
)
def test_bad_estimator_options(call, fragments):
    with pytest.raises(ValidationError) as info:
        call()
    for fragment in fragments:
        assert fragment in str(info.value), (fragment, str(info.value))


def test_peak_velocity_argument_is_checked():
    with pytest.raises(ValidationError, match=r"peak_velocity must be in \[0, 5\] m/s; got 6"):
        WangSymmetric().force(0.0, 0.1, peak_velocity=6.0)
    with pytest.raises(ValidationError, match="peak_velocity"):
        WangSymmetric().force(0.0, 0.1, peak_velocity=-0.1)


# ----------------------------------------------------------------------------------
# closed loop: why the default estimator matters (model reference, section 2.4, erratum 7)
def wheel_on_damper(model: WangSymmetric, current: float, duration: float, dt: float = 1e-4):
    """A 90 kg wheel on the damper (to a fixed body) and a 285 kN/m tyre hit by a 3.5 cm step.

    Up-positive ``z``; damper stroke ``x_d = z``; ``m z'' = k_t (z_r - z) - F_d``;
    explicit Euler, the damper sampled with the previous step's acceleration.
    """
    mass, k_t, z_r = 90.0, 285e3, 0.035
    kern = model.kernel(dt)
    z = zd = acc = 0.0
    forces, peaks, speeds = [], [], []
    for _ in range(round(duration / dt)):
        K.damper_sample(
            kern.kind, kern.params, kern.state, kern.estimator_code, kern.estimator_params,
            kern.estimator_state, z, zd, acc, current,
        )  # fmt: skip
        force = K.damper_force(kern.kind, kern.params, kern.state, z, zd, current)
        K.damper_advance(kern.kind, kern.params, kern.state, z, zd, current, dt)
        forces.append(force)
        peaks.append(kern.state[0])
        speeds.append(abs(zd))
        if not math.isfinite(force):
            break
        acc = (k_t * (z_r - z) - force) / mass
        z, zd = z + dt * zd, zd + dt * acc
    return np.array(forces), np.array(peaks), np.array(speeds)


def force_bound(ref, v_max: float, i_max: float) -> float:
    """sup |F_d| for v_m <= v_max and |v_d| <= v_m: C_i(i_max) F_t(v_max) (1 + k_v(v_max) v_max)."""
    return ref.current_gain(i_max) * ref.transition_force(v_max) * (1.0 + ref.k_v(v_max) * v_max)


@pytest.mark.parametrize("current", [0.0, 0.25, 0.5])
def test_runaway_is_impossible_with_the_default_estimator(current, wang_reference):
    ref = wang_reference("wang-symmetric-low")
    model = WangSymmetric()
    v_max = model.estimator.v_max  # type: ignore[attr-defined]
    bound = force_bound(ref, v_max, 0.5)
    # the bound is (up to tanh(alpha v/2) ~ 1) the force at v = v_m = v_max, i = i_max
    at_limit = float(model.force(0.0, v_max, 0.0, 0.5, peak_velocity=v_max))
    assert at_limit == pytest.approx(bound, rel=2e-3)
    forces, peaks, speeds = wheel_on_damper(model, current, duration=0.3)
    assert np.all(np.isfinite(forces))
    assert peaks.max() <= v_max
    # |F_d| <= C_i F_t(v_m) (1 + k_v |v_d|) with v_m <= v_max and k_v <= k1
    limit = float(ref.current_gain(0.5) * ref.transition_force(v_max)) * (
        1.0 + model.values["k1"] * speeds.max()
    )
    assert np.abs(forces).max() <= limit
    assert np.abs(forces).max() > 1000.0  # the damper did work against the step


def test_unclamped_instantaneous_estimate_runs_away(wang_reference):
    ref = wang_reference("wang-symmetric-low")
    bound = force_bound(ref, 1.0, 0.5)
    model = WangSymmetric(estimator=InstantaneousPeak(v_max=5.0))
    forces, peaks, _ = wheel_on_damper(model, 0.5, duration=0.04)
    # the acceleration feeds back into (2.14): v_m goes to the clamp and F_t ~ exp(a1 v_m)
    assert peaks.max() == 5.0
    finite = forces[np.isfinite(forces)]
    assert (not np.all(np.isfinite(forces))) or np.abs(finite).max() > 1e3 * bound


# ----------------------------------------------------------------------------------
# cycle-rms (the default; model reference, section 2.4, revised 2026-11-24)
def brute_force_cycle_rms(v, n: int, v_min: float, v_max: float) -> np.ndarray:
    """sqrt(2 mean(v^2)) over the last n samples (fewer at the start), clamped."""
    out = []
    for k in range(len(v)):
        w = np.asarray(v[max(0, k - n + 1) : k + 1], dtype=float)
        out.append(min(max(math.sqrt(2.0 * float(np.mean(w * w))), v_min), v_max))
    return np.array(out)


def test_cycle_rms_is_the_default_with_the_sets_identified_range():
    model = WangSymmetric()
    assert isinstance(model.estimator, CycleRms)
    assert model.parameters.velocity_range == (0.008, 0.75)
    assert model.estimator == CycleRms(window=1.0, v_min=1e-3, v_max=0.75)
    # a user's v_max wins; the high-frequency set carries its own range
    assert WangSymmetric(v_max=0.9).estimator.v_max == 0.9  # type: ignore[attr-defined]
    assert WangSymmetric("wang-symmetric-high").estimator.v_max == 0.75  # type: ignore[attr-defined]
    assert make_estimator() == CycleRms()


def test_a_set_without_a_velocity_range_gets_the_default_clamp():
    from mrsuspension import parameters

    pset = parameters.get("wang-symmetric-low")
    bare = parameters.ParameterSet(name="bare", model=pset.model, values=dict(pset.values))
    assert bare.velocity_range is None
    assert WangSymmetric(bare).estimator.v_max == 0.75  # type: ignore[attr-defined]
    with pytest.raises(ValidationError, match=r"velocity_range must be \[low, high\]"):
        parameters.ParameterSet(
            name="bad", model=pset.model, values=dict(pset.values), velocity_range=(0.5, 0.1)
        )


@settings(max_examples=120, deadline=None)
@given(
    values=st.lists(st.floats(-2.0, 2.0), min_size=1, max_size=200),
    n=st.integers(1, 40),
)
def test_cycle_rms_kernel_is_the_windowed_mean_square(values, n):
    est = CycleRms(window=n * 0.01, v_min=1e-3, v_max=1.0)
    ep, es = est.params_for(0.01), est.buffer(0.01)
    assert int(ep[2]) == n
    got = [K.estimator_update(est.code, ep, es, 0.0, v, 0.0) for v in values]
    np.testing.assert_allclose(got, brute_force_cycle_rms(values, n, 1e-3, 1.0), rtol=1e-12)


def test_cycle_rms_does_not_drift_over_long_records():
    # 2e5 samples of a decaying then growing signal: the running sum is re-summed each
    # time the ring wraps, so round-off cannot accumulate
    rng = np.random.default_rng(4)
    n = 97
    v = rng.normal(size=200_000) * np.geomspace(1.0, 1e-3, 200_000)
    est = CycleRms(window=n * 1e-3, v_min=1e-9, v_max=5.0)
    ep, es = est.params_for(1e-3), est.buffer(1e-3)
    for u in v:
        got = K.estimator_update(est.code, ep, es, 0.0, u, 0.0)
    tail = v[-n:]
    assert got == pytest.approx(math.sqrt(2.0 * float(np.mean(tail * tail))), rel=1e-9)


@pytest.mark.parametrize("frequency", [0.5, 1.0, 1.5, 2.5, 7.0])
@pytest.mark.parametrize("phase", [0.0, 0.7])
def test_cycle_rms_is_exact_for_a_sinusoid_over_whole_half_periods(frequency, phase):
    # a 1 s window holds a whole number of half periods at any multiple of 0.5 Hz
    dt, amplitude = 1e-4, 0.01
    t = np.arange(round(3.0 / dt)) * dt
    v = 2 * math.pi * frequency * amplitude * np.cos(2 * math.pi * frequency * t + phase)
    r = WangSymmetric().response(t, 0.0, v, 0.0, 0.1)
    expected = 2 * math.pi * frequency * amplitude  # the dissertation's v_m = 2 pi f a_m
    np.testing.assert_allclose(r.peak_velocity[t >= 1.0], expected, rtol=1e-9)


@pytest.mark.parametrize("frequency", [0.75, 1.25, 2.9, 4.1])
def test_cycle_rms_ripple_is_within_its_bound_between_half_periods(frequency):
    dt, amplitude, window = 1e-4, 0.02, 1.0
    t = np.arange(round(4.0 / dt)) * dt
    v = 2 * math.pi * frequency * amplitude * np.sin(2 * math.pi * frequency * t)
    r = WangSymmetric().response(t, 0.0, v, 0.0, 0.1)
    expected = 2 * math.pi * frequency * amplitude
    wt = 2 * math.pi * frequency * window
    # mean of sin^2 over the window: 1/2 (1 +- |sin(wT)|/(wT)); v_m is its square root
    bound = 1.0 - math.sqrt(1.0 - abs(math.sin(wt)) / wt)
    err = np.abs(r.peak_velocity[t >= window] / expected - 1.0)
    assert err.max() <= bound + 1e-6
    assert err.max() > 0.2 * bound  # the bound is the real size of the ripple


def test_cycle_mean_of_the_2_14_radicand_is_twice_the_mean_square_velocity():
    # the identity behind cycle-rms, on a periodic motion with harmonics (wheel hop)
    t = np.linspace(0.0, 1.0, 200_001)[:-1]  # one period of 1 Hz, exactly sampled
    w = 2 * math.pi
    x = 0.03 * np.sin(w * t) + 0.004 * np.sin(10 * w * t + 0.3) + 0.002 * np.cos(3 * w * t)
    v = (
        0.03 * w * np.cos(w * t)
        + 0.04 * w * np.cos(10 * w * t + 0.3)
        - 0.006 * w * np.sin(3 * w * t)
    )
    a = (
        -0.03 * w * w * np.sin(w * t)
        - 0.4 * w * w * np.sin(10 * w * t + 0.3)
        - 0.018 * w * w * np.cos(3 * w * t)
    )
    assert float(np.mean(v * v - a * x)) == pytest.approx(2.0 * float(np.mean(v * v)), rel=1e-9)


def test_cycle_rms_is_insensitive_to_a_spike_where_the_window_peak_is_not():
    dt = 1e-3
    t = np.arange(3000) * dt
    v = 0.3 * np.sin(2 * math.pi * 1.5 * t)
    v[2500] = 2.0  # one switching spike
    rms = WangSymmetric().response(t, 0.0, v, 0.0, 0.1).peak_velocity
    peak = WangSymmetric(estimator="window").response(t, 0.0, v, 0.0, 0.1).peak_velocity
    # the spike adds its energy share of the 1000-sample window: 2 * 2.0^2 / 1000 to v_m^2
    assert rms[2600] ** 2 == pytest.approx(0.3**2 + 2 * 2.0**2 / 1000, rel=0.02)
    assert rms[2600] < 0.315  # +5 %
    assert peak[2600] == 0.75  # pinned at the clamp for a whole window
