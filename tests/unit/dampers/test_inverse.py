"""The inverse model (model reference, section 2.3): recover the drive current from the force."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mrsuspension.dampers import WangAsymmetric, WangSymmetric
from mrsuspension.errors import ValidationError

FIG_2_10_PEAK_VELOCITY = 2.0 * math.pi * 1.5 * 0.025  # x_d = 0.025 sin(3 pi t)


def fig_2_10_signals():
    """Fig. 2.10 check: i = 0.25 + 0.2 sin(3 pi t), x = 0.025 sin(3 pi t), exact derivatives."""
    t = np.linspace(0.0, 2.0, 2000)
    w = 3.0 * math.pi
    current = 0.25 + 0.2 * np.sin(w * t)
    x = 0.025 * np.sin(w * t)
    v = 0.025 * w * np.cos(w * t)
    a = -0.025 * w * w * np.sin(w * t)
    return t, current, x, v, a


@pytest.mark.parametrize("hysteresis", [True, False])
@pytest.mark.parametrize("force_gain", [1.0, 2.5])
def test_fig_2_10_current_is_recovered(hysteresis, force_gain):
    _, current, x, v, a = fig_2_10_signals()
    model = WangSymmetric(vh_variant="2.13", hysteresis=hysteresis, force_gain=force_gain)
    force = model.force(x, v, a, current, peak_velocity=FIG_2_10_PEAK_VELOCITY)
    recovered = model.inverse_current(force, v, a, stroke=x, peak_velocity=FIG_2_10_PEAK_VELOCITY)
    assert recovered.shape == current.shape
    assert np.max(np.abs(recovered - current)) <= 1e-9


def test_fig_2_10_with_the_instantaneous_estimator():
    # (2.14) is exact for the sinusoid, so the estimator gives the same v_m inside both
    _, current, x, v, a = fig_2_10_signals()
    model = WangSymmetric(vh_variant="2.13", estimator="instantaneous")
    force = model.force(x, v, a, current)
    recovered = model.inverse_current(force, v, a, stroke=x)
    assert np.max(np.abs(recovered - current)) <= 1e-9


def test_passive_hysteron_matches_eq_2_8(wang_reference):
    ref = wang_reference("wang-symmetric-low")
    model = WangSymmetric(vh_variant="2.13", force_gain=2.5)
    for v, a, vm in [(0.1, -1.0, 0.25), (-0.3, 2.0, 0.5), (0.05, 0.0, 0.1)]:
        got = float(model.passive_hysteron(v, a, peak_velocity=vm))
        assert got == pytest.approx(ref.passive_hysteron(v, a, vm), rel=1e-12)
        # F_d = k_d C_i F_h for the (2.13) variant
        f = float(model.force(0.0, v, a, 0.3, peak_velocity=vm))
        assert f == pytest.approx(
            2.5 * ref.current_gain(0.3) * ref.passive_hysteron(v, a, vm), rel=1e-12
        )


@settings(max_examples=150, deadline=None)
@given(
    speed=st.floats(0.01, 1.0),
    velocity_sign=st.sampled_from([-1.0, 1.0]),
    accel_sign=st.sampled_from([-1.0, 0.0, 1.0]),
    peak_velocity=st.floats(0.01, 1.0),
    current=st.floats(0.0, 0.5),
    force_gain=st.floats(1.0, 3.0),
    hysteresis=st.booleans(),
    set_name=st.sampled_from(["wang-symmetric-low", "wang-symmetric-high"]),
)
def test_inverse_recovers_any_current(
    speed, velocity_sign, accel_sign, peak_velocity, current, force_gain, hysteresis, set_name
):
    v = velocity_sign * speed
    a = accel_sign * 3.0
    model = WangSymmetric(set_name, vh_variant="2.13", force_gain=force_gain, hysteresis=hysteresis)
    # invertible only where the damper produces a force at all
    assume(float(model.passive_hysteron(v, a, peak_velocity=peak_velocity)) != 0.0)
    force = model.force(0.01, v, a, current, peak_velocity=peak_velocity)
    recovered = float(model.inverse_current(force, v, a, stroke=0.01, peak_velocity=peak_velocity))
    assert abs(recovered - current) <= 1e-9
    # only the magnitude of the target matters
    recovered_neg = float(model.inverse_current(-force, v, a, peak_velocity=peak_velocity))
    assert abs(recovered_neg - current) <= 1e-9


def test_target_below_the_passive_force_gives_zero(wang_reference):
    ref = wang_reference("wang-symmetric-low")
    model = WangSymmetric(vh_variant="2.13", force_gain=2.5)
    v, a, vm = 0.2, -1.0, 0.3
    passive = 2.5 * abs(ref.passive_hysteron(v, a, vm))
    targets = np.array([0.0, 0.5 * passive, 0.999 * passive, -0.9 * passive])
    np.testing.assert_array_equal(model.inverse_current(targets, v, a, peak_velocity=vm), 0.0)


def test_target_above_the_maximum_force_gives_max_current(wang_reference):
    ref = wang_reference("wang-symmetric-low")
    model = WangSymmetric(vh_variant="2.13")
    v, a, vm = -0.2, 1.0, 0.3
    f_max = abs(ref.current_gain(0.5) * ref.passive_hysteron(v, a, vm))
    targets = np.array([1.001 * f_max, -2.0 * f_max, 1e9])
    np.testing.assert_array_equal(model.inverse_current(targets, v, a, peak_velocity=vm), 0.5)
    # a lower limit is honoured
    lim = model.inverse_current(targets, v, a, peak_velocity=vm, max_current=0.3)
    np.testing.assert_array_equal(lim, 0.3)
    # a target just below the maximum force is reached with a current just below 0.5 A
    just_below = float(model.inverse_current(0.999 * f_max, v, a, peak_velocity=vm))
    assert 0.45 < just_below < 0.5


def test_inverse_current_closed_form_hand_value():
    # invert (2.9) by hand for C = 2: y = (C - 1)/k2 + sigma(a2 I0); i = -I0 - ln(1/y - 1)/a2
    k2, a2, i0 = 9.244, 7.258, 0.079
    y = 1.0 / k2 + 1.0 / (1.0 + math.exp(-a2 * i0))
    expected = -i0 - math.log(1.0 / y - 1.0) / a2
    model = WangSymmetric(vh_variant="2.13")
    f_h = float(model.passive_hysteron(0.3, -1.0, peak_velocity=0.4))
    got = float(model.inverse_current(2.0 * f_h, 0.3, -1.0, peak_velocity=0.4))
    assert got == pytest.approx(expected, abs=1e-12)
    assert 0.0 < expected < 0.5


def test_asymmetric_model_has_no_inverse():
    model = WangAsymmetric()
    assert model.values["k5"] != 0
    with pytest.raises(ValidationError, match="symmetric"):
        model.inverse_current(100.0, 0.1, -1.0, peak_velocity=0.2)


def test_asymmetric_model_with_a_symmetric_set_has_an_inverse():
    model = WangAsymmetric("wang-symmetric-low", vh_variant="2.13")
    f = model.force(0.0, 0.1, -1.0, 0.3, peak_velocity=0.2)
    assert float(model.inverse_current(f, 0.1, -1.0, peak_velocity=0.2)) == pytest.approx(
        0.3, abs=1e-9
    )


def test_inverse_rejects_bad_inputs():
    model = WangSymmetric(vh_variant="2.13")
    with pytest.raises(ValidationError, match="target_force"):
        model.inverse_current(float("nan"), 0.1)
    with pytest.raises(ValidationError, match="max_current"):
        model.inverse_current(100.0, 0.1, max_current=0.7)
    with pytest.raises(ValidationError, match="broadcast"):
        model.inverse_current([1.0, 2.0], [0.1, 0.2, 0.3])
