"""The damper kernels' tanh (one exp or one division) against 40-digit decimal arithmetic.

The reference is computed here with :mod:`decimal` (``tanh x = (e^{2x} - 1)/(e^{2x} + 1)``,
and its Taylor series where that would cancel), never from the package or libm.
"""

from __future__ import annotations

import math
from decimal import Decimal, localcontext

import numpy as np
import pytest

from mrsuspension.dampers import kernels as K

EPS = 2.0**-52


def tanh_reference(x: float) -> Decimal:
    with localcontext() as ctx:
        ctx.prec = 40
        d = Decimal(x)
        if abs(x) < 1e-4:
            return d - d**3 / 3 + 2 * d**5 / 15 - 17 * d**7 / 315
        e = (2 * d).exp()
        return (e - 1) / (e + 1)


def relative_error(x: float) -> float:
    ref = tanh_reference(x)
    return float(abs(Decimal(K.fast_tanh(x)) - ref) / abs(ref))


def sample_points() -> np.ndarray:
    rng = np.random.default_rng(3)
    t = K.TANH_RATIONAL_BELOW
    return np.concatenate(
        [
            rng.uniform(-1.0, 1.0, 3000),
            rng.uniform(-25.0, 25.0, 1500),
            10.0 ** rng.uniform(-300.0, 1.5, 1500) * rng.choice([-1.0, 1.0], 1500),
            np.linspace(t - 1e-3, t + 1e-3, 401),  # both sides of the switch
            [t, np.nextafter(t, 0.0), -t, 20.0, np.nextafter(20.0, 30.0), 5e-324],
        ]
    )


def test_relative_error_is_round_off_everywhere() -> None:
    worst = max(relative_error(float(x)) for x in sample_points())
    # libm's tanh reaches ~1.3 ulp on the same points; the rational branch ~1.6 ulp
    assert worst < 2.0 * EPS, worst / EPS


@pytest.mark.parametrize("x", [0.3, 0.54, 0.56, 2.0, 19.0])
def test_odd(x: float) -> None:
    assert K.fast_tanh(-x) == -K.fast_tanh(x)


def test_special_values() -> None:
    assert K.fast_tanh(0.0) == 0.0
    assert math.copysign(1.0, K.fast_tanh(-0.0)) == -1.0
    assert K.fast_tanh(math.inf) == 1.0
    assert K.fast_tanh(-math.inf) == -1.0
    assert K.fast_tanh(40.0) == 1.0
    assert K.fast_tanh(-40.0) == -1.0
    assert math.isnan(K.fast_tanh(math.nan))


def test_monotone_across_the_switch() -> None:
    x = np.linspace(K.TANH_RATIONAL_BELOW - 1e-6, K.TANH_RATIONAL_BELOW + 1e-6, 2001)
    y = np.array([K.fast_tanh(float(u)) for u in x])
    assert np.all(np.diff(y) >= 0.0)


def test_the_damper_force_uses_it_at_round_off() -> None:
    """The Wang force with the kernels' tanh equals the model reference's formula with math.tanh."""
    from mrsuspension.dampers import WangSymmetric

    model = WangSymmetric(vh_variant="2.12")  # H(i) in v_h: every factor exercised
    p = model.kernel(1e-3).params
    vm, sgn_a = 0.2, -1.0
    for v in np.linspace(-0.4, 0.4, 81):
        i = 0.3
        ci = 1.0 + p[K.W_K2] * (K.sigmoid(p[K.W_A2] * (i + p[K.W_I0])) - p[K.W_SA2])
        h = 1.0 + p[K.W_K3] * (K.sigmoid(p[K.W_A3] * (i + p[K.W_I1])) - p[K.W_SA3])
        ft = p[K.W_F0] * (1.0 + math.exp(p[K.W_A1] * vm))
        alpha = p[K.W_A0] / (1.0 + p[K.W_K0] * vm)
        kv = p[K.W_K1C] * math.exp(-p[K.W_A4] * vm)
        vh = sgn_a * p[K.W_K4] * vm * h
        expected = ci * ft * math.tanh(0.5 * alpha * (v + vh)) * (1.0 + kv * abs(v))
        got = K.wang_force(p, float(v), sgn_a, i, vm)
        assert got == pytest.approx(expected, rel=1e-14, abs=1e-12)
