"""Current shaping (model reference, section 3): ADFG (2.1)/(2.3), CM (3.8), drive current (3.9)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrsuspension.errors import ValidationError
from mrsuspension.shaping import (
    adfg_multiplier,
    cm_multiplier,
    drive_current,
    onoff_adfg_current,
)


def m_p(v: float, vm: float, p: float, xi: float) -> float:
    """Eq. (2.3), written from the model reference (section 3)."""
    s = p if v > 0 else 1.0
    return (1 + p) / 2 + (2 / math.pi) * (s - (1 + p) / 2) * abs(math.atan(xi * v / vm))


def m_c(z: float, p_c: float, xi_c: float) -> float:
    """Eq. (3.8), written from the model reference (section 3)."""
    s = p_c if z >= 0 else 1.0
    return (1 + p_c) / 2 + (2 / math.pi) * (s - (1 + p_c) / 2) * abs(math.atan(xi_c * z))


velocities = st.floats(-1e3, 1e3, allow_nan=False)
peaks = st.floats(1e-3, 10.0)
ps = st.floats(0.0, 1.0)
pcs = st.floats(0.0, 1.0, exclude_max=True)
xis = st.floats(1e-3, 1e3)
SETTINGS = settings(max_examples=200, deadline=None)


# ----------------------------------------------------------------------------------
# ADFG multiplier M_p, eq. (2.3)
def test_adfg_hand_values():
    # p = 0, xi = 2, v_m = 0.3: compression 0.1 m/s -> 1/2 - atan(2/3)/pi
    assert float(adfg_multiplier(0.1, 0.3, p=0.0, xi=2.0)) == pytest.approx(
        0.5 - math.atan(2.0 / 3.0) / math.pi, rel=1e-14
    )
    assert 0.5 - math.atan(2.0 / 3.0) / math.pi == pytest.approx(0.312832958, rel=1e-8)
    # rebound -0.1 m/s -> 1/2 + atan(2/3)/pi
    assert float(adfg_multiplier(-0.1, 0.3, p=0.0, xi=2.0)) == pytest.approx(
        0.5 + math.atan(2.0 / 3.0) / math.pi, rel=1e-14
    )
    # p = 0.4, xi = 4.5, v = 0.2, v_m = 0.25: 0.7 + (2/pi)(0.4 - 0.7) atan(3.6)
    assert float(adfg_multiplier(0.2, 0.25, p=0.4, xi=4.5)) == pytest.approx(
        0.7 - 0.6 / math.pi * math.atan(3.6), rel=1e-14
    )


@SETTINGS
@given(v=velocities, vm=peaks, p=ps, xi=xis)
def test_adfg_matches_eq_2_3_and_is_bounded(v, vm, p, xi):
    got = float(adfg_multiplier(v, vm, p=p, xi=xi))
    assert got == pytest.approx(m_p(v, vm, p, xi), rel=1e-12, abs=1e-15)
    assert min(p, 1.0) - 1e-12 <= got <= 1.0 + 1e-12


@SETTINGS
@given(p=ps, xi=xis, vm=peaks)
def test_adfg_limits(p, xi, vm):
    assert float(adfg_multiplier(1e300, vm, p=p, xi=xi)) == pytest.approx(p, abs=1e-12)
    assert float(adfg_multiplier(-1e300, vm, p=p, xi=xi)) == pytest.approx(1.0, abs=1e-12)
    assert float(adfg_multiplier(0.0, vm, p=p, xi=xi)) == (1.0 + p) / 2.0


@SETTINGS
@given(eps=st.floats(1e-12, 1e-3), vm=peaks, p=ps, xi=xis)
def test_adfg_is_continuous_at_zero_velocity(eps, vm, p, xi):
    # |M(eps) - M(-eps)| = (2/pi)(1-p) atan(xi eps / v_m) <= (2/pi) xi eps / v_m
    jump = abs(
        float(adfg_multiplier(eps, vm, p=p, xi=xi)) - float(adfg_multiplier(-eps, vm, p=p, xi=xi))
    )
    assert jump <= 2.0 / math.pi * xi * eps / vm * (1 + 1e-9) + 1e-15


@SETTINGS
@given(v=velocities, vm=peaks, xi=xis)
def test_adfg_p_one_is_exactly_one(v, vm, xi):
    assert float(adfg_multiplier(v, vm, p=1.0, xi=xi)) == 1.0


def test_adfg_broadcasts():
    out = adfg_multiplier(
        np.linspace(-1, 1, 12).reshape(3, 4), np.array([0.2, 0.3, 0.4, 0.5]), p=0.0, xi=2
    )
    assert out.shape == (3, 4)


# ----------------------------------------------------------------------------------
# CM multiplier M_c, eq. (3.8)
def test_cm_hand_values():
    # p_c = 0, xi_c = 10: z_c = 0.05 -> 1/2 - atan(0.5)/pi; z_c = -0.05 -> 1/2 + atan(0.5)/pi
    assert float(cm_multiplier(0.05, p_c=0.0, xi_c=10.0)) == pytest.approx(
        0.5 - math.atan(0.5) / math.pi, rel=1e-14
    )
    assert 0.5 - math.atan(0.5) / math.pi == pytest.approx(0.352416382, rel=1e-8)
    assert float(cm_multiplier(-0.05, p_c=0.0, xi_c=10.0)) == pytest.approx(
        0.5 + math.atan(0.5) / math.pi, rel=1e-14
    )
    # p_c = 0.2, xi_c = 50, z_c = 0.01: 0.6 + (2/pi)(0.2 - 0.6) atan(0.5)
    assert float(cm_multiplier(0.01, p_c=0.2, xi_c=50.0)) == pytest.approx(
        0.6 - 0.8 / math.pi * math.atan(0.5), rel=1e-14
    )


@SETTINGS
@given(z=velocities, p_c=pcs, xi_c=xis)
def test_cm_matches_eq_3_8_and_is_bounded(z, p_c, xi_c):
    got = float(cm_multiplier(z, p_c=p_c, xi_c=xi_c))
    assert got == pytest.approx(m_c(z, p_c, xi_c), rel=1e-12, abs=1e-15)
    assert p_c - 1e-12 <= got <= 1.0 + 1e-12


@SETTINGS
@given(p_c=pcs, xi_c=xis)
def test_cm_limits(p_c, xi_c):
    assert float(cm_multiplier(1e300, p_c=p_c, xi_c=xi_c)) == pytest.approx(p_c, abs=1e-12)
    assert float(cm_multiplier(-1e300, p_c=p_c, xi_c=xi_c)) == pytest.approx(1.0, abs=1e-12)
    assert float(cm_multiplier(0.0, p_c=p_c, xi_c=xi_c)) == (1.0 + p_c) / 2.0


@SETTINGS
@given(eps=st.floats(1e-12, 1e-3), p_c=pcs, xi_c=xis)
def test_cm_is_continuous_at_zero(eps, p_c, xi_c):
    jump = abs(
        float(cm_multiplier(eps, p_c=p_c, xi_c=xi_c))
        - float(cm_multiplier(-eps, p_c=p_c, xi_c=xi_c))
    )
    assert jump <= 2.0 / math.pi * xi_c * eps * (1 + 1e-9) + 1e-15


# ----------------------------------------------------------------------------------
# on-off ADFG, eq. (2.1)
def test_onoff_adfg():
    out = onoff_adfg_current(0.3, [0.1, -0.1, 0.0, 1e-9], p=0.2)
    np.testing.assert_allclose(out, [0.06, 0.3, 0.3, 0.06], rtol=1e-15)
    np.testing.assert_array_equal(onoff_adfg_current([0.1, 0.4], 0.5, p=0.0), [0.0, 0.0])
    np.testing.assert_array_equal(onoff_adfg_current([0.1, 0.4], -0.5, p=0.0), [0.1, 0.4])
    np.testing.assert_array_equal(onoff_adfg_current([0.1, 0.4], 0.5, p=1.0), [0.1, 0.4])


# ----------------------------------------------------------------------------------
# drive current, eqs. (3.9)/(3.16)
@SETTINGS
@given(
    i_z=st.floats(0.0, 2.0),
    v=velocities,
    vm=peaks,
    z=velocities,
    p=ps,
    xi=xis,
    p_c=pcs,
    xi_c=xis,
    i_max=st.floats(0.05, 1.0),
)
def test_drive_current_is_the_clipped_product(i_z, v, vm, z, p, xi, p_c, xi_c, i_max):
    got = float(drive_current(i_z, v, vm, z, p=p, xi=xi, p_c=p_c, xi_c=xi_c, max_current=i_max))
    expected = min(max(m_p(v, vm, p, xi) * m_c(z, p_c, xi_c) * i_z, 0.0), i_max)
    assert got == pytest.approx(expected, rel=1e-12, abs=1e-15)
    assert 0.0 <= got <= i_max


def test_drive_current_hand_values_and_clip():
    # SCM (p = 1), z_c = -1 (high current wanted): i = M_c(-1) i_z
    mc = 0.5 + math.atan(10.0) / math.pi
    got = float(drive_current(0.4, -0.2, 0.3, -1.0, p=1.0, xi=4.5, p_c=0.0, xi_c=10.0))
    assert got == pytest.approx(mc * 0.4, rel=1e-14)
    # clipped at i_max
    assert float(drive_current(3.0, -0.2, 0.3, -1e9, max_current=0.5)) == 0.5
    assert float(drive_current(3.0, -0.2, 0.3, -1e9, max_current=0.3)) == 0.3
    # zero demand gives zero
    assert float(drive_current(0.0, 0.2, 0.3, -1.0)) == 0.0
    # ACM (p = 0) in strong compression with z_c strongly positive: almost nothing
    assert float(drive_current(0.4, 1e6, 0.3, 1e6, p=0.0, p_c=0.0)) < 1e-6
    # shape follows broadcasting
    out = drive_current(np.full((2, 3), 0.2), np.linspace(-1, 1, 3), 0.3, np.array([[-1.0], [1.0]]))
    assert out.shape == (2, 3)


# ----------------------------------------------------------------------------------
# validation: the message names the parameter and the valid range
@pytest.mark.parametrize(
    ("call", "fragments"),
    [
        (lambda: adfg_multiplier(0.1, 0.3, p=-0.1, xi=2.0), ["p", "[0, 1]", "-0.1"]),
        (lambda: adfg_multiplier(0.1, 0.3, p=1.5, xi=2.0), ["p", "[0, 1]", "1.5"]),
        (lambda: adfg_multiplier(0.1, 0.3, p=math.nan, xi=2.0), ["p", "[0, 1]", "nan"]),
        (lambda: adfg_multiplier(0.1, 0.3, p=0.5, xi=0.0), ["xi", "(0, inf)", "got 0"]),
        (lambda: adfg_multiplier(0.1, 0.3, p=0.5, xi=-2.0), ["xi", "(0, inf)", "-2"]),
        (lambda: adfg_multiplier(float("nan"), 0.3, p=0.5, xi=2.0), ["velocity", "finite", "nan"]),
        (lambda: adfg_multiplier(0.1, 0.0, p=0.5, xi=2.0), ["peak_velocity", "(0, inf)"]),
        (lambda: cm_multiplier(0.1, p_c=1.0, xi_c=10.0), ["p_c", "[0, 1)", "got 1"]),
        (lambda: cm_multiplier(0.1, p_c=-0.5, xi_c=10.0), ["p_c", "[0, 1)", "-0.5"]),
        (lambda: cm_multiplier(0.1, p_c=0.0, xi_c=0.0), ["xi_c", "(0, inf)"]),
        (lambda: cm_multiplier(float("inf"), p_c=0.0, xi_c=1.0), ["switching", "finite", "inf"]),
        (lambda: onoff_adfg_current(0.3, 0.1, p=2.0), ["p", "[0, 1]", "2"]),
        (lambda: onoff_adfg_current(-0.3, 0.1, p=0.5), ["control_current", "[0, inf)", "-0.3"]),
        (lambda: onoff_adfg_current(0.3, float("nan"), p=0.5), ["velocity", "finite"]),
        (lambda: drive_current(0.2, float("nan"), 0.3, 0.0), ["velocity", "finite", "nan"]),
        (lambda: drive_current(0.2, 0.1, 0.3, 0.0, p=1.01), ["p", "[0, 1]"]),
        (lambda: drive_current(0.2, 0.1, 0.3, 0.0, p_c=1.0), ["p_c", "[0, 1)"]),
        (lambda: drive_current(0.2, 0.1, 0.3, 0.0, xi=0.0), ["xi", "(0, inf)"]),
        (lambda: drive_current(0.2, 0.1, 0.3, 0.0, xi_c=-1.0), ["xi_c", "(0, inf)"]),
        (lambda: drive_current(-0.2, 0.1, 0.3, 0.0), ["i_z", ">= 0", "-0.2"]),
        (lambda: drive_current(0.2, 0.1, 0.3, 0.0, max_current=0.0), ["max_current", "(0, 10]"]),
    ],
)
def test_invalid_inputs_raise_naming_parameter_and_range(call, fragments):
    with pytest.raises(ValidationError) as info:
        call()
    message = str(info.value)
    assert message.startswith(f"{fragments[0]} "), message  # names the parameter first
    for fragment in fragments[1:]:
        assert fragment in message, (fragment, message)
