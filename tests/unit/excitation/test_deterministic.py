"""Harmonic (3.36), two-stage stepped sweep (3.37, erratum 2) and rounded pulse (3.38, erratum 9).

Closed forms are written here from the model reference, section 8, not taken from the package.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from _helpers import raises_validation as _raises
from mrsuspension.excitation import (
    HIL_FREQUENCIES,
    Excitation,
    Harmonic,
    RoundedPulse,
    SteppedSweep,
    log_frequencies,
    two_stage_amplitude,
)


def _central_difference(fun, t: np.ndarray, h: float) -> np.ndarray:
    return (fun(t + h) - fun(t - h)) / (2 * h)


# -- harmonic ---------------------------------------------------------------------------
class TestHarmonic:
    def test_rms_of_a_whole_number_of_cycles_is_a_over_sqrt2(self):
        z = Harmonic(2.5, 0.02)
        t = np.arange(0, 4.0, 1e-4)  # 10 cycles, half-open
        assert np.sqrt(np.mean(z.displacement(t) ** 2)) == pytest.approx(
            0.02 / math.sqrt(2), rel=1e-10
        )

    def test_acceleration_is_minus_omega_squared_displacement(self):
        z = Harmonic(3.7, 0.015)
        t = np.linspace(0.0, 2.0, 1001)
        w = 2 * math.pi * 3.7
        np.testing.assert_allclose(z.acceleration(t), -(w**2) * z.displacement(t), atol=1e-12)
        np.testing.assert_allclose(z.velocity(t), 0.015 * w * np.cos(w * t), atol=1e-14)
        assert z.peak_acceleration == pytest.approx(0.015 * w * w)

    def test_derivatives_match_finite_differences(self):
        z = Harmonic(1.3, 0.03)
        t = np.linspace(0.1, 3.0, 50)
        np.testing.assert_allclose(
            _central_difference(z.displacement, t, 1e-5), z.velocity(t), atol=1e-8
        )
        np.testing.assert_allclose(
            _central_difference(z.velocity, t, 1e-5), z.acceleration(t), atol=1e-6
        )

    def test_vectorised_shapes(self):
        z = Harmonic(1.0, 0.01)
        assert z.displacement(0.3).shape == ()
        assert z.velocity(np.zeros((3, 4))).shape == (3, 4)

    @pytest.mark.parametrize(
        ("f", "start", "cycles"),
        [
            (0.5, 20.0, 10),  # 10 cycles of settling (20 s) > 5 s; 10 cycles = 20 s
            (1.5, 10 / 1.5, 10),
            (2.0, 5.0, 10),  # 5 s = 10 cycles exactly
            (4.0, 5.0, 10),  # 10 cycles = 2.5 s >= 2 s
            (15.0, 5.0, 30),  # 2 s = 30 cycles
            (7.3, 5.0, 15),  # ceil(14.6) = 15 cycles
        ],
    )
    def test_measure_window_follows_spec_9(self, f, start, cycles):
        z = Harmonic(f, 0.01)
        t0, t1 = z.measure_window()
        assert t0 == pytest.approx(start)
        assert (t1 - t0) * f == pytest.approx(cycles)
        assert t1 - t0 >= 2.0 - 1e-12
        assert z.duration == pytest.approx(t1)

    def test_describe_is_plain_data(self):
        d = Harmonic(1.5, 0.025).describe()
        assert d["kind"] == "harmonic"
        assert d["frequency"] == 1.5
        assert d["amplitude"] == 0.025
        assert isinstance(d["measure_window"], list)

    def test_is_an_excitation_and_frozen(self):
        z = Harmonic(1.0, 0.01)
        assert isinstance(z, Excitation)
        with pytest.raises(AttributeError):
            z.frequency = 2.0  # type: ignore[misc]

    @pytest.mark.parametrize(
        ("kwargs", "fragments"),
        [
            ({"frequency": 0.0, "amplitude": 0.01}, ("frequency", "(0, 1000] Hz")),
            ({"frequency": -1.0, "amplitude": 0.01}, ("frequency",)),
            ({"frequency": float("nan"), "amplitude": 0.01}, ("frequency", "finite")),
            ({"frequency": 1.0, "amplitude": 0.0}, ("amplitude", "(0, 1] m")),
            ({"frequency": 1.0, "amplitude": "big"}, ("amplitude", "number", "'big'")),
            ({"frequency": True, "amplitude": 0.01}, ("frequency", "number")),
        ],
    )
    def test_bad_parameters(self, kwargs, fragments):
        _raises(lambda: Harmonic(**kwargs), *fragments)

    def test_nan_time_is_rejected(self):
        _raises(lambda: Harmonic(1.0, 0.01).displacement([0.0, float("nan")]), "time", "finite")


# -- two-stage sweep ----------------------------------------------------------------------
class TestTwoStage:
    @pytest.mark.parametrize(("a", "acc"), [(0.015, 2.61), (0.025, 4.35), (0.035, 6.09)])
    def test_constant_acceleration_above_transition(self, a, acc):
        f = np.array([2.1, 3.0, 5.0, 9.9, 15.0])
        amp = two_stage_amplitude(f, a)
        peak_acc = amp * (2 * np.pi * f) ** 2
        np.testing.assert_allclose(peak_acc, peak_acc[0], rtol=1e-12)
        assert peak_acc[0] == pytest.approx(acc, abs=0.005)

    def test_constant_displacement_below_transition(self):
        f = np.array([0.5, 1.0, 2.0, 2.1])
        np.testing.assert_array_equal(two_stage_amplitude(f, 0.025), 0.025)

    def test_corrected_law_is_quadratic_not_linear(self):
        # erratum 2: (f_T/f)^2, the printed f_T/f would give 0.0125 at 4.2 Hz
        assert two_stage_amplitude(4.2, 0.025) == pytest.approx(0.00625)
        assert isinstance(two_stage_amplitude(4.2, 0.025), float)

    def test_transition_frequency_option(self):
        assert two_stage_amplitude(4.0, 0.01, transition_frequency=2.0) == pytest.approx(0.0025)

    def test_bad_frequency(self):
        _raises(lambda: two_stage_amplitude([1.0, 0.0], 0.01), "frequency", "index 1")


class TestSteppedSweep:
    def test_one_harmonic_per_frequency_at_two_stage_amplitude(self):
        sweep = SteppedSweep([0.5, 2.1, 4.2, 8.4], 0.025)
        runs = sweep.excitations()
        assert [h.frequency for h in runs] == [0.5, 2.1, 4.2, 8.4]
        assert [h.amplitude for h in runs] == pytest.approx([0.025, 0.025, 0.00625, 0.0015625])
        assert all(isinstance(h, Harmonic) for h in sweep)
        assert len(sweep) == 4
        assert sweep.duration == pytest.approx(sum(h.duration for h in runs))

    def test_hil_sweep(self):
        sweep = SteppedSweep.hil(0.01)
        assert sweep.frequencies == (0.75, 1, 1.25, 1.75, 2, 2.5, 3, 4, 5, 6, 8, 10, 12, 15)
        assert sweep.frequencies == HIL_FREQUENCIES
        assert sweep.transition_frequency == 2.0
        assert sweep.amplitudes[-1] == pytest.approx(0.01 * (2 / 15) ** 2)

    def test_log_frequencies(self):
        f = log_frequencies(30)
        assert f[0] == pytest.approx(0.5)
        assert f[-1] == pytest.approx(15.0)
        np.testing.assert_allclose(np.diff(np.log(f)), np.log(30) / 29)
        _raises(lambda: log_frequencies(0), "n", ">= 1")
        _raises(lambda: log_frequencies(5, 2.0, 1.0), "f_max", "> f_min")

    def test_describe(self):
        d = SteppedSweep([1.0, 4.2], 0.025).describe()
        assert d["kind"] == "swept"
        assert d["amplitudes"] == pytest.approx([0.025, 0.00625])
        assert d["constant_acceleration"] == pytest.approx(4.35, abs=0.005)

    @pytest.mark.parametrize(
        ("freqs", "fragments"),
        [
            ([], ("at least one",)),
            ([1.0, -2.0], ("frequencies[1]",)),
            ([1.0, 2.0, 1.0], ("repeat", "1 Hz", "indices 0 and 2")),
            ("1,2", ("sequence",)),
            ([1.0, "x"], ("frequencies[1]", "number")),
        ],
    )
    def test_bad_frequencies(self, freqs, fragments):
        _raises(lambda: SteppedSweep(freqs, 0.01), *fragments)


# -- rounded pulse ------------------------------------------------------------------------
class TestRoundedPulse:
    @pytest.mark.parametrize("mu", [1.0, 2.0, 3.0])
    @pytest.mark.parametrize("a", [0.02, 0.035, 0.05])
    def test_peak_is_a_at_two_over_mu_omega0(self, a, mu):
        p = RoundedPulse(a, mu)
        tau_peak = 2.0 / (mu * 10.4)
        assert p.peak_time == pytest.approx(0.5 + tau_peak)
        assert float(p.displacement(p.peak_time)) == pytest.approx(a, rel=1e-14)
        t = np.linspace(0.0, p.duration, 200001)
        z = p.displacement(t)
        assert z.max() == pytest.approx(a, rel=1e-8)
        assert t[np.argmax(z)] == pytest.approx(p.peak_time, abs=t[1])
        assert float(p.velocity(p.peak_time)) == pytest.approx(0.0, abs=1e-12)

    def test_formula_3_38(self):
        p = RoundedPulse(0.035, 2.0, delay=0.3)
        tau = np.array([0.0, 0.05, 0.1, 0.2, 0.4])
        k = 2.0 * 10.4
        expected = 0.25 * 0.035 * math.e**2 * (k * tau) ** 2 * np.exp(-k * tau)
        np.testing.assert_allclose(p.displacement(0.3 + tau), expected, rtol=1e-13)
        assert np.all(p.displacement([-1.0, 0.0, 0.29]) == 0.0)
        assert np.all(p.acceleration([0.0, 0.29]) == 0.0)

    def test_duration_is_about_3_pi_over_mu_omega0(self):
        p = RoundedPulse(0.05, 3.0)
        assert p.pulse_duration == pytest.approx(3 * math.pi / (3 * 10.4))
        # after 3 pi/(mu w0) the bump has fallen to ~1.3 % of its height
        end = p.delay + p.pulse_duration
        assert 0.005 < float(p.displacement(end)) / 0.05 < 0.02
        assert p.duration == pytest.approx(p.delay + p.pulse_duration + 2.0)

    def test_omega0_scales_linearly_with_speed(self):
        assert RoundedPulse(0.02, 1, speed_kmh=50.0).omega == pytest.approx(10.4)
        assert RoundedPulse(0.02, 1, speed_kmh=100.0).omega == pytest.approx(20.8)
        assert RoundedPulse(0.02, 1, speed_kmh=75.0).omega == pytest.approx(15.6)
        assert RoundedPulse(0.02, 1, omega0=7.0, speed_kmh=100.0).omega == 7.0
        fast = RoundedPulse(0.02, 1, speed_kmh=100.0)
        slow = RoundedPulse(0.02, 1, speed_kmh=50.0)
        assert fast.pulse_duration == pytest.approx(slow.pulse_duration / 2)

    def test_derivatives_match_finite_differences(self):
        p = RoundedPulse(0.05, 2.0, delay=0.2)
        t = np.linspace(0.21, 0.8, 60)  # away from the onset kink in acceleration
        np.testing.assert_allclose(
            _central_difference(p.displacement, t, 1e-6), p.velocity(t), atol=1e-7
        )
        np.testing.assert_allclose(
            _central_difference(p.velocity, t, 1e-6), p.acceleration(t), atol=1e-5
        )

    def test_peak_acceleration_is_at_the_onset(self):
        p = RoundedPulse(0.05, 3.0)
        t = np.append(np.linspace(0.0, p.duration, 100001), p.delay)
        assert np.max(np.abs(p.acceleration(t))) == pytest.approx(p.peak_acceleration, rel=1e-12)
        assert float(p.acceleration(p.delay)) == pytest.approx(p.peak_acceleration)

    @pytest.mark.parametrize("mu", [1.0, 2.0, 3.0])
    @pytest.mark.parametrize("speed", [50.0, 100.0, 72.0])
    @pytest.mark.parametrize("a", [0.02, 0.035, 0.05, -0.03])
    def test_after_onset_peak_closed_form(self, mu: float, speed: float, a: float):
        # d2/dx2 (x^2 e^-x) = (x^2 - 4x + 2) e^-x: 2 at x = 0; extrema of the rest at
        # x^2 - 6x + 6 = 0, the larger |.| at x = 3 - sqrt 3: (2 sqrt 3 - 2) e^(sqrt 3 - 3)
        p = RoundedPulse(a, mu, speed_kmh=speed)
        c = 0.25 * abs(a) * math.e**2
        w = mu * 10.4 * speed / 50.0
        factor = (2 * math.sqrt(3) - 2) * math.exp(math.sqrt(3) - 3)
        assert factor == pytest.approx(0.412010, abs=1e-6)
        assert p.after_onset_peak_acceleration == pytest.approx(factor * c * w * w, rel=1e-12)
        assert p.peak_acceleration == pytest.approx(2 * c * w * w, rel=1e-12)
        assert p.peak_acceleration / p.after_onset_peak_acceleration == pytest.approx(
            4.854250, rel=1e-6
        )
        # independent check: the largest |z_r''| after the acceleration's zero crossing,
        # on a fine grid (the crossing is at x = 2 - sqrt 2)
        t0 = p.delay + (2 - math.sqrt(2)) / w
        t = np.linspace(t0, p.delay + 12.0 / w, 400001)
        assert np.max(np.abs(p.acceleration(t))) == pytest.approx(
            p.after_onset_peak_acceleration, rel=1e-9
        )
        assert abs(float(p.acceleration(p.after_onset_time))) == pytest.approx(
            p.after_onset_peak_acceleration, rel=1e-12
        )
        assert "after_onset_peak_acceleration" in p.describe()

    def test_negative_amplitude_is_a_pothole(self):
        p = RoundedPulse(-0.02, 1.0)
        assert float(p.displacement(p.peak_time)) == pytest.approx(-0.02)

    def test_describe(self):
        d = RoundedPulse(0.035, 3, speed_kmh=100.0).describe()
        assert d["kind"] == "pulse"
        assert d["omega0"] == pytest.approx(20.8)
        assert d["severity"] == 3.0

    @pytest.mark.parametrize(
        ("kwargs", "fragments"),
        [
            ({"amplitude": 0.0, "severity": 1}, ("amplitude", "nonzero")),
            ({"amplitude": 0.02, "severity": 0}, ("severity",)),
            ({"amplitude": 0.02, "severity": 1, "speed_kmh": -50.0}, ("speed_kmh", "km/h")),
            ({"amplitude": 0.02, "severity": 1, "omega0": 0.0}, ("omega0", "rad/s")),
            ({"amplitude": 0.02, "severity": 1, "delay": -0.1}, ("delay", "[0, 10000] s")),
        ],
    )
    def test_bad_parameters(self, kwargs, fragments):
        _raises(lambda: RoundedPulse(**kwargs), *fragments)


# -- uniform grids (what the engine samples) ---------------------------------------------
@pytest.mark.parametrize("frequency", [0.5, 2.1, 15.0, 80.0])
@pytest.mark.parametrize("n", [1, 63, 64, 65, 20001])
def test_harmonic_grid_matches_pointwise_evaluation(frequency: float, n: int) -> None:
    z = Harmonic(frequency, 0.03)
    zr, vr = z.sample_grid(n, 5e-5)
    t = np.arange(n) * 5e-5
    assert zr.shape == vr.shape == (n,)
    # a few ulp of the amplitude (the direct form's own angle rounds at 1e-16 relative)
    w = z.angular_frequency
    atol = 8 * np.finfo(float).eps * max(1.0, w * t[-1])
    np.testing.assert_allclose(zr, z.displacement(t), rtol=0, atol=atol * 0.03)
    np.testing.assert_allclose(vr, z.velocity(t), rtol=0, atol=atol * 0.03 * w)


class _Parabola(Excitation):
    """An excitation with the default (pointwise) grid: ``z_r = t^2``."""

    name = "parabola"

    def displacement(self, t):
        return np.asarray(t, dtype=float) ** 2

    def velocity(self, t):
        return 2.0 * np.asarray(t, dtype=float)

    def acceleration(self, t):
        return np.full(np.shape(t), 2.0)

    @property
    def duration(self) -> float:
        return 1.0

    def describe(self):
        return {"kind": self.name}


def test_default_grid_is_pointwise_evaluation() -> None:
    exc = _Parabola()
    zr, vr = exc.sample_grid(101, 0.01)
    t = np.arange(101) * 0.01
    np.testing.assert_array_equal(zr, exc.displacement(t))
    np.testing.assert_array_equal(vr, exc.velocity(t))


@pytest.mark.parametrize("start", [0.0, 0.3, 0.5, 12.25])
@pytest.mark.parametrize("severity", [1.0, 3.0])
def test_pulse_grid_matches_pointwise_evaluation(start: float, severity: float) -> None:
    bump = RoundedPulse(amplitude=-0.05, severity=severity, speed_kmh=100.0, delay=0.5)
    n = 20001
    zr, vr = bump.sample_grid(n, 5e-5, start=start)
    t = start + np.arange(n) * 5e-5
    z0, v0 = bump.displacement(t), bump.velocity(t)
    # the same operations; only numba's exp may differ from numpy's (by an ulp)
    np.testing.assert_allclose(zr, z0, rtol=4 * np.finfo(float).eps, atol=0)
    np.testing.assert_allclose(vr, v0, rtol=4 * np.finfo(float).eps, atol=1e-20)
    if start < bump.delay:
        assert np.all(zr[t < bump.delay] == 0.0)
        assert np.all(vr[t < bump.delay] == 0.0)


@pytest.mark.parametrize("frequency", [1.5, 80.0])
@pytest.mark.parametrize("start", [0.0, 1e-3, 12.345, 3599.9995, -0.25])
@pytest.mark.parametrize("n", [1, 21, 130])
def test_harmonic_grid_from_a_start_time(frequency: float, start: float, n: int) -> None:
    """A grid from ``start`` (a HiL tick's half steps) is the pointwise road there."""
    z = Harmonic(frequency, 0.03)
    zr, vr = z.sample_grid(n, 5e-5, start=start)
    t = start + np.arange(n) * 5e-5
    w = z.angular_frequency
    atol = 8 * np.finfo(float).eps * max(1.0, w * np.max(np.abs(t)))
    np.testing.assert_allclose(zr, z.displacement(t), rtol=0, atol=atol * 0.03)
    np.testing.assert_allclose(vr, z.velocity(t), rtol=0, atol=atol * 0.03 * w)
    # and it is the same signal as the grid from 0, shifted (not the grid from 0)
    if start > 0.0 and n > 1:
        assert np.max(np.abs(zr - z.sample_grid(n, 5e-5)[0])) > 1e-6


def test_default_grid_from_a_start_time_is_pointwise_evaluation() -> None:
    exc = _Parabola()
    zr, vr = exc.sample_grid(101, 0.01, start=-0.3)
    t = -0.3 + np.arange(101) * 0.01
    np.testing.assert_array_equal(zr, exc.displacement(t))
    np.testing.assert_array_equal(vr, exc.velocity(t))
    assert zr[0] == pytest.approx(0.09)


def test_grid_refuses_a_bad_start() -> None:
    for start in (math.nan, math.inf, [0.0, 1.0]):
        _raises(lambda s=start: Harmonic(1.0, 0.01).sample_grid(5, 1e-3, start=s), "start")
        _raises(lambda s=start: RoundedPulse(0.05, 2).sample_grid(5, 1e-3, start=s), "start")
        _raises(lambda s=start: _Parabola().sample_grid(5, 1e-3, start=s), "start")
    # numbers that are not plain floats take the checked path and still work
    z0, _ = Harmonic(1.0, 0.01).sample_grid(np.int64(5), np.float32(0.25), start=np.float64(1))
    np.testing.assert_allclose(z0, Harmonic(1.0, 0.01).displacement(1.0 + np.arange(5) * 0.25))


@pytest.mark.parametrize(
    ("n", "step", "fragments"),
    [(0, 1e-3, ("n", "0")), (5, 0.0, ("step", "0")), (5, -1e-3, ("step",))],
)
def test_grid_refuses_bad_sizes(n: int, step: float, fragments: tuple[str, ...]) -> None:
    _raises(lambda: Harmonic(1.0, 0.01).sample_grid(n, step), *fragments)
    _raises(lambda: RoundedPulse(amplitude=0.05, severity=2).sample_grid(n, step), *fragments)
    _raises(lambda: _Parabola().sample_grid(n, step), *fragments)
